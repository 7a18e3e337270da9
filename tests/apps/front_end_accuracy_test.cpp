// End to end: the simulated apartment mapped by the vacuum-profile front end, scored with the
// same LocErr_ave / ATE code as dpcr-eval. Bounds are generous regression guards (the measured
// figures are in docs/front-end-accuracy.md); the odometry pipeline on the same run shows that
// they are far from what dead reckoning gets, so the test can fail.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/mapper.hpp"
#include "host_sim/sim/heading_only_ticks.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "host_sim/eval/accuracy.hpp"

namespace {
using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;

// `heading_only_ticks`: the wheel samples carry the integrated gyro's yaw and no translation (ticks
// made of an IMU's yaw, as real XV-11 recordings were converted), no gyro rate.
dpcr::eval::AccuracyResult MapApartment(bool registration, double minutes, bool heading_only_ticks = false,
                                        std::uint32_t* samples_without_translation = nullptr) {
  auto mapper = std::make_unique<MapperType>();
  dpcr::MapperConfig config;
  dpcr::sim::SimConfig sim_config;
  sim_config.duration_min = minutes;
  config.lidar = dpcr::sim::MapperLidarConfig(sim_config);
  config.front_end.enable_registration = registration;
  REQUIRE(mapper->Init(config) == dpcr::Status::kOk);
  dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
  dpcr::sim::SimEvent event;
  dpcr::eval::Trajectory estimate, truth;
  dpcr::sim::HeadingOnlyTicks ticks;
  while (sim.Step(&event)) {
    if (event.type == dpcr::sim::SimEventType::kOdometry) {
      if (heading_only_ticks) ticks.Apply(&event.odometry);
      mapper->AddOdometry(event.odometry);
      continue;
    }
    static_cast<void>(mapper->AddScan(event.scan));  // a SimScan is the vacuum mapper's scan type
    estimate.push_back({event.scan.stamp_us, mapper->pose()});
    truth.push_back({event.scan.stamp_us, event.truth.ToPose2()});
  }
  if (samples_without_translation != nullptr) *samples_without_translation = mapper->counters().odometry_without_wheel_translation;
  return dpcr::eval::EvaluateAgainstGroundTruth(estimate, truth);
}

}  // namespace

TEST_CASE("Apartment, 5 simulated minutes: the front end stays within centimetres of the truth") {
  const dpcr::eval::AccuracyResult front_end = MapApartment(true, 5.0);
  const dpcr::eval::AccuracyResult odometry = MapApartment(false, 5.0);
  INFO("front end LocErr_ave " << front_end.loc_err_ave_m << " m, ATE " << front_end.ate_rmse_m << " m; odometry LocErr_ave "
                               << odometry.loc_err_ave_m << " m");
  CHECK(front_end.loc_err_ave_m < 0.06);
  CHECK(front_end.ate_rmse_m < 0.04);
  CHECK(odometry.loc_err_ave_m > 10.0 * front_end.loc_err_ave_m);
}

TEST_CASE("Apartment, 5 simulated minutes, wheel ticks that carry only the heading: set aside, the run tracks") {
  // The wheels say "standing still" all along; taken at their word they hold the registration back
  // at every scan (without the wheel check: 0.043 m here, 0.022 m with it; an XV-11's 10-minute
  // device replay 2.9 m against 0.031 m).
  std::uint32_t without_translation = 0;
  const dpcr::eval::AccuracyResult r = MapApartment(true, 5.0, true, &without_translation);
  INFO("LocErr_ave " << r.loc_err_ave_m << " m, ATE " << r.ate_rmse_m << " m, samples without translation " << without_translation);
  CHECK(without_translation > 25000);  // of 30000: switched off within the first seconds
  CHECK(r.loc_err_ave_m < 0.032);
}

// XV-11 without odometry, apartment seeds 1-`seeds` for `minutes`: the heading error at the end
// (the map's frame is the robot's first pose, turned off the walls when they lie along the grid's
// axes), rms over the seeds, in degrees.
double LidarOnlyHeadingRmsDeg(double minutes, bool fixed_lag, std::uint64_t seeds) {
  double sum_sq = 0.0;
  int runs = 0;
  for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
    dpcr::sim::SimConfig sim_config;
    sim_config.seed = seed;
    sim_config.duration_min = minutes;
    sim_config.lidar = dpcr::sim::Xv11LidarConfig();
    dpcr::MapperConfig config;
    config.lidar = dpcr::sim::MapperLidarConfig(sim_config);
    config.lidar.drop_isolated_returns = true;  // as dpcr-sim --lidar xv11 (its junk readings)
    config.front_end.lidar_only_fixed_lag = fixed_lag;
    auto mapper = std::make_unique<MapperType>();
    REQUIRE(mapper->Init(config) == dpcr::Status::kOk);
    dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
    dpcr::sim::SimEvent event;
    float error = 0.0f;
    while (sim.Step(&event)) {
      if (event.type != dpcr::sim::SimEventType::kScan) continue;  // no odometry at all
      static_cast<void>(mapper->AddScan(event.scan));
      const float turned = event.truth.ToPose2().theta - sim.start_pose().ToPose2().theta;
      // A robot that starts square to the walls gets its map's frame turned off them
      // (FrontEnd::TurnFrameFromWalls): the robot's first pose is at that turn.
      error = dpcr::NormalizeAngle(mapper->pose().theta - mapper->front_end_counters().grid_turn_rad - turned);
    }
    sum_sq += static_cast<double>(error) * static_cast<double>(error);
    ++runs;
  }
  return std::sqrt(sum_sq / runs) * 180.0 / 3.14159265358979;
}

TEST_CASE("XV-11 without odometry: the turns at the start of a run keep their heading") {
  // Nothing measures a turn here: each step is registered from the constant velocity's guess,
  // which lags every start and stop of a turn by one revolution (17 deg at 5 Hz). Its prior is
  // weakened for that (FrontEnd::kPriorThetaWithoutHeading); at full strength the heading after
  // the first turns was 2.4 deg rms over these seeds against 1.4 (both without the fixed lag).
  const double rms_deg = LidarOnlyHeadingRmsDeg(0.1, true, 20);
  INFO("heading error after 6 s, rms over 20 seeds: " << rms_deg << " deg");
  CHECK(rms_deg < 2.1);
}

TEST_CASE("XV-11 without odometry: scans go into the maps a revolution late, de-skewed from both sides") {
  // The de-skew assumes the motion of the revolution before; the run's first scan, projected
  // with no motion known while the robot starts to turn, rotated the whole first map (0.2-2.75 deg,
  // apartment seeds 1-10), and every bent scan kept out left the maps thin. With the fixed lag
  // (FrontEndConfig::lidar_only_fixed_lag) each scan goes in once the next one is registered,
  // projected with the motion on both sides of its revolution and registered again.
  const double lag = LidarOnlyHeadingRmsDeg(0.5, true, 10), no_lag = LidarOnlyHeadingRmsDeg(0.5, false, 10);
  INFO("heading error after 30 s, rms over 10 seeds: " << lag << " deg with the lag, " << no_lag << " deg without");
  CHECK(lag < 0.5 * no_lag);
}
