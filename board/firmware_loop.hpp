// dpcr-firmware's loop, in three parts: set-up (the board's ports opened, each owning its
// descriptor, so that every early return closes them), the loop (RunFirmwareLoop: only the hal
// ports, so a test drives it with fake devices and a fake clock) and tear-down (the final save).
#pragma once

#include <cstdio>

#include "board/firmware.hpp"

namespace dpcr::board {

// Waits on `waiter` until a port has something or the next timer is due, and services it:
// lidar bytes and CAN frames into the firmware, then its timers. Returns the exit code: 0 on a
// stop request, 1 when the wait fails, 2 when the lidar stays silent past its timeout. After
// start-up nothing here allocates or waits on anything but `waiter` (tests/board/
// firmware_allocation_test.cpp).
int RunFirmwareLoop(Firmware* firmware, PortWaiter* waiter, const Clock& clock);

// The board: opens the lidar UART, the CAN interface (mapping from the lidar alone while it is
// not there), the stop-signal pipe and the systemd notify socket ($NOTIFY_SOCKET), runs the loop
// and saves the map at the end. Returns the process exit code (0 clean stop, 1 start-up, device
// or save error, 2 lidar timeout). Status and errors go to `log`.
int RunFirmware(const FirmwareConfig& config, std::FILE* log);

}  // namespace dpcr::board
