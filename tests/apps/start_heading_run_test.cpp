// End to end: the start heading refined with the gyro (core/front_end/start_heading.hpp) on the
// simulated XV-11 with wheels and a gyro heading. The start's heading against the map, judged by
// the truth (the later scans' heading errors relative to the start), is closer with the fit than
// without; with the wheels' heading nothing moves and the trajectory is the maps' alone.
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
using Outcome = dpcr::StartHeadingFit::Outcome;

struct StartRun {
  double start_error_deg = 0.0;  // mean over 5-60 s of the scans' heading error relative to the start
  Outcome outcome = Outcome::kNone;
  bool others_unmoved = true;    // every scan after the start written where its map places it
  bool start_unmoved = true;
};

// The robots: an LD06 with the wheels' heading; an XV-11 with wheels and the gyro's heading; an
// XV-11 whose wheel samples carry only the integrated gyro's yaw (ticks made of an IMU's heading,
// as real recordings were converted), no gyro rate.
enum class Robot { kLd06Wheels, kXv11Gyro, kXv11HeadingTicks };

StartRun RunApartment(std::uint64_t seed, Robot robot, float window_s) {
  const bool xv11 = robot != Robot::kLd06Wheels;
  dpcr::sim::SimConfig sim_config;
  sim_config.seed = seed;
  sim_config.duration_min = 1.0;
  if (xv11) sim_config.lidar = dpcr::sim::Xv11LidarConfig();
  dpcr::MapperConfig config;
  config.lidar = dpcr::test::SimulatedLidarConfig(sim_config, xv11 ? dpcr::LidarKind::kXv11 : dpcr::LidarKind::kLd06);
  config.front_end.gyro_heading = robot == Robot::kXv11Gyro;
  config.front_end.start_heading.window_s = window_s;
  auto mapper = std::make_unique<MapperType>();
  REQUIRE(mapper->Init(config) == dpcr::Status::kOk);
  dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
  struct Record {
    std::int64_t stamp_us;
    int region;
    dpcr::Pose2 in_region, online;
    float true_heading;
  };
  std::vector<Record> records;
  dpcr::sim::SimEvent event;
  dpcr::sim::HeadingOnlyTicks ticks;
  while (sim.Step(&event)) {
    if (event.type == dpcr::sim::SimEventType::kOdometry) {
      if (robot == Robot::kXv11HeadingTicks) ticks.Apply(&event.odometry);
      mapper->AddOdometry(event.odometry);
      continue;
    }
    if (mapper->AddScan(event.scan) != dpcr::Status::kOk) continue;  // the XV-11's spin-up: in no map
    records.push_back({event.scan.stamp_us, mapper->last_scan_region(), mapper->last_scan_in_region(), mapper->pose(),
                       event.truth.ToPose2().theta});
  }
  REQUIRE(records.size() > 200);
  StartRun run;
  run.outcome = mapper->start_heading().outcome();
  const Record& start = records.front();
  const float start_heading = mapper->ScanWorldPose(start.stamp_us, start.region, start.in_region, start.online).theta;
  run.start_unmoved = start_heading == (mapper->region_anchor(start.region) * start.in_region).theta;
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 1; i < records.size(); ++i) {
    const Record& r = records[i];
    const dpcr::Pose2 written = mapper->ScanWorldPose(r.stamp_us, r.region, r.in_region, r.online);
    const dpcr::Pose2 maps = r.region >= 0 ? mapper->region_anchor(r.region) * r.in_region : r.online;
    if (written.theta != maps.theta || written.x != maps.x || written.y != maps.y) run.others_unmoved = false;
    if (r.stamp_us - start.stamp_us < 5'000'000) continue;
    sum += static_cast<double>(dpcr::NormalizeAngle((written.theta - start_heading) - (r.true_heading - start.true_heading)));
    ++n;
  }
  run.start_error_deg = sum / n * 180.0 / 3.14159265358979;
  return run;
}

// XV-11, apartment seeds 1-10: the start's heading error, rms, is below `max_ratio` of what it is
// without the fit.
void CheckStartRefined(Robot robot, double max_ratio) {
  // Without the fit the first scan's noise leaves the start off the map by up to half a degree
  // (seeds 1-10); the fit moves the start scan alone, and only when its offset is over 0.2 deg.
  double with_sq = 0.0, without_sq = 0.0;
  int applied = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const StartRun with = RunApartment(seed, robot, 30.0f), without = RunApartment(seed, robot, 0.0f);
    CHECK(with.others_unmoved);
    CHECK(without.outcome == Outcome::kNone);
    if (with.outcome == Outcome::kApplied) ++applied;
    with_sq += with.start_error_deg * with.start_error_deg;
    without_sq += without.start_error_deg * without.start_error_deg;
  }
  const double with_rms = std::sqrt(with_sq / 10), without_rms = std::sqrt(without_sq / 10);
  INFO("start heading error rms over seeds 1-10: " << with_rms << " deg with the fit (" << applied << " applied), "
                                                   << without_rms << " deg without");
  CHECK(applied >= 2);
  CHECK(with_rms < max_ratio * without_rms);
}

}  // namespace

TEST_CASE("XV-11 with a gyro heading: the refined start sits where the later scans place it") {
  CheckStartRefined(Robot::kXv11Gyro, 0.75);  // measured 0.145 against 0.264 deg
}

TEST_CASE("XV-11 with heading-only wheel ticks: the start is refined once the ticks are found a heading") {
  // The first seconds' turns come from the wheels, until the wheel check sets their translation
  // aside (5-7 s); the switch to their yaw rate leaves a turn or two unmeasured, bridged.
  CheckStartRefined(Robot::kXv11HeadingTicks, 0.8);  // measured 0.254 against 0.354 deg
}

TEST_CASE("LD06 with the wheels heading: the start is not moved") {
  // Wheels that measure the translation err in heading with the turn (the track width), not with
  // time: a fit of offset and bias would be wrong.
  const StartRun run = RunApartment(1, Robot::kLd06Wheels, 30.0f);
  CHECK(run.outcome == Outcome::kWheels);
  CHECK(run.start_unmoved);
  CHECK(run.others_unmoved);
}
