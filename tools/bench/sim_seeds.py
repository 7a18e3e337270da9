#!/usr/bin/env python3
"""LocErr_ave of dpcr-sim over many seeds, with the share of runs that failed.

Where a run can lose the map (a sparse XV-11 without wheel translation, a 3.5 Hz lidar), the mean
over ten seeds is one or two failures and says little: a change moves which seeds fail more than
how many. This runs dpcr-sim on a range of seeds in parallel and reports the median, the mean, the
worst run, how many runs exceed a threshold (failed), the mean of the rigid-aligned LocErr_ave (what is
left once one rigid motion of each whole run is taken out: a run whose start-aligned error is mostly
one turn of the map about the start shows it here), first registrations rejected, time lost and
relocalisation fixes over 0.3 m off (metrics.json). Compare two builds on 60 seeds or more.

  tools/bench/sim_seeds.py --first 1 --last 60 -- --lidar xv11 --odometry heading-ticks \\
      --lidar-valid 0.5 --lidar-min-hz 3.5 --minutes 10

Everything after `--` goes to dpcr-sim. Runs are written under --out (default: a temporary
directory, removed afterwards).
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor


def run_seed(sim, seed, out_dir, sim_args):
    run_dir = os.path.join(out_dir, "s%d" % seed)
    cmd = [sim, "--seed", str(seed), "--out", run_dir] + sim_args
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        return seed, None, "dpcr-sim exited with %d: %s" % (done.returncode, done.stderr.strip()[-300:])
    try:
        with open(os.path.join(run_dir, "metrics.json")) as f:
            return seed, json.load(f), None
    except (OSError, ValueError) as e:
        return seed, None, "no readable metrics.json: %s" % e


def run_seeds(sim, seeds, out_dir, sim_args, jobs):
    """run_seed for each of `seeds`, `jobs` at once: [(seed, metrics or None, problem or None)]."""
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        return list(pool.map(lambda s: run_seed(sim, s, out_dir, sim_args), seeds))


def summarise(results, threshold_m):
    errors = [m["accuracy"]["loc_err_ave_m"] for _, m in results]
    rigid = [m["accuracy"]["rigid_loc_err_ave_m"] for _, m in results]
    rejected = [m["tracking"]["first_rejected_fraction"] for _, m in results]
    lost_s = sum(m["tracking"]["lost_seconds"] for _, m in results)
    fixes = wrong = 0
    for _, m in results:
        each = m.get("relocalisation", {}).get("all_fixes", {})
        fixes += each.get("fixes", 0)
        wrong += each.get("wrong_fixes", 0)
    failed = [seed for seed, m in results if m["accuracy"]["loc_err_ave_m"] > threshold_m]
    return {
        "runs": len(results),
        "median_m": statistics.median(errors),
        "mean_m": statistics.fmean(errors),
        "worst_m": max(errors),
        "rigid_mean_m": statistics.fmean(rigid),
        "failed": len(failed),
        "failed_seeds": failed,
        "rejected_mean": statistics.fmean(rejected),
        "rejected_max": max(rejected),
        "lost_s": lost_s,
        "fixes": fixes,
        "wrong_fixes": wrong,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sim", default="build/host/host_sim/apps/dpcr-sim", help="the dpcr-sim binary")
    parser.add_argument("--first", type=int, default=1, help="first seed")
    parser.add_argument("--last", type=int, default=10, help="last seed")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="runs at once")
    parser.add_argument("--fail-above", type=float, default=0.2, help="a run over this LocErr_ave (m) failed")
    parser.add_argument("--out", help="keep the runs here (default: a temporary directory)")
    parser.add_argument("--json", action="store_true", help="print the summary as JSON")
    parser.add_argument("sim_args", nargs="*", help="after --: options for dpcr-sim")
    args = parser.parse_args()
    if args.last < args.first:
        parser.error("--last %d is before --first %d" % (args.last, args.first))
    if not os.access(args.sim, os.X_OK):
        parser.error("no dpcr-sim at %s (build it, or pass --sim)" % args.sim)
    out_dir = args.out or tempfile.mkdtemp(prefix="dpcr-sim-seeds-")
    try:
        done = run_seeds(args.sim, range(args.first, args.last + 1), out_dir, args.sim_args, args.jobs)
    finally:
        if args.out is None:
            shutil.rmtree(out_dir, ignore_errors=True)
    problems = [(seed, why) for seed, _, why in done if why is not None]
    for seed, why in problems:
        print("seed %d: %s" % (seed, why), file=sys.stderr)
    if problems:
        return 1
    results = [(seed, metrics) for seed, metrics, _ in done]
    s = summarise(results, args.fail_above)
    if args.json:
        print(json.dumps(s))
        return 0
    for seed, m in results:
        print("seed %d: LocErr_ave %.3f m" % (seed, m["accuracy"]["loc_err_ave_m"]))
    print("seeds %d-%d: median %.3f m, mean %.3f m, worst %.3f m, failed (> %.2f m) %d of %d %s"
          % (args.first, args.last, s["median_m"], s["mean_m"], s["worst_m"], args.fail_above, s["failed"],
             s["runs"], s["failed_seeds"]))
    print("rigid-aligned LocErr_ave: mean %.4f m (start-aligned mean %.4f m)" % (s["rigid_mean_m"], s["mean_m"]))
    print("first registrations rejected: mean %.2f %%, worst run %.2f %%; lost %.0f s in all; "
          "relocalisation fixes %d, over 0.3 m off %d"
          % (100 * s["rejected_mean"], 100 * s["rejected_max"], s["lost_s"], s["fixes"], s["wrong_fixes"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
