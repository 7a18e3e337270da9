#!/bin/sh
# Instructions per scan -> submap registration (450-beam simulated scans, perturbed starts), for
# both methods, and per reference build (obstacle cells, lines, distance transform; "build"): the
# bench toggles callgrind collection around each call and dumps the counts after it; this script
# takes the median over the dumps. The last column is iterations, or lines for "build".
# Usage: tools/bench/callgrind_registration.sh [path/to/dpcr-bench] [registrations per method]
set -eu
BENCH=${1:-build/host/tools/bench/dpcr-bench}
COUNT=${2:-60}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "| method | calls | median instructions | p90 instructions | median iterations (build: lines) |"
echo "|---|---|---|---|---|"
for METHOD in improved classic build; do
  N_CALLS=$COUNT
  [ "$METHOD" = build ] && N_CALLS=$((COUNT < 36 ? COUNT : 36))  # 36 simulated submaps
  valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file="$OUT/$METHOD.%p" \
    "$BENCH" registration --callgrind "$N_CALLS" --method "$METHOD" > "$OUT/$METHOD.log" 2> "$OUT/$METHOD.err"
  # One dump file per registration (callgrind appends .N); the "totals:" line is its Ir count.
  grep -h '^totals:' "$OUT"/"$METHOD".*.[0-9]* | awk '{print $2}' | sort -n > "$OUT/$METHOD.ir"
  N=$(wc -l < "$OUT/$METHOD.ir")
  MED=$(awk -v n="$N" 'NR == int((n + 1) / 2) {print}' "$OUT/$METHOD.ir")
  P90=$(awk -v n="$N" 'NR == int(0.9 * n + 0.5) {print}' "$OUT/$METHOD.ir")
  IT=$(awk '{print $6}' "$OUT/$METHOD.log" | sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
  echo "| $METHOD | $N | $MED | $P90 | $IT |"
done
