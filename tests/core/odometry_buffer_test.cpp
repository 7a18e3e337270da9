#include <catch2/catch.hpp>

#include "core/front_end/odometry_buffer.hpp"

using dpcr::OdometrySample;
using dpcr::Pose2;

namespace {
OdometrySample At(std::int64_t t_us, float x, float theta = 0.0f) {
  OdometrySample s;
  s.stamp_us = t_us;
  s.pose = Pose2{x, 0.0f, theta};
  return s;
}
}  // namespace

TEST_CASE("Odometry is interpolated between samples and along the short way round") {
  dpcr::OdometryBuffer b;
  b.Add(At(0, 0.0f, 3.0f));
  b.Add(At(100000, 1.0f, -3.0f));
  const Pose2 mid = b.PoseAt(50000);
  REQUIRE(mid.x == Approx(0.5f));
  REQUIRE(std::fabs(mid.theta) == Approx(dpcr::kPi).margin(1e-3));  // through pi, not through 0
  REQUIRE(b.PoseAt(-5).x == Approx(0.0f));
}

TEST_CASE("Odometry extrapolates briefly at the last velocity, then holds") {
  dpcr::OdometryBuffer b;
  b.Add(At(0, 0.0f));
  b.Add(At(100000, 0.1f));
  REQUIRE(b.PoseAt(150000).x == Approx(0.15f));
  REQUIRE(b.PoseAt(10000000).x == Approx(0.2f));  // capped at kMaxExtrapolationUs
}

TEST_CASE("Jittered stamps give no velocity explosion, and steps back are counted") {
  dpcr::OdometryBuffer b;
  b.Add(At(0, 0.0f));
  b.Add(At(1000, 0.5f));  // 1 ms apart: too close to estimate a velocity from
  REQUIRE(b.PoseAt(50000).x == Approx(0.5f));
  b.Add(At(500, 0.6f));
  REQUIRE(b.steps_back() == 1);
  REQUIRE(b.PoseAt(500).x == Approx(0.6f));
}

TEST_CASE("A burst of samples stamped a millisecond apart is not taken for a speed") {
  // As intel.clf logs them: a robot at 0.2 m/s, a record every 0.2 s, then ten records that
  // cover 0.3 m of motion stamped 1 ms apart. Measured over 5 ms and carried 100 ms ahead, that
  // burst says 3 m (30 m/s); measured over at least half the 100 ms it is carried, 0.16 m.
  dpcr::OdometryBuffer b;
  for (int k = 0; k <= 5; ++k) b.Add(At(k * 200000, 0.04f * static_cast<float>(k)));
  for (int k = 1; k <= 10; ++k) b.Add(At(1000000 + k * 1000, 0.2f + 0.03f * static_cast<float>(k)));
  const float ahead = b.PoseAt(1010000 + 100000).x - 0.5f;
  CHECK(ahead >= 0.0f);
  CHECK(ahead < 0.2f);
  // Samples at a steady rate extrapolate at that rate however far back the span reaches.
  dpcr::OdometryBuffer steady;
  for (int k = 0; k <= 50; ++k) steady.Add(At(k * 10000, 0.003f * static_cast<float>(k)));
  CHECK(steady.PoseAt(500000 + 30000).x == Approx(0.159f));
  CHECK(steady.PoseAt(500000 + 5000).x == Approx(0.1515f));
}

TEST_CASE("The gyro rate integrates to a yaw between samples, and absent rates give none") {
  dpcr::OdometryBuffer buf;
  float yaw = 0.0f;
  REQUIRE_FALSE(buf.GyroYawAt(0, &yaw));
  // 100 Hz, 0.5 rad/s for 1 s while the wheels claim no turn at all.
  for (int k = 0; k <= 100; ++k) {
    dpcr::OdometrySample s;
    s.stamp_us = k * 10000;
    s.has_gyro = true;
    s.gyro_yaw_rate = 0.5f;
    buf.Add(s);
  }
  float a = 0.0f, b = 0.0f;
  REQUIRE(buf.GyroYawAt(500000, &a));
  REQUIRE(buf.GyroYawAt(905000, &b));  // between two samples: interpolated
  REQUIRE(dpcr::NormalizeAngle(b - a) == Approx(0.2025f).margin(1e-4));
  REQUIRE(buf.GyroYawAt(1050000, &b));  // past the newest: extrapolated at its rate
  REQUIRE(dpcr::NormalizeAngle(b - a) == Approx(0.275f).margin(1e-4));
  REQUIRE_FALSE(buf.GyroYawAt(0, &a));  // older than the buffer
  dpcr::OdometrySample wheels_only;
  wheels_only.stamp_us = 1010000;
  buf.Add(wheels_only);
  REQUIRE_FALSE(buf.GyroYawAt(1010000, &a));
}

TEST_CASE("With gyro_heading the prediction turns by the gyro, and moves by the wheels") {
  // Wheels: straight 0.1 m along x; gyro: 0.3 rad over the same 0.1 s.
  dpcr::OdometryBuffer buf;
  for (int k = 0; k <= 10; ++k) {
    dpcr::OdometrySample s;
    s.stamp_us = k * 10000;
    s.pose = dpcr::Pose2{0.01f * static_cast<float>(k), 0.0f, 0.0f};
    s.has_gyro = true;
    s.gyro_yaw_rate = 3.0f;
    buf.Add(s);
  }
  float y0 = 0.0f, y1 = 0.0f;
  REQUIRE(buf.GyroYawAt(0, &y0));
  REQUIRE(buf.GyroYawAt(100000, &y1));
  REQUIRE(dpcr::NormalizeAngle(y1 - y0) == Approx(0.3f).margin(1e-5));
  REQUIRE(buf.PoseAt(100000).x == Approx(0.1f));
  REQUIRE(buf.PoseAt(100000).theta == Approx(0.0f));
}
