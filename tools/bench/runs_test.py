#!/usr/bin/env python3
"""ctest bench_runs (label "bench"): the bench's peak memory of a program is the program's own.
A parent holding 120 MB starts a child that touches 40 MB: the child's figure must be near 40 MB,
not the parent's 120 MB that wait4's ru_maxrss carries across exec."""
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench import runs  # noqa: E402

CHILD = "import time; b = bytearray(40 << 20); b[::4096] = b'x' * len(b[::4096]); time.sleep(0.3)"


def main():
    parent = bytearray(120 << 20)
    parent[::4096] = b"y" * len(parent[::4096])  # resident, not just reserved
    stats = {}
    runs.run([sys.executable, "-c", CHILD], stats=stats)
    peak = stats["peak_rss_mb"]
    print(f"bench_runs: child's peak {peak:.1f} MB (touched 40 MB; parent holds {len(parent) >> 20} MB)")
    if not 40.0 <= peak < 100.0:
        print("bench_runs: FAILED, the peak is not the child's own", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
