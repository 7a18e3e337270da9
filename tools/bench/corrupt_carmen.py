#!/usr/bin/env python3
"""Write a CARMEN log with the faults of a worse robot: range noise, lost returns, a range scale,
and odometry with calibration errors, a heading drift or random slips.

A public log comes from one robot with one lidar and one odometry. The logs the project is scored
on, and the robots it ships on, have others: an odometry whose wheel radius is off by a few per
cent, a lidar with centimetres of noise, returns lost on glass. This turns one log into those, so
a replay shows what each fault costs (its relations file still holds: the timestamps and the
robot's true path are unchanged).

  tools/bench/corrupt_carmen.py ../shared/data/intel.clf /tmp/intel-odom5.clf --odom-scale 1.05 1
  build/host/host_sim/apps/dpcr-replay --carmen /tmp/intel-odom5.clf \\
      --relations ../shared/data/intel.relations --out /tmp/odom5

Reads FLASER and ODOM lines (other lines are copied as they are). The odometry of both kinds of
line is one sequence in file order: each step between two readings is turned into the robot's
frame, corrupted, and integrated again from the first reading. In FLASER lines the laser pose
fields move with the odometry by the same step (they are the robot's pose plus the mount). The
same seed gives the same file.
"""
import argparse
import math
import random
import sys


def wrap(a):
    return (a + math.pi) % (2.0 * math.pi) - math.pi


class OdometryCorruption:
    """Re-integrates odometry steps with a scale error, a heading drift and random slips."""

    def __init__(self, args, rng):
        self.trans_scale, self.rot_scale = args.odom_scale
        self.drift_rad_per_m = math.radians(args.odom_heading_drift)
        self.slip = args.odom_slip
        self.rng = rng
        self.last_logged = None
        self.estimate = None

    def active(self):
        return (self.trans_scale, self.rot_scale) != (1.0, 1.0) or self.drift_rad_per_m != 0.0 or self.slip > 0.0

    def next(self, pose):
        if self.last_logged is None:
            self.last_logged = pose
            self.estimate = pose
            return pose
        x0, y0, t0 = self.last_logged
        dx, dy = pose[0] - x0, pose[1] - y0
        c, s = math.cos(t0), math.sin(t0)
        fx, fy, dt = c * dx + s * dy, -s * dx + c * dy, wrap(pose[2] - t0)
        self.last_logged = pose
        d = math.hypot(fx, fy)
        fx, fy, dt = fx * self.trans_scale, fy * self.trans_scale, dt * self.rot_scale + self.drift_rad_per_m * d
        if self.slip > 0.0:
            fx += self.rng.gauss(0.0, self.slip * d)
            fy += self.rng.gauss(0.0, self.slip * d)
            dt += self.rng.gauss(0.0, self.slip * (abs(dt) + d))
        ex, ey, et = self.estimate
        c, s = math.cos(et), math.sin(et)
        self.estimate = (ex + c * fx - s * fy, ey + s * fx + c * fy, wrap(et + dt))
        return self.estimate


def corrupt_ranges(ranges, args, rng):
    out = []
    for text in ranges:
        r = float(text)
        # A reading at 0 or at the sensor's far end is "no return": left alone.
        if 0.0 < r < args.no_return_from:
            if rng.random() < args.dropout:
                out.append("0.000")
                continue
            sigma = args.range_noise[0] + args.range_noise[1] * r * args.range_scale
            if args.range_scale == 1.0 and sigma == 0.0:
                out.append(text)  # untouched: as logged
                continue
            r *= args.range_scale
            if sigma > 0.0:
                r = max(0.001, r + rng.gauss(0.0, sigma))
            out.append("%.3f" % r)
        else:
            out.append(text)
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("log", help="CARMEN log to read")
    p.add_argument("out", help="CARMEN log to write")
    p.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    p.add_argument("--range-noise", type=float, nargs=2, default=(0.0, 0.0), metavar=("BASE", "FRACTION"),
                   help="add Gaussian range noise, sigma = BASE + FRACTION x range (m)")
    p.add_argument("--range-scale", type=float, default=1.0, help="multiply every return by this")
    p.add_argument("--dropout", type=float, default=0.0, help="share of returns lost (written as 0)")
    p.add_argument("--no-return-from", type=float, default=80.0,
                   help="readings at or beyond this are no return and stay as they are (m, default 80)")
    p.add_argument("--odom-scale", type=float, nargs=2, default=(1.0, 1.0), metavar=("TRANSLATION", "ROTATION"),
                   help="scale the odometry's steps (a wheel radius or track width off)")
    p.add_argument("--odom-heading-drift", type=float, default=0.0, help="odometry heading drift (degrees per metre driven)")
    p.add_argument("--odom-slip", type=float, default=0.0,
                   help="random odometry error per step, sigma as a share of the step (translation, and turn plus translation)")
    args = p.parse_args()
    if not 0.0 <= args.dropout <= 1.0:
        p.error("--dropout must be in [0, 1]")
    rng = random.Random(args.seed)
    odometry = OdometryCorruption(args, rng)
    lines = 0
    with open(args.log) as src, open(args.out, "w") as dst:
        for lineno, line in enumerate(src, 1):
            f = line.split()
            if not f or f[0] not in ("FLASER", "ODOM"):
                dst.write(line)
                continue
            try:
                if f[0] == "ODOM":
                    if odometry.active():
                        x, y, t = odometry.next((float(f[1]), float(f[2]), float(f[3])))
                        f[1:4] = ["%.6f" % x, "%.6f" % y, "%.6f" % t]
                else:
                    n = int(f[1])
                    f[2:2 + n] = corrupt_ranges(f[2:2 + n], args, rng)
                    if odometry.active():
                        laser = [float(v) for v in f[2 + n:5 + n]]
                        logged = [float(v) for v in f[5 + n:8 + n]]
                        x, y, t = odometry.next(tuple(logged))
                        # The laser pose keeps its offset from the robot's, in the robot's frame.
                        c, s = math.cos(logged[2]), math.sin(logged[2])
                        ox, oy = laser[0] - logged[0], laser[1] - logged[1]
                        mx, my, mt = c * ox + s * oy, -s * ox + c * oy, wrap(laser[2] - logged[2])
                        c, s = math.cos(t), math.sin(t)
                        f[2 + n:8 + n] = ["%.6f" % v for v in (x + c * mx - s * my, y + s * mx + c * my, wrap(t + mt), x, y, t)]
            except (ValueError, IndexError) as e:
                sys.exit("%s:%d: cannot read this %s line (%s)" % (args.log, lineno, f[0], e))
            dst.write(" ".join(f) + "\n")
            lines += 1
    print("%s: %d FLASER/ODOM lines written" % (args.out, lines))


if __name__ == "__main__":
    main()
