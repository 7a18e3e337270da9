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
  if (!sample.has_wheels) return;
  // Below a millisecond apart (logs that jitter, a stamp stepping back) the rate is kept.
  const std::int64_t dt_us = sample.stamp_us - wheel_stamp_us_;
  if (have_wheels_ && dt_us >= 1000) {
    wheel_turn_rate_ = NormalizeAngle(sample.pose.theta - wheel_pose_.theta) / (static_cast<float>(dt_us) * 1e-6f);
  }
  wheel_pose_ = sample.pose;
  wheel_stamp_us_ = sample.stamp_us;
  have_wheels_ = true;
}

OdometrySample WheelCheck::Filter(const OdometrySample& sample) const {
  if (!sample.has_wheels || !translation_.rejected) return sample;
  OdometrySample s = sample;
  s.has_wheels = false;
  s.pose = Pose2::Identity();  // a sample without wheels carries a constant pose
  if (!s.has_gyro && heading_used()) {
    s.has_gyro = true;
    s.gyro_yaw_rate = wheel_turn_rate_;
  }
  return s;
}

void WheelCheck::RestartWindows(const Pose2& pose, std::int64_t stamp_us) {
  start_xy_ = Point2{pose.x, pose.y};
  start_wheels_xy_ = Point2{wheel_pose_.x, wheel_pose_.y};
  previous_theta_ = pose.theta;
  previous_wheels_theta_ = wheel_pose_.theta;
  translation_start_us_ = turn_start_us_ = stamp_us;
  turned_ = wheels_turned_ = 0.0f;
  window_open_ = true;
}

void WheelCheck::AddScan(const Pose2& pose, std::int64_t stamp_us, bool tracked) {
  if (!have_wheels_ || !tracked) {
    window_open_ = window_doubt_ = false;  // an untracked scan says nothing of where the robot went
    return;
  }
  if (!window_open_) {
    RestartWindows(pose, stamp_us);
    return;
  }
  // Translation: net distances, so that a standing robot's jitter adds up to nothing.
  const float moved = std::hypot(pose.x - start_xy_.x, pose.y - start_xy_.y);
  const float ratio = moved > 0.0f ? std::hypot(wheel_pose_.x - start_wheels_xy_.x, wheel_pose_.y - start_wheels_xy_.y) / moved : 1.0f;
  window_doubt_ = moved >= kDoubtDistanceM && ratio < kMissRatio;
  if (moved >= kWindowDistanceM) {
    if (ratio < kMissRatio) ++translation_misses_;
    if (ratio >= kAgreeRatio) translation_confirmed_ = true;
    if (ratio < kMissRatio || ratio >= kAgreeRatio) {
      if (translation_.Vote(ratio >= kAgreeRatio) && translation_.rejected) ++switched_off_;
    }
  }
  if (moved >= kWindowDistanceM || stamp_us - translation_start_us_ > kWindowMaxUs) {
    start_xy_ = Point2{pose.x, pose.y};
    start_wheels_xy_ = Point2{wheel_pose_.x, wheel_pose_.y};
    translation_start_us_ = stamp_us;
    window_doubt_ = false;
  }
  // Heading: signed turns summed scan by scan (a net angle would wrap).
  turned_ += NormalizeAngle(pose.theta - previous_theta_);
  wheels_turned_ += NormalizeAngle(wheel_pose_.theta - previous_wheels_theta_);
  previous_theta_ = pose.theta;
  previous_wheels_theta_ = wheel_pose_.theta;
  if (std::fabs(turned_) >= kWindowTurnRad) {
    const float turn_ratio = wheels_turned_ / turned_;  // negative: the wheels turn the other way
    if (turn_ratio < kMissRatio || (turn_ratio >= kAgreeRatio && turn_ratio <= 1.0f / kAgreeRatio)) {
      (void)heading_.Vote(turn_ratio >= kAgreeRatio);
    }
  }
  if (std::fabs(turned_) >= kWindowTurnRad || stamp_us - turn_start_us_ > kWindowMaxUs) {
    turned_ = wheels_turned_ = 0.0f;
    turn_start_us_ = stamp_us;
  }
}

}  // namespace dpcr
