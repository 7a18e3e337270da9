#!/bin/sh
# dpcr-firmware's command line and --config: every mistake is one error line and exit 1, found
# before any device is opened; the example robot configuration (board/robot.example.json) and
# dpcr-sim's device.json are accepted.
# usage: firmware_cli.sh DPCR_FIRMWARE SOURCE_DIR
set -u
fw=$1
src=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/dpcr_firmware_cli_XXXXXX")
trap 'rm -rf "$tmp"' EXIT
failures=0
# expect EXIT_CODE TEXT -- ARGS: runs the firmware, checks its exit code and that stderr has TEXT in one error line.
expect() {
  code=$1 text=$2
  shift 3
  "$fw" "$@" > "$tmp/out" 2> "$tmp/err"
  rc=$?
  if [ "$rc" != "$code" ] || ! grep -qF -- "$text" "$tmp/err"; then
    echo "FAIL: dpcr-firmware $*: exit $rc (want $code), stderr:"; cat "$tmp/err"; echo "(wanted: $text)"
    failures=$((failures + 1))
  elif [ "$code" = 1 ] && [ "$(grep -c 'error' "$tmp/err")" != 1 ]; then
    echo "FAIL: dpcr-firmware $*: more than one error line:"; cat "$tmp/err"
    failures=$((failures + 1))
  else
    echo "ok: dpcr-firmware $* -> $text"
  fi
}
expect 1 "configuration: ticks_per_rev: not stated" -- --uart /dev/dpcr-none --map-dir "$tmp"
expect 1 "error: --wheel-radius: 'abc' is not a number" -- --wheel-radius abc --ticks-per-rev 4096
expect 1 "error: --angle-sign: '2' (1 or -1)" -- --angle-sign 2
expect 1 "configuration: baud: 9600" -- --baud 9600 --ticks-per-rev 4096
expect 1 "error: unknown option --tick-per-rev" -- --tick-per-rev 4096
expect 1 "robot.json: cannot be read" -- --config "$tmp/robot.json"
printf '{"ticks_per_rev": 4096, "wheel_radius": 0.03}\n' > "$tmp/robot.json"
expect 1 "robot.json: wheel_radius: unknown key" -- --config "$tmp/robot.json"
# Accepted configurations reach the devices: the example (its map directory overridden) and a
# device.json, each stopped by the missing UART.
expect 1 "error: lidar UART /dev/dpcr-none: open" -- --config "$src/board/robot.example.json" --map-dir "$tmp" --uart /dev/dpcr-none
printf '{"lidar": "ld06", "angle_sign": 1.0, "wheel_radius_m": 0.035, "track_width_m": 0.235, "ticks_per_rev": 4096.0, "max_range_m": 12.0, "laser_offset_m": 0.0}\n' > "$tmp/device.json"
expect 1 "error: lidar UART /dev/dpcr-none: open" -- --config "$tmp/device.json" --map-dir "$tmp" --uart /dev/dpcr-none
# An unwritable map directory is found at start, before the devices.
expect 1 "error: map directory $tmp/none is not writable: ENOENT" -- --config "$tmp/device.json" --map-dir "$tmp/none" --uart /dev/dpcr-none
exit $((failures > 0))
