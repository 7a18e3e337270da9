// End to end: the start placed in the finished first map (core/front_end/start_scans.hpp) on the
// simulated apartment. The whole map is turned about the start by the first scans' noise; the
// start scans registered again at the end of the run measure that turn, and the trajectory written
// after Mapper::RefineStart is turned less against the truth than the one written before it.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/mapper.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "tests/apps/sim_lidar_config.hpp"

namespace {

using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;

struct Turns {
  double before_deg = 0.0;  // the map's mean turn against the truth about the start, as written before RefineStart
  double after_deg = 0.0;   // and after
  dpcr::StartRefinement refinement;
};

// Mean over the scans after the first minute of their written heading against the truth, both
// relative to the start: the turn of the whole map about the start.
struct Record {
  std::int64_t stamp_us;
  int region;
  dpcr::Pose2 in_region, online;
  float true_heading;
};

double MeanTurnDeg(const MapperType& mapper, const std::vector<Record>& records) {
  const Record& s = records.front();
  const float start = mapper.ScanWorldPose(s.stamp_us, s.region, s.in_region, s.online).theta;
  double sum = 0.0;
  int n = 0;
  for (const Record& r : records) {
    if (r.stamp_us - s.stamp_us < 60'000'000) continue;
    const float written = mapper.ScanWorldPose(r.stamp_us, r.region, r.in_region, r.online).theta;
    sum += static_cast<double>(dpcr::NormalizeAngle((written - start) - (r.true_heading - s.true_heading)));
    ++n;
  }
  return n > 0 ? sum / n * 180.0 / M_PI : 0.0;
}

Turns RunApartment(std::uint64_t seed, bool xv11) {
  dpcr::sim::SimConfig sim_config;
  sim_config.seed = seed;
  sim_config.duration_min = 10.0;
  if (xv11) sim_config.lidar = dpcr::sim::Xv11LidarConfig();
  dpcr::MapperConfig config;
  config.lidar = dpcr::test::SimulatedLidarConfig(sim_config, xv11 ? dpcr::LidarKind::kXv11 : dpcr::LidarKind::kLd06);
  config.front_end.gyro_heading = xv11;        // as dpcr-sim's default: the gyro for an XV-11
  auto mapper = std::make_unique<MapperType>();
  REQUIRE(mapper->Init(config) == dpcr::Status::kOk);
  dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
  std::vector<Record> records;
  dpcr::sim::SimEvent event;
  while (sim.Step(&event)) {
    if (event.type == dpcr::sim::SimEventType::kOdometry) {
      mapper->AddOdometry(event.odometry);
      continue;
    }
    if (mapper->AddScan(event.scan) != dpcr::Status::kOk) continue;  // the XV-11's spin-up: in no map
    records.push_back({event.scan.stamp_us, mapper->last_scan_region(), mapper->last_scan_in_region(), mapper->pose(),
                       static_cast<float>(event.truth.ToPose2().theta)});
  }
  REQUIRE(records.size() > 1000);
  Turns t;
  t.before_deg = MeanTurnDeg(*mapper, records);
  const std::size_t tiles = mapper->tiles_used();
  t.refinement = mapper->RefineStart();
  // The kept scans' tiles went back to the pool; the maps kept theirs.
  CHECK(mapper->tiles_used() == tiles - static_cast<std::size_t>(dpcr::StartScans::kTiles));
  t.after_deg = MeanTurnDeg(*mapper, records);
  // A second call changes nothing.
  const dpcr::StartRefinement again = mapper->RefineStart();
  CHECK(again.refined == t.refinement.refined);
  CHECK(again.offset_rad == t.refinement.offset_rad);
  CHECK(MeanTurnDeg(*mapper, records) == t.after_deg);
  return t;
}

}  // namespace

TEST_CASE("The start placed in the finished map turns an XV-11 map less against the truth") {
  double before = 0.0, after = 0.0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Turns t = RunApartment(seed, true);
    INFO("XV-11 seed " << seed << ": turn " << t.before_deg << " -> " << t.after_deg << " deg, start scans "
                       << t.refinement.registered << " of " << t.refinement.kept);
    CHECK(t.refinement.kept >= 20);
    CHECK(t.refinement.refined);
    before += std::fabs(t.before_deg);
    after += std::fabs(t.after_deg);
  }
  // Measured: 0.84 -> 0.48 degrees summed over the six seeds.
  INFO("XV-11: summed turn " << before << " -> " << after << " deg");
  CHECK(after < 0.7 * before);
}

TEST_CASE("An LD06 map is turned at most by the start placement's own error") {
  // Its maps are turned less to begin with (0.08 degrees rms over 40 seeds); the placement errs by
  // about as much (docs/back-end.md), so it is checked for sense, not for gain: 0.02-0.15 degrees
  // measured on these seeds, where a wrong registration or fit would give degrees.
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Turns t = RunApartment(seed, false);
    INFO("LD06 seed " << seed << ": turn " << t.before_deg << " -> " << t.after_deg << " deg");
    CHECK(t.refinement.refined);
    CHECK(std::fabs(t.after_deg) < 0.25);
  }
}
