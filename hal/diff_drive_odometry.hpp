// Differential-drive odometry from cumulative wheel ticks: exact circular-arc integration
// (constant wheel speeds between samples), accumulated in double so long runs do not drift
// from rounding.
#pragma once

#include <cstdint>

#include "core/front_end/odometry.hpp"
#include "core/geometry/pose2.hpp"
#include "core/base/status.hpp"
#include "hal/wheel_can_protocol.hpp"

namespace dpcr {

struct DiffDriveConfig {
  float wheel_radius_m = 0.035f;   // typical vacuum drive wheel
  float track_width_m = 0.235f;    // distance between the wheel contact points
  float ticks_per_rev = 1000.0f;   // encoder ticks per wheel revolution (after gearing)
  [[nodiscard]] Status Validate() const;
};

class DiffDriveOdometry {
 public:
  explicit DiffDriveOdometry(const DiffDriveConfig& config = DiffDriveConfig());

  // Integrates to these cumulative ticks; the first call only sets the reference.
  // Returns the absolute wheel pose stamped `stamp_us` (gyro fields unset).
  OdometrySample Update(const WheelTicks& ticks, std::int64_t stamp_us);
  Pose2 pose() const;
  void Reset();
  // After a gap in the ticks: the next call only sets the reference again, the pose kept.
  void Resume() { started_ = false; }

 private:
  DiffDriveConfig config_;
  bool started_ = false;
  std::int64_t last_left_ = 0;
  std::int64_t last_right_ = 0;
  double x_ = 0.0;
  double y_ = 0.0;
  double theta_ = 0.0;
};

}  // namespace dpcr
