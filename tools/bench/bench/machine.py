"""What machine, commit and date a run's figures come from (every figure in RESULTS.md names them)."""
import datetime
import os
import platform
import subprocess


def _cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def _git(repo, *args):
    try:
        return subprocess.run(["git", "-C", repo, *args], capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def describe(repo):
    load1, load5, _ = os.getloadavg()
    dirty = _git(repo, "status", "--porcelain", "--untracked-files=no")
    return {
        "date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "nproc": os.cpu_count(),
        "cpu_model": _cpu_model(),
        "kernel": platform.release(),
        "load_average_at_start": [round(load1, 2), round(load5, 2)],
        "commit": _git(repo, "rev-parse", "--short=10", "HEAD") + ("+changes" if dirty not in ("", "unknown") else ""),
        "branch": _git(repo, "rev-parse", "--abbrev-ref", "HEAD"),
    }
