"""Many seeds: LocErr_ave of dpcr-sim over a range of seeds for each lidar and odometry a robot may
have (the simulated LD06 and XV-11; wheels, a gyro alone, heading-only ticks, nothing) on the
apartment and the office. One run of a seed is one cleaning plan and one draw of the noise: a mean
over seeds says what a setting does, and the runs over 0.2 m say how often it loses the map.
Uses tools/bench/sim_seeds.py's run and summary."""
import os

import sim_seeds
from bench.runs import command_text, say

# (what the robot has, dpcr-sim's options); every set on seeds 1..ctx.seed_sets_last.
SETS = [
    ("apartment: LD06, wheels", ["--world", "apartment"]),
    ("apartment: XV-11, wheels and gyro", ["--world", "apartment", "--lidar", "xv11"]),
    ("apartment: XV-11, gyro alone", ["--world", "apartment", "--lidar", "xv11", "--odometry", "gyro"]),
    ("apartment: XV-11, heading-only ticks", ["--world", "apartment", "--lidar", "xv11", "--odometry", "heading-ticks"]),
    ("apartment: XV-11, nothing", ["--world", "apartment", "--lidar", "xv11", "--odometry", "none"]),
    ("office: LD06, wheels", ["--world", "office"]),
    ("office: XV-11, wheels and gyro, 15 min", ["--world", "office", "--lidar", "xv11", "--minutes", "15"]),
    ("office: XV-11, gyro alone, 15 min", ["--world", "office", "--lidar", "xv11", "--odometry", "gyro", "--minutes", "15"]),
]
FAIL_ABOVE_M = 0.2


def seed_sets(ctx):
    """Each of SETS over seeds 1..ctx.seed_sets_last, as many runs at once as there are cores; its sim_seeds summary."""
    first, last = 1, ctx.seed_sets_last
    rows = []
    for name, args in SETS:
        say(f"{name}, seeds {first}-{last}")
        out_dir = os.path.join(ctx.out, "seeds", name.replace(":", "").replace(",", "").replace(" ", "_"))
        done = sim_seeds.run_seeds(ctx.bins["sim"], range(first, last + 1), out_dir, args, os.cpu_count() or 1)
        problems = [f"seed {seed}: {why}" for seed, _, why in done if why is not None]
        command = command_text(["tools/bench/sim_seeds.py", "--first", str(first), "--last", str(last), "--", *args], ctx.repo)
        row = {"setting": name, "command": command, "first": first, "last": last}
        if problems:
            row["error"] = "; ".join(problems)[:300]
        else:
            row.update(sim_seeds.summarise([(seed, m) for seed, m, _ in done], FAIL_ABOVE_M))
        rows.append(row)
    return {"fail_above_m": FAIL_ABOVE_M, "rows": rows}
