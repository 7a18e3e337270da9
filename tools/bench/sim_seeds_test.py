#!/usr/bin/env python3
"""sim_seeds.py on two short dpcr-sim runs: the summary's figures (the rigid-aligned mean too) are the runs' own, a threshold
below every run counts every run as failed, and a dpcr-sim that fails is reported, not averaged."""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "sim_seeds.py")


def run(*args):
    return subprocess.run([sys.executable, SCRIPT] + list(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          text=True)


def main():
    sim = sys.argv[1]
    with tempfile.TemporaryDirectory() as out:
        done = run("--sim", sim, "--first", "3", "--last", "4", "--out", out, "--json", "--fail-above", "0",
                   "--", "--minutes", "0.3")
        assert done.returncode == 0, done.stderr
        s = json.loads(done.stdout)
        errors, rigid = [], []
        for seed in (3, 4):
            with open(os.path.join(out, "s%d" % seed, "metrics.json")) as f:
                accuracy = json.load(f)["accuracy"]
            errors.append(accuracy["loc_err_ave_m"])
            rigid.append(accuracy["rigid_loc_err_ave_m"])
        assert s["runs"] == 2, s
        assert abs(s["mean_m"] - sum(errors) / 2) < 1e-12, (s, errors)
        assert abs(s["worst_m"] - max(errors)) < 1e-12, (s, errors)
        assert abs(s["rigid_mean_m"] - sum(rigid) / 2) < 1e-12, (s, rigid)
        assert s["failed"] == 2 and s["failed_seeds"] == [3, 4], s
    bad = run("--sim", sim, "--first", "1", "--last", "1", "--", "--no-such-option")
    assert bad.returncode == 1 and "seed 1: dpcr-sim exited" in bad.stderr, (bad.returncode, bad.stderr)
    print("sim_seeds.py: ok")


if __name__ == "__main__":
    main()
