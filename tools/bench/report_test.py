#!/usr/bin/env python3
"""ctest bench_report (label "bench"): tools/bench's report generator on a small made-up results.json
(no app runs): RESULTS.md gets every section, its tables, the measured cells and the quoted figures
labelled as quoted. Plots are drawn when matplotlib is there, and said to be missing otherwise."""
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench import plots, report  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def scan_times(p50):
    return {"scans": 100, "mean_ms": p50 * 1.5, "p50_ms": p50, "p90_ms": p50 * 2, "p99_ms": p50 * 5,
            "max_ms": p50 * 20, "total_s": p50 * 0.15}


def office_row(s, regions, err):
    return {"S_m": s, "regions": regions, "map_file_bytes": 12345 * regions, "map_storage_bytes": 54321 * regions,
            "backend_total_ms": 100.0 + regions, "loc_err_ave_m": err, "scan_times": scan_times(0.2),
            "command": f"build/host/host_sim/apps/dpcr-sim --world office --region-width {s}", "wall_spread": 0.1 * regions}


RESULTS = {
    "command": "tools/bench/run --quick",
    "machine": {"date_utc": "2000-01-01 00:00 UTC", "nproc": 2, "cpu_model": "Test CPU", "kernel": "0",
                "load_average_at_start": [0.5, 0.5], "commit": "abc", "branch": "test"},
    "plan": {"mode": "quick", "repetitions": 1, "region_widths_m": [3, 4], "office_minutes": 35,
             "office_long_minutes": 0, "apartment_minutes": 35, "seed": 1, "logs": ["intel.clf", "missing.clf"],
             "peer_logs": ["intel.clf"], "callgrind_apartment_minutes": 3, "callgrind_intel_scans": 0,
             "back_end_callgrind": False},
    "part_seconds": {"table1": 1.0},
    "total_seconds": 2.0,
    "table1": {"world": "office", "minutes": 35, "seed": 1,
               "rows": [office_row(3, 16, 0.0123), office_row(4, 12, 0.0456), {"S_m": 13, "error": "refused"}]},
    "table2": {"world": "apartment", "minutes": 35, "seed": 1,
               "result": {"map_file_bytes": 32010, "map_storage_bytes": 500000, "scan_times": scan_times(0.13),
                          "backend_total_ms": 374.0, "backend_calls": 430, "backend_max_ms": 5.3,
                          "loc_err_ave_m": 0.0234, "command": "build/host/host_sim/apps/dpcr-sim --world apartment"}},
    "seeds": {"fail_above_m": 0.2, "rows": [
        {"setting": "apartment: XV-11, gyro alone", "first": 1, "last": 3, "runs": 3, "median_m": 0.0234, "mean_m": 0.0256,
         "worst_m": 0.0312, "failed": 1, "rigid_mean_m": 0.0101, "rejected_mean": 0.0012,
         "command": "tools/bench/sim_seeds.py --first 1 --last 3 -- --lidar xv11 --odometry gyro"},
        {"setting": "office: LD06, wheels", "first": 1, "last": 3, "error": "seed 2: dpcr-sim exited with 1"}]},
    "logs": [{"log": "intel.clf", "clf": "intel.clf", "scans": 13631, "scan_times": scan_times(0.06),
              "relations": {"trans_mean_m": 0.2197, "rot_mean_deg": 1.28, "under_10s": {"trans_mean_m": 0.0185},
                            "over_10s": {"trans_mean_m": 0.513}},
              "process_wall_s": 4.36, "peak_rss_mb": 17.0, "map_file_bytes": 372046, "command": "dpcr-replay"},
             {"log": "missing.clf", "skipped": "log not found"}],
    "peer": {"rows": [{"system": "MRPT icp-slam (test)", "log": "intel.clf", "process_wall_s": 56.4,
                       "wall_ratio_peer_over_dpcr": 12.9, "peak_rss_mb": 99.0,
                       "relations": {"trans_mean_m": 1.2804, "rot_mean_deg": 9.7}, "commands": ["icp-slam x.ini"]}]},
    "cost": {"footprint": {"command": "t", "profiles": {"vacuum": {"sizeof_mapper_bytes": 2096688,
                                                                   "budget_bytes": 2097152}}},
             "allocations": {"command": "t", "passed": True, "counts": [{"what": "run", "allocations": 0}]},
             "per_scan": [{"label": "apartment (vacuum profile)", "scans_counted": 258, "median_ir": 1085952,
                           "mean_ir": 1338956, "p90_ir": 2279496, "max_ir": 4792339, "command": "sh x"}],
             "back_end": {"skipped": "not in --quick"}, "armhf": "not measured: test"},
}

EXPECTED = [
    "## Paper Table 1: region width S, simulated office", "| 3 | 16 | 16 |", "| 4 | 12 | 12 |", "error: refused",
    "## Paper Table 2: simulated apartment", "DPCR-SLAM (paper) *(quoted)*", "Cartographer (paper) *(quoted)*",
    "| 2.3 |",  # the apartment's LocErr_ave in cm
    "## Many seeds: lidars and odometry", "| apartment: XV-11, gyro alone | 1-3 | 2.34 | 2.56 | 3.1 | 1 of 3 | 1.01 | 0.12 % |",
    "error: seed 2: dpcr-sim exited with 1", "--lidar xv11 --odometry gyro",
    "## Public logs (CARMEN)", "0.2197 m / 1.28°", "0.0185 m", "missing.clf: skipped",
    "Cartographer (Hess et al. 2016, published) *(quoted)*", "0.0229 m",
    "## Side by side: MRPT icp-slam", "12.9 ×",
    "## Cost", "lie up to 160 % of", "| vacuum | 2 096 688 |", "1 085 952", "not in --quick", "Test CPU", "tools/bench/run --quick",
]


def main():
    with tempfile.TemporaryDirectory() as tmp:
        docs = os.path.join(tmp, "RESULTS.md")
        report.write(RESULTS, docs, REPO)
        text = open(docs).read()
        missing = [e for e in EXPECTED if e not in text]
        for e in missing:
            print(f"FAIL: RESULTS.md lacks {e!r}")
        pngs = sorted(os.listdir(os.path.join(tmp, "results")))
        if plots.available() and pngs != ["scan_times.png", "table1_region_width.png"]:
            print(f"FAIL: plots {pngs}")
            missing.append("plots")
        if not plots.available() and "Plots not drawn" not in text:
            print("FAIL: no plots and no word of it")
            missing.append("plots note")
        print(f"report: {len(EXPECTED)} checks, {len(missing)} failed; plots: {pngs or 'none (no matplotlib)'}")
        return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
