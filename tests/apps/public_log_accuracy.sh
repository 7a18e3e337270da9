#!/bin/sh
# intel.clf replayed whole, scored on its ground-truth relations: a regression guard on the mapper's
# accuracy on a real building (docs/back-end.md). Skips (77) when the log is not there.
# Usage: public_log_accuracy.sh DPCR_REPLAY DEFAULT_DATA_DIR [draws | closures | guess]   ($DPCR_DATA_DIR overrides the second)
#
# Without a mode: the default replay. The bound sits between today's figure (0.021 m on all pairs)
# and the 0.030 m of the build before submap clouds were registered about their centroid, so that
# change undone fails here.
#
# With "draws": intel.clf under two small perturbations (a range limit and a region width) that once
# sent it metres off, for reasons in the log's own recording, not in the perturbation
# (docs/back-end.md, "Intel's bad draws were two recording faults"):
# - range 21 m, regions 3.8 m: the robot stops after a burst of records stamped 1 ms apart; the
#   odometry, extrapolated at the burst's 35 m/s, predicted it 2.6 m down a corridor, a look-alike
#   place took it there, and the last 300 s of the log were 2.1 m off (0.155 m all pairs).
# - range 20 m, regions 4.2 m: the front end's pose jumped 0.3-0.5 m whenever the back end moved
#   its region, the wheel check counted each jump as motion the wheels had missed, set the wheels
#   aside after three in a row with the robot standing, and the robot was lost for 690 s (0.61 m).
# Each draw must keep the wheels (their translation never switched off: they are right) and stay
# under 0.05 m on all pairs (0.02-0.03 m today; tools/bench/log_perturbations.sh runs 64 draws).
#
# With "closures": three draws whose first lap back into the start corridor met a look-alike
# 0.9-2.5 m along it, scoring 0.94-0.95 of the true pose's peak (or the true pose 0.94 of the
# look-alike's); the look-alike was taken and held the log off (all pairs 0.041 m at range 23 m,
# 0.089 m at 17.5 m with regions 3.6 m, 0.109 m at 23 m with regions 3.8 m). A doubtful closure now
# waits for a second search of that map to agree (core/back_end/closure_confirmation.hpp): each draw
# must stay under 0.03 m (0.020-0.023 m) and have made at least one closure wait. These draws are
# replayed with the odometry as logged (--calibrate-odometry false): calibrated online, the front
# end no longer meets the look-alike in them.
#
# With "guess": intel.clf with its odometry calibrated (steps x 0.962, turns x 0.956: what the
# registrations measure of it; tools/bench/corrupt_carmen.py), at range 18.5 m with regions 3.6 m
# and at 21 m with 3.8 m. In both the search of the first lap's return to the start corridor found
# no clear peak over its 3.3 m window, PLICP from the guess settled 1.2-1.5 m along the corridor,
# and that closure held the graph while the clear closures of the next maps were refused (all
# pairs 0.232 and 0.051 m). Such a closure now waits for a second search too
# (BackEndConfig::confirm_guess_window_m): each must stay under 0.03 m (0.019 m) with a closure that
# waited. Needs python3 for the corruption.
set -eu
REPLAY=$1
DATA=${DPCR_DATA_DIR:-$2}
MODE=${3:-default}
LOG=$DATA/intel.clf
RELATIONS=$DATA/intel.relations
if [ ! -f "$LOG" ] || [ ! -f "$RELATIONS" ]; then
  echo "SKIP: $LOG or $RELATIONS not found (set DPCR_DATA_DIR)"
  exit 77
fi
T=$(mktemp -d "${TMPDIR:-/tmp}/dpcr_public_log_accuracy_XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# replay NAME [options...]: replays the log into $T/NAME and sets E to its all-pairs error (m).
replay() {
  NAME=$1
  shift
  # shellcheck disable=SC2086  # EXTRA: words
  "$REPLAY" --carmen "$LOG" --relations "$RELATIONS" ${EXTRA:-} "$@" --out "$T/$NAME" > "$T/$NAME.txt" 2>&1 ||
    { cat "$T/$NAME.txt" >&2; fail "dpcr-replay $*"; }
  cat "$T/$NAME.txt"
  E=$(sed -n 's/.*relations \([0-9.]*\) +- .*/\1/p' "$T/$NAME.txt")
  [ -n "$E" ] || fail "no relations figure in the replay's summary"
  grep -q "(2984 matched, 0 unmatched)" "$T/$NAME.txt" || fail "not every relation matched"
}

if [ "$MODE" = default ]; then
  replay intel
  awk -v e="$E" 'BEGIN { exit !(e <= 0.025) }' || fail "intel.clf all pairs $E m, bound 0.025 m"
  echo "intel.clf all pairs $E m (bound 0.025 m): ok"
  exit 0
fi
# check_draws BOUND PATTERN FAILURE "RANGE WIDTH"...: replays each draw (range limit and region
# width, m); each must have PATTERN in its metrics.json (else it fails with FAILURE) and all pairs
# within BOUND m.
check_draws() {
  BOUND=$1 PATTERN=$2 FAILURE=$3
  shift 3
  for DRAW in "$@"; do
    RANGE=${DRAW% *} WIDTH=${DRAW#* }
    replay "range$RANGE-width$WIDTH" --max-range "$RANGE" --region-width "$WIDTH"
    grep -q "$PATTERN" "$T/range$RANGE-width$WIDTH/metrics.json" || fail "range $RANGE m, regions $WIDTH m: $FAILURE"
    awk -v e="$E" -v b="$BOUND" 'BEGIN { exit !(e <= b) }' || fail "range $RANGE m, regions $WIDTH m: all pairs $E m, bound $BOUND m"
    echo "range $RANGE m, regions $WIDTH m: all pairs $E m (bound $BOUND m): ok"
  done
}

case "$MODE" in
  guess)
    LOG=$T/intel-calibrated.clf
    "${PYTHON3:-python3}" "$(dirname "$0")/../../tools/bench/corrupt_carmen.py" "$DATA/intel.clf" "$LOG" \
      --odom-scale 0.962 0.956 || fail "corrupt_carmen.py"
    check_draws 0.03 '"loop_closures_unconfirmed": [1-9]' "no closure waited" "18.5 3.6" "21 3.8" ;;
  draws) check_draws 0.05 '"translation_switched_off": 0' "the wheels were set aside" "21 3.8" "20 4.2" ;;
  closures)
    EXTRA="--calibrate-odometry false"
    check_draws 0.03 '"loop_closures_unconfirmed": [1-9]' "no closure waited" "23 4" "17.5 3.6" "23 3.8" ;;
  *) fail "unknown mode $MODE (default, draws, closures or guess)" ;;
esac
