#include "hal/wheel_lift_state.hpp"

namespace dpcr {

std::int64_t DeviceTimeDifferenceUs(std::int64_t a_us, std::int64_t b_us) {
  const std::int64_t half = kWheelTimeWrapUnits / 2;
  const std::int64_t units = (a_us - b_us) / kWheelTimeUnitUs;
  // Into [-half, half): the remainder's sign follows the dividend's, hence the double modulo.
  const std::int64_t wrapped = ((units + half) % kWheelTimeWrapUnits + kWheelTimeWrapUnits) % kWheelTimeWrapUnits - half;
  return wrapped * kWheelTimeUnitUs;
}

void WheelLiftState::Observe(const RobotStatus& status) {
  previous_ = latest_;
  latest_ = status;
  if (observed_ < 2) ++observed_;
}

bool WheelLiftState::LiftedAt(std::int64_t device_time_us) const {
  if (observed_ == 0) return false;
  const std::int64_t since_latest = DeviceTimeDifferenceUs(device_time_us, latest_.device_time_us);
  if (since_latest >= 0) return since_latest <= kStaleUs && latest_.lifted;
  // Taken before the latest status frame: the state before it (unknown before the first frame).
  return observed_ == 2 && previous_.lifted &&
         DeviceTimeDifferenceUs(device_time_us, previous_.device_time_us) <= kStaleUs;
}

}  // namespace dpcr
