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
// A step whose turn nothing measured (odometry that starts after the lidar, a gyro sample missing,
// the switch from heading-only wheel ticks to their yaw rate) is bridged with the registered turn:
// it adds nothing to the fit. The fit is refused when it has too few scans, mostly unmeasured
// turns, a bias no gyro has, or an offset beyond what noise makes,
// and when the turns came from wheels that also measure the translation (their heading errs with
// the turn, through the track width, not with time); an offset below min_offset_rad (the fit's own
// error, measured) is left alone.
#pragma once

#include <cstdint>

#include "core/config.hpp"

namespace dpcr {

class StartHeadingFit {
 public:
  enum class State : std::uint8_t { kIdle, kFitting, kDone };
  enum class Outcome : std::uint8_t {
    kNone,     // not fitted (no heading sensor, a loaded map, disabled) or not yet finished
    kApplied,  // offset_rad() is the start's heading in the map minus its recorded one
    kSmall,    // fitted, under min_offset_rad: the start is kept
    kRefused,  // too few scans, mostly unmeasured turns, an implausible bias or offset
    kAborted,  // the robot lost itself or a scan left the front end's tracking within the window
    kWheels,   // the turns came from wheels that measure the translation too
  };
  // One scan after the start: its world heading, the turn predicted for it since the last scan and
  // whether a sensor measured that turn, whether its registration was accepted.
  struct Step {
    std::int64_t stamp_us = 0;
    float heading_rad = 0.0f;
    float turn_rad = 0.0f;
    bool turn_measured = false;
    bool accepted = false;
  };

  void Reset() { *this = StartHeadingFit(); }
  // The start scan: its stamp and world heading. Only from kIdle.
  void Begin(std::int64_t stamp_us, float heading_rad);
  // Every scan after the start, accepted or not (kFitting only). `wheel_turns`: the turns so far
  // came from wheels that measure the translation too. Returns true when this scan closes the
  // window: the fit is then done (outcome() says how).
  bool AddScan(const Step& step, bool wheel_turns, const StartHeadingConfig& config);
  // The robot lost itself, or a scan went where the fit cannot follow: nothing is applied.
  void Abort();

  State state() const { return state_; }
  Outcome outcome() const { return outcome_; }
  std::int64_t start_stamp_us() const { return start_us_; }
  float offset_rad() const { return offset_rad_; }  // the fitted offset (kApplied, kSmall, kRefused, kWheels)
  float bias_rad_s() const { return bias_rad_s_; }  // the sensor's, fitted: its turn over the registered one, per second
  std::uint32_t samples() const { return n_; }

 private:
  void Finish(bool wheel_turns, const StartHeadingConfig& config);

  State state_ = State::kIdle;
  Outcome outcome_ = Outcome::kNone;
  std::uint32_t n_ = 0;
  std::uint32_t steps_ = 0, measured_ = 0;  // scans after the start, and those whose turn a sensor measured
  std::int64_t start_us_ = 0;
  float start_heading_ = 0.0f;
  float last_heading_ = 0.0f;
  float sensor_turn_ = 0.0f;  // unwrapped, since the start
  // Least-squares sums over (t, r).
  float st_ = 0.0f, stt_ = 0.0f, sr_ = 0.0f, str_ = 0.0f;
  float offset_rad_ = 0.0f;
  float bias_rad_s_ = 0.0f;
};

}  // namespace dpcr
