// A lidar packet in device-independent form, as the ScanAssembler takes it: up to 12 points
// at evenly spaced angles, with the time of the first point and the time between points.
#pragma once

#include <cstdint>

namespace dpcr {

constexpr int kMaxPointsPerPacket = 12;

struct LidarPacket {
  std::int64_t stamp_us = 0;     // time of point 0 (host time base)
  float start_deg = 0.0f;        // angle of point 0 in [0, 360), in the device's rotation sense
  float step_deg = 0.0f;         // angle between consecutive points (>= 0)
  float point_dt_us = 0.0f;      // time between consecutive points
  std::uint8_t count = 0;        // points used in range_mm
  std::uint16_t range_mm[kMaxPointsPerPacket] = {};  // 0 = no return
};

}  // namespace dpcr
