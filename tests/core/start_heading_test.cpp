// StartHeadingFit: the start's heading in the map, fitted from the registered headings of the
// scans after it and the gyro's turn since it; unmeasured turns are bridged; a small offset, too
// few scans, an implausible gyro, wheels' turns and a broken window change nothing.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>

#include "core/front_end/start_heading.hpp"
#include "core/geometry/pose2.hpp"

namespace {

using dpcr::StartHeadingConfig;
using dpcr::StartHeadingFit;
using Outcome = dpcr::StartHeadingFit::Outcome;

struct Run {
  float start_heading = 0.3f;
  float offset_rad = 0.008f;    // the later scans' headings in the map minus the start's turn
  float gyro_bias_rad_s = 0.002f;
  float seconds = 35.0f;
  float turn_rate_rad_s = 0.6f;  // turning the whole time: headings wrap, the gyro's turn passes 2 pi
  float noise_rad = 0.002f;      // registration noise, alternating in sign
  int scan_rate_hz = 5;
};

// Feeds a run at the scan rate, the turn measured for each scan (every `unmeasured_every`-th not);
// returns the scan that closed the window (-1: none).
int Feed(StartHeadingFit* fit, const Run& run, const StartHeadingConfig& config, bool wheel_turns = false,
         int unmeasured_every = 0) {
  const std::int64_t period_us = 1000000 / run.scan_rate_hz;
  fit->Begin(1'000'000, run.start_heading);
  float truth_turn = 0.0f;
  const int scans = static_cast<int>(run.seconds * static_cast<float>(run.scan_rate_hz));
  for (int i = 1; i <= scans; ++i) {
    const float dt = 1.0f / static_cast<float>(run.scan_rate_hz);
    truth_turn += run.turn_rate_rad_s * dt;
    const float noise = (i % 2 == 0 ? 1.0f : -1.0f) * run.noise_rad;
    StartHeadingFit::Step step;
    step.stamp_us = 1'000'000 + i * period_us;
    step.heading_rad = dpcr::NormalizeAngle(run.start_heading + truth_turn + run.offset_rad + noise);
    step.turn_rad = (run.turn_rate_rad_s + run.gyro_bias_rad_s) * dt;
    step.turn_measured = unmeasured_every == 0 || i % unmeasured_every != 0;
    step.accepted = true;
    if (fit->AddScan(step, wheel_turns, config)) return i;
  }
  return -1;
}

}  // namespace

TEST_CASE("A start off the later scans by half a degree is fitted and applied", "[start_heading]") {
  StartHeadingFit fit;
  const StartHeadingConfig config;
  const Run run;
  CHECK(Feed(&fit, run, config) == 150);  // 30 s at 5 Hz
  CHECK(fit.state() == StartHeadingFit::State::kDone);
  REQUIRE(fit.outcome() == Outcome::kApplied);
  CHECK(fit.offset_rad() == Approx(run.offset_rad).margin(3e-4));
  CHECK(fit.bias_rad_s() == Approx(run.gyro_bias_rad_s).margin(5e-5));
  CHECK(fit.samples() == 146u);  // from 1 s on: the first turn skipped
}

TEST_CASE("A start heading offset the other way is fitted with its sign", "[start_heading]") {
  StartHeadingFit fit;
  Run run;
  run.offset_rad = -0.006f;
  run.gyro_bias_rad_s = -0.004f;
  (void)Feed(&fit, run, StartHeadingConfig{});
  REQUIRE(fit.outcome() == Outcome::kApplied);
  CHECK(fit.offset_rad() == Approx(run.offset_rad).margin(3e-4));
  CHECK(fit.bias_rad_s() == Approx(run.gyro_bias_rad_s).margin(5e-5));
}

TEST_CASE("An offset under the fits own error is left alone", "[start_heading]") {
  StartHeadingFit fit;
  Run run;
  run.offset_rad = 0.001f;  // 0.06 degrees
  (void)Feed(&fit, run, StartHeadingConfig{});
  CHECK(fit.outcome() == Outcome::kSmall);
  CHECK(fit.offset_rad() == Approx(run.offset_rad).margin(3e-4));
}

TEST_CASE("Too few scans an implausible gyro bias or offset refuse the fit", "[start_heading]") {
  StartHeadingConfig config;
  Run run;
  SECTION("too few scans") {
    run.scan_rate_hz = 1;
    config.min_samples = 40;  // 30 at 1 Hz
  }
  SECTION("a gyro off by 2 degrees a second") { run.gyro_bias_rad_s = 0.035f; }
  SECTION("an offset of 5 degrees") { run.offset_rad = 0.087f; }
  StartHeadingFit fit;
  (void)Feed(&fit, run, config);
  CHECK(fit.outcome() == Outcome::kRefused);
}

TEST_CASE("Turns no sensor measured are bridged by the registered ones", "[start_heading]") {
  // One scan in 25 without a measured turn (a missing gyro sample, the switch from heading-only
  // wheel ticks to their yaw rate): the fit loses those steps, not the offset. (Each bridge takes
  // the registration's noise on both sides into every later r: a few, not a scan in ten.)
  StartHeadingFit fit;
  const Run run;
  (void)Feed(&fit, run, StartHeadingConfig{}, false, 25);
  REQUIRE(fit.outcome() == Outcome::kApplied);
  // The bias over a bridged step is lost too: within 0.09 deg (a turn left out would be 7 deg).
  CHECK(fit.offset_rad() == Approx(run.offset_rad).margin(1.5e-3));
}

TEST_CASE("Turns mostly unmeasured are not fitted", "[start_heading]") {
  // No sensor but the lidar: every r is bridged to the first, and a fit of them says nothing.
  StartHeadingFit fit;
  (void)Feed(&fit, Run{}, StartHeadingConfig{}, false, 1);
  CHECK(fit.outcome() == Outcome::kRefused);
}

TEST_CASE("Turns from wheels that measure the translation too are not fitted", "[start_heading]") {
  StartHeadingFit fit;
  (void)Feed(&fit, Run{}, StartHeadingConfig{}, true);
  CHECK(fit.outcome() == Outcome::kWheels);
}

TEST_CASE("A window the tracking broke applies nothing", "[start_heading]") {
  StartHeadingFit fit;
  fit.Begin(0, 0.0f);
  fit.Abort();
  CHECK(fit.outcome() == Outcome::kAborted);
  StartHeadingFit::Step late;
  late.stamp_us = 40'000'000;
  late.accepted = true;
  CHECK_FALSE(fit.AddScan(late, false, StartHeadingConfig{}));
  CHECK(fit.outcome() == Outcome::kAborted);
  CHECK(fit.samples() == 0u);
}

TEST_CASE("A fit never begun or disabled stays idle", "[start_heading]") {
  StartHeadingFit fit;
  StartHeadingFit::Step late;
  late.stamp_us = 40'000'000;
  late.accepted = true;
  CHECK_FALSE(fit.AddScan(late, false, StartHeadingConfig{}));
  fit.Abort();
  CHECK(fit.state() == StartHeadingFit::State::kIdle);
  CHECK(fit.outcome() == Outcome::kNone);
}
