#!/bin/sh
# intel.clf replayed under two small perturbations (a range limit and a region width) that once
# sent it metres off, for reasons in the log's own recording, not in the perturbation:
# - range 21 m, regions 3.8 m: the robot stops after a burst of records stamped 1 ms apart; the
#   odometry, extrapolated at the burst's 35 m/s, predicted it 2.6 m down a corridor, a look-alike
#   place took it there, and the last 300 s of the log were 2.1 m off (0.155 m all pairs).
# - range 20 m, regions 4.2 m: the front end's pose jumped 0.3-0.5 m whenever the back end moved
#   its region, the wheel check counted each jump as motion the wheels had missed, set the wheels
#   aside after three in a row with the robot standing, and the robot was lost for 690 s (0.61 m).
# Each draw must keep the wheels (their translation never switched off: they are right) and stay
# under 0.05 m on all pairs (0.02-0.03 m today; tools/bench/log_perturbations.sh runs 64 draws).
# Skips (77) when the log is not there.
# Usage: public_log_draws.sh DPCR_REPLAY DEFAULT_DATA_DIR   ($DPCR_DATA_DIR overrides the second)
set -eu
REPLAY=$1
DATA=${DPCR_DATA_DIR:-$2}
LOG=$DATA/intel.clf
RELATIONS=$DATA/intel.relations
if [ ! -f "$LOG" ] || [ ! -f "$RELATIONS" ]; then
  echo "SKIP: $LOG or $RELATIONS not found (set DPCR_DATA_DIR)"
  exit 77
fi
T=$(mktemp -d "${TMPDIR:-/tmp}/dpcr_public_log_draws_XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

for DRAW in "21 3.8" "20 4.2"; do
  set -- $DRAW
  OUT="$T/range$1-width$2"
  "$REPLAY" --carmen "$LOG" --relations "$RELATIONS" --max-range "$1" --region-width "$2" --out "$OUT" > "$OUT.txt" 2>&1 ||
    { cat "$OUT.txt" >&2; fail "dpcr-replay --max-range $1 --region-width $2"; }
  cat "$OUT.txt"
  E=$(sed -n 's/.*relations \([0-9.]*\) +- .*/\1/p' "$OUT.txt")
  [ -n "$E" ] || fail "no relations figure in the replay's summary"
  grep -q '"translation_switched_off": 0' "$OUT/metrics.json" || fail "range $1 m, regions $2 m: the wheels were set aside"
  awk -v e="$E" 'BEGIN { exit !(e <= 0.05) }' || fail "range $1 m, regions $2 m: all pairs $E m, bound 0.05 m"
  echo "range $1 m, regions $2 m: all pairs $E m (bound 0.05 m), wheels kept: ok"
done
