"""The peer, side by side in the same run: MRPT's icp-slam (Debian package mrpt-apps) on the same
CARMEN log as dpcr-replay. Optional: skipped, and said so, when the package is not installed.

Conversion. Debian's carmen2rawlog (MRPT 2.5) stamps every observation of the log with one time,
and icp-slam's pose extrapolator keys odometry by time, so odometry would be ignored. The rawlog is
therefore made from a prepared copy of the log and then re-stamped with the log's own times:
 - the copy holds the FLASER lines only, after two PARAM lines that carmen2rawlog reads: the
   angular resolution 180/N degrees (so each scan spans the 180 deg field of view: MRPT assumes
   0.5 deg, 90 deg for intel's 180 beams) and the maximum range (dpcr-replay's --max-range);
 - carmen2rawlog writes one odometry and one range-scan observation per line, each holding that
   one 64-bit time stamp; the rawlog is unpacked (gzip) and each pair is rewritten with its line's
   time (the count of stamps is checked: exactly two per line, else the peer is skipped); MRPT
   reads the plain rawlog as well.
icp-slam then runs on the rawlog with a point-map ICP configuration (ICP_CONFIG below); its pose
after each range scan, stamped with the scan's log time, is scored on the relations by dpcr-eval.
"""
import gzip
import os
import shutil
import struct

from bench.runs import RunError, command_text, median, run, say

MAX_RANGE_M = 20.0  # as dpcr-replay's default --max-range

ICP_CONFIG = """# icp-slam configuration written by tools/bench (bench/peer.py): a point map, classic ICP.
[ICP]
maxIterations = 80
minAbsStep_trans = 1e-6
minAbsStep_rot = 1e-6
thresholdDist = 0.3
thresholdAng_DEG = 5
ALFA = 0.8
smallestThresholdDist = 0.05
onlyClosestCorrespondences = true
onlyUniqueRobust = true
ICP_algorithm = icpClassic
corresponding_points_decimation = 5

[MappingApplication]
rawlog_offset = 0
logOutput_dir = {out_dir}
LOG_FREQUENCY = 0
SAVE_3D_SCENE = 0
SAVE_POSE_LOG = 0
CAMERA_3DSCENE_FOLLOWS_ROBOT = 0
SHOW_PROGRESS_3D_REAL_TIME = 0
SHOW_LASER_SCANS_3D = false
localizationLinDistance = 0.2
localizationAngDistance = 5
insertionLinDistance = 0.5
insertionAngDistance = 15.0
minICPgoodnessToAccept = 0.40
matchAgainstTheGrid = 0
occupancyGrid_count = 0
gasGrid_count = 0
landmarksMap_count = 0
beaconMap_count = 0
pointsMap_count = 1
likelihoodMapSelection = -1

[MappingApplication_pointsMap_00_insertOpts]
minDistBetweenLaserPoints = 0.05
fuseWithExisting = false
isPlanarMap = 1
"""


def available():
    missing = [t for t in ("icp-slam", "carmen2rawlog") if shutil.which(t) is None]
    return None if not missing else f"{', '.join(missing)} not installed (Debian package mrpt-apps; optional)"


def _prepare_log(clf, path):
    """The FLASER lines of clf after the PARAM lines; returns each line's log time as text."""
    stamps, lines = [], []
    with open(clf) as f:
        for line in f:
            if line.startswith("FLASER "):
                fields = line.split()
                lines.append(line)
                stamps.append(fields[-3])  # ipc_timestamp (the relations' time base)
    if not lines:
        raise RunError(f"{os.path.basename(clf)}: no FLASER lines")
    beams = int(lines[0].split()[1])
    with open(path, "w") as f:
        f.write(f"PARAM laser_front_laser_resolution {180.0 / beams:.9f} nohost 0\n")
        f.write(f"PARAM robot_front_laser_max {MAX_RANGE_M:g} nohost 0\n")
        f.writelines(lines)
    return stamps, beams


