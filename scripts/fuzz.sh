#!/usr/bin/env bash
# Builds the fuzz preset (clang, libFuzzer, ASan + UBSan) and runs every fuzz target of fuzz/ for
# N seconds each (default 30), from the generated seeds (dpcr-fuzz-seeds) and the checked-in ones
# (fuzz/seeds/<target>/). Fails on any crash, sanitizer report, leak, timeout (10 s per input) or
# out-of-memory; the input that did it is in build/fuzz/artifacts/<target>/ (reproduce:
# build/fuzz/fuzz/<target> FILE). What a run finds new is kept in build/fuzz/corpus/<target>/ for
# the next run. Runs as many targets at a time as there are cores (DPCR_FUZZ_JOBS=N overrides).
# Prints one line per target: runs, executions per second, corpus size, result.
# DPCR_FUZZ_SEED=N fixes libFuzzer's random seed (.ci/run sets it, so that CI explores the same
# way each time and does not fail at random on a new finding; unset or 0: a random seed).
# DPCR_FUZZ_RUNS=N runs each target for N executions instead of a time (the seconds are then
# ignored): DPCR_FUZZ_RUNS=10000000 bash scripts/fuzz.sh 0 fuzz_ld06 is a 10^7-execution campaign.
# Usage: bash scripts/fuzz.sh [seconds-per-target] [target...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
[ $# -gt 0 ] && shift
bash scripts/install-deps.sh --fuzz
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz

build=build/fuzz
if [ $# -gt 0 ]; then
  targets=("$@")
else
  targets=()
  for f in fuzz/fuzz_*.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi
rm -rf "$build/seeds"
"$build/fuzz/dpcr-fuzz-seeds" "$build/seeds" >/dev/null

# run_target T: fuzzes T for $seconds, writes its summary line to $build/logs/T.summary and
# returns non-zero on a finding.
run_target() {
  local t=$1
  mkdir -p "$build/corpus/$t" "$build/artifacts/$t" "$build/logs"
  local dirs=("$build/corpus/$t")
  for d in "$build/seeds/$t" "fuzz/seeds/$t"; do [ -d "$d" ] && dirs+=("$d"); done
  local log="$build/logs/$t.log" start status=0 result
  start=$(date +%s)
  "$build/fuzz/$t" "${budget[@]}" -seed="${DPCR_FUZZ_SEED:-0}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/$t/" "${dirs[@]}" >"$log" 2>&1 || status=$?
  local elapsed=$(( $(date +%s) - start ))
  local runs speed corpus
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  corpus=$(find "$build/corpus/$t" -type f | wc -l)
  if [ $status -eq 0 ]; then
    result=ok
  else
    result="FAILED (exit $status, log $log)"
    grep -m1 -E "ERROR: |FUZZ_CHECK|runtime error" "$log" >&2 || tail -5 "$log" >&2
  fi
  printf '%-24s %4ss %10s runs %7s exec/s %5s corpus  %s\n' "$t" "$elapsed" "${runs:-?}" "${speed:-?}" "$corpus" \
    "$result" > "$build/logs/$t.summary"
  return $status
}

# Each target's budget: a time, or a number of executions.
runs=${DPCR_FUZZ_RUNS:-0}
if [ "$runs" -gt 0 ]; then budget=(-runs="$runs"); label="$runs executions"; else budget=(-max_total_time="$seconds"); label="${seconds}s"; fi

# As many targets at a time as there are cores (DPCR_FUZZ_JOBS overrides): each is one process.
jobs=${DPCR_FUZZ_JOBS:-$(nproc)}
mkdir -p "$build/logs"
for t in "${targets[@]}"; do
  rm -f "$build/logs/$t.summary"
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  run_target "$t" &
done
wait || true

failed=()
summary=()
for t in "${targets[@]}"; do
  if [ -f "$build/logs/$t.summary" ]; then summary+=("$(cat "$build/logs/$t.summary")"); else summary+=("$t: no result"); fi
  case "${summary[-1]}" in *"  ok") ;; *) failed+=("$t") ;; esac
done

echo "== fuzz: ${label} per target"
printf '%s\n' "${summary[@]}"
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: ${#failed[@]} target(s) failed: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, no crash"
