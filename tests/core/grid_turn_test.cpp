// A new map's grid turned off walls that would lie along its axes (FrontEndConfig::grid_turn_rad):
// a robot that starts square to the walls, as from its dock, gets a world frame 15 degrees off its
// first pose, and tracks in it as well as in an unturned one.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/mapper.hpp"
#include "tests/budget/synthetic_run.hpp"

namespace {

using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;

struct Tracked {
  dpcr::Pose2 first;  // the estimate after the first scan
  dpcr::Pose2 last;   // after the last
  float turn_rad = 0.0f;
  float walls_rad = 0.0f;
  // With a spin-up revolution: the first scan's and the second's final world poses
  // (ScanWorldPose), and the second's online one.
  dpcr::Pose2 spin_up_world, mapped_world, mapped_online;
};

// The synthetic room run (the robot starts square to the walls, exact ranges) with the lidar's
// range noise declared as `noise_m`. With `spin_up`, the first revolution returns one beam in 15
// (30 of 450, under FrontEndConfig::min_start_hits), as an XV-11's first does.
Tracked Run(float noise_m, float turn_rad, bool spin_up = false) {
  auto mapper = std::make_unique<MapperType>();
  dpcr::MapperConfig config;
  config.lidar.range_noise_m = noise_m;
  config.front_end.grid_turn_rad = turn_rad;
  REQUIRE(mapper->Init(config) == dpcr::Status::kOk);
  dpcr::test::SyntheticRun<MapperType> run(8.0f, 120, 450);
  if (spin_up) {
    for (std::size_t b = 0; b < run.scans[0].beams.size(); ++b) {
      if (b % 15 != 0) run.scans[0].beams[b].range_m = 0.0f;
    }
  }
  Tracked t;
  int region[2] = {-1, -1};
  dpcr::Pose2 in_region[2], online[2];
  std::size_t odom = 0;
  for (std::size_t i = 0; i < run.scans.size(); ++i) {
    while (odom < run.odometry.size() && run.odometry[odom].stamp_us <= run.scans[i].stamp_us) {
      mapper->AddOdometry(run.odometry[odom++]);
    }
    (void)mapper->AddScan(run.scans[i]);
    if (i == 0) t.first = mapper->pose();
    if (i < 2) {
      region[i] = mapper->last_scan_region();
      in_region[i] = mapper->last_scan_in_region();
      online[i] = mapper->pose();
    }
  }
  t.spin_up_world = mapper->ScanWorldPose(run.scans[0].stamp_us, region[0], in_region[0], online[0]);
  t.mapped_world = mapper->ScanWorldPose(run.scans[1].stamp_us, region[1], in_region[1], online[1]);
  t.mapped_online = online[1];
  t.last = mapper->pose();
  t.turn_rad = mapper->front_end_counters().grid_turn_rad;
  t.walls_rad = mapper->front_end_counters().first_wall_direction_rad;
  return t;
}

}  // namespace

TEST_CASE("A robot square to the walls gets a grid turned 15 degrees and tracks the same in it") {
  const float turn = 15.0f * dpcr::kPi / 180.0f;
  const Tracked turned = Run(0.025f, turn);
  const Tracked plain = Run(0.025f, 0.0f);
  INFO("walls at " << turned.walls_rad << " rad, turn " << turned.turn_rad << " rad");
  CHECK(std::fabs(turned.walls_rad) < 0.01f);
  CHECK(std::fabs(turned.turn_rad - turn) < 0.01f);
  CHECK(std::fabs(turned.first.theta - turned.turn_rad) < 1e-4f);
  CHECK(std::hypot(turned.first.x, turned.first.y) < 1e-3f);  // turned about the robot's start
  CHECK(plain.turn_rad == 0.0f);
  CHECK(std::fabs(plain.first.theta) < 0.01f);
  // The motion from the first scan to the last is the same in both frames (within the tracking's
  // centimetre), and the truth's: 12 s of lanes.
  const dpcr::Pose2 moved_turned = turned.first.Inverse() * turned.last;
  const dpcr::Pose2 moved_plain = plain.first.Inverse() * plain.last;
  const dpcr::Pose2 truth0 = dpcr::test::SyntheticRun<MapperType>::Sample(0.095f, 0.25f, 8.0f).pose;
  const dpcr::Pose2 truth1 = dpcr::test::SyntheticRun<MapperType>::Sample(11.995f, 0.25f, 8.0f).pose;
  const dpcr::Pose2 moved_truth = truth0.Inverse() * truth1;
  CHECK(std::hypot(moved_turned.x - moved_truth.x, moved_turned.y - moved_truth.y) < 0.03f);
  CHECK(std::fabs(dpcr::NormalizeAngle(moved_turned.theta - moved_truth.theta)) < 0.01f);
  CHECK(std::hypot(moved_turned.x - moved_plain.x, moved_turned.y - moved_plain.y) < 0.03f);
}

TEST_CASE("Without a declared range noise the grid is not turned") {
  const Tracked t = Run(0.0f, 15.0f * dpcr::kPi / 180.0f);
  CHECK(t.turn_rad == 0.0f);
  CHECK(std::isnan(t.walls_rad));  // not looked for
  CHECK(std::fabs(t.first.theta) < 0.01f);
}

TEST_CASE("A spin-up revolution before the first mapped scan leaves the grid turn to that scan") {
  const float turn = 15.0f * dpcr::kPi / 180.0f;
  const Tracked t = Run(0.025f, turn, true);
  INFO("walls at " << t.walls_rad << " rad, turn " << t.turn_rad << " rad");
  // The sparse first revolution is skipped and shows no wall; the first mapped scan does.
  CHECK(std::fabs(t.walls_rad) < 0.01f);
  CHECK(std::fabs(t.turn_rad - turn) < 0.01f);
  CHECK(std::fabs(t.mapped_online.theta - t.turn_rad) < 0.01f);
  // The skipped scan, reported before the turn, is written in the turned frame with the rest: its
  // motion to the first mapped scan is the truth's (0.1 s of a straight lane).
  const dpcr::Pose2 moved = t.spin_up_world.Inverse() * t.mapped_world;
  const dpcr::Pose2 truth0 = dpcr::test::SyntheticRun<MapperType>::Sample(0.095f, 0.25f, 8.0f).pose;
  const dpcr::Pose2 truth1 = dpcr::test::SyntheticRun<MapperType>::Sample(0.195f, 0.25f, 8.0f).pose;
  const dpcr::Pose2 moved_truth = truth0.Inverse() * truth1;
  CHECK(std::fabs(dpcr::NormalizeAngle(t.spin_up_world.theta - t.turn_rad)) < 0.01f);
  CHECK(std::hypot(moved.x - moved_truth.x, moved.y - moved_truth.y) < 0.01f);
  CHECK(std::fabs(dpcr::NormalizeAngle(moved.theta - moved_truth.theta)) < 0.01f);
}
