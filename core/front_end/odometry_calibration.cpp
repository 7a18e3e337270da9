#include "core/front_end/odometry_calibration.hpp"

#include <algorithm>
#include <cmath>

namespace dpcr {

void OdometryCalibration::Add(const Pose2& registered, const Pose2& wheels) {
  const float wheels_m = std::hypot(wheels.x, wheels.y);
  if (!(wheels_m <= kMaxStepM) || !(std::fabs(wheels.theta) <= kMaxStepRad)) return;
  if (!std::isfinite(registered.x) || !std::isfinite(registered.y) || !std::isfinite(registered.theta)) return;
  const Pose2 predicted = Apply(wheels);
  if (std::hypot(registered.x - predicted.x, registered.y - predicted.y) > kOutlierM ||
      std::fabs(NormalizeAngle(registered.theta - predicted.theta)) > kOutlierRad) {
    return;
  }
  const float k = kMemory;
  sum_reg_dot_wheels_ = k * sum_reg_dot_wheels_ + registered.x * wheels.x + registered.y * wheels.y;
  sum_wheels_sq_ = k * sum_wheels_sq_ + wheels_m * wheels_m;
  const float r = wheels.theta;
  sum_rr_ = k * sum_rr_ + r * r;
  sum_rt_ = k * sum_rt_ + r * registered.theta;
  distance_m_ = k * distance_m_ + wheels_m;
  turned_rad_ = k * turned_rad_ + std::fabs(r);
}

float OdometryCalibration::translation_scale() const {
  if (distance_m_ < kMinDistanceM || !(sum_wheels_sq_ > 0.0f)) return 1.0f;
  return std::clamp(sum_reg_dot_wheels_ / sum_wheels_sq_, 1.0f - kMaxScaleError, 1.0f + kMaxScaleError);
}

float OdometryCalibration::turn_scale() const {
  if (turned_rad_ < kMinTurnRad || !(sum_rr_ > 0.0f)) return 1.0f;
  return std::clamp(sum_rt_ / sum_rr_, 1.0f - kMaxScaleError, 1.0f + kMaxScaleError);
}

Pose2 OdometryCalibration::Apply(const Pose2& wheels) const {
  const float kt = translation_scale();
  return Pose2{kt * wheels.x, kt * wheels.y, turn_scale() * wheels.theta};
}

}  // namespace dpcr
