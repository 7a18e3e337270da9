// A simulated XV-11 run on the apartment (or another built-in world) through a vacuum Mapper, for
// the end-to-end tests of sparse scans and weak odometry: the mapper told of the lidar as dpcr-sim
// tells it (the model's settings, the simulated range noise), each odometry sample shaped by what
// the robot has, and the position error of every mapped scan relative to the first one.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/mapper.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "tests/apps/sim_lidar_config.hpp"

namespace dpcr::test {

struct Xv11RunResult {
  double mean_error_m = 0.0;  // position error relative to the first mapped scan, mean over the run
  double max_error_m = 0.0;
  int scans = 0;              // mapped scans (the spin-up revolution is in no map)
  double rejected_share = 0.0;  // first registrations rejected
};

// `sim_config.lidar` must be an XV-11's (sim::Xv11LidarConfig); `config`'s lidar is replaced by the
// simulated one. `robot(OdometrySample*)` turns a simulated sample into what the robot has.
template <class Robot>
Xv11RunResult RunXv11World(const char* world, const sim::SimConfig& sim_config, MapperConfig config, Robot robot) {
  config.lidar = SimulatedLidarConfig(sim_config, LidarKind::kXv11);
  auto mapper = std::make_unique<Mapper<VacuumProfile>>();
  REQUIRE(mapper->Init(config) == Status::kOk);
  sim::Simulation sim(sim::LoadBuiltinWorld(world), sim_config);
  sim::SimEvent event;
  bool started = false;
  Pose2 first_estimate, first_truth;
  Xv11RunResult run;
  while (sim.Step(&event)) {
    if (event.type == sim::SimEventType::kOdometry) {
      robot(&event.odometry);
      mapper->AddOdometry(event.odometry);
      continue;
    }
    if (mapper->AddScan(event.scan) != Status::kOk) continue;  // the spin-up: in no map
    const Pose2 truth = event.truth.ToPose2();
    if (!started) {
      started = true;
      first_estimate = mapper->pose();
      first_truth = truth;
    }
    const Pose2 estimate = Between(first_estimate, mapper->pose());
    const Pose2 expected = Between(first_truth, truth);
    const double error = std::hypot(static_cast<double>(estimate.x - expected.x), static_cast<double>(estimate.y - expected.y));
    run.mean_error_m += error;
    run.max_error_m = std::max(run.max_error_m, error);
    ++run.scans;
  }
  if (run.scans > 0) run.mean_error_m /= run.scans;
  const FrontEndCounters& fe = mapper->front_end_counters();
  if (fe.first_registrations > 0) run.rejected_share = static_cast<double>(fe.first_rejected) / static_cast<double>(fe.first_registrations);
  return run;
}

template <class Robot>
Xv11RunResult RunXv11Apartment(const sim::SimConfig& sim_config, MapperConfig config, Robot robot) {
  return RunXv11World("apartment", sim_config, config, robot);
}

// A robot with a gyro and no wheel encoders (as the real XV-11 recordings: an IMU's yaw, no wheel
// translation), the gyro giving the prediction's heading.
inline Xv11RunResult RunXv11GyroOnly(const char* world, const sim::SimConfig& sim_config, MapperConfig config) {
  config.front_end.gyro_heading = true;
  return RunXv11World(world, sim_config, config, [](OdometrySample* sample) {
    sample->pose = Pose2::Identity();
    sample->has_wheels = false;
  });
}

}  // namespace dpcr::test
