#!/bin/sh
# dpcr-sim's sensor-quality options: --lidar-noise BASE,FRACTION sets the simulated range noise
# and --ideal-wheels removes the wheels' calibration error and slips; metrics.json's "input" says
# what was simulated, and a value out of range is refused.
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

"$SIM" --world apartment --minutes 0.5 --lidar-noise 0,0 --ideal-wheels --out "$T/exact" 2> /dev/null ||
  fail "dpcr-sim --lidar-noise 0,0 --ideal-wheels"
tr -d ' \n' < "$T/exact/metrics.json" > "$T/exact.json"
grep -q '"lidar_noise":\[0.0,0.0\]' "$T/exact.json" || fail "--lidar-noise ignored"
grep -q '"ideal_wheels":true' "$T/exact.json" || fail "--ideal-wheels ignored"
grep -q '"slip_events":0' "$T/exact.json" || fail "--ideal-wheels: the wheels still slipped"
cmp -s "$T/default/trajectory.tum" "$T/exact/trajectory.tum" && fail "exact sensors gave the very same trajectory"

if "$SIM" --world apartment --minutes 0.5 --lidar-noise -0.01,0 --out "$T/bad" 2> "$T/err"; then
  fail "a negative noise accepted"
fi
grep -q "lidar-noise" "$T/err" || fail "no clear error for a negative noise"
echo "sim sensor options: ok"
