#!/bin/sh
# Instructions per Mapper::AddScan on a CARMEN log (default intel.clf, all 13631 scans) or a
# simulated run (bench options --world apartment --minutes 5): the bench toggles callgrind
# collection around every k-th AddScan and dumps the count after it; this script prints the
# median, p90 and max over the dumps (docs/front-end-cost.md).
# Usage: tools/bench/callgrind_mapper.sh [path/to/dpcr-bench] [clf ("": $DPCR_DATA_DIR/intel.clf)] [stride k] [scans (0: all)] [bench options...]
# (bench options, e.g. --k1 20 or --world apartment, are passed to `dpcr-bench mapper`).
set -eu
BENCH=${1:-build/host/tools/bench/dpcr-bench}
DATA=${DPCR_DATA_DIR:-$(dirname "$0")/../../../shared/data}  # as tools/public_logs.hpp
CLF=${2:-$DATA/intel.clf}
STRIDE=${3:-7}  # coprime with K1, Ks, K2: counted scans are not in step with the schedule
SCANS=${4:-0}
[ $# -ge 4 ] && shift 4 || shift $#
LABEL=$(basename "$CLF")
PREV=
for A in "$@"; do
  [ "$PREV" = "--world" ] && LABEL="world $A"
  PREV=$A
done
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
valgrind --tool=callgrind --collect-atstart=no --dump-instr=no --callgrind-out-file="$OUT/cg.%p" \
  "$BENCH" mapper --clf "$CLF" --scans "$SCANS" --callgrind-stride "$STRIDE" "$@" > "$OUT/log" 2> "$OUT/err" ||
  { RC=$?; grep -v '^==' "$OUT/err" >&2; exit "$RC"; }  # e.g. the log is missing (77)
# One dump file per counted scan (callgrind appends .N); its "totals:" line is the Ir count.
grep -h '^totals:' "$OUT"/cg.*.[0-9]* | awk '{print $2}' | sort -n > "$OUT/ir"
N=$(wc -l < "$OUT/ir")
MED=$(awk -v n="$N" 'NR == int((n + 1) / 2) {print}' "$OUT/ir")
P90=$(awk -v n="$N" 'NR == int(0.9 * n + 0.5) {print}' "$OUT/ir")
MAX=$(tail -n 1 "$OUT/ir")
MEAN=$(awk '{s += $1} END {printf "%.0f", s / NR}' "$OUT/ir")
echo "| input | scans counted (every ${STRIDE}th) | median Ir/scan | mean | p90 | max |"
echo "|---|---|---|---|---|---|"
echo "| $LABEL | $N | $MED | $MEAN | $P90 | $MAX |"
