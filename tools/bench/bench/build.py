"""The binaries the runner needs, built with the host preset (build/host) unless --build-dir names
an existing build."""
import os
import subprocess

from bench.runs import say

TARGETS = {
    "sim": "host_sim/apps/dpcr-sim",
    "replay": "host_sim/apps/dpcr-replay",
    "map": "tools/map/dpcr-map",
    "bench": "tools/bench/dpcr-bench",
    "eval": "tools/dpcr-eval",
    "budget_tests": "tests/budget/dpcr_budget_tests",
    "back_end_cost_run": "tests/budget/dpcr_back_end_cost_run",
}
OPTIONAL = {"budget_tests", "back_end_cost_run"}  # test binaries: absent when tests are off


def _target(path):
    return os.path.basename(path)


def ensure(repo, build_dir, no_build):
    """Returns {name: absolute path or None}. Builds (cmake presets, -j2) unless no_build."""
    if not no_build:
        if not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
            if os.path.realpath(build_dir) != os.path.realpath(os.path.join(repo, "build", "host")):
                raise SystemExit(f"bench: {build_dir} is not a configured build (configure it, or leave out --build-dir)")
            say("configuring: cmake --preset host")
            subprocess.run(["cmake", "--preset", "host"], cwd=repo, check=True, stdout=subprocess.DEVNULL)
        targets = [_target(p) for p in TARGETS.values()]
        say("building: cmake --build " + os.path.relpath(build_dir, repo) + " -j2 --target " + " ".join(targets))
        p = subprocess.run(["cmake", "--build", build_dir, "-j2", "--target", *targets], cwd=repo,
                           capture_output=True, text=True)
        if p.returncode != 0:
            # The test binaries need Catch2 and DPCR_ALLOCATION_TESTS; build the apps alone then.
            apps = [_target(p) for n, p in TARGETS.items() if n not in OPTIONAL]
            subprocess.run(["cmake", "--build", build_dir, "-j2", "--target", *apps], cwd=repo, check=True,
                           stdout=subprocess.DEVNULL)
    found = {}
    for name, path in TARGETS.items():
        full = os.path.join(build_dir, path)
        found[name] = full if os.access(full, os.X_OK) else None
        if found[name] is None and name not in OPTIONAL:
            raise SystemExit(f"bench: {path} not built in {build_dir} (run without --no-build)")
    return found
