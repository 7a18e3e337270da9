// Wheel odometry that stalls and then catches up in one step. A logger (or a wheel board behind a
// busy bus) can repeat the same odometry pose for several scans while the robot moves and then
// deliver the whole motion at once: mit-csail.clf holds still for 2-4 scans and then jumps 0.4-0.9 m
// and 10-90° in one scan, three times. The scans of the stall register from the constant
// velocity's guess or on their own, so the robot's pose has already moved on; the catch-up step,
// applied on top, predicts the motion twice, the registration from it fails, and a retry from the
// constant velocity is all that is left (which lost the heading by 36° in one replay of that log).
// So the catch-up is taken from where the odometry stalled: the motion registered during the
// stall is taken out of it.
#pragma once

#include <cmath>

#include "core/geometry/pose2.hpp"

namespace dpcr {

class OdometryStall {
 public:
  // Once per scan with the wheels' step since the last scan, before the prediction; `still`: the
  // wheels' pose is exactly the last scan's; `expected`: the step a steady robot would have made
  // (the constant velocity's). Returns the step to predict with and tells whether it took the
  // stall out of it: when the stall moved the robot at least kMinMotion and the step less what
  // was registered meanwhile is nearer the expected step than the step itself. Wheels that resume
  // where they stopped (a wheel board that was silent, a CAN bus that was down, counting on from
  // its last pose) make a step of their own size, and that one is kept.
  Pose2 Step(const Pose2& wheel_step, bool still, const Pose2& expected, bool* caught_up) {
    *caught_up = false;
    Pose2 step = wheel_step;
    if (!still && stalled_ && (std::hypot(motion_.x, motion_.y) >= kMinMotionM || std::fabs(motion_.theta) >= kMinMotionRad)) {
      const Pose2 less = motion_.Inverse() * wheel_step;
      if (Distance(less, expected) < Distance(wheel_step, expected)) {
        step = less;
        *caught_up = true;
      }
    }
    if (!still) motion_ = Pose2::Identity();
    stalled_ = still;
    return step;
  }
  // Once per scan after its registration: the registered step (in the earlier scan's frame).
  void AddRegistered(const Pose2& step) {
    if (stalled_) motion_ = motion_ * step;
  }
  // A break in tracking (lost, a restart): what was registered no longer says where the robot went.
  void Reset() { *this = OdometryStall(); }

  // Below these the stall is a standing robot's jitter (intel.clf: 43 stalls, all under 1 cm and
  // 1.5°), and taking it out would only add the registration's noise to the next step.
  static constexpr float kMinMotionM = 0.05f;
  static constexpr float kMinMotionRad = 0.05f;

 private:
  // Metres and radians alike (a radian of turn moves a point a metre from the robot by a metre).
  static float Distance(const Pose2& a, const Pose2& b) {
    return std::hypot(a.x - b.x, a.y - b.y) + std::fabs(NormalizeAngle(a.theta - b.theta));
  }
  Pose2 motion_;  // registered since the wheels' pose last changed
  bool stalled_ = false;
};

}  // namespace dpcr
