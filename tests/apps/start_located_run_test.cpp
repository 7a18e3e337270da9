// End to end: the start scan searched for in the finished first map (StartScansConfig::locate,
// FrontEnd::RefineStart). An XV-11 returning 40 % of its readings, with
// heading-only wheel ticks (no translation measured), on the simulated apartment: at seed 30 the
// robot drives off along a room whose far end is out of the lidar's reach while the young submap
// holds the pose, and the whole run is mapped about 2 m from its start. The map is right; the
// start is not. Found in the finished map, the start moves there and the written trajectory
// follows the truth again.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/mapper.hpp"
#include "host_sim/sim/heading_only_ticks.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "tests/apps/sim_lidar_config.hpp"

namespace {

using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;

struct Record {
  std::int64_t stamp_us;
  int region;
  dpcr::Pose2 in_region, online, truth;
};

enum class Odometry { kWheelsAndGyro, kHeadingTicks };

struct Located {
  dpcr::StartRefinement refinement;
  double before_m = 0.0;  // mean position error from 15 s on, written before RefineStart
  double after_m = 0.0;   // and after
};

// Mean over the scans from 15 s on of the written position's error against the truth, both taken
// relative to the first written scan (the start-aligned error of dpcr-eval).
double MeanErrorFrom15s(const MapperType& mapper, const std::vector<Record>& records) {
  const Record& s = records.front();
  const dpcr::Pose2 start = mapper.ScanWorldPose(s.stamp_us, s.region, s.in_region, s.online);
  double sum = 0.0;
  int n = 0;
  for (const Record& r : records) {
    if (r.stamp_us - s.stamp_us < 15'000'000) continue;
    const dpcr::Pose2 written = dpcr::Between(start, mapper.ScanWorldPose(r.stamp_us, r.region, r.in_region, r.online));
    const dpcr::Pose2 truth = dpcr::Between(s.truth, r.truth);
    sum += std::hypot(static_cast<double>(written.x - truth.x), static_cast<double>(written.y - truth.y));
    ++n;
  }
  return n > 0 ? sum / n : 0.0;
}

Located RunApartment(std::uint64_t seed, double valid, Odometry odometry, bool locate, bool firm_turns = true,
                     bool hold_weak_directions = true) {
  dpcr::sim::SimConfig sim_config;
  sim_config.seed = seed;
  sim_config.duration_min = 1.0;
  sim_config.lidar = dpcr::sim::Xv11LidarConfig();
  sim_config.lidar.invalid_probability = 1.0 - valid;
  dpcr::MapperConfig config;
  config.lidar = dpcr::test::SimulatedLidarConfig(sim_config, dpcr::LidarKind::kXv11);
  config.front_end.gyro_heading = true;  // as dpcr-sim's default for an XV-11
  config.front_end.start_scans.locate = locate;
  config.front_end.turn_holds_translation = firm_turns;
  if (!hold_weak_directions) config.front_end.weak_direction_information = 0.0f;
  auto mapper = std::make_unique<MapperType>();
  REQUIRE(mapper->Init(config) == dpcr::Status::kOk);
  dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
  dpcr::sim::HeadingOnlyTicks ticks;
  std::vector<Record> records;
  dpcr::sim::SimEvent event;
  while (sim.Step(&event)) {
    if (event.type == dpcr::sim::SimEventType::kOdometry) {
      if (odometry == Odometry::kHeadingTicks) ticks.Apply(&event.odometry);
      mapper->AddOdometry(event.odometry);
      continue;
    }
    if (mapper->AddScan(event.scan) != dpcr::Status::kOk) continue;  // the spin-up: in no map
    records.push_back({event.scan.stamp_us, mapper->last_scan_region(), mapper->last_scan_in_region(), mapper->pose(), event.truth.ToPose2()});
  }
  REQUIRE(records.size() > 200);
  Located out;
  out.before_m = MeanErrorFrom15s(*mapper, records);
  out.refinement = mapper->RefineStart();
  out.after_m = MeanErrorFrom15s(*mapper, records);
  // A second call changes nothing.
  const dpcr::StartRefinement again = mapper->RefineStart();
  CHECK(again.moved == out.refinement.moved);
  CHECK(MeanErrorFrom15s(*mapper, records) == out.after_m);
  return out;
}

}  // namespace

TEST_CASE("A start that slid is found in the finished map and the trajectory follows the truth") {
  // Seed 30 turns in place for 2 s at the start. The slid start was recorded with the weak
  // translation prior through that turn; with the turn held (FrontEndConfig::turn_holds_translation)
  // the start stays put and the drive-off after it slides instead, so the first map holds the true
  // start and there is nothing to find (1.8 m off with and without the search; no seed of 1-120
  // slides its start then: docs/back-end.md, "A robot that turns in place"). So does a turn whose
  // registrations keep near the guess along the directions the walls barely fix
  // (FrontEndConfig::weak_direction_information). The search is tested on the start as it slid.
  const Located off = RunApartment(30, 0.4, Odometry::kHeadingTicks, false, false, false);
  const Located on = RunApartment(30, 0.4, Odometry::kHeadingTicks, true, false, false);
  INFO("seed 30: error from 15 s " << off.after_m << " m without the search; " << on.before_m << " -> " << on.after_m
                                   << " m with it, start moved by (" << on.refinement.shift.x << ", " << on.refinement.shift.y << ") m");
  // The scenario has the failure: without the search the run is mapped ~2 m from its start
  // (measured 2.05 m).
  CHECK_FALSE(off.refinement.located);
  CHECK(off.after_m > 1.5);
  // Measured: moved by (1.93, 0.74) m, 0.015 m from 15 s on.
  CHECK(on.refinement.located);
  CHECK(on.refinement.moved);
  CHECK(std::hypot(on.refinement.shift.x, on.refinement.shift.y) > 1.5);
  CHECK(on.before_m > 1.5);
  CHECK(on.after_m < 0.05);
}

TEST_CASE("A start that did not slide stays where it was recorded") {
  // With 70 % of the readings (the model's) the start holds: found within millimetres of where it
  // was recorded (measured at most 5 mm), not moved, the written trajectory as without the search.
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Located run = RunApartment(seed, 0.7, Odometry::kHeadingTicks, true);
    const Located off = RunApartment(seed, 0.7, Odometry::kHeadingTicks, false);
    INFO("seed " << seed << ": found (" << run.refinement.shift.x << ", " << run.refinement.shift.y << ") m from where recorded");
    CHECK(run.refinement.located);
    CHECK_FALSE(run.refinement.moved);
    CHECK(std::hypot(run.refinement.shift.x, run.refinement.shift.y) < 0.05);
    CHECK(run.after_m == off.after_m);
  }
}

TEST_CASE("Wheels that measure the translation hold the start and it is not searched for") {
  const Located run = RunApartment(1, 0.7, Odometry::kWheelsAndGyro, true);
  CHECK(run.refinement.refined);  // the heading is still placed
  CHECK_FALSE(run.refinement.located);
  CHECK_FALSE(run.refinement.moved);
}
