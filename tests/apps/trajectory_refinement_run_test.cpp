// End to end: the trajectory registered again in the finished maps
// (host_sim/output/trajectory_refinement.hpp) on the simulated apartment. Scans displaced in their
// map come back to where the map places them; the start, a scan in no map and a scan displaced past
// the bounds keep the pose they were given; the maps are not touched.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/mapper.hpp"
#include "host_sim/output/trajectory_refinement.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "tests/apps/sim_lidar_config.hpp"

namespace {

using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;
using dpcr::Pose2;

struct Run {
  std::unique_ptr<MapperType> mapper = std::make_unique<MapperType>();
  dpcr::output::ScanPointRecord record;
  std::vector<int> region;
  std::vector<Pose2> in_region;
};

// Five minutes of the apartment, every scan's map, pose in it and returns recorded.
void MapApartment(Run* run) {
  dpcr::sim::SimConfig sim_config;
  sim_config.seed = 3;
  sim_config.duration_min = 5.0;
  dpcr::MapperConfig config;
  config.lidar = dpcr::test::SimulatedLidarConfig(sim_config, dpcr::LidarKind::kLd06);
  REQUIRE(run->mapper->Init(config) == dpcr::Status::kOk);
  run->record.Attach(*run->mapper);
  dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
  dpcr::sim::SimEvent event;
  while (sim.Step(&event)) {
    if (event.type == dpcr::sim::SimEventType::kOdometry) {
      run->mapper->AddOdometry(event.odometry);
      continue;
    }
    (void)run->mapper->AddScan(event.scan);
    run->record.AfterScan(*run->mapper);
    run->region.push_back(run->mapper->last_scan_region());
    run->in_region.push_back(run->mapper->last_scan_in_region());
  }
  REQUIRE(run->region.size() > 2000);
  REQUIRE(run->mapper->region_count() >= 2);
}

Pose2 Displaced(const Pose2& p, float dx, float dy, float dtheta) { return Pose2{p.x + dx, p.y + dy, p.theta + dtheta}; }

}  // namespace

TEST_CASE("Scans displaced in their map come back to where the finished map places them") {
  Run run;
  MapApartment(&run);
  // The trajectory as the run placed it, refined: the reference every displaced scan must reach.
  std::vector<Pose2> refined = run.in_region;
  const dpcr::output::RefinementStats first = dpcr::output::RefineTrajectory(*run.mapper, run.record, run.region, &refined);
  CHECK(first.recorded == run.region.size());
  CHECK(20 * first.registered > 19 * first.recorded);  // 95 %
  CHECK(first.stored_bytes > 0);
  // Each seventh scan 3 cm and 0.6 degrees off where the run placed it.
  std::vector<Pose2> displaced = run.in_region;
  for (std::size_t i = 7; i < displaced.size(); i += 7) displaced[i] = Displaced(displaced[i], 0.03f, -0.02f, 0.0105f);
  const std::size_t tiles = run.mapper->tiles_used();
  const dpcr::output::RefinementStats again = dpcr::output::RefineTrajectory(*run.mapper, run.record, run.region, &displaced);
  CHECK(run.mapper->tiles_used() == tiles);  // the maps are read, not changed
  // Displaced by 36 mm and 0.6 degrees, they must come back most of the way: the prior still
  // holds them a little towards where they were given (measured: 4.5 mm and 0.07 degrees left).
  int checked = 0;
  double off_sum = 0.0, turn_sum = 0.0;
  for (std::size_t i = 7; i < displaced.size(); i += 7) {
    if (run.region[i] < 0 || refined[i].x == run.in_region[i].x) continue;  // in no map, or refused the first time
    ++checked;
    off_sum += static_cast<double>(std::hypot(displaced[i].x - refined[i].x, displaced[i].y - refined[i].y));
    turn_sum += static_cast<double>(std::fabs(dpcr::NormalizeAngle(displaced[i].theta - refined[i].theta)));
  }
  REQUIRE(checked > 200);
  const double off_mm = 1000.0 * off_sum / checked, turn_deg = turn_sum / checked * 180.0 / M_PI;
  INFO("displaced scans left " << off_mm << " mm and " << turn_deg << " deg from the undisplaced ones' refinement; registered "
                               << again.registered << ", refused " << again.refused << ", too far " << again.too_far);
  CHECK(off_mm < 8.0);
  CHECK(turn_deg < 0.1);
}

TEST_CASE("The start and a scan displaced past the bounds keep the pose they were given") {
  Run run;
  MapApartment(&run);
  std::vector<Pose2> poses = run.in_region;
  poses[0] = Displaced(poses[0], 0.03f, 0.0f, 0.01f);
  poses[1000] = Displaced(poses[1000], 0.5f, 0.0f, 0.0f);  // half a metre: another wall, if any
  const Pose2 start = poses[0], far = poses[1000];
  const dpcr::output::RefinementStats stats = dpcr::output::RefineTrajectory(*run.mapper, run.record, run.region, &poses);
  CHECK(poses[0].x == start.x);
  CHECK(poses[0].theta == start.theta);
  CHECK(poses[1000].x == far.x);
  CHECK(poses[1000].y == far.y);
  CHECK(stats.refused + stats.too_far >= 1);
  // Bounds tightened to nothing: every scan refused or kept where it was.
  std::vector<Pose2> kept = run.in_region;
  dpcr::output::RefinementConfig still;
  still.max_move_m = 0.0f;
  still.max_turn_rad = 0.0f;
  const dpcr::output::RefinementStats none = dpcr::output::RefineTrajectory(*run.mapper, run.record, run.region, &kept, still);
  CHECK(none.registered <= none.recorded / 100);
  // A reference of no map, or of one map twice, is refused.
  CHECK_FALSE(run.mapper->BeginMapRegistration(-1));
  CHECK_FALSE(run.mapper->BeginMapRegistration(run.mapper->region_count()));
  CHECK_FALSE(run.mapper->BeginMapRegistration(0, 0));
  CHECK_FALSE(run.mapper->BeginMapRegistration(0, run.mapper->region_count()));
  CHECK(run.mapper->BeginMapRegistration(0, 1));
}
