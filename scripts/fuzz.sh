#!/usr/bin/env bash
# Builds the fuzz preset (clang, libFuzzer, ASan + UBSan) and runs every fuzz target of fuzz/ for
# N seconds each (default 30), from the generated seeds (dpcr-fuzz-seeds) and the checked-in ones
# (fuzz/seeds/<target>/). Fails on any crash, sanitizer report, leak, timeout (10 s per input) or
# out-of-memory; the input that did it is in build/fuzz/artifacts/<target>/ (reproduce:
# build/fuzz/fuzz/<target> FILE). What a run finds new is kept in build/fuzz/corpus/<target>/ for
# the next run. Prints one line per target: runs, executions per second, corpus size, result.
# DPCR_FUZZ_SEED=N fixes libFuzzer's random seed (.ci/run sets it, so that CI explores the same
# way each time and does not fail at random on a new finding; unset or 0: a random seed).
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

failed=()
summary=()
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t" "$build/artifacts/$t" "$build/logs"
  dirs=("$build/corpus/$t")
  for d in "$build/seeds/$t" "fuzz/seeds/$t"; do [ -d "$d" ] && dirs+=("$d"); done
  log="$build/logs/$t.log"
  start=$(date +%s)
  status=0
  "$build/fuzz/$t" -max_total_time="$seconds" -seed="${DPCR_FUZZ_SEED:-0}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/$t/" "${dirs[@]}" >"$log" 2>&1 || status=$?
  elapsed=$(( $(date +%s) - start ))
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  corpus=$(find "$build/corpus/$t" -type f | wc -l)
  if [ $status -eq 0 ]; then
    result=ok
  else
    result="FAILED (exit $status, log $log)"
    failed+=("$t")
    grep -m1 -E "ERROR: |FUZZ_CHECK|runtime error" "$log" >&2 || tail -5 "$log" >&2
  fi
  summary+=("$(printf '%-24s %4ss %10s runs %7s exec/s %5s corpus  %s' "$t" "$elapsed" "${runs:-?}" "${speed:-?}" "$corpus" "$result")")
done

echo "== fuzz: ${seconds}s per target"
printf '%s\n' "${summary[@]}"
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: ${#failed[@]} target(s) failed: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, no crash"
