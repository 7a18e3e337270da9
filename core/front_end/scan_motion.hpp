// The robot's motion within one lidar revolution, for the de-skew: from what the robot has, each
// part from its best source. Heading: the gyro when the prediction takes it (FrontEndConfig::
// gyro_heading, or no wheels), else the wheels, else the constant velocity; translation: the
// wheels, else the constant velocity (the last registered scan-to-scan motion per second). A
// robot without wheels spinning at 120°/s turns 24° within one 5 Hz revolution: without this the
// last beams would sit 24° off the first, and the registration settles half-way.
#pragma once

#include <cstdint>

#include "core/front_end/odometry_buffer.hpp"
#include "core/geometry/pose2.hpp"

namespace dpcr {

class ScanMotion {
 public:
  // `velocity_per_s`: the constant-velocity motion over one second (x, y, theta in the robot frame).
  // Past kMaxSpeedMps or kMaxTurnRateRadS it is scaled down to them, and one that is not finite
  // is no motion: it is a scan-to-scan step over the time between two stamps, and two scans
  // stamped within microseconds of each other (or at the same time: 0 / 0) made it a NaN that
  // went into the maps (fuzz_mapper_scans).
  static constexpr float kMaxSpeedMps = 20.0f;
  static constexpr float kMaxTurnRateRadS = 100.0f;
  ScanMotion(const OdometryBuffer& odometry, bool gyro_heading, const Pose2& velocity_per_s, std::int64_t stamp_us);

  // The robot's pose at stamp + offset_us in its frame at the stamp.
  Pose2 At(std::int32_t offset_us) const;
  bool wheels() const { return wheels_; }
  bool gyro() const { return gyro_; }
  const Pose2& velocity() const { return velocity_; }
  std::int64_t stamp_us() const { return stamp_us_; }
  // False when every At() is the identity (nothing to de-skew with).
  bool moves() const { return wheels_ || gyro_ || velocity_.x != 0.0f || velocity_.y != 0.0f || velocity_.theta != 0.0f; }

 private:
  const OdometryBuffer& odometry_;
  Pose2 velocity_;
  std::int64_t stamp_us_;
  bool wheels_ = false;
  bool gyro_ = false;
  Pose2 odom_at_stamp_inv_;
  float yaw_at_stamp_ = 0.0f;
};

}  // namespace dpcr
