// The de-skew's motion (core/front_end/scan_motion.hpp): wheels as before, the gyro's heading
// where the prediction takes it, the constant velocity for what the sensors lack.
#include "core/front_end/scan_motion.hpp"

#include <catch2/catch.hpp>

using dpcr::OdometryBuffer;
using dpcr::OdometrySample;
using dpcr::Pose2;
using dpcr::ScanMotion;

namespace {

// 100 Hz samples from t = 0: the wheels drive at 0.2 m/s turning at 0.5 rad/s; the gyro says 2 rad/s.
OdometryBuffer Samples(bool wheels, bool gyro) {
  OdometryBuffer b;
  for (int k = 0; k <= 40; ++k) {
    OdometrySample s;
    s.stamp_us = k * 10000;
    const float t = static_cast<float>(k) * 0.01f;
    s.has_wheels = wheels;
    s.pose = wheels ? Pose2{0.2f * t, 0.0f, 0.5f * t} : Pose2::Identity();
    s.has_gyro = gyro;
    s.gyro_yaw_rate = gyro ? 2.0f : 0.0f;
    b.Add(s);
  }
  return b;
}

}  // namespace

TEST_CASE("With wheels the de-skew follows the wheels, with gyro_heading, the gyro's turn") {
  const OdometryBuffer b = Samples(true, true);
  const Pose2 velocity{1.0f, 1.0f, 1.0f};  // ignored: the wheels have it
  const ScanMotion wheels(b, false, velocity, 100000);
  const Pose2 expected = dpcr::Between(b.PoseAt(100000), b.PoseAt(200000));
  const Pose2 p = wheels.At(100000);
  CHECK(p.x == Approx(expected.x).margin(1e-5));
  CHECK(p.y == Approx(expected.y).margin(1e-5));
  CHECK(p.theta == Approx(0.05f).margin(1e-4));
  const ScanMotion gyro(b, true, velocity, 100000);
  CHECK(gyro.At(100000).theta == Approx(0.2f).margin(1e-4));
  CHECK(gyro.At(100000).x == Approx(expected.x).margin(1e-5));
}

TEST_CASE("A gyro alone turns the de-skew, the constant velocity moves it") {
  const OdometryBuffer b = Samples(false, true);
  const ScanMotion m(b, false, Pose2{0.3f, 0.0f, 5.0f}, 100000);
  REQUIRE(m.moves());
  const Pose2 p = m.At(200000);
  CHECK(p.theta == Approx(0.4f).margin(1e-4));  // the gyro's 2 rad/s, not the velocity's 5
  CHECK(p.x == Approx(0.06f).margin(1e-5));
  CHECK(p.y == Approx(0.0f).margin(1e-6));
}

TEST_CASE("Without odometry the de-skew is the constant velocity, and none without one") {
  const OdometryBuffer empty;
  const ScanMotion m(empty, true, Pose2{0.1f, -0.2f, 1.5f}, 0);
  const Pose2 p = m.At(200000);
  CHECK(p.x == Approx(0.02f).margin(1e-6));
  CHECK(p.y == Approx(-0.04f).margin(1e-6));
  CHECK(p.theta == Approx(0.3f).margin(1e-6));
  CHECK(!ScanMotion(empty, false, Pose2::Identity(), 0).moves());
}
