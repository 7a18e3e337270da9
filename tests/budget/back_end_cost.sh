#!/bin/sh
# Worst-scan instruction budget (ctest label "budget"): runs dpcr_back_end_cost_run under
# callgrind, which dumps one profile per AddScan call in which the back end worked or the robot
# was lost (relocalisation after kidnaps); the largest
# total is the worst single AddScan, compared with the vacuum profile's kBudgetWorstScanInstr.
# The run must have exercised the back end (optimisations and loop closures), or the test fails.
# Usage: back_end_cost.sh VALGRIND RUNNER
set -eu
VALGRIND=$1; RUNNER=$2
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
"$VALGRIND" --tool=callgrind --callgrind-out-file="$OUT/cg.%p" "$RUNNER" > "$OUT/log" 2> "$OUT/err" || { cat "$OUT/err"; exit 2; }
cat "$OUT/log"
value() { awk -v k="$1" '$1 == k {print $2}' "$OUT/log"; }
BUDGET=$(awk '$1 == "budget" && $2 == "worst_scan" {print $3}' "$OUT/log")
# Each dump's "totals:" line is the instructions of one AddScan call.
WORST=$(cat "$OUT"/cg.*.* 2>/dev/null | awk '$1 == "totals:" {if ($2 > m) m = $2} END {print m + 0}')
DUMPS=$(ls "$OUT"/cg.*.* 2>/dev/null | wc -l)
echo "dumps $DUMPS worst_scan_Ir $WORST budget $BUDGET"
[ "$(value optimizations)" -gt 0 ] || { echo "FAIL: no optimisation ran"; exit 1; }
[ "$(value loop_closures_accepted)" -gt 0 ] || { echo "FAIL: no loop closure was accepted"; exit 1; }
[ "$(value relocalisations)" -gt 0 ] || { echo "FAIL: no relocalisation after the kidnaps"; exit 1; }
[ "$DUMPS" -gt 0 ] || { echo "FAIL: no per-scan dump"; exit 1; }
[ "$WORST" -le "$BUDGET" ] || { echo "FAIL: worst AddScan over budget"; exit 1; }
echo "ok"
