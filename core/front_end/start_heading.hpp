// The run's start heading, refined with the gyro once the first map has matured.
//
// The first scan is the world frame's only reference when mapping begins: the first turn's scans
// are registered to its walls, and a wall fitted to twenty returns with the range noise of a
// low-cost lidar is tilted by up to half a degree. The whole first map inherits that tilt, and the
// start pose is then off the map by it (XV-11, apartment seeds 1-10: -0.44 to +0.55 degrees;
// docs/back-end.md). Later scans know better where the start was, through the gyro: over a window,
// each accepted scan's registered heading minus the gyro's turn since the start is the start's
// heading in the map, minus the gyro's bias times the time, plus noise. A least-squares line
// r(t) = offset - bias * t over the window gives the offset at t = 0.
//
// The fit is refused when it has too few scans, a bias no gyro has, or an offset beyond what noise
// makes; an offset below min_offset_rad (the fit's own error, measured) is left alone.
#pragma once

#include <cstdint>

#include "core/config.hpp"

namespace dpcr {

class StartHeadingFit {
 public:
  enum class State : std::uint8_t { kIdle, kFitting, kDone };
  enum class Outcome : std::uint8_t {
    kNone,       // not fitted (no gyro, a loaded map, disabled) or not yet finished
    kApplied,    // offset() is the start's heading in the map minus its recorded one
    kSmall,      // fitted, under min_offset_rad: the start is kept
    kRefused,    // too few scans, an implausible bias or offset
    kAborted,    // the gyro's turn was interrupted or the robot lost itself within the window
  };

  void Reset() { *this = StartHeadingFit(); }
  // The start scan: its stamp and world heading. Only from kIdle.
  void Begin(std::int64_t stamp_us, float heading_rad);
  // Each prediction's heading step measured by the gyro after the start (kFitting only).
  void AddGyroTurn(float step_rad);
  // An accepted registration's world heading. Returns true when this scan closes the window: the
  // fit is then done (outcome() says how).
  bool AddScan(std::int64_t stamp_us, float heading_rad, const StartHeadingConfig& config);
  // The gyro's turn or the tracking broke within the window: nothing is applied.
  void Abort();

  State state() const { return state_; }
  Outcome outcome() const { return outcome_; }
  std::int64_t start_stamp_us() const { return start_us_; }
  float offset_rad() const { return offset_rad_; }  // the fitted offset (kApplied, kSmall, kRefused)
  float bias_rad_s() const { return bias_rad_s_; }  // the gyro's, fitted: its turn over the registered one, per second
  std::uint32_t samples() const { return n_; }

 private:
  void Finish(const StartHeadingConfig& config);

  State state_ = State::kIdle;
  Outcome outcome_ = Outcome::kNone;
  std::uint32_t n_ = 0;
  std::int64_t start_us_ = 0;
  float start_heading_ = 0.0f;
  float gyro_turn_ = 0.0f;  // unwrapped, since the start
  // Least-squares sums over (t, r).
  float st_ = 0.0f, stt_ = 0.0f, sr_ = 0.0f, str_ = 0.0f;
  float offset_rad_ = 0.0f;
  float bias_rad_s_ = 0.0f;
};

}  // namespace dpcr
