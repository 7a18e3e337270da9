// The robot's own parameters for dpcr-firmware --config FILE: a JSON object whose keys are the
// device.json keys (hal/device_options.hpp; dpcr-sim --emit-device and dpcr-firmware --record
// write them) plus the board's:
//   uart, baud, lidar ("ld06" | "xv11"), lidar_timing ("arrival" | "device"), angle_sign,
//   max_range_m, laser_offset_m, can, wheel_radius_m, track_width_m, ticks_per_rev (required),
//   max_accel_mps2,
//   heading ("model" | "wheels" | "gyro"), profile ("vacuum"), map_dir, autosave_s, lidar_timeout_ms,
//   wheel_timeout_ms, can_retry_ms, status_period_s
// An unknown key, a value of the wrong type or out of its range, or a missing ticks_per_rev is
// an error: one line naming the file and the key. Checked at start, before any device is opened.
#pragma once

#include <string>

#include "board/firmware.hpp"

namespace dpcr::board {

// Applies FILE's keys to `config`. False with "FILE: key: what is wrong" in `error`.
bool LoadFirmwareConfigFile(const std::string& path, FirmwareConfig* config, std::string* error);

// The whole configuration's ranges (whatever set them: file or command line). False with
// "key: what is wrong" in `error`.
bool ValidateFirmwareConfig(const FirmwareConfig& config, std::string* error);

}  // namespace dpcr::board
