// Wheel odometry as the core takes it: absolute poses in the odometry frame, stamped.
// Increments are accumulated into an absolute pose by the caller-facing Mapper API.
#pragma once

#include <cstdint>

#include "core/geometry/pose2.hpp"

namespace dpcr {

struct OdometrySample {
  std::int64_t stamp_us = 0;
  Pose2 pose;                  // wheel pose in the odometry frame (drifts; only increments matter)
  // false: a gyro-only robot (no wheel encoders): `pose` is constant, only the rate tells motion
  // (or wheels whose translation the WheelCheck set aside: `pose` is theirs, for that check only).
  bool has_wheels = true;
  bool has_gyro = false;
  // The wheels are off the floor (a vacuum's wheel-drop switches; the motors stop): the robot is
  // being carried, so neither wheels nor lidar say where it goes. The front end keeps every scan
  // out of the maps and relocalises once the wheels are down again.
  bool lifted = false;
  float gyro_yaw_rate = 0.0f;  // rad/s, when has_gyro
};

}  // namespace dpcr
