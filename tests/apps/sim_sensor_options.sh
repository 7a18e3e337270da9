#!/bin/sh
# dpcr-sim's sensor-quality options: --lidar-noise BASE,FRACTION sets the simulated range noise
# and --ideal-wheels removes the wheels' calibration error and slips, --near-weight M how near
# returns weigh in the first registration; metrics.json's "input" says what was simulated, and a
# value out of range is refused.
# Usage: sim_sensor_options.sh DPCR_SIM
set -eu
SIM=$1
T=$(mktemp -d "${TMPDIR:-/tmp}/dpcr_sim_sensor_options_XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$SIM" --world apartment --minutes 0.5 --out "$T/default" 2> /dev/null || fail "dpcr-sim (defaults)"
tr -d ' \n' < "$T/default/metrics.json" > "$T/default.json"
grep -q '"lidar_noise":\[0.01,0.005\]' "$T/default.json" || fail "default lidar noise not reported"
grep -q '"ideal_wheels":false' "$T/default.json" || fail "ideal_wheels not reported"
grep -q '"near_weight_range_m":0.5' "$T/default.json" || fail "the vacuum lidar's near weighting not reported"

"$SIM" --world apartment --minutes 0.5 --lidar-noise 0,0 --ideal-wheels --out "$T/exact" 2> /dev/null ||
  fail "dpcr-sim --lidar-noise 0,0 --ideal-wheels"
tr -d ' \n' < "$T/exact/metrics.json" > "$T/exact.json"
grep -q '"lidar_noise":\[0.0,0.0\]' "$T/exact.json" || fail "--lidar-noise ignored"
grep -q '"ideal_wheels":true' "$T/exact.json" || fail "--ideal-wheels ignored"
grep -q '"slip_events":0' "$T/exact.json" || fail "--ideal-wheels: the wheels still slipped"
cmp -s "$T/default/trajectory.tum" "$T/exact/trajectory.tum" && fail "exact sensors gave the very same trajectory"

"$SIM" --world apartment --minutes 0.5 --near-weight 0 --out "$T/alike" 2> /dev/null || fail "dpcr-sim --near-weight 0"
tr -d ' \n' < "$T/alike/metrics.json" | grep -q '"near_weight_range_m":0.0' || fail "--near-weight 0 ignored"
if "$SIM" --world apartment --minutes 0.5 --near-weight -1 --out "$T/bad" 2> "$T/err"; then
  fail "a negative near weighting accepted"
fi
grep -q "near-weight" "$T/err" || fail "no clear error for a negative near weighting"

if "$SIM" --world apartment --minutes 0.5 --lidar-noise -0.01,0 --out "$T/bad" 2> "$T/err"; then
  fail "a negative noise accepted"
fi
grep -q "lidar-noise" "$T/err" || fail "no clear error for a negative noise"
echo "sim sensor options: ok"
