// End to end: the simulated apartment mapped by the vacuum-profile front end, scored with the
// same LocErr_ave / ATE code as dpcr-eval. Bounds are generous regression guards (the measured
// figures are in docs/front-end-accuracy.md); the odometry pipeline on the same run shows that
// they are far from what dead reckoning gets, so the test can fail.
#include <catch2/catch.hpp>

#include <memory>

#include "core/mapper.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "host_sim/eval/accuracy.hpp"

namespace {
using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;

dpcr::eval::AccuracyResult MapApartment(bool registration, double minutes) {
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
  while (sim.Step(&event)) {
    if (event.type == dpcr::sim::SimEventType::kOdometry) {
      mapper->AddOdometry(event.odometry);
      continue;
    }
    static_cast<void>(mapper->AddScan(event.scan));  // a SimScan is the vacuum mapper's scan type
    estimate.push_back({event.scan.stamp_us, mapper->pose()});
    truth.push_back({event.scan.stamp_us, event.truth.ToPose2()});
  }
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
