// Wheel samples that carry only the heading: the gyro's rate integrated into the wheel pose's yaw,
// no translation and no gyro rate (a recorder that turned its IMU's yaw into wheel ticks, as real
// XV-11 recordings were converted). dpcr-sim --odometry heading-ticks and the tests' robots.
#pragma once

#include <cstdint>

#include "core/front_end/odometry.hpp"
#include "core/geometry/pose2.hpp"

namespace dpcr::sim {

class HeadingOnlyTicks {
 public:
  // Rewrites a simulated sample (with its gyro rate) in place.
  void Apply(OdometrySample* sample) {
    // The rate is the mean over the interval that ends at the sample (core/front_end/odometry_buffer.hpp).
    if (last_us_ >= 0) yaw_ = NormalizeAngle(yaw_ + sample->gyro_yaw_rate * static_cast<float>(sample->stamp_us - last_us_) * 1e-6f);
    last_us_ = sample->stamp_us;
    sample->pose = Pose2{0.0f, 0.0f, yaw_};
    sample->has_gyro = false;
  }

 private:
  float yaw_ = 0.0f;
  std::int64_t last_us_ = -1;
};

}  // namespace dpcr::sim