def _restamp(rawlog, stamps):
    """Rewrites the one time stamp carmen2rawlog gave every observation with each line's own time."""
    with open(rawlog, "rb") as f:
        data = f.read()
    if data[:2] == b"\x1f\x8b":  # carmen2rawlog writes gzip (stored blocks at -z 0): unpack first
        data = gzip.decompress(data)
    data = bytearray(data)
    # The shared stamp: the 64-bit value that occurs 2 x lines times (100 ns ticks since 1601).
    first = None
    for i in range(0, min(len(data) - 8, 4096)):
        v = struct.unpack_from("<Q", data, i)[0]
        if 1.2e17 < v < 1.6e17 and data.count(data[i:i + 8]) == 2 * len(stamps):
            first = bytes(data[i:i + 8])
            break
    if first is None:
        raise RunError("rawlog: could not find carmen2rawlog's shared time stamp exactly twice per scan")
    base = struct.unpack("<Q", first)[0]
    t0 = float(stamps[0])
    pos, k = 0, 0
    while True:
        pos = data.find(first, pos)
        if pos < 0:
            break
        tick = base + int(round((float(stamps[k // 2]) - t0) * 1e7))
        struct.pack_into("<Q", data, pos, tick)
        pos += 8
        k += 1
    with open(rawlog, "wb") as f:
        f.write(data)


def _trajectory(out_dir, stamps, tum_path):
    """icp-slam's log_estimated_path.txt ('step x y yaw', one line per observation: the odometry
    of scan k is step 2k, its range scan 2k + 1) as a TUM file on the log's times."""
    import math
    poses = {}
    with open(os.path.join(out_dir, "log_estimated_path.txt")) as f:
        for line in f:
            p = line.split()
            if len(p) == 4:
                poses[int(p[0])] = (float(p[1]), float(p[2]), float(p[3]))
    with open(tum_path, "w") as f:
        for k, stamp in enumerate(stamps):
            if 2 * k + 1 not in poses:
                continue
            x, y, yaw = poses[2 * k + 1]
            f.write(f"{stamp} {x:.6f} {y:.6f} 0 0 0 {math.sin(yaw / 2):.9f} {math.cos(yaw / 2):.9f}\n")


def _relations_split(relations, out_dir):
    """The relations file split at 10 s apart (as dpcr-replay's metrics.json)."""
    near, far = os.path.join(out_dir, "relations_under_10s"), os.path.join(out_dir, "relations_over_10s")
    with open(relations) as f, open(near, "w") as fn, open(far, "w") as ff:
        for line in f:
            p = line.split()
            if len(p) >= 2:
                (fn if abs(float(p[1]) - float(p[0])) < 10.0 else ff).write(line)
    return near, far


def _score(ctx, tum, relations):
    import json
    out_json = tum + ".eval.json"
    run([ctx.bins["eval"], tum, "--relations", relations, "--out", out_json])
    with open(out_json) as f:
        return json.load(f)["relations"]


def icp_slam(ctx, log, dpcr_row):
    """icp-slam on one log, ctx.reps times; its relations error and its wall time beside dpcr's."""
    name = os.path.basename(log["clf"])
    out = os.path.join(ctx.out, "peer", os.path.splitext(name)[0])
    os.makedirs(out, exist_ok=True)
    say(f"peer: MRPT icp-slam on {name} x {ctx.reps}")
    prepared = os.path.join(out, "flaser.clf")
    stamps, beams = _prepare_log(log["clf"], prepared)
    rawlog = os.path.join(out, "log.rawlog")
    convert = ["carmen2rawlog", "-q", "-w", "-z", "0", "-i", prepared, "-o", rawlog]
    run(convert)
    _restamp(rawlog, stamps)
    walls, internal, rss = [], [], []
    for k in range(ctx.reps):
        rep_dir = os.path.join(out, f"rep{k + 1}")
        os.makedirs(rep_dir, exist_ok=True)
        ini = os.path.join(rep_dir, "icp-slam.ini")
        with open(ini, "w") as f:
            f.write(ICP_CONFIG.format(out_dir=os.path.join(rep_dir, "icp-slam")))
        cmd = ["icp-slam", ini, rawlog]
        usage = {}
        wall, text = run(cmd, log_path=os.path.join(rep_dir, "run.log"), timeout=ctx.peer_timeout_s, stats=usage)
        walls.append(wall)
        rss.append(usage.get("peak_rss_mb"))
        for line in text.splitlines():
            if "**END** (total time:" in line:
                internal.append(float(line.split("total time:")[1].split()[0]))
    result = {
        "system": "MRPT icp-slam (mrpt-apps " + _mrpt_version() + ")",
        "log": name, "beams": beams, "max_range_m": MAX_RANGE_M,
        "commands": [command_text(convert, ctx.repo) + "  (then re-stamped: bench/peer.py)",
                     command_text(["icp-slam", os.path.join(out, "rep1", "icp-slam.ini"), rawlog], ctx.repo)],
        "process_wall_s": median(walls), "internal_total_s": median(internal), "peak_rss_mb": max(rss), "repetitions": len(walls),
    }
    tum = os.path.join(out, "trajectory.tum")
    _trajectory(os.path.join(out, "rep1", "icp-slam"), stamps, tum)
    if log.get("relations") and os.path.exists(log["relations"]):
        result["relations"] = _score(ctx, tum, log["relations"])
        near, far = _relations_split(log["relations"], out)
        result["relations"]["under_10s"] = _score(ctx, tum, near)
        result["relations"]["over_10s"] = _score(ctx, tum, far)
    if dpcr_row and dpcr_row.get("process_wall_s"):
        result["wall_ratio_peer_over_dpcr"] = result["process_wall_s"] / dpcr_row["process_wall_s"]
    return result


def _mrpt_version():
    import subprocess
    p = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "mrpt-apps"], capture_output=True, text=True)
    return p.stdout.strip() or "unknown version"


def peers(ctx, log_rows):
    reason = available()
    if reason:
        say(f"peer skipped: {reason}")
        return {"skipped": reason}
    rows = []
    for log in ctx.peer_logs:
        dpcr_row = next((r for r in log_rows if r.get("clf") == log["clf"] and "error" not in r), None)
        if not os.path.exists(log["clf"]):
            rows.append({"log": os.path.basename(log["clf"]), "skipped": "log not found"})
            continue
        try:
            rows.append(icp_slam(ctx, log, dpcr_row))
        except (RunError, OSError) as e:
            rows.append({"log": os.path.basename(log["clf"]), "error": str(e)})
        except Exception as e:  # subprocess.TimeoutExpired and the like: say it, go on
            rows.append({"log": os.path.basename(log["clf"]), "error": f"{type(e).__name__}: {e}"})
    return {"rows": rows}
