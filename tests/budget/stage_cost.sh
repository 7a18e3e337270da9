#!/bin/sh
# Per-stage instruction budgets (ctest label "budget"): runs dpcr_stage_cost_run under callgrind,
# sums each stage's inclusive instructions (stage functions are DPCR_STAGE, never inlined),
# divides by the scans and compares with the profile's budgets (core/capacity.hpp).
# Usage: stage_cost.sh VALGRIND CALLGRIND_ANNOTATE RUNNER PROFILE [CLF]
# Exit: 0 within budget, 1 over budget, 77 skipped (no log), 2 error.
set -eu
VALGRIND=$1; ANNOTATE=$2; RUNNER=$3; PROFILE=$4; CLF=${5:-}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
set +e
"$VALGRIND" --tool=callgrind --callgrind-out-file="$OUT/cg" "$RUNNER" "$PROFILE" $CLF > "$OUT/log" 2> "$OUT/err"
RC=$?
set -e
cat "$OUT/log"
[ "$RC" -eq 77 ] && exit 77
[ "$RC" -ne 0 ] && { cat "$OUT/err"; exit 2; }
"$ANNOTATE" --inclusive=yes --threshold=100 "$OUT/cg" > "$OUT/annotate"
# Inclusive Ir of a function (first line naming it), 0 if callgrind never saw it.
incl() { grep -F "$1" "$OUT/annotate" | head -n 1 | awk '{gsub(",", "", $1); v = $1} END {print v + 0}'; }
stage() {
  case $1 in
    prediction) echo $(( $(incl 'dpcr::FrontEnd::Predict(') + $(incl 'dpcr::ProjectScan(') )) ;;
    first_registration) incl 'dpcr::FrontEnd::RegisterScan(' ;;
    second_registration) incl 'dpcr::FrontEnd::RegisterSubmap(' ;;
    insertion) echo $(( $(incl 'dpcr::Submap::Add(') + $(incl 'dpcr::RegionSet::InsertScan(') + \
                        $(incl 'dpcr::RegionSet::SeedFromSubmap(') )) ;;
    line_extraction) echo $(( $(incl 'dpcr::RegistrationReference::Build(') + $(incl 'dpcr::FrontEnd::BuildRegionReference(') + \
                              $(incl 'dpcr::FrontEnd::RefitSubmapLines(') )) ;;
  esac
}
SCANS=$(awk '$1 == "scans" {print $2}' "$OUT/log")
FAIL=0
printf '%-20s %14s %14s\n' stage "Ir/scan" "budget/scan"
for S in prediction first_registration second_registration insertion line_extraction; do
  BUDGET=$(awk -v s="$S" '$1 == "budget" && $2 == s {print $3}' "$OUT/log")
  TOTAL=$(stage "$S")
  PER=$((TOTAL / SCANS))
  VERDICT=ok
  if [ "$TOTAL" -eq 0 ]; then VERDICT="NOT SEEN (stage function renamed or inlined?)"; FAIL=1; fi
  if [ "$PER" -gt "$BUDGET" ]; then VERDICT="OVER BUDGET"; FAIL=1; fi
  printf '%-20s %14d %14d  %s\n' "$S" "$PER" "$BUDGET" "$VERDICT"
done
exit $FAIL
