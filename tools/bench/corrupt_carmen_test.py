#!/usr/bin/env python3
"""corrupt_carmen.py on a made-up log of three scans: nothing asked, nothing changed; each fault
does what it says; the same seed gives the same file."""
import math
import os
import subprocess
import sys
import tempfile

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corrupt_carmen.py")

LOG = """# a made-up log
PARAM robot_frontlaser_offset 0.2 nohost 0
ODOM 0.000000 0.000000 0.000000 0 0 0 100.0 nohost 100.0
FLASER 4 1.00 2.00 81.91 3.00 0.200000 0.000000 0.000000 0.000000 0.000000 0.000000 100.1 nohost 100.1
ODOM 1.000000 0.000000 0.000000 0 0 0 101.0 nohost 101.0
FLASER 4 1.10 2.10 81.91 3.10 1.200000 0.000000 1.570796 1.000000 0.000000 1.570796 101.1 nohost 101.1
FLASER 4 1.20 2.20 0.00 3.20 1.200000 1.200000 1.570796 1.200000 1.000000 1.570796 102.1 nohost 102.1
"""


def corrupt(tmp, name, *options):
    src = os.path.join(tmp, "in.clf")
    out = os.path.join(tmp, name + ".clf")
    subprocess.run([sys.executable, TOOL, src, out] + list(options), check=True, stdout=subprocess.DEVNULL)
    with open(out) as f:
        return f.read()


def scans(text):
    rows = []
    for line in text.splitlines():
        f = line.split()
        if f and f[0] == "FLASER":
            n = int(f[1])
            rows.append(([float(v) for v in f[2:2 + n]], [float(v) for v in f[2 + n:8 + n]]))
    return rows


def check(cond, what):
    if not cond:
        sys.exit("FAIL: " + what)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "in.clf"), "w") as f:
            f.write(LOG)
        check(corrupt(tmp, "none") == LOG, "with no fault asked the log is copied as it is")

        # Every return lost; "no return" readings (0, the far end) stay.
        for ranges, _ in scans(corrupt(tmp, "dropout", "--dropout", "1")):
            check(ranges[0] == 0.0 and ranges[1] == 0.0 and ranges[3] == 0.0, "--dropout 1 loses every return")
        check(scans(corrupt(tmp, "dropout", "--dropout", "1"))[0][0][2] == 81.91, "a no-return reading stays")

        scaled = scans(corrupt(tmp, "scale", "--range-scale", "1.5"))
        check(abs(scaled[0][0][0] - 1.5) < 1e-9 and scaled[0][0][2] == 81.91, "--range-scale scales returns only")

        a = corrupt(tmp, "noise_a", "--range-noise", "0.05", "0", "--seed", "3")
        b = corrupt(tmp, "noise_b", "--range-noise", "0.05", "0", "--seed", "3")
        c = corrupt(tmp, "noise_c", "--range-noise", "0.05", "0", "--seed", "4")
        check(a == b and a != c, "the same seed gives the same file, another seed another")
        check(scans(a)[0][0] != scans(LOG)[0][0], "--range-noise moves the returns")

        # Odometry steps twice as long: the robot's path doubles, turns stay; the laser pose keeps
        # its 0.2 m mount ahead of the robot.
        doubled = scans(corrupt(tmp, "odom", "--odom-scale", "2", "1"))
        _, last = doubled[-1]
        lx, ly, lt, x, y, t = last
        check(abs(x - 2.4) < 1e-5 and abs(y - 2.0) < 1e-5 and abs(t - math.pi / 2) < 1e-5,
              "--odom-scale 2 1 doubles every step (got %.3f %.3f %.3f)" % (x, y, t))
        check(abs(lx - x) < 1e-5 and abs(ly - (y + 0.2)) < 1e-5 and abs(lt - t) < 1e-5, "the laser pose keeps its mount")
        turned = scans(corrupt(tmp, "turn", "--odom-scale", "1", "0.5"))
        check(abs(turned[-1][1][5] - math.pi / 4) < 1e-5, "--odom-scale 1 0.5 halves the turns")

        bad = os.path.join(tmp, "bad.clf")
        with open(bad, "w") as f:
            f.write("FLASER 4 1.0 x\n")
        done = subprocess.run([sys.executable, TOOL, bad, os.path.join(tmp, "o.clf")], capture_output=True, text=True)
        check(done.returncode != 0 and "bad.clf:1" in done.stderr, "a bad line is named with its line number")
    print("corrupt_carmen: all checks passed")


if __name__ == "__main__":
    main()
