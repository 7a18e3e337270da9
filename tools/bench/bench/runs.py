"""Running the apps: one command, its wall time, and medians over repetitions."""
import math
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time


class RunError(RuntimeError):
    pass


def rel(path, repo):
    """A path as written into results and docs: relative to the repository (no machine paths)."""
    path = os.path.abspath(path)
    try:
        r = os.path.relpath(path, repo)
    except ValueError:
        return os.path.basename(path)
    return r if not r.startswith("../../") else os.path.basename(path)


def _quote(arg):
    if arg and all(c.isalnum() or c in "@%+=:,./-_" for c in arg):
        return arg
    if "'" in arg and not any(c in arg for c in '"$`\\'):
        return '"' + arg + '"'
    return shlex.quote(arg)


def command_text(cmd, repo):
    """The command line as a reader would type it from the repository root."""
    out = []
    for a in cmd:
        a = str(a)
        if os.path.isabs(a):
            a = rel(a, repo)
        out.append(_quote(a))
    return " ".join(out)


def _high_water_kb(pid):
    """The process's peak resident memory so far (VmHWM, KiB), or None once it has exited."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except (OSError, ValueError):
        pass
    return None


def run(cmd, log_path=None, env=None, timeout=None, stats=None):
    """Runs cmd; returns (wall seconds, stdout + stderr). Raises RunError with the tail of the
    output on failure. With a dict `stats`, also stores the child's peak RSS (peak_rss_mb).
    The peak is the program's own VmHWM, read while it runs: wait4's ru_maxrss would not do, as
    it keeps the high-water mark of the memory the child had before exec, a copy of this Python
    process (60 MB once the bench has loaded its results), larger than dpcr-replay's own."""
    with tempfile.TemporaryFile("w+") as out:
        start = time.monotonic()
        p = subprocess.Popen([str(c) for c in cmd], stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                             env=env, text=True)
        high_water_kb = None
        while True:
            hw = _high_water_kb(p.pid)
            if hw is not None:
                high_water_kb = hw if high_water_kb is None else max(high_water_kb, hw)
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid != 0:
                break
            if timeout is not None and time.monotonic() - start > timeout:
                p.kill()
                os.wait4(p.pid, 0)
                raise RunError(f"{os.path.basename(str(cmd[0]))}: no result after {timeout:.0f} s, stopped")
            time.sleep(0.005)
        wall = time.monotonic() - start
        p.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        text = out.read()
    if stats is not None:
        # A program that ended before the first read (a few ms): wait4's figure, an upper bound.
        stats["peak_rss_mb"] = (high_water_kb if high_water_kb is not None else usage.ru_maxrss) / 1024.0  # KiB
    if log_path:
        with open(log_path, "w") as f:
            f.write("$ " + " ".join(str(c) for c in cmd) + "\n" + text)
    if p.returncode != 0:
        tail = "\n".join(text.strip().splitlines()[-5:])
        raise RunError(f"{os.path.basename(str(cmd[0]))} exited {p.returncode}: {tail}")
    return wall, text


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def percentile(sorted_values, q):
    """Nearest-rank percentile of an ascending list (q in 0..1)."""
    if not sorted_values:
        return None
    k = max(0, min(len(sorted_values) - 1, math.ceil(q * len(sorted_values)) - 1))
    return sorted_values[k]


def scan_time_stats(path):
    """Per-scan AddScan times (ms) from an app's --scan-times file."""
    with open(path) as f:
        ms = sorted(float(line) for line in f if line.strip())
    return {
        "scans": len(ms),
        "mean_ms": sum(ms) / len(ms) if ms else None,
        "p50_ms": percentile(ms, 0.50),
        "p90_ms": percentile(ms, 0.90),
        "p99_ms": percentile(ms, 0.99),
        "max_ms": ms[-1] if ms else None,
        "total_s": sum(ms) / 1000.0,
    }


def say(text):
    print(f"bench: {text}", file=sys.stderr, flush=True)
