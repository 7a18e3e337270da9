#include "core/front_end/odometry_buffer.hpp"

namespace dpcr {

Pose2 Interpolate(const Pose2& a, const Pose2& b, float t) {
  return Pose2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y),
               NormalizeAngle(a.theta + t * NormalizeAngle(b.theta - a.theta))};
}

void OdometryBuffer::Add(const OdometrySample& sample) {
  if (!samples_.empty() && sample.stamp_us < samples_.back().stamp_us) {
    ++steps_back_;
    samples_.clear();
  }
  if (samples_.full()) samples_.pop_front();
  (void)samples_.push_back(sample);
}

Pose2 OdometryBuffer::PoseAt(std::int64_t stamp_us) const {
  if (samples_.empty()) return Pose2::Identity();
  const std::size_t n = samples_.size();
  const OdometrySample& newest = samples_[n - 1];
  if (stamp_us >= newest.stamp_us) {
    // Extrapolate from the newest sample and the last one far enough back to give a velocity.
    for (std::size_t i = n - 1; i-- > 0;) {
      const std::int64_t span = newest.stamp_us - samples_[i].stamp_us;
      if (span < kMinVelocitySpanUs) continue;
      std::int64_t ahead = stamp_us - newest.stamp_us;
      if (ahead > kMaxExtrapolationUs) ahead = kMaxExtrapolationUs;
      const Pose2 step = Between(samples_[i].pose, newest.pose);
      const float f = static_cast<float>(ahead) / static_cast<float>(span);
      return newest.pose * Interpolate(Pose2::Identity(), step, f);
    }
    return newest.pose;
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
