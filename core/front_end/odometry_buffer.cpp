#include "core/front_end/odometry_buffer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dpcr {

Pose2 Interpolate(const Pose2& a, const Pose2& b, float t) {
  return Pose2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y),
               NormalizeAngle(a.theta + t * NormalizeAngle(b.theta - a.theta))};
}

void OdometryBuffer::Add(const OdometrySample& sample) {
  if (!samples_.empty() && sample.stamp_us < samples_.back().stamp_us) {
    ++steps_back_;
    samples_.clear();
    gyro_yaw_.clear();
  }
  float yaw = std::numeric_limits<float>::quiet_NaN();
  if (sample.has_gyro) {
    const bool integrate = !samples_.empty() && !std::isnan(gyro_yaw_.back());
    if (integrate) {
      const float dt = static_cast<float>(sample.stamp_us - samples_.back().stamp_us) * 1e-6f;
      yaw_ = NormalizeAngle(yaw_ + sample.gyro_yaw_rate * dt);
    }
    yaw = yaw_;
  }
  if (samples_.full()) {
    samples_.pop_front();
    gyro_yaw_.pop_front();
  }
  (void)samples_.push_back(sample);
  (void)gyro_yaw_.push_back(yaw);
}

bool OdometryBuffer::GyroYawAt(std::int64_t stamp_us, float* yaw) const {
  const std::size_t n = samples_.size();
  if (n == 0 || stamp_us < samples_[0].stamp_us) return false;
  const OdometrySample& newest = samples_[n - 1];
  if (stamp_us >= newest.stamp_us) {
    if (std::isnan(gyro_yaw_[n - 1])) return false;
    std::int64_t ahead = stamp_us - newest.stamp_us;
    if (ahead > kMaxExtrapolationUs) ahead = kMaxExtrapolationUs;
    *yaw = NormalizeAngle(gyro_yaw_[n - 1] + newest.gyro_yaw_rate * static_cast<float>(ahead) * 1e-6f);
    return true;
  }
  for (std::size_t i = n - 1; i-- > 0;) {
    if (samples_[i].stamp_us > stamp_us) continue;
    const float a = gyro_yaw_[i], b = gyro_yaw_[i + 1];
    if (std::isnan(a) || std::isnan(b)) return false;
    const std::int64_t span = samples_[i + 1].stamp_us - samples_[i].stamp_us;
    const float t = span > 0 ? static_cast<float>(stamp_us - samples_[i].stamp_us) / static_cast<float>(span) : 1.0f;
    *yaw = NormalizeAngle(a + t * NormalizeAngle(b - a));
    return true;
  }
  return false;
}

Pose2 OdometryBuffer::PoseAt(std::int64_t stamp_us) const {
  if (samples_.empty()) return Pose2::Identity();
  const std::size_t n = samples_.size();
  const OdometrySample& newest = samples_[n - 1];
  if (stamp_us >= newest.stamp_us) {
    // Extrapolate from the newest sample and one far enough back to give a velocity: at least
    // kMinVelocitySpanUs, and at least 1 / kMaxExtrapolationRatio of the way ahead, when the
    // buffer holds it. A velocity measured over a few milliseconds and carried 100 ms ahead
    // multiplies the stamps' jitter: intel.clf logs bursts of records 1 ms apart that span a
    // second of motion (35 m/s over 7 ms), and a robot standing after one was predicted 2.6 m down
    // a corridor, where a look-alike place took it.
    std::int64_t ahead = stamp_us - newest.stamp_us;
    if (ahead > kMaxExtrapolationUs) ahead = kMaxExtrapolationUs;
    const std::int64_t wanted_span = std::max(kMinVelocitySpanUs, ahead / kMaxExtrapolationRatio);
    std::size_t from = n;  // the sample the velocity is measured from
    for (std::size_t i = n - 1; i-- > 0;) {
      const std::int64_t span = newest.stamp_us - samples_[i].stamp_us;
      if (span < kMinVelocitySpanUs) continue;
      from = i;
      if (span >= wanted_span) break;
    }
    if (from == n) return newest.pose;
    const Pose2 step = Between(samples_[from].pose, newest.pose);
    const float f = static_cast<float>(ahead) / static_cast<float>(newest.stamp_us - samples_[from].stamp_us);
    return newest.pose * Interpolate(Pose2::Identity(), step, f);
  }
  if (stamp_us <= samples_[0].stamp_us) return samples_[0].pose;
  // Newest first: scans ask about the recent past.
  for (std::size_t i = n - 1; i-- > 0;) {
    const OdometrySample& a = samples_[i];
    if (a.stamp_us <= stamp_us) {
      const OdometrySample& b = samples_[i + 1];
      const std::int64_t span = b.stamp_us - a.stamp_us;
      if (span <= 0) return b.pose;
      const float t = static_cast<float>(stamp_us - a.stamp_us) / static_cast<float>(span);
      return Interpolate(a.pose, b.pose, t);
    }
  }
  return samples_[0].pose;
}

}  // namespace dpcr
