#include "core/front_end/scan_motion.hpp"

#include <cmath>

namespace dpcr {
namespace {

Pose2 PlausibleVelocity(const Pose2& v) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.theta)) return Pose2{};
  Pose2 out = v;
  const float speed = std::hypot(v.x, v.y);
  if (speed > ScanMotion::kMaxSpeedMps) {
    out.x *= ScanMotion::kMaxSpeedMps / speed;
    out.y *= ScanMotion::kMaxSpeedMps / speed;
  }
  out.theta = std::fmax(-ScanMotion::kMaxTurnRateRadS, std::fmin(ScanMotion::kMaxTurnRateRadS, v.theta));
  return out;
}

}  // namespace

ScanMotion::ScanMotion(const OdometryBuffer& odometry, bool gyro_heading, const Pose2& velocity_per_s,
                       std::int64_t stamp_us)
    : odometry_(odometry), velocity_(PlausibleVelocity(velocity_per_s)), stamp_us_(stamp_us) {
  wheels_ = !odometry.empty() && odometry.newest().has_wheels;
  if (wheels_) odom_at_stamp_inv_ = odometry.PoseAt(stamp_us).Inverse();
  gyro_ = (gyro_heading || !wheels_) && !odometry.empty() && odometry.GyroYawAt(stamp_us, &yaw_at_stamp_);
}

Pose2 ScanMotion::At(std::int32_t offset_us) const {
  const std::int64_t t_us = stamp_us_ + offset_us;
  const float t = static_cast<float>(offset_us) * 1e-6f;
  Pose2 p = wheels_ ? odom_at_stamp_inv_ * odometry_.PoseAt(t_us) : Pose2{velocity_.x * t, velocity_.y * t, velocity_.theta * t};
  float yaw = 0.0f;
  if (gyro_ && odometry_.GyroYawAt(t_us, &yaw)) p.theta = NormalizeAngle(yaw - yaw_at_stamp_);
  return p;
}

}  // namespace dpcr
