// Scans taken in a fast turn (LidarConfig::map_max_turn_rate_rad_s): tracked and kept in the
// submap, but out of the regional maps and counted; with the limit at 0 every scan is mapped.
// A 10 Hz, 450-beam lidar (an LD06) in the cabinet room; the robot stands, turns 180 degrees in
// place at 90 deg/s, and stands again.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/mapper.hpp"
#include "tests/core/cabinet_room.hpp"

namespace {

using M = dpcr::Mapper<dpcr::VacuumProfile>;
constexpr float kRevolutionS = 0.1f;
constexpr float kTurnRate = dpcr::kPi / 2.0f;  // 90 deg/s: 9 degrees a revolution
constexpr float kTurnStartS = 1.0f, kTurnEndS = 3.0f;
constexpr int kScans = 40;

float Heading(float t) {
  if (t < kTurnStartS) return 0.0f;
  if (t < kTurnEndS) return kTurnRate * (t - kTurnStartS);
  return kTurnRate * (kTurnEndS - kTurnStartS);
}

struct TurnResult {
  dpcr::MapperCounters counters;
  float worst_heading_error = 0.0f;
  float final_heading_error = 0.0f;
};

// `wheels`: wheel odometry at 100 Hz (the turn measured); otherwise none at all (the fixed-lag
// de-skew maps each scan one revolution late).
TurnResult Turn(float max_turn_deg_per_s, bool wheels) {
  auto m = std::make_unique<M>();
  dpcr::MapperConfig config;
  config.lidar.map_max_turn_rate_rad_s = max_turn_deg_per_s * dpcr::kPi / 180.0f;
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  const float x = 2.3f, y = 1.6f;
  int odom = 0;
  TurnResult result;
  for (int s = 0; s < kScans; ++s) {
    const float t_scan = static_cast<float>(s) * kRevolutionS;
    for (; wheels && static_cast<float>(odom) * 0.01f <= t_scan + kRevolutionS; ++odom) {
      const float t = static_cast<float>(odom) * 0.01f;
      dpcr::OdometrySample o;
      o.stamp_us = static_cast<std::int64_t>(std::lround(t * 1e6f));
      o.pose = dpcr::Pose2{0.0f, 0.0f, Heading(t)};
      m->AddOdometry(o);
    }
    (void)m->AddScan(dpcr::test::CabinetRoomRevolution<M::ScanType>(x, y, t_scan, kRevolutionS, 450, Heading));
    const float error = std::fabs(dpcr::NormalizeAngle(m->pose().theta - Heading(t_scan)));
    result.worst_heading_error = std::fmax(result.worst_heading_error, error);
    result.final_heading_error = error;
  }
  result.counters = m->counters();
  return result;
}

}  // namespace

TEST_CASE("Scans taken in a fast turn are tracked but kept out of the regional maps") {
  const bool wheels = GENERATE(true, false);
  INFO((wheels ? "wheel odometry" : "no odometry"));
  const TurnResult limited = Turn(60.0f, wheels);
  // The turn spans 20 revolutions at 90 deg/s; without odometry the first of them is predicted
  // still (the constant velocity learns the turn from it), and the one after the stop turned too.
  INFO("turning scans kept out " << limited.counters.scans_turning_not_mapped);
  CHECK(limited.counters.scans_turning_not_mapped >= 18);
  CHECK(limited.counters.scans_turning_not_mapped <= 22);
  CHECK(limited.counters.scans_not_inserted >= limited.counters.scans_turning_not_mapped);
  // Tracked through the turn (without odometry the constant velocity lags at its start and end).
  INFO("heading error: worst " << limited.worst_heading_error << ", final " << limited.final_heading_error << " rad");
  CHECK(limited.worst_heading_error < (wheels ? 0.02f : 0.06f));
  CHECK(limited.final_heading_error < 0.01f);

  // Turning slower than the limit, or with no limit: every turning scan is mapped.
  CHECK(Turn(120.0f, wheels).counters.scans_turning_not_mapped == 0);
  const TurnResult unlimited = Turn(0.0f, wheels);
  CHECK(unlimited.counters.scans_turning_not_mapped == 0);
  CHECK(unlimited.counters.scans_not_inserted + 18 <= limited.counters.scans_not_inserted);
}
