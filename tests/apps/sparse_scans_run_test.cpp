// End to end: an XV-11 that returns 40 % of its readings (the sparsest of the real recordings),
// with heading-only wheel ticks (an IMU's yaw), on the simulated apartment. A sparse scan's first
// registration allows its own noise (FrontEndConfig::sparse_scan_share): without that, the young
// submap's registrations were rejected at the start while the robot drove off, and the map began
// metres from the robot (seeds 5 and 8: 1.7 and 2.5 m).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/mapper.hpp"
#include "hal/device_options.hpp"
#include "host_sim/sim/heading_only_ticks.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"

namespace {

using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;

struct SparseRun {
  double mean_error_m = 0.0;  // position error relative to the first mapped scan, mean over the run
  double rejected_share = 0.0;  // first registrations rejected
};

SparseRun RunSparseApartment(std::uint64_t seed, float sparse_scan_share) {
  dpcr::sim::SimConfig sim_config;
  sim_config.seed = seed;
  sim_config.duration_min = 1.0;
  sim_config.lidar = dpcr::sim::Xv11LidarConfig();
  sim_config.lidar.invalid_probability = 0.6;
  dpcr::MapperConfig config;
  config.lidar = dpcr::sim::MapperLidarConfig(sim_config);
  const float range_noise_m = config.lidar.range_noise_m;
  dpcr::ApplyLidarModel(dpcr::LidarKind::kXv11, &config.lidar);
  config.lidar.range_noise_m = range_noise_m;  // as dpcr-sim: the simulated noise
  config.front_end.sparse_scan_share = sparse_scan_share;
  auto mapper = std::make_unique<MapperType>();
  REQUIRE(mapper->Init(config) == dpcr::Status::kOk);
  dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
  dpcr::sim::SimEvent event;
  dpcr::sim::HeadingOnlyTicks ticks;
  bool started = false;
  dpcr::Pose2 first_estimate, first_truth;
  double sum = 0.0;
  int n = 0;
  while (sim.Step(&event)) {
    if (event.type == dpcr::sim::SimEventType::kOdometry) {
      ticks.Apply(&event.odometry);
      mapper->AddOdometry(event.odometry);
      continue;
    }
    if (mapper->AddScan(event.scan) != dpcr::Status::kOk) continue;  // the spin-up: in no map
    const dpcr::Pose2 truth = event.truth.ToPose2();
    if (!started) {
      started = true;
      first_estimate = mapper->pose();
      first_truth = truth;
    }
    const dpcr::Pose2 estimate = dpcr::Between(first_estimate, mapper->pose());
    const dpcr::Pose2 expected = dpcr::Between(first_truth, truth);
    sum += std::hypot(static_cast<double>(estimate.x - expected.x), static_cast<double>(estimate.y - expected.y));
    ++n;
  }
  REQUIRE(n > 200);
  const dpcr::FrontEndCounters& fe = mapper->front_end_counters();
  SparseRun run;
  run.mean_error_m = sum / n;
  run.rejected_share = static_cast<double>(fe.first_rejected) / static_cast<double>(fe.first_registrations);
  return run;
}

}  // namespace

TEST_CASE("An XV-11 returning 40 percent of its readings keeps the map from its start") {
  const float share = dpcr::FrontEndConfig{}.sparse_scan_share;
  double worst_with = 0.0, worst_without = 0.0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const SparseRun with = RunSparseApartment(seed, share), without = RunSparseApartment(seed, 0.0f);
    INFO("seed " << seed << ": mean error " << with.mean_error_m << " m, " << 100.0 * with.rejected_share
                 << " % rejected; without the sparse bound " << without.mean_error_m << " m, "
                 << 100.0 * without.rejected_share << " %");
    CHECK(with.mean_error_m < 0.15);    // measured at most 0.047 m
    CHECK(with.rejected_share < 0.08);  // measured at most 3.9 %
    worst_with = std::max(worst_with, with.mean_error_m);
    worst_without = std::max(worst_without, without.mean_error_m);
  }
  INFO("worst mean error over seeds 1-8: " << worst_with << " m, without the sparse bound " << worst_without << " m");
  // The scenario needs the change: without it some run's map began far from the robot.
  CHECK(worst_without > 0.5);
}
