"""The measured scenarios: the simulated office over region widths (paper Table 1), the simulated
apartment (paper Table 2) and the public CARMEN logs. Each run of an app writes its out dir
(metrics.json, map, trajectory), its saved map file and its per-scan times; wall times are the
median over the context's repetitions, run one after the other."""
import json
import os
import re

from bench.runs import RunError, command_text, median, rel, run, say, scan_time_stats


def _load(path):
    with open(path) as f:
        return json.load(f)


def _map_info_bytes(ctx, map_path):
    """The map file's size as `dpcr-map info` reports it (a check on the file the run saved)."""
    _, text = run([ctx.bins["map"], "info", map_path])
    m = re.search(r"^file:.*\((\d+) bytes\)", text, re.M)
    return int(m.group(1)) if m else None


def _one_run(ctx, app, args, out_dir):
    """One run of dpcr-sim or dpcr-replay into out_dir; returns its figures."""
    os.makedirs(out_dir, exist_ok=True)
    map_path = os.path.join(out_dir, "map.dpcr")
    times_path = os.path.join(out_dir, "scan_times.txt")
    cmd = [ctx.bins[app], *args, "--out", out_dir, "--save-map", map_path, "--scan-times", times_path]
    usage = {}
    wall, _ = run(cmd, log_path=os.path.join(out_dir, "run.log"), stats=usage)
    m = _load(os.path.join(out_dir, "metrics.json"))
    backend = m.get("backend", {})
    fig = {
        "command": command_text(cmd, ctx.repo),
        "process_wall_s": wall,
        "peak_rss_mb": usage.get("peak_rss_mb"),
        "mapper": m.get("mapper"),
        "scans": m.get("scans"),
        "scans_rejected": m.get("scans_rejected"),
        "regions": m.get("regions"),
        "map_file_bytes": os.path.getsize(map_path),
        "map_info_bytes": _map_info_bytes(ctx, map_path),
        "static_ram_bytes": m.get("static_ram_bytes"),
        "map_storage_bytes": m.get("map_storage_bytes"),
        "tiles_used": m.get("tiles_used"),
        "backend_total_ms": backend.get("total_ms"),
        "backend_max_ms": backend.get("max_ms"),
        "backend_calls": backend.get("calls"),
        "backend_optimizations": backend.get("optimizations"),
        "scan_times": scan_time_stats(times_path),
        "out_dir": rel(out_dir, ctx.repo),
    }
    if "accuracy" in m:
        fig["loc_err_ave_m"] = m["accuracy"].get("loc_err_ave_m")
        fig["ate_rmse_m"] = m["accuracy"].get("ate_rmse_m")
    if "relations" in m:
        r = m["relations"]
        fig["relations"] = {k: r.get(k) for k in ("trans_mean_m", "trans_std_m", "rot_mean_deg", "rot_std_deg",
                                                  "matched", "unmatched")}
        for split in ("under_10s", "over_10s"):
            if split in r:
                fig["relations"][split] = {k: r[split].get(k) for k in ("trans_mean_m", "rot_mean_deg", "matched")}
    return fig


# Figures that change from one repetition to the next (times): their median is reported.
_TIMED = ("process_wall_s", "backend_total_ms", "backend_max_ms")
_TIMED_SCAN = ("mean_ms", "p50_ms", "p90_ms", "p99_ms", "max_ms", "total_s")


def repeated(ctx, app, args, out_dir):
    """ctx.reps runs; the first run's figures, its times replaced by the medians over all runs.
    The mapping itself is deterministic: a run whose regions or map size differ is flagged."""
    figs = []
    for k in range(ctx.reps):
        figs.append(_one_run(ctx, app, args, os.path.join(out_dir, f"rep{k + 1}")))
    result = dict(figs[0])
    for key in _TIMED:
        result[key] = median([f.get(key) for f in figs])
    result["scan_times"] = dict(figs[0]["scan_times"])
    for key in _TIMED_SCAN:
        result["scan_times"][key] = median([f["scan_times"].get(key) for f in figs])
    result["repetitions"] = len(figs)
    walls = [f["process_wall_s"] for f in figs]
    result["wall_spread"] = (max(walls) - min(walls)) / median(walls) if len(walls) > 1 else None
    result["deterministic"] = all(f["regions"] == figs[0]["regions"] and f["map_file_bytes"] == figs[0]["map_file_bytes"]
                                  for f in figs)
    return result


def office_region_widths(ctx):
    """Paper Table 1: the simulated three-room office (21 m x 5 m) at each region width S."""
    rows = []
    for s in ctx.region_widths:
        say(f"office, S = {s:g} m, {ctx.office_minutes:g} min x {ctx.reps}")
        args = ["--world", "office", "--minutes", f"{ctx.office_minutes:g}", "--seed", str(ctx.seed),
                "--region-width", f"{s:g}"]
        try:
            row = repeated(ctx, "sim", args, os.path.join(ctx.out, "office", f"{ctx.office_minutes:g}min", f"S{s:g}"))
        except RunError as e:
            row = {"error": str(e)}
        row["S_m"] = s
        rows.append(row)
    return {"world": "office", "minutes": ctx.office_minutes, "seed": ctx.seed, "rows": rows}


def apartment(ctx):
    """Paper Table 2: the simulated apartment (about 100 m2)."""
    say(f"apartment, {ctx.apartment_minutes:g} min x {ctx.reps}")
    args = ["--world", "apartment", "--minutes", f"{ctx.apartment_minutes:g}", "--seed", str(ctx.seed)]
    try:
        row = repeated(ctx, "sim", args, os.path.join(ctx.out, "apartment"))
    except RunError as e:
        row = {"error": str(e)}
    return {"world": "apartment", "minutes": ctx.apartment_minutes, "seed": ctx.seed, "result": row}


def public_logs(ctx):
    """dpcr-replay on each CARMEN log (with its relations when there are some)."""
    rows = []
    for log in ctx.logs:
        name = os.path.basename(log["clf"])
        if not os.path.exists(log["clf"]):
            say(f"SKIP {name}: not found (set DPCR_DATA_DIR or --log)")
            rows.append({"log": name, "skipped": "log not found"})
            continue
        say(f"{name} x {ctx.reps}")
        args = ["--carmen", log["clf"]]
        if log.get("relations"):
            if os.path.exists(log["relations"]):
                args += ["--relations", log["relations"]]
            else:
                say(f"{name}: relations {os.path.basename(log['relations'])} not found, mapping without them")
        try:
            row = repeated(ctx, "replay", args, os.path.join(ctx.out, "logs", os.path.splitext(name)[0]))
        except RunError as e:
            row = {"error": str(e)}
        row["log"] = name
        row["clf"] = log["clf"]
        row["relations_file"] = log.get("relations") if "--relations" in args else None
        rows.append(row)
    return rows
