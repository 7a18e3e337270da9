// The constant-velocity guess of a robot whose wheels do not measure the translation (a gyro
// alone, heading-only ticks): its velocity changes from scan to scan by no more than the robot can
// accelerate. A registration that moves the pose against the guess is mostly a correction of where
// the robot is, not a new speed: taken whole as the next step's velocity (x / dt), a 7 cm
// correction after an in-place turn became 0.34 m/s backwards, each sparse scan in a lane then
// registered close to that guess (the lane gives little hold along the way), and the estimate
// drove backwards while the robot drove on (XV-11, half its readings, 3.5-5 Hz, gyro alone, seed
// 5: 1.3 m off within 2 s). The pose keeps the registration's answer; only the velocity is limited.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/geometry/pose2.hpp"

namespace dpcr {

// `step`, the registered motion over `dt_us` (in the earlier scan's frame), with its velocity
// moved from the last step's (`last_step` over `last_us`; none yet: standing) by at most
// `max_accel_mps2` × dt. The turn is left as registered. `max_accel_mps2` <= 0: no limit.
inline Pose2 LimitAcceleration(const Pose2& last_step, std::int64_t last_us, const Pose2& step, std::int64_t dt_us,
                               float max_accel_mps2) {
  if (max_accel_mps2 <= 0.0f || dt_us <= 0) return step;
  const float dt = static_cast<float>(dt_us) * 1e-6f;
  const float last_s = static_cast<float>(last_us) * 1e-6f;
  const float vx = last_us > 0 ? last_step.x / last_s : 0.0f;
  const float vy = last_us > 0 ? last_step.y / last_s : 0.0f;
  float dvx = step.x / dt - vx, dvy = step.y / dt - vy;
  const float dv = std::hypot(dvx, dvy), most = max_accel_mps2 * dt;
  if (!(dv > most)) return step;  // within the limit (a NaN step is the caller's to judge)
  dvx *= most / dv;
  dvy *= most / dv;
  return Pose2{(vx + dvx) * dt, (vy + dvy) * dt, step.theta};
}

}  // namespace dpcr
