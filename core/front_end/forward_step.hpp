// The constant-velocity guess of a differential drive moves along the robot's heading, never
// sideways. Where no wheel measures the translation (a gyro alone, heading-only ticks), the guess is
// the last registered step. A degenerate registration (a doorway into a room longer than the lidar's
// reach: nothing across the way) holds the pose only across its weak direction; along it, the step
// is the prior's echo plus whatever the registration let slide, sideways and backwards, and the
// next scans registered close to that: the estimate drove off while the robot drove on (office,
// XV-11, gyro alone, seed 2: 7 m off). A vacuum's wheels cannot slide sideways, so after such a
// registration the guess keeps only the step's part along the robot's heading halfway through it:
// the chord of an arc, as a robot that drives and turns at once draws.
#pragma once

#include <cmath>

#include "core/geometry/pose2.hpp"

namespace dpcr {

// `step` (in the earlier pose's frame) without its part across the mid-step heading; the turn as it was.
inline Pose2 ForwardStep(const Pose2& step) {
  const float c = std::cos(0.5f * step.theta), s = std::sin(0.5f * step.theta);
  const float forward = c * step.x + s * step.y;
  return Pose2{c * forward, s * forward, step.theta};
}

}  // namespace dpcr
