#include <catch2/catch.hpp>

#include <cmath>

#include "hal/diff_drive_odometry.hpp"

using dpcr::DiffDriveConfig;
using dpcr::DiffDriveOdometry;
using dpcr::WheelTicks;

namespace {
constexpr double kTwoPi = 6.283185307179586;
}

TEST_CASE("odometry follows a closed-form arc") {
  DiffDriveConfig c;
  c.wheel_radius_m = 0.035f;
  c.track_width_m = 0.24f;
  c.ticks_per_rev = 1000.0f;
  REQUIRE(c.Validate() == dpcr::Status::kOk);
  const double m_per_tick = kTwoPi * 0.035 / 1000.0;
  // Per step: left 8 ticks, right 12 ticks, 400 steps.
  const int steps = 400;
  DiffDriveOdometry odo(c);
  WheelTicks t;
  static_cast<void>(odo.Update(t, 0));
  for (int i = 1; i <= steps; ++i) {
    t.left_ticks += 8;
    t.right_ticks += 12;
    static_cast<void>(odo.Update(t, i * 10000));
  }
  const double dl = steps * 8 * m_per_tick;
  const double dr = steps * 12 * m_per_tick;
  const double theta = (dr - dl) / 0.24;
  const double radius = 0.24 / 2 * (dr + dl) / (dr - dl);
  const dpcr::Pose2 p = odo.pose();
  CHECK(p.x == Approx(radius * std::sin(theta)).margin(1e-5));
  CHECK(p.y == Approx(radius * (1 - std::cos(theta))).margin(1e-5));
  CHECK(p.theta == Approx(std::remainder(theta, kTwoPi)).margin(1e-5));
}

TEST_CASE("odometry: straight line, spin in place and a full circle") {
  DiffDriveConfig c;
  c.wheel_radius_m = 0.05f;
  c.track_width_m = 0.2f;
  c.ticks_per_rev = 360.0f;
  DiffDriveOdometry odo(c);
  WheelTicks t;
  static_cast<void>(odo.Update(t, 0));
  t.left_ticks = t.right_ticks = 360;  // one wheel turn forward
  dpcr::OdometrySample s = odo.Update(t, 1);
  CHECK(s.pose.x == Approx(kTwoPi * 0.05).margin(1e-6));
  CHECK(s.pose.y == Approx(0.0).margin(1e-6));
  // Spin in place by 90 degrees: each wheel travels (pi/2) * b/2.
  const double ticks_90 = (kTwoPi / 4 * 0.1) / (kTwoPi * 0.05) * 360;  // 90 ticks
  t.left_ticks -= std::lround(ticks_90);
  t.right_ticks += std::lround(ticks_90);
  s = odo.Update(t, 2);
  CHECK(s.pose.x == Approx(kTwoPi * 0.05).margin(1e-6));
  CHECK(s.pose.theta == Approx(kTwoPi / 4).margin(1e-6));
  CHECK(s.stamp_us == 2);
}

TEST_CASE("odometry closes a full circle driven in many small steps") {
  DiffDriveConfig c;
  c.wheel_radius_m = 0.035f;
  c.track_width_m = 0.25f;
  c.ticks_per_rev = 1000.0f;
  DiffDriveOdometry odo(c);
  WheelTicks t;
  static_cast<void>(odo.Update(t, 0));
  // Right wheel only (pivot about the left wheel): full turn when right travels 2 pi b.
  const double m_per_tick = kTwoPi * 0.035 / 1000.0;
  const auto total = static_cast<std::int64_t>(std::lround(kTwoPi * 0.25 / m_per_tick));
  for (std::int64_t i = 0; i < total; ++i) {
    t.right_ticks += 1;
    static_cast<void>(odo.Update(t, i));
  }
  const dpcr::Pose2 p = odo.pose();
  CHECK(std::hypot(p.x, p.y) < 2e-3f);
  CHECK(std::fabs(p.theta) < 2e-3f);
}

TEST_CASE("odometry config validation") {
  DiffDriveConfig c;
  c.track_width_m = 0.0f;
  CHECK(c.Validate() == dpcr::Status::kInvalidArgument);
}
