"""Cost of the core: instructions per scan and per back-end call (valgrind callgrind), static RAM
per profile (sizeof(Mapper<Profile>), printed by the footprint test) and heap allocations after
start-up (the counting allocator of tests/budget). Reuses tools/bench/callgrind_mapper.sh,
tests/budget's runners and test binary; each part is skipped, and says why, when its tool or
binary is missing."""
import glob
import os
import re
import shutil
import statistics
import tempfile

from bench.runs import RunError, command_text, run, say

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def footprint(ctx):
    if not ctx.bins.get("budget_tests"):
        return {"skipped": "tests/budget/dpcr_budget_tests not built (needs the host preset with tests)"}
    cmd = [ctx.bins["budget_tests"], "Each profile's core state fits its RAM budget"]
    _, text = run(cmd)
    profiles = {}
    for m in re.finditer(r"footprint: profile (\S+)\s+sizeof\(Mapper\) =\s*(\d+) bytes .* of budget (\d+) bytes", text):
        profiles[m.group(1)] = {"sizeof_mapper_bytes": int(m.group(2)), "budget_bytes": int(m.group(3))}
    return {"command": command_text(cmd, ctx.repo), "profiles": profiles}


# The assertions of tests/budget that hold an allocation count, and what each run is.
_ALLOCATION_RUNS = {
    "AllocationsDuringRun<dpcr::VacuumProfile>(600) == 0": "Mapper<vacuum>: 600 scans and their odometry after Init",
    "AllocationsDuringRun<dpcr::TinyProfile>(300) == 0": "Mapper<tiny>: 300 scans and their odometry after Init",
    "allocations == 0": "device pipeline (LD06 bytes, CAN wheel frames) into Mapper<vacuum>, after start-up",
}


def allocations(ctx):
    if not ctx.bins.get("budget_tests"):
        return {"skipped": "tests/budget/dpcr_budget_tests not built (needs the host preset with tests)"}
    cases = ["A full mapping run makes zero heap allocations",
             "The device pipeline into the mapper makes zero heap allocations after start-up"]
    cmd = [ctx.bins["budget_tests"], "-s", ",".join(cases)]  # Catch2: a comma between names is "or"
    try:
        _, text = run(cmd)
        passed = True
    except RunError as e:
        text, passed = str(e), False
    # Catch2 -s prints each assertion with its values: "REQUIRE( <expr> )\nwith expansion:\n  0 == 0".
    counts = []
    for m in re.finditer(r"(?:REQUIRE|CHECK)\( (.*?) \)\s*\nwith expansion:\s*\n\s*(\d+) == 0", text):
        if "llocation" in m.group(1):
            counts.append({"what": _ALLOCATION_RUNS.get(m.group(1), m.group(1)), "allocations": int(m.group(2))})
    passed = passed and len(counts) >= 2 and "No tests ran" not in text
    return {"command": command_text(cmd, ctx.repo), "passed": passed, "counts": counts}


def _callgrind_table(text):
    rows = [line for line in text.splitlines() if line.startswith("| ") and not line.startswith("| input")]
    if not rows:
        return None
    cells = [c.strip() for c in rows[-1].strip("|").split("|")]
    return {"input": cells[0], "scans_counted": int(cells[1]), "median_ir": int(cells[2]), "mean_ir": int(cells[3]),
            "p90_ir": int(cells[4]), "max_ir": int(cells[5])}


def per_scan_instructions(ctx):
    """Instructions per Mapper::AddScan, every 7th scan counted (tools/bench/callgrind_mapper.sh)."""
    if not shutil.which("valgrind"):
        return [{"skipped": "valgrind not installed (scripts/install-deps.sh --bench)"}]
    script = os.path.join(HERE, "callgrind_mapper.sh")
    jobs = [("apartment (vacuum profile)", [ctx.bins["bench"], "", "7", "0", "--world", "apartment",
                                            "--minutes", f"{ctx.callgrind_minutes:g}", "--seed", str(ctx.seed)])]
    intel = next((l["clf"] for l in ctx.logs if os.path.basename(l["clf"]) == "intel.clf"), None)
    if intel and ctx.callgrind_intel_scans > 0:
        jobs.append(("intel.clf (building profile)", [ctx.bins["bench"], intel, "7", str(ctx.callgrind_intel_scans)]))
    out = []
    for label, args in jobs:
        say(f"callgrind: instructions per scan, {label}")
        cmd = ["sh", script, *args]
        try:
            wall, text = run(cmd, env=dict(os.environ, DPCR_DATA_DIR=ctx.data_dir))
            row = _callgrind_table(text) or {"error": "no table in the output"}
        except RunError as e:
            row = {"error": str(e)}
        row.update({"label": label, "command": command_text(cmd, ctx.repo)})
        out.append(row)
    return out


def back_end_instructions(ctx):
    """Instructions of each AddScan call in which the back end worked (a graph job or a loop-closure
    search): tests/budget's back_end_cost_run (simulated apartment, 12 min) under callgrind."""
    if not shutil.which("valgrind"):
        return {"skipped": "valgrind not installed (scripts/install-deps.sh --bench)"}
    if not ctx.bins.get("back_end_cost_run"):
        return {"skipped": "tests/budget/dpcr_back_end_cost_run not built"}
    if not ctx.back_end_callgrind:
        return {"skipped": "not in --quick (about 10 min under callgrind on 2 cores); run the full bench"}
    say("callgrind: instructions per back-end call (apartment, 12 min)")
    with tempfile.TemporaryDirectory() as tmp:
        cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={tmp}/cg.%p", ctx.bins["back_end_cost_run"]]
        try:
            _, text = run(cmd)
        except RunError as e:
            return {"error": str(e), "command": command_text(cmd, ctx.repo)}
        totals = []
        for path in glob.glob(os.path.join(tmp, "cg.*.*")):
            with open(path) as f:
                for line in f:
                    if line.startswith("totals:"):
                        totals.append(int(line.split()[1]))
    values = dict(re.findall(r"^(\w+) (\d+)$", text, re.M))
    totals.sort()
    return {"command": command_text(["valgrind", "--tool=callgrind", ctx.bins["back_end_cost_run"]], ctx.repo),
            "scans": int(values.get("scans", 0)), "back_end_calls": len(totals),
            "optimizations": int(values.get("optimizations", 0)), "loop_searches": int(values.get("loop_searches", 0)),
            "median_ir": int(statistics.median(totals)) if totals else None, "max_ir": totals[-1] if totals else None,
            "total_ir": sum(totals)}


def armhf_note():
    return ("not measured: Debian's qemu-user runs armhf binaries but ships no instruction-counting TCG plugin "
            "(libinsn.so; building one needs qemu's plugin header, which no Debian 12 package installs), and wall "
            "time under qemu-user measures the emulator, not a Cortex-A7. The x86-64 counts above are the "
            "portable proxy; the armhf build and its tests run under qemu in CI (.ci/run).")
