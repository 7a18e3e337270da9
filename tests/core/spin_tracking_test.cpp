// An in-place spin at 120°/s seen by a 5 Hz, 360-beam lidar (24° per revolution, each beam at its
// own time: the revolution is bent while the rate changes): tracked without odometry (the
// constant velocity, the re-deskew, bent scans tracked but kept out of the maps) and with a gyro;
// and a robot at rest after a turn, with an XV-11's invalid beams and range noise.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/mapper.hpp"
#include "tests/core/cabinet_room.hpp"

namespace {

using M = dpcr::Mapper<dpcr::VacuumProfile>;
constexpr float kRate = 2.0943951f, kAccel = 6.0f;  // 120°/s, reached in 0.35 s
constexpr float kRevolutionS = 0.2f;

// Heading at time t: at rest for 0.5 s, then up to 120°/s, 3 s at that rate, down, at rest.
float Heading(float t) {
  const float ramp = kRate / kAccel, t0 = 0.5f, t1 = t0 + ramp, t2 = t1 + 3.0f, t3 = t2 + ramp;
  const float full = 0.5f * kAccel * ramp * ramp;
  if (t < t0) return 0.0f;
  if (t < t1) return 0.5f * kAccel * (t - t0) * (t - t0);
  if (t < t2) return full + kRate * (t - t1);
  if (t < t3) return full + kRate * 3.0f + kRate * (t - t2) - 0.5f * kAccel * (t - t2) * (t - t2);
  return 2.0f * full + kRate * 3.0f + kRate * ramp - 0.5f * kAccel * ramp * ramp;
}

// A turn towards a waypoint as the simulator drives it (3 rad/s^2 up to 1.5 rad/s, then down):
// 135 deg from t = 0.5 s, at rest from about 2.6 s.
float Turn(float t) {
  constexpr float kTurnAccel = 3.0f, kTurnRate = 1.5f, kAngle = 2.3561945f;
  const float ramp = kTurnRate / kTurnAccel, cruise = (kAngle - kTurnRate * ramp) / kTurnRate;
  const float t0 = 0.5f, t1 = t0 + ramp, t2 = t1 + cruise, t3 = t2 + ramp;
  const float full = 0.5f * kTurnAccel * ramp * ramp;
  if (t < t0) return 0.0f;
  if (t < t1) return 0.5f * kTurnAccel * (t - t0) * (t - t0);
  if (t < t2) return full + kTurnRate * (t - t1);
  if (t < t3) return full + kTurnRate * cruise + kTurnRate * (t - t2) - 0.5f * kTurnAccel * (t - t2) * (t - t2);
  return kAngle;
}

struct SpinResult {
  std::uint32_t rejected = 0;
  float heading_error = 0.0f;
  float worst_at_rest = 0.0f;  // the largest heading error once the profile is at rest again
  std::uint32_t scans = 0;
};

// An XV-11's faults, drawn from a fixed seed: 30 % of the beams without a return, range noise of
// 1 cm + 1 % (uniform, same sigma).
float Degrade(float range, std::uint32_t* state) {
  const auto next = [state] {
    *state = *state * 1664525u + 1013904223u;
    return static_cast<float>(*state >> 8) / 16777216.0f;
  };
  const float invalid = next(), noise = next();
  if (invalid < 0.3f) return 0.0f;
  return range + (2.0f * noise - 1.0f) * 1.732f * (0.01f + 0.01f * range);
}

SpinResult Spin(bool gyro, float (*heading)(float) = Heading, float at_rest_from_s = 1e9f, bool noisy = false) {
  std::uint32_t rng = 12345u;
  auto m = std::make_unique<M>();
  REQUIRE(m->Init(dpcr::MapperConfig{}) == dpcr::Status::kOk);
  const float x = 2.3f, y = 1.6f;
  int odom = 0;
  SpinResult result;
  for (int s = 0; s < 30; ++s) {
    const float t_scan = static_cast<float>(s) * kRevolutionS;
    // Gyro-only samples at 100 Hz up to the revolution's end (the rate is the mean over each interval).
    for (; gyro && static_cast<float>(odom) * 0.01f <= t_scan + kRevolutionS; ++odom) {
      const float t = static_cast<float>(odom) * 0.01f;
      dpcr::OdometrySample o;
      o.stamp_us = static_cast<std::int64_t>(std::lround(t * 1e6f));
      o.has_wheels = false;
      o.has_gyro = true;
      o.gyro_yaw_rate = odom == 0 ? 0.0f : (heading(t) - heading(t - 0.01f)) / 0.01f;
      m->AddOdometry(o);
    }
    M::ScanType scan = dpcr::test::CabinetRoomRevolution<M::ScanType>(x, y, t_scan, kRevolutionS, 360, heading);
    for (std::size_t b = 0; noisy && b < scan.beams.size(); ++b) scan.beams[b].range_m = Degrade(scan.beams[b].range_m, &rng);
    (void)m->AddScan(scan);
    result.heading_error = std::fabs(dpcr::NormalizeAngle(m->pose().theta - heading(t_scan)));
    if (t_scan >= at_rest_from_s) result.worst_at_rest = std::fmax(result.worst_at_rest, result.heading_error);
  }
  result.rejected = m->front_end_counters().first_rejected;
  result.scans = m->front_end_counters().first_registrations;
  return result;
}

}  // namespace

TEST_CASE("An in-place spin at 120 deg/s is tracked without odometry") {
  const SpinResult r = Spin(false);
  REQUIRE(r.scans == 29);
  CHECK(r.rejected * 10 < r.scans);  // fewer than 10 % rejected
  INFO("heading error " << r.heading_error << " rad");
  CHECK(r.heading_error < 0.035f);  // 2° after 1.3 turns
}

TEST_CASE("An in-place spin at 120 deg/s is tracked with a gyro alone") {
  const SpinResult r = Spin(true);
  CHECK(r.rejected == 0);
  CHECK(r.heading_error < 0.02f);
}

TEST_CASE("A robot at rest after a turn is held without odometry") {
  // A turn as the simulator drives one, seen with an XV-11's faults: once the robot stands still
  // the pose must too. (In the simulated apartment without odometry a wrong step after a turn,
  // carried on by the constant velocity, swung a standing robot by tens of degrees; this clean
  // room does not provoke that case: docs/front-end-accuracy.md.)
  const SpinResult r = Spin(false, Turn, 3.0f, true);
  CHECK(r.rejected * 10 < r.scans);
  INFO("worst at rest " << r.worst_at_rest << " rad");
  CHECK(r.worst_at_rest < 0.035f);
}
