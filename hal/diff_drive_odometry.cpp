#include "hal/diff_drive_odometry.hpp"

#include <cmath>

namespace dpcr {
namespace {

constexpr double kTwoPi = 6.283185307179586;
// Below this heading change the arc formula loses precision: use the straight-segment limit.
constexpr double kStraightDtheta = 1e-9;

}  // namespace

Status DiffDriveConfig::Validate() const {
  if (!(wheel_radius_m > 0.0f) || !(track_width_m > 0.0f) || !(ticks_per_rev > 0.0f)) {
    return Status::kInvalidArgument;
  }
  return Status::kOk;
}

DiffDriveOdometry::DiffDriveOdometry(const DiffDriveConfig& config) : config_(config) {}

void DiffDriveOdometry::Reset() {
  started_ = false;
  x_ = y_ = theta_ = 0.0;
}

OdometrySample DiffDriveOdometry::Update(const WheelTicks& ticks, std::int64_t stamp_us) {
  if (started_) {
    const double metres_per_tick = kTwoPi * static_cast<double>(config_.wheel_radius_m) /
                                   static_cast<double>(config_.ticks_per_rev);
    const double dl = static_cast<double>(ticks.left_ticks - last_left_) * metres_per_tick;
    const double dr = static_cast<double>(ticks.right_ticks - last_right_) * metres_per_tick;
    const double ds = 0.5 * (dl + dr);
    const double dtheta = (dr - dl) / static_cast<double>(config_.track_width_m);
    if (std::fabs(dtheta) < kStraightDtheta) {
      x_ += ds * std::cos(theta_ + 0.5 * dtheta);
      y_ += ds * std::sin(theta_ + 0.5 * dtheta);
    } else {
      const double radius = ds / dtheta;
      x_ += radius * (std::sin(theta_ + dtheta) - std::sin(theta_));
      y_ -= radius * (std::cos(theta_ + dtheta) - std::cos(theta_));
    }
    theta_ = std::remainder(theta_ + dtheta, kTwoPi);
  }
  started_ = true;
  last_left_ = ticks.left_ticks;
  last_right_ = ticks.right_ticks;
  OdometrySample sample;
  sample.stamp_us = stamp_us;
  sample.pose = pose();
  return sample;
}

Pose2 DiffDriveOdometry::pose() const {
  return Pose2{static_cast<float>(x_), static_cast<float>(y_),
               NormalizeAngle(static_cast<float>(theta_))};
}

}  // namespace dpcr
