"""tools/bench/run: options, the plan of a quick and a full run, and the order of the parts."""
import argparse
import json
import os
import time

from bench import build, cost, machine, peer, report, scenarios, seed_sets
from bench.runs import rel, say

QUICK = {"reps": 1, "region_widths": [3, 4, 6, 10], "office_minutes": 35, "office_long_minutes": 0,
         "apartment_minutes": 35, "default_logs": ["intel"], "callgrind_minutes": 3, "callgrind_intel_scans": 0,
         "back_end_callgrind": False, "seed_sets_last": 2}
FULL = {"reps": 3, "region_widths": [3, 4, 5, 6, 7, 8, 9, 10], "office_minutes": 35, "office_long_minutes": 70,
        "apartment_minutes": 35, "default_logs": ["intel", "mit-csail"], "callgrind_minutes": 10,
        "callgrind_intel_scans": 3000, "back_end_callgrind": True, "seed_sets_last": 10}
DEFAULT_LOGS = {"intel": ("intel.clf", "intel.relations"), "mit-csail": ("mit-csail.clf", None)}


def parse_args(argv):
    p = argparse.ArgumentParser(prog="tools/bench/run", description=(
        "Runs dpcr's benchmark scenarios (paper Tables 1 and 2 on the simulator, the public CARMEN logs, cost, "
        "MRPT icp-slam side by side), writes out/bench/results.json and regenerates docs/RESULTS.md and its plots."))
    p.add_argument("--quick", action="store_true", help="1 repetition, 4 region widths, intel.clf only, short "
                   "callgrind runs (<= 5 min on 2 cores); default: the full run (3 repetitions, <= 60 min)")
    p.add_argument("--log", action="append", default=[], metavar="FILE[:RELATIONS]",
                   help="also map this CARMEN log (and score it on these relations); repeatable")
    p.add_argument("--no-default-logs", action="store_true", help="only the --log logs, not intel/mit-csail")
    p.add_argument("--build-dir", default=None, help="an existing build (default: build/host, built with the host preset)")
    p.add_argument("--no-build", action="store_true", help="use the build dir as it is")
    p.add_argument("--out", default=None, help="output folder (default: out/bench)")
    p.add_argument("--docs", default=None, help="RESULTS.md to write (default: docs/RESULTS.md; plots in docs/results/)")
    p.add_argument("--report-only", metavar="RESULTS_JSON", help="regenerate RESULTS.md and plots from a results.json")
    p.add_argument("--skip", action="append", default=[], choices=["table1", "table2", "seeds", "logs", "cost", "peer"],
                   help="leave a part out (repeatable)")
    p.add_argument("--seed", type=int, default=1, help="simulation seed (default 1)")
    p.add_argument("--no-install", action="store_true", help="do not call scripts/install-deps.sh --bench first")
    return p.parse_args(argv)


class Context:
    """What every part needs: paths, binaries and the plan (quick or full)."""

    def __init__(self, args, repo):
        plan = QUICK if args.quick else FULL
        self.repo = repo
        self.quick = args.quick
        self.seed = args.seed
        self.out = os.path.abspath(args.out or os.path.join(repo, "out", "bench"))
        self.build_dir = os.path.abspath(args.build_dir or os.path.join(repo, "build", "host"))
        self.data_dir = os.environ.get("DPCR_DATA_DIR") or os.path.normpath(os.path.join(repo, "..", "shared", "data"))
        for key, value in plan.items():
            setattr(self, key, value)
        self.peer_timeout_s = 900
        self.logs = []
        if not args.no_default_logs:
            for name in plan["default_logs"]:
                clf, relations = DEFAULT_LOGS[name]
                self.logs.append({"clf": os.path.join(self.data_dir, clf),
                                  "relations": os.path.join(self.data_dir, relations) if relations else None})
        for spec in args.log:
            clf, _, relations = spec.partition(":")
            self.logs.append({"clf": os.path.abspath(clf), "relations": os.path.abspath(relations) if relations else None})
        # The peer runs on the logs with relations (its error is the point), else on the first log.
        self.peer_logs = [l for l in self.logs if l.get("relations")] or self.logs[:1]
        self.bins = {}

    def plan(self):
        return {"mode": "quick" if self.quick else "full", "repetitions": self.reps,
                "region_widths_m": self.region_widths, "office_minutes": self.office_minutes,
                "office_long_minutes": self.office_long_minutes, "apartment_minutes": self.apartment_minutes,
                "seed": self.seed, "logs": [os.path.basename(l["clf"]) for l in self.logs],
                "peer_logs": [os.path.basename(l["clf"]) for l in self.peer_logs],
                "callgrind_apartment_minutes": self.callgrind_minutes,
                "callgrind_intel_scans": self.callgrind_intel_scans,
                "back_end_callgrind": self.back_end_callgrind, "seed_sets_seeds": [1, self.seed_sets_last]}


