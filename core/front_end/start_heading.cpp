#include "core/front_end/start_heading.hpp"

#include <cmath>

#include "core/geometry/pose2.hpp"

namespace dpcr {

void StartHeadingFit::Begin(std::int64_t stamp_us, float heading_rad) {
  if (state_ != State::kIdle) return;
  state_ = State::kFitting;
  start_us_ = stamp_us;
  start_heading_ = last_heading_ = heading_rad;
}

bool StartHeadingFit::AddScan(const Step& step, bool wheel_turns, const StartHeadingConfig& config) {
  if (state_ != State::kFitting) return false;
  // An unmeasured turn is taken as registered: r does not change across it.
  sensor_turn_ += step.turn_measured ? step.turn_rad : NormalizeAngle(step.heading_rad - last_heading_);
  ++steps_;
  if (step.turn_measured) ++measured_;
  last_heading_ = step.heading_rad;
  const float t = static_cast<float>(step.stamp_us - start_us_) * 1e-6f;
  if (step.accepted && t >= config.skip_s) {
    // Headings and the sensor's turn both grow without bound; their difference stays near zero.
    const float r = NormalizeAngle(NormalizeAngle(step.heading_rad - start_heading_) - NormalizeAngle(sensor_turn_));
    ++n_;
    st_ += t;
    stt_ += t * t;
    sr_ += r;
    str_ += t * r;
  }
  if (t < config.window_s) return false;
  Finish(wheel_turns, config);
  return true;
}

void StartHeadingFit::Abort() {
  if (state_ != State::kFitting) return;
  state_ = State::kDone;
  outcome_ = Outcome::kAborted;
}

void StartHeadingFit::Finish(bool wheel_turns, const StartHeadingConfig& config) {
  state_ = State::kDone;
  const float n = static_cast<float>(n_);
  const float det = n * stt_ - st_ * st_;
  // Too few scans, all at one instant (no line), or mostly turns that no sensor measured.
  if (n_ < static_cast<std::uint32_t>(config.min_samples) || !(det > 1e-3f * n * n) || 2 * measured_ < steps_) {
    outcome_ = Outcome::kRefused;
    return;
  }
  offset_rad_ = (stt_ * sr_ - st_ * str_) / det;
  bias_rad_s_ = -(n * str_ - st_ * sr_) / det;  // r falls as the sensor's turn runs ahead
  if (wheel_turns) {
    outcome_ = Outcome::kWheels;
  } else if (!(std::fabs(bias_rad_s_) <= config.max_bias_rad_s) || !(std::fabs(offset_rad_) <= config.max_offset_rad)) {
    outcome_ = Outcome::kRefused;
  } else {
    outcome_ = std::fabs(offset_rad_) < config.min_offset_rad ? Outcome::kSmall : Outcome::kApplied;
  }
}

}  // namespace dpcr
