// dpcr-firmware's main loop: one poll() over the lidar UART, the CAN socket and a signal pipe,
// feeding LidarStream -> Mapper::AddScan and WheelCanDecoder -> DiffDriveOdometry ->
// Mapper::AddOdometry. Status line per second, periodic autosave, atomic map save on
// SIGINT/SIGTERM (exit 0), lidar silence past the timeout reported (map saved, exit 2).
#pragma once

#include <cstdio>
#include <string>

#include "hal/diff_drive_odometry.hpp"
#include "hal/lidar_stream.hpp"

namespace dpcr::board {

struct FirmwareConfig {
  std::string uart_device = "/dev/ttyS1";
  int baud = 230400;
  LidarKind lidar = LidarKind::kLd06;
  LidarAngleMap angle_map;                 // upright LD06: clockwise (angle_sign -1)
  std::string can_interface = "can0";
  int can_fd = -1;                         // an already-open fd carrying struct can_frame (tests)
  DiffDriveConfig wheels;
  std::string map_dir = ".";               // writes map.pgm + map.yaml there
  int autosave_s = 60;                     // 0: only on exit
  int lidar_timeout_ms = 2000;             // no packet for this long: reported, exit 2
  int status_period_ms = 1000;
};

// Runs until a signal or a fatal error; returns the process exit code (0 clean stop,
// 1 device or save error, 2 lidar timeout). Status and errors go to `log`.
int RunFirmware(const FirmwareConfig& config, std::FILE* log);

// Renders the mapper's fused map and writes DIR/map.pgm and DIR/map.yaml atomically.
struct MapSaveResult {
  bool ok = false;
  int width = 0;
  int height = 0;
  std::string error;
};

}  // namespace dpcr::board
