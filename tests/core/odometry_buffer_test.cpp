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
