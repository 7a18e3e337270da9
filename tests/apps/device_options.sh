#!/bin/sh
# One set of device options: dpcr-sim --emit-device describes the device in DIR/device.json,
# dpcr-replay --uart reads it as its defaults (the command line overrides), and an option that
# does not apply to the input is an error, not silently ignored.
# Usage: device_options.sh DPCR_SIM DPCR_REPLAY
set -eu
SIM=$1; REPLAY=$2
T=$(mktemp -d "${TMPDIR:-/tmp}/dpcr_device_options_XXXXXX")
trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$SIM" --world apartment --minutes 1 --out "$T/a" --emit-device "$T/dev" 2> /dev/null || fail "dpcr-sim --emit-device"
[ -s "$T/dev/device.json" ] || fail "no device.json"
grep -q '"ticks_per_rev": 4096' "$T/dev/device.json" || fail "device.json: ticks"
"$REPLAY" --uart "$T/dev/lidar.uart" --candump "$T/dev/wheels.log" --out "$T/r" 2> /dev/null || fail "dpcr-replay --uart"
grep -q "\"description\": \"$T/dev/device.json\"" "$T/r/metrics.json" || fail "replay did not read device.json"
grep -q '"angle_sign": 1.0' "$T/r/metrics.json" || fail "replay: angle sign not from device.json"
grep -q '"lidar_range_noise_m": 0.02' "$T/r/metrics.json" || fail "replay: the LD06's range noise not declared"
"$REPLAY" --uart "$T/dev/lidar.uart" --candump "$T/dev/wheels.log" --out "$T/r2" --max-range 5 --laser-offset 0.02 2> /dev/null ||
  fail "dpcr-replay --uart --max-range"
grep -q '"max_range_m": 5.0' "$T/r2/metrics.json" || fail "--max-range ignored with --uart"
grep -q '"laser_offset_m": 0.0199' "$T/r2/metrics.json" || fail "--laser-offset ignored with --uart"
if "$REPLAY" --uart "$T/dev/lidar.uart" --candump "$T/dev/wheels.log" --out "$T/r3" --odometry odom 2> "$T/err"; then
  fail "--odometry accepted with --uart"
fi
grep -q "does not apply" "$T/err" || fail "no clear error for --odometry with --uart"
echo "device options: ok"
