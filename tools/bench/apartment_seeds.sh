#!/bin/sh
# LocErr_ave of the simulated apartment over several seeds (each seed changes the lidar noise,
# the odometry calibration error and the slips; the cleaning plan is the same). One seed says
# little: the same change can move one seed's figure by +-2 cm (docs/front-end-accuracy.md).
# Usage: tools/bench/apartment_seeds.sh [path/to/dpcr-bench] [first seed] [last seed] [minutes] [bench options...]
# (bench options, e.g. --hit-margin 0 or --k2 25, are passed to `dpcr-bench mapper`).
set -eu
BENCH=${1:-build/host/tools/bench/dpcr-bench}
FIRST=${2:-1}
LAST=${3:-10}
MINUTES=${4:-35}
[ $# -ge 4 ] && shift 4 || shift $#
SEED=$FIRST
ALL=
while [ "$SEED" -le "$LAST" ]; do
  E=$("$BENCH" mapper --world apartment --minutes "$MINUTES" --seed "$SEED" "$@" | awk '/^LocErr_ave/ {print $2}')
  [ -n "$E" ] || { echo "seed $SEED: no LocErr_ave from $BENCH" >&2; exit 1; }
  echo "seed $SEED: LocErr_ave $E m"
  ALL="$ALL $E"
  SEED=$((SEED + 1))
done
echo "$ALL" | awk '{s = 0; m = 0; for (i = 1; i <= NF; ++i) { s += $i; if ($i > m) m = $i }
                   printf "seeds '"$FIRST"'-'"$LAST"': mean %.3f m, worst %.3f m\n", s / NF, m}'
