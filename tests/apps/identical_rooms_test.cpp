// End to end: a world of four identical rooms along a corridor (tests/data/identical_rooms.world),
// mapped with the back end. A loop closure into the wrong room would shift the map by 3 m; the
// run must close loops (so the test exercises them) and stay within centimetres of the truth.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/mapper.hpp"
#include "host_sim/eval/accuracy.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"

TEST_CASE("Identical rooms: loops close, none into the wrong room") {
  using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;
  auto mapper = std::make_unique<MapperType>();
  dpcr::sim::SimConfig sim_config;
  sim_config.duration_min = 20.0;
  sim_config.seed = 2;
  dpcr::MapperConfig config;
  config.lidar = dpcr::sim::MapperLidarConfig(sim_config);
  REQUIRE(mapper->Init(config) == dpcr::Status::kOk);
  const dpcr::sim::World world = dpcr::sim::LoadWorldFile(DPCR_TEST_DATA_DIR "/identical_rooms.world");
  dpcr::sim::Simulation sim(world, sim_config);
  dpcr::sim::SimEvent event;
  int scans_with_optimisation = 0;
  double follow_error_m = 0.0;
  std::vector<int> region;
  std::vector<dpcr::Pose2> in_region;
  dpcr::eval::Trajectory estimate, truth;
  while (sim.Step(&event)) {
    if (event.type == dpcr::sim::SimEventType::kOdometry) {
      mapper->AddOdometry(event.odometry);
      continue;
    }
    const std::uint32_t optimisations_before = mapper->back_end().counters().optimizations;
    static_cast<void>(mapper->AddScan(event.scan));
    estimate.push_back({event.scan.stamp_us, mapper->pose()});
    // The robot follows the vertex its pose is known in: after a back-end step inside this call
    // moved the anchors, the live pose is still that map's anchor times the scan's pose in it.
    if (mapper->last_scan_region() >= 0 && mapper->back_end().counters().optimizations != optimisations_before) {
      const dpcr::Pose2 followed = mapper->region_anchor(mapper->last_scan_region()) * mapper->last_scan_in_region();
      const dpcr::Pose2 live = mapper->pose();
      ++scans_with_optimisation;
      follow_error_m = std::max(follow_error_m, static_cast<double>(std::hypot(live.x - followed.x, live.y - followed.y)));
    }
    region.push_back(mapper->last_scan_region());
    in_region.push_back(mapper->last_scan_in_region());
    truth.push_back({event.scan.stamp_us, event.truth.ToPose2()});
  }
  // The trajectory as the maps have it at the end (final anchors).
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    if (region[i] >= 0) estimate[i].pose = mapper->region_anchor(region[i]) * in_region[i];
  }
  const dpcr::eval::AccuracyResult a = dpcr::eval::EvaluateAgainstGroundTruth(estimate, truth);
  const auto& b = mapper->back_end().counters();
  INFO("LocErr_ave " << a.loc_err_ave_m << " m, ATE " << a.ate_rmse_m << " m, max " << a.max_err_m << " m, closures " << b.loop_closures_accepted
                     << " accepted / " << b.loop_closures_rejected << " rejected, optimisations " << b.optimizations);
  CHECK(scans_with_optimisation >= 3);
  CHECK(follow_error_m < 1e-3);
  CHECK(b.loop_closures_accepted >= 3);
  CHECK(b.optimizations >= 3);
  // A closure into the wrong room would bend the map (aligned error) and put scans metres off
  // (maximum). The start-aligned mean of the worst tenth (LocErr_ave) is left out: with the seed's
  // own plan it mostly measures the heading the first minutes gave the map.
  CHECK(a.ate_rmse_m < 0.03);
  CHECK(a.max_err_m < 0.15);
}
