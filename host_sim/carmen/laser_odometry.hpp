// The odometry pose of a CARMEN laser record is the logger's newest one when the scan came. When
// no odometry message arrived between two scans it is repeated exactly, and the motion of that
// time arrives in one step with a later scan: mit-csail.clf repeats 87 poses, then steps by up
// to 0.85 m and 50 deg in 0.2 s. A repeated pose is therefore no measurement (a robot at rest
// loses nothing by it: the mapper holds the pose once its odometry stops, OdometryBuffer), and
// the mapper is not told "no motion" for a scan that moved.
#pragma once

#include "core/geometry/pose2.hpp"

namespace dpcr::carmen {

class LaserOdometry {
 public:
  // False when `pose` repeats the previous record's exactly.
  bool IsNewMeasurement(const Pose2& pose) {
    const bool repeated = have_last_ && pose.x == last_.x && pose.y == last_.y && pose.theta == last_.theta;
    last_ = pose;
    have_last_ = true;
    if (repeated) ++repeats_;
    return !repeated;
  }
  long repeats() const { return repeats_; }

 private:
  Pose2 last_;
  bool have_last_ = false;
  long repeats_ = 0;
};

}  // namespace dpcr::carmen