def _timed(results, name, fn):
    start = time.monotonic()
    value = fn()
    results["part_seconds"][name] = round(time.monotonic() - start, 1)
    return value


def main(argv, repo):
    args = parse_args(argv)
    docs = os.path.abspath(args.docs or os.path.join(repo, "docs", "RESULTS.md"))
    if args.report_only:
        with open(args.report_only) as f:
            results = json.load(f)
        report.write(results, docs, repo)
        say(f"wrote {rel(docs, repo)}")
        return 0
    ctx = Context(args, repo)
    start = time.monotonic()
    ctx.bins = build.ensure(repo, ctx.build_dir, args.no_build)
    os.makedirs(ctx.out, exist_ok=True)
    command = "tools/bench/run" + ("".join(" " + a for a in argv) if argv else "")
    results = {"command": command, "machine": machine.describe(repo), "plan": ctx.plan(), "part_seconds": {},
               "reference_file": "tools/bench/reference_figures.json"}
    say(f"{results['plan']['mode']} run on {results['machine']['cpu_model']} x {results['machine']['nproc']}")
    if "table1" not in args.skip:
        results["table1"] = _timed(results, "table1", lambda: scenarios.office_region_widths(ctx))
        if ctx.office_long_minutes:
            long_ctx = _Override(ctx, office_minutes=ctx.office_long_minutes, reps=1)
            results["table1_long"] = _timed(results, "table1_long", lambda: scenarios.office_region_widths(long_ctx))
    if "table2" not in args.skip:
        results["table2"] = _timed(results, "table2", lambda: scenarios.apartment(ctx))
    if "seeds" not in args.skip:
        results["seeds"] = _timed(results, "seeds", lambda: seed_sets.seed_sets(ctx))
    log_rows = []
    if "logs" not in args.skip:
        log_rows = results["logs"] = _timed(results, "logs", lambda: scenarios.public_logs(ctx))
    if "peer" not in args.skip:
        results["peer"] = _timed(results, "peer", lambda: peer.peers(ctx, log_rows))
    if "cost" not in args.skip:
        results["cost"] = _timed(results, "cost", lambda: {
            "footprint": cost.footprint(ctx), "allocations": cost.allocations(ctx),
            "per_scan": cost.per_scan_instructions(ctx), "back_end": cost.back_end_instructions(ctx),
            "armhf": cost.armhf_note()})
    results["total_seconds"] = round(time.monotonic() - start, 1)
    results["machine"]["load_average_at_end"] = [round(v, 2) for v in os.getloadavg()[:2]]
    path = os.path.join(ctx.out, "results.json")
    with open(path, "w") as f:
        json.dump(results, f, indent=1)
    say(f"wrote {rel(path, repo)} ({results['total_seconds']:.0f} s)")
    report.write(results, docs, repo)
    say(f"wrote {rel(docs, repo)} and its plots")
    return 0


class _Override:
    """A context with a few plan values changed (the 70-minute office runs)."""

    def __init__(self, ctx, **changes):
        self.__dict__.update(ctx.__dict__)
        self.__dict__.update(changes)
