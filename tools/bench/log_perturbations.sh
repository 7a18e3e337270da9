#!/bin/sh
# The relations error of one CARMEN log replayed under small perturbations: range limits from 15
# to 28 m, each at the default region width and at 3.6 m (WIDTHS). One replay says little: the region
# graph decides which loop closures it takes, and a change that moves nothing in the mapping can
# move one replay of intel.clf from 0.03 to 0.3 m (docs/back-end.md, "Intel under perturbation").
# The mean, the median and the draws over 5 cm say more than the default replay alone.
# WIDTHS="3.6 3.8 4.2" doubles the draws (64) where 32 cannot tell two builds apart.
# Usage: tools/bench/log_perturbations.sh [path/to/dpcr-replay] [log.clf] [log.relations] [replay options...]
# Defaults: build/host/host_sim/apps/dpcr-replay, $DPCR_DATA_DIR/intel.clf (DPCR_DATA_DIR defaults
# to ../shared/data) and the log's .relations beside it. Runs as many replays at once as `nproc`
# says; each writes into a temporary directory, removed at the end (KEEP=1 keeps it and says where).
set -eu
DATA=${DPCR_DATA_DIR:-../shared/data}
REPLAY=${1:-build/host/host_sim/apps/dpcr-replay}
LOG=${2:-$DATA/intel.clf}
RELATIONS=${3:-${LOG%.clf}.relations}
if [ $# -ge 3 ]; then shift 3; else shift $#; fi
[ -x "$REPLAY" ] || { echo "$0: $REPLAY: not an executable (build first: cmake --preset host && cmake --build build/host)" >&2; exit 2; }
[ -f "$LOG" ] || { echo "$0: $LOG: not found (set DPCR_DATA_DIR or pass the log)" >&2; exit 2; }
[ -f "$RELATIONS" ] || { echo "$0: $RELATIONS: not found (the relations metric needs it)" >&2; exit 2; }
OUT=$(mktemp -d "${TMPDIR:-/tmp}/dpcr-perturbations.XXXXXX")
[ "${KEEP:-0}" = 1 ] || trap 'rm -rf "$OUT"' EXIT
JOBS=$(nproc 2>/dev/null || echo 1)

# One draw per line: a name, then the replay options that make it.
DRAWS="$OUT/draws.txt"
# WIDTHS: the region widths tried besides the default at each range limit ("3.6 3.8 4.2": 64 draws).
for RANGE in 20 15 15.5 16 16.5 17 17.5 18 18.5 19 19.5 21 22 23 25 28; do
  echo "range$RANGE --max-range $RANGE"
  for WIDTH in ${WIDTHS:-3.6}; do
    echo "range$RANGE-width$WIDTH --max-range $RANGE --region-width $WIDTH"
  done
done > "$DRAWS"

# Each draw prints "name error" (the all-pairs translation mean, m) or fails the whole run.
export REPLAY LOG RELATIONS OUT
EXTRA="$*"
export EXTRA
# shellcheck disable=SC2016  # expanded by the inner shell
xargs -P "$JOBS" -L 1 sh -c '
  name=$1; shift
  if ! "$REPLAY" --carmen "$LOG" --relations "$RELATIONS" "$@" $EXTRA --out "$OUT/$name" > "$OUT/$name.log" 2>&1; then
    echo "$name: dpcr-replay failed, see $OUT/$name.log" >&2; exit 255
  fi
  e=$(sed -n "s/.*relations \([0-9.]*\) +-.*/\1/p" "$OUT/$name.log")
  [ -n "$e" ] || { echo "$name: no relations figure in $OUT/$name.log" >&2; exit 255; }
  echo "$name $e"
' sh < "$DRAWS" | sort -k2 -g > "$OUT/errors.txt"

cat "$OUT/errors.txt"
awk '{ e[NR] = $2; s += $2; if ($2 > 0.05) bad++ }
     END { m = (NR % 2) ? e[(NR + 1) / 2] : (e[NR / 2] + e[NR / 2 + 1]) / 2
           printf "%d draws: mean %.4f m, median %.4f m, worst %.4f m, over 0.05 m: %d\n", NR, s / NR, m, e[NR], bad }' "$OUT/errors.txt"
[ "${KEEP:-0}" = 1 ] && echo "replays kept in $OUT"
exit 0
