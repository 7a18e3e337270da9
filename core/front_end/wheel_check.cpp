#include "core/front_end/wheel_check.hpp"

#include <cmath>

namespace dpcr {

bool WheelCheck::Verdict::Vote(bool agrees) {
  // A vote for the current state breaks a run against it.
  if (agrees != rejected) {
    run = 0;
    return false;
  }
  if (++run < kVotesToSwitch) return false;
  run = 0;
  rejected = !rejected;
  return true;
}

void WheelCheck::AddOdometry(const OdometrySample& sample) {
  if (!sample.has_wheels) {
    // Wheels gone silent (a gyro-only sample): nothing to compare until they are back.
    have_wheels_ = window_open_ = false;
    return;
  }
  // Below a millisecond apart (logs that jitter, a stamp stepping back) the rate is kept.
  const std::int64_t dt_us = sample.stamp_us - wheel_stamp_us_;
  if (have_wheels_ && dt_us >= 1000) {
    wheel_turn_rate_ = NormalizeAngle(sample.pose.theta - wheel_theta_) / (static_cast<float>(dt_us) * 1e-6f);
  }
  wheel_theta_ = sample.pose.theta;
  wheel_stamp_us_ = sample.stamp_us;
  have_wheels_ = true;
}

OdometrySample WheelCheck::Filter(const OdometrySample& sample) const {
  if (!sample.has_wheels || !translation_.rejected) return sample;
  OdometrySample s = sample;
  s.has_wheels = false;
  // Its pose stays: unused without wheels (FrontEnd::Predict, ScanMotion), it gives the check the
  // wheels' pose at each scan's stamp (OdometryBuffer::PoseAt) while they are set aside.
  if (!s.has_gyro && heading_used()) {
    s.has_gyro = true;
    // Only a clear scale error is corrected: near 1 the estimate's own noise would cost more.
    const float k = heading_scale();
    s.gyro_yaw_rate = wheel_turn_rate_ * (std::fabs(k - 1.0f) > kScaleDeadBand ? k : 1.0f);
  }
  return s;
}

float WheelCheck::heading_scale() const {
  if (scale_wheels_rad_ < kMinScaleEvidenceRad) return 1.0f;
  const float k = scale_registered_rad_ / scale_wheels_rad_;
  return k < kAgreeRatio ? kAgreeRatio : (k > 1.0f / kAgreeRatio ? 1.0f / kAgreeRatio : k);
}

void WheelCheck::RestartWindows(const Pose2& wheels, std::int64_t stamp_us) {
  moved_xy_ = Point2{0.0f, 0.0f};
  start_wheels_xy_ = Point2{wheels.x, wheels.y};
  previous_wheels_theta_ = wheels.theta;
  translation_start_us_ = turn_start_us_ = stamp_us;
  turned_ = wheels_turned_ = 0.0f;
  window_open_ = true;
  window_unclean_ = false;
}

void WheelCheck::AddScan(const Pose2& step, const Pose2& wheels, std::int64_t stamp_us, bool tracked, bool clean_fit) {
  if (!have_wheels_ || !tracked) {
    // An untracked scan says nothing of where the robot went.
    window_open_ = wheels_short_ = false;
    return;
  }
  if (!window_open_) {
    RestartWindows(wheels, stamp_us);
    return;
  }
  if (!clean_fit) window_unclean_ = true;
  const float c = std::cos(registered_heading_), s = std::sin(registered_heading_);
  moved_xy_.x += c * step.x - s * step.y;
  moved_xy_.y += s * step.x + c * step.y;
  registered_heading_ = NormalizeAngle(registered_heading_ + step.theta);
  CheckTranslation(wheels, stamp_us);
  CheckHeading(step, wheels, stamp_us);
}

void WheelCheck::CheckTranslation(const Pose2& wheels, std::int64_t stamp_us) {
  // Net distances, so that a standing robot's jitter adds up to nothing. The window closes once
  // either has gone kWindowDistanceM: the lidar (wheels that stand still or turn only) or the
  // wheels (a robot stuck on a rug's edge whose wheels spin on).
  const float moved = std::hypot(moved_xy_.x, moved_xy_.y);
  const float wheeled = std::hypot(wheels.x - start_wheels_xy_.x, wheels.y - start_wheels_xy_.y);
  wheels_short_ = moved >= kDoubtDistanceM && wheeled < kMissRatio * moved;
  const float longer = std::fmax(moved, wheeled), shorter = std::fmin(moved, wheeled);
  if (longer >= kWindowDistanceM) {
    const bool wheels_long = wheeled > moved;
    // Wheels that ran on count as spinning only on the word of clean fits (AddScan).
    const bool miss = shorter < kMissRatio * longer && !(wheels_long && window_unclean_);
    const bool agree = shorter >= kAgreeRatio * longer;
    if (miss) ++translation_misses_;
    if (miss && !translation_.rejected) {
      // Misses count in a row only the same way round. Logged odometry that stalls and then
      // catches up in one step (mit-csail.clf: 0.9 m in one window after two of 0.04 and 0 m
      // against 0.46 m registered) is neither wheels that miss the motion nor wheels that spin on,
      // and switching it off lost the robot for 240 of the log's 420 s.
      if (translation_.run > 0 && wheels_long != miss_wheels_long_) translation_.run = 0;
      miss_wheels_long_ = wheels_long;
    }
    if (agree) translation_confirmed_ = true;
    if ((miss || agree) && translation_.Vote(agree) && translation_.rejected) ++switched_off_;
  }
  if (longer >= kWindowDistanceM || stamp_us - translation_start_us_ > kWindowMaxUs) {
    moved_xy_ = Point2{0.0f, 0.0f};
    start_wheels_xy_ = Point2{wheels.x, wheels.y};
    translation_start_us_ = stamp_us;
    wheels_short_ = window_unclean_ = false;
  }
}

void WheelCheck::CheckHeading(const Pose2& step, const Pose2& wheels, std::int64_t stamp_us) {
  // Signed turns summed scan by scan (a net angle would wrap).
  turned_ += NormalizeAngle(step.theta);
  wheels_turned_ += NormalizeAngle(wheels.theta - previous_wheels_theta_);
  previous_wheels_theta_ = wheels.theta;
  if (std::fabs(turned_) >= kWindowTurnRad) {
    const float turn_ratio = wheels_turned_ / turned_;  // negative: the wheels turn the other way
    const bool agree = turn_ratio >= kAgreeRatio && turn_ratio <= 1.0f / kAgreeRatio;
    if (turn_ratio < kMissRatio || agree) (void)heading_.Vote(agree);
    if (agree) {
      scale_registered_rad_ = kScaleMemory * scale_registered_rad_ + std::fabs(turned_);
      scale_wheels_rad_ = kScaleMemory * scale_wheels_rad_ + std::fabs(wheels_turned_);
    }
  }
  if (std::fabs(turned_) >= kWindowTurnRad || stamp_us - turn_start_us_ > kWindowMaxUs) {
    turned_ = wheels_turned_ = 0.0f;
    turn_start_us_ = stamp_us;
  }
}

}  // namespace dpcr
