#!/bin/busybox sh
# /init of the emulated board (tools/emulated-board-test): vcan0 up, dpcr-firmware on the
# pci-serial UART (/dev/ttyS0) and vcan0, the wheel frames replayed onto vcan0 (dpcr-canplay says
# DPCR-READY on the console as it starts them; the host then starts the lidar bytes), SIGTERM once both streams have
# ended, and the results (trajectory, map.dpcr, recorded streams with their device.json, logs) as a gzipped tar on the
# second serial port (/dev/ttyS1). Kernel command-line words: DPCR_CASE, DPCR_DROP_EVERY and
# DPCR_DUP_EVERY (wheel frames dropped / sent twice, 0: none).
/bin/busybox --install -s /bin
export PATH=/bin
mkdir -p /proc /sys /dev /out/map /out/rec
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
echo "dpcr-init: up at $(cut -d' ' -f1 /proc/uptime)s, case ${DPCR_CASE:-?}, kernel $(uname -r) $(uname -m)"

finish() {
  echo "$1" > /out/init-status
  stty -F /dev/ttyS1 raw -echo -onlcr 2>/dev/null
  tar -c -C /out . | gzip -1 > /dev/ttyS1
  echo "dpcr-init: results sent ($1)"
  poweroff -f
}

for m in can can-raw can-dev vcan; do
  insmod /lib/modules/$m.ko || finish "insmod $m failed"
done
ip link add dev vcan0 type vcan && ip link set up vcan0 || finish "vcan0 failed"

# The robot's parameters: the scenario's device.json (dpcr-sim wrote it: 4096 ticks, angle +1) as
# the --config file; the board's own on the command line.
dpcr-firmware --config /scenario/device.json --uart /dev/ttyS0 --can vcan0 --map-dir /out/map \
  --trajectory /out/trajectory.tum --record /out/rec --autosave 20 --lidar-timeout-ms 5000 --status-period 10 \
  2> /out/firmware.log &
fw=$!
n=0
until grep -q "dpcr-firmware: running" /out/firmware.log; do
  kill -0 $fw 2>/dev/null || { cat /out/firmware.log; finish "firmware did not start"; }
  n=$((n + 1)); [ $n -lt 200 ] || finish "firmware start timeout"
  sleep 0.05
done
# dpcr-canplay says DPCR-READY on the console once its log is loaded, and sends its first frame
# then: the host starts the lidar bytes on that line, so both streams start together.
dpcr-canplay --log /scenario/wheels.log --iface vcan0 --drop-every "${DPCR_DROP_EVERY:-0}" \
  --dup-every "${DPCR_DUP_EVERY:-0}" --ready /dev/console > /out/canplay.log 2>&1
echo "dpcr-init: wheel frames done: $(tail -1 /out/canplay.log)"

# The lidar ends with the wheels; wait until the UART has been quiet for 1.5 s (bytes counted by
# the 8250 driver), at most 60 s.
rx() { sed -n 's/^0: .* rx:\([0-9]*\).*/\1/p' /proc/tty/driver/serial; }
last=-1 quiet=0 n=0
while [ $quiet -lt 3 ] && [ $n -lt 120 ]; do
  now=$(rx)
  if [ "$now" = "$last" ]; then quiet=$((quiet + 1)); else quiet=0; fi
  last=$now n=$((n + 1))
  sleep 0.5
done
echo "dpcr-init: lidar quiet after $last bytes"
kill -TERM $fw
wait $fw
echo $? > /out/firmware.rc
echo "dpcr-init: firmware exit $(cat /out/firmware.rc): $(grep summary /out/firmware.log | tail -1)"
finish ok
