#!/bin/sh
# Smoke test of dpcr-firmware against a real SocketCAN interface (vcan) fed by canplayer, and
# a pseudo-terminal fed with LD06 bytes. Needs: vcan kernel module, can-utils, socat, root
# (to create vcan0). Prints "skipped: no vcan" and exits 0 where any of that is missing.
# usage: tools/vcan-smoke.sh BUILD_DIR DEVICE_DIR   (DEVICE_DIR holds lidar.uart + wheels.log + device.json,
#        e.g. from dpcr-sim --emit-device)
set -eu
build=${1:-build/host}
devdir=${2:-}
fw="$build/board/dpcr-firmware"

skip() { echo "skipped: no vcan ($1)"; exit 0; }
command -v canplayer >/dev/null 2>&1 || skip "canplayer not installed"
command -v socat >/dev/null 2>&1 || skip "socat not installed"
[ -x "$fw" ] || skip "$fw not built"
[ -n "$devdir" ] && [ -f "$devdir/wheels.log" ] && [ -f "$devdir/lidar.uart" ] && [ -f "$devdir/device.json" ] ||
  skip "no device files given"
if ! ip link show vcan0 >/dev/null 2>&1; then
  modprobe vcan 2>/dev/null || skip "vcan module unavailable"
  ip link add dev vcan0 type vcan 2>/dev/null || skip "cannot create vcan0 (not root?)"
  ip link set up vcan0 || skip "cannot bring vcan0 up"
fi

work=$(mktemp -d)
trap 'kill $socat_pid 2>/dev/null || true; rm -rf "$work"' EXIT
socat -d pty,raw,echo=0,link="$work/lidar" pty,raw,echo=0,link="$work/feed" &
socat_pid=$!
sleep 1
# The device files describe the robot (device.json: ticks per revolution, angle direction).
"$fw" --config "$devdir/device.json" --uart "$work/lidar" --can vcan0 --map-dir "$work" --lidar-timeout-ms 5000 &
fw_pid=$!
sleep 1
# wheels.log was recorded on can0: canplayer maps it to vcan0.
canplayer -I "$devdir/wheels.log" vcan0=can0 &
player_pid=$!
# Strip the capture's timestamps and comments: raw bytes into the pty.
grep -v '^#' "$devdir/lidar.uart" | cut -d' ' -f2 | xxd -r -p > "$work/feed"
wait $player_pid || true
kill -TERM $fw_pid
wait $fw_pid
rc=$?
[ $rc -eq 0 ] || { echo "FAIL: dpcr-firmware exited $rc"; exit 1; }
[ -s "$work/map.dpcr" ] || { echo "FAIL: no map saved"; exit 1; }
echo "ok: vcan smoke test, map.dpcr of $(wc -c < "$work/map.dpcr") bytes"
