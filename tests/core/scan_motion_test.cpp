// The de-skew's motion (core/front_end/scan_motion.hpp): wheels as before, the gyro's heading
// where the prediction takes it, the constant velocity for what the sensors lack; and a scan kept
// packed for the fixed-lag de-skew (core/geometry/scan.hpp: PackedBeam).
#include "core/front_end/scan_motion.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/geometry/scan.hpp"
#include "core/geometry/scan_projection.hpp"

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

TEST_CASE("A constant velocity that is not finite is no motion and a huge one is bounded") {
  // Two scans stamped at the same time made the lidar-only path's velocity 0 / 0 (fuzz_mapper_scans).
  const OdometryBuffer empty;
  for (const float bad : {NAN, INFINITY, -INFINITY}) {
    const ScanMotion m(empty, false, Pose2{bad, 0.1f, 0.2f}, 0);
    CHECK(!m.moves());
    CHECK(m.At(1000000).x == 0.0f);
  }
  // A step of a metre over a microsecond: 10^6 m/s and rad/s.
  const ScanMotion fast(empty, false, Pose2{6e5f, -8e5f, -1e6f}, 0);
  const Pose2 p = fast.At(100000);
  CHECK(std::hypot(p.x, p.y) == Approx(0.1f * ScanMotion::kMaxSpeedMps).epsilon(1e-5));
  CHECK(p.x / p.y == Approx(-0.75f).epsilon(1e-5));  // the direction kept
  CHECK(fast.velocity().theta == -ScanMotion::kMaxTurnRateRadS);
}

TEST_CASE("A scan kept packed projects within a millimetre of the scan it came from") {
  // FrontEnd's fixed-lag de-skew keeps the waiting scan as PackedBeam (8 bytes a beam, not 12).
  std::vector<dpcr::Beam> beams;
  for (int i = 0; i < 360; ++i) {
    dpcr::Beam b;
    b.angle_rad = dpcr::NormalizeAngle(0.0174533f * static_cast<float>(i) + 0.3f);
    b.range_m = i % 17 == 0 ? 0.0f : 0.5f + 0.015f * static_cast<float>(i);  // some without a return
    b.offset_us = 200000 * i / 360 + 3;
    beams.push_back(b);
  }
  std::vector<dpcr::PackedBeam> packed;
  for (const dpcr::Beam& b : beams) packed.push_back(dpcr::PackedBeam::Pack(b));
  // Angles wrap to one turn, offsets round to 16 us and stay within +-0.52 s.
  CHECK(dpcr::PackedBeam::Pack(dpcr::Beam{3.14159265f, 1.0f, 0}).Unpack().angle_rad == Approx(-3.14159265f).margin(1e-4));
  CHECK(dpcr::PackedBeam::Pack(dpcr::Beam{-7.0f, 1.0f, 0}).Unpack().angle_rad == Approx(dpcr::NormalizeAngle(-7.0f)).margin(1e-4));
  CHECK(dpcr::PackedBeam::Pack(dpcr::Beam{0.0f, 1.0f, -25}).Unpack().offset_us == -32);
  CHECK(dpcr::PackedBeam::Pack(dpcr::Beam{0.0f, 1.0f, 2000000}).Unpack().offset_us == 32767 * 16);
  dpcr::LidarConfig lidar;
  lidar.max_range_m = 6.0f;
  lidar.no_return_free_m = 1.0f;
  const OdometryBuffer none;
  const ScanMotion motion(none, false, Pose2{0.3f, 0.0f, 2.0f}, 0);  // 120 deg/s
  std::vector<dpcr::Point2> hits(360), free_ends(360), packed_hits(360), packed_free_ends(360);
  const dpcr::ProjectedScan a = dpcr::ProjectScan(dpcr::Span<const dpcr::Beam>(beams.data(), beams.size()), lidar, motion,
                                                  dpcr::Span<dpcr::Point2>(hits.data(), hits.size()),
                                                  dpcr::Span<dpcr::Point2>(free_ends.data(), free_ends.size()));
  const dpcr::ProjectedScan b = dpcr::ProjectScan(dpcr::Span<const dpcr::PackedBeam>(packed.data(), packed.size()), lidar,
                                                  motion, dpcr::Span<dpcr::Point2>(packed_hits.data(), packed_hits.size()),
                                                  dpcr::Span<dpcr::Point2>(packed_free_ends.data(), packed_free_ends.size()));
  REQUIRE(a.hits == b.hits);
  REQUIRE(a.free_ends == b.free_ends);
  REQUIRE(a.hits > 300);
  for (std::size_t i = 0; i < a.hits; ++i) CHECK(std::hypot(hits[i].x - packed_hits[i].x, hits[i].y - packed_hits[i].y) < 1e-3f);
  for (std::size_t i = 0; i < a.free_ends; ++i) {
    CHECK(std::hypot(free_ends[i].x - packed_free_ends[i].x, free_ends[i].y - packed_free_ends[i].y) < 1e-3f);
  }
}
