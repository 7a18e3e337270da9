// dpcr-firmware's main loop: one poll() over the lidar UART, the CAN socket and a signal pipe,
// each ready port serviced by Firmware (firmware.hpp): LidarStream -> Mapper::AddScan and
// WheelCanDecoder -> DiffDriveOdometry -> Mapper::AddOdometry. Status line per second, periodic
// autosave, atomic map save on SIGINT/SIGTERM (exit 0), lidar silence past the timeout reported
// (map saved, exit 2).
#pragma once

#include <cstdio>

#include "board/firmware.hpp"

namespace dpcr::board {

// Runs until a signal or a fatal error; returns the process exit code (0 clean stop,
// 1 device or save error, 2 lidar timeout). Status and errors go to `log`.
int RunFirmware(const FirmwareConfig& config, std::FILE* log);

}  // namespace dpcr::board
