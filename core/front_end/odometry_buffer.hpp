// Recent wheel-odometry samples, for the odometry pose at any scan or beam time.
// Samples must arrive in time order; a sample stamped earlier than the newest one restarts
// the buffer from it (counted), because logs such as intel.clf step back in time and the
// file order, not the stamps, is the physical order.
#pragma once

#include <cstdint>

#include "core/front_end/odometry.hpp"
#include "core/base/ring_buffer.hpp"

namespace dpcr {

class OdometryBuffer {
 public:
  void Add(const OdometrySample& sample);
  void Clear() {
    samples_.clear();
    gyro_yaw_.clear();
    yaw_ = 0.0f;
  }
  bool empty() const { return samples_.empty(); }
  const OdometrySample& newest() const { return samples_.back(); }
  const OdometrySample& oldest() const { return samples_.front(); }

  // Interpolated between the bracketing samples; before the oldest: the oldest; after the newest:
  // extrapolated at the last velocity for at most kMaxExtrapolationUs, then held.
  Pose2 PoseAt(std::int64_t stamp_us) const;

  std::uint32_t steps_back() const { return steps_back_; }

  // The gyro's integrated yaw (rad, wrapped) at `stamp_us`: each sample's gyro_yaw_rate is taken
  // as the mean rate over the interval that ends at it (as the wheel board and dpcr-sim send it).
  // Interpolated between samples; after the newest, extrapolated at its rate like PoseAt. False
  // when the bracketing samples carry no gyro rate, or `stamp_us` is before the oldest sample.
  // Only differences between two stamps mean something.
  bool GyroYawAt(std::int64_t stamp_us, float* yaw) const;

  // 64 samples at 100 Hz cover 0.64 s, more than one revolution of a 5-10 Hz lidar.
  static constexpr int kCapacity = 64;
  static constexpr std::int64_t kMaxExtrapolationUs = 100000;
  // Below this spacing two samples give no usable velocity (intel.clf jitters to ~0 ms).
  static constexpr std::int64_t kMinVelocitySpanUs = 5000;
  // A velocity is carried ahead at most this many times the span it was measured over, when the
  // buffer reaches back that far (a wheel board at 100 Hz: up to 20 ms ahead on its 10 ms step).
  static constexpr std::int64_t kMaxExtrapolationRatio = 2;

 private:
  RingBuffer<OdometrySample, kCapacity> samples_;
  RingBuffer<float, kCapacity> gyro_yaw_;  // integrated yaw at each sample (NaN: no gyro)
  float yaw_ = 0.0f;
  std::uint32_t steps_back_ = 0;
};

// Linear interpolation of poses; the angle along the shorter way.
Pose2 Interpolate(const Pose2& a, const Pose2& b, float t);

}  // namespace dpcr
