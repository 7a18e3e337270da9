// End to end, in the simulated apartment: a map made in one session (35 min, kept in memory),
// then second sessions from it. Kidnaps (the robot carried with its wheels lifted) must be
// recovered within 3 s of the put-down at the right place, with nothing inserted into any map
// while the robot does not know where it is; a start at an unknown pose must be found; in
// localise-only mode the saved map must come out byte for byte as it went in.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "core/mapper.hpp"
#include "core/persistence/map_stream.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "tests/core/map_file_fixtures.hpp"

namespace {

using M = dpcr::Mapper<dpcr::VacuumProfile>;

using dpcr::test::VectorSink;

dpcr::sim::SimConfig SimConfigFor(std::uint64_t seed, double minutes) {
  dpcr::sim::SimConfig c;
  c.seed = seed;
  c.duration_min = minutes;
  return c;
}

dpcr::MapperConfig MapperConfigFor(const dpcr::sim::SimConfig& sim) {
  dpcr::MapperConfig c;
  c.lidar = dpcr::sim::MapperLidarConfig(sim);
  return c;
}

// The first session, made once: its saved bytes and where its frame lies in the world.
struct SavedMap {
  std::vector<std::uint8_t> bytes;
  dpcr::Pose2 origin;  // the map frame (the robot's first pose) in the world
};

const SavedMap& Apartment() {
  static const SavedMap saved = [] {
    const dpcr::sim::SimConfig sim_config = SimConfigFor(1, 35.0);
    auto m = std::make_unique<M>();
    REQUIRE(m->Init(MapperConfigFor(sim_config)) == dpcr::Status::kOk);
    dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
    dpcr::sim::SimEvent e;
    while (sim.Step(&e)) {
      if (e.type == dpcr::sim::SimEventType::kOdometry) {
        m->AddOdometry(e.odometry);
      } else {
        (void)m->AddScan(e.scan);
      }
    }
    REQUIRE(m->counters().lost_events == 0);  // an ordinary session never gets lost
    SavedMap s;
    VectorSink sink;
    REQUIRE(m->SaveMap(sink).ok());
    s.bytes = sink.bytes;
    s.origin = sim.start_pose().ToPose2();
    return s;
  }();
  return saved;
}

std::unique_ptr<M> Loaded(const dpcr::MapperConfig& config, const dpcr::Pose2& start = dpcr::Pose2::Identity()) {
  auto m = std::make_unique<M>();
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  dpcr::MemoryMapSource source(dpcr::Span<const std::uint8_t>(Apartment().bytes.data(), Apartment().bytes.size()));
  REQUIRE(m->LoadMap(source, start).ok());
  return m;
}

double ErrorM(const dpcr::Pose2& estimate, const dpcr::Pose2& truth_in_world) {
  const dpcr::Pose2 truth = Apartment().origin.Inverse() * truth_in_world;
  return std::hypot(static_cast<double>(estimate.x - truth.x), static_cast<double>(estimate.y - truth.y));
}

std::vector<std::int16_t> Render(const M& m) {
  const dpcr::CellBox box = m.MapBounds();
  std::vector<std::int16_t> cells(static_cast<std::size_t>(box.width() * box.height()));
  REQUIRE(m.RenderMap(box, dpcr::Span<std::int16_t>(cells.data(), cells.size())) == dpcr::Status::kOk);
  return cells;
}

}  // namespace

// The target is >= 95 % of kidnaps within 3 s: of six, five; an ambiguous first round
// (a search over all maps takes about 2.5 s) may make one wait for a second.
TEST_CASE("Kidnapped with the wheels lifted: found again within 3 s, in the right place, nothing inserted meanwhile") {
  // The same seed as the first session: the robot starts where that map's frame is.
  dpcr::sim::SimConfig sim_config = SimConfigFor(1, 4.0);
  sim_config.kidnaps.count = 6;
  sim_config.kidnaps.from_min = 0.5;
  auto m = Loaded(MapperConfigFor(sim_config));
  dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
  dpcr::sim::SimEvent e;
  std::vector<std::int16_t> at_lift;
  std::size_t tiles_at_lift = 0;
  bool carried = false, lost_since_lift = false;
  std::int64_t down_us = -1;
  int recovered = 0, in_time = 0, checked_unchanged = 0;
  double worst_m = 0.0, slowest_s = 0.0;
  while (sim.Step(&e)) {
    if (e.type == dpcr::sim::SimEventType::kOdometry) {
      if (e.odometry.lifted && !carried) {
        carried = lost_since_lift = true;
        at_lift = Render(*m);
        tiles_at_lift = m->tiles_used();
      }
      if (!e.odometry.lifted && carried) {
        carried = false;
        down_us = e.time_us;
      }
      m->AddOdometry(e.odometry);
      continue;
    }
    const std::uint32_t fixes = m->counters().relocalisations;
    (void)m->AddScan(e.scan);
    if (lost_since_lift && m->status() == dpcr::MapperStatus::kLost) {
      // Lost since the lift: no map has changed.
      REQUIRE(m->tiles_used() == tiles_at_lift);
      if (!carried && down_us >= 0 && e.scan.stamp_us - down_us < 200000) {
        REQUIRE(Render(*m) == at_lift);
        ++checked_unchanged;
      }
    }
    if (m->counters().relocalisations != fixes && down_us >= 0 && !carried) {
      ++recovered;
      lost_since_lift = false;
      worst_m = std::fmax(worst_m, ErrorM(m->pose(), e.truth.ToPose2()));
      const double took_s = static_cast<double>(e.scan.stamp_us - down_us) * 1e-6;
      slowest_s = std::fmax(slowest_s, took_s);
      if (took_s <= 3.0) ++in_time;
      down_us = -1;
    }
  }
  INFO("recovered " << recovered << " (" << in_time << " within 3 s) of " << sim.kidnaps().size() << ", worst error " << worst_m << " m, slowest " << slowest_s << " s");
  REQUIRE(sim.kidnaps().size() == 6);
  CHECK(m->counters().lost_events >= 6);
  CHECK(m->counters().lifted_scans > 6 * 25);
  CHECK(checked_unchanged >= 6);
  CHECK(recovered == 6);
  CHECK(worst_m < 0.3);
  CHECK(in_time >= 5);
  CHECK(slowest_s <= 9.0);
}

TEST_CASE("Started at an unknown pose in a saved map: found within seconds, in the right place") {
  for (std::uint64_t seed : {2u, 3u, 4u}) {
    const dpcr::sim::SimConfig sim_config = SimConfigFor(seed, 0.25);
    dpcr::MapperConfig config = MapperConfigFor(sim_config);
    config.localisation.unknown_start = true;
    auto m = Loaded(config);
    REQUIRE(m->status() == dpcr::MapperStatus::kLost);  // lost until found
    dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
    dpcr::sim::SimEvent e;
    std::int64_t first_us = -1, found_us = -1;
    double error_m = 1e9;
    while (sim.Step(&e) && found_us < 0) {
      if (e.type == dpcr::sim::SimEventType::kOdometry) {
        m->AddOdometry(e.odometry);
        continue;
      }
      if (first_us < 0) first_us = e.scan.stamp_us;
      (void)m->AddScan(e.scan);
      if (m->counters().relocalisations > 0) {
        found_us = e.scan.stamp_us;
        error_m = ErrorM(m->pose(), e.truth.ToPose2());
      }
    }
    INFO("seed " << seed << ": found after " << static_cast<double>(found_us - first_us) * 1e-6 << " s, error " << error_m << " m");
    REQUIRE(found_us >= 0);
    CHECK(found_us - first_us <= 5000000);
    CHECK(error_m < 0.3);
    CHECK(m->status() == dpcr::MapperStatus::kTracking);
  }
}

TEST_CASE("Localise-only: the maps and the graph come out exactly as they went in") {
  dpcr::sim::SimConfig sim_config = SimConfigFor(5, 2.0);
  sim_config.kidnaps.count = 2;
  dpcr::MapperConfig config = MapperConfigFor(sim_config);
  config.localisation.unknown_start = true;
  config.localisation.localise_only = true;
  auto m = Loaded(config);
  dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
  dpcr::sim::SimEvent e;
  double sum_m = 0.0;
  int placed = 0;
  while (sim.Step(&e)) {
    if (e.type == dpcr::sim::SimEventType::kOdometry) {
      m->AddOdometry(e.odometry);
      continue;
    }
    (void)m->AddScan(e.scan);
    if (m->status() == dpcr::MapperStatus::kTracking) {
      sum_m += ErrorM(m->pose(), e.truth.ToPose2());
      ++placed;
    }
  }
  VectorSink after;
  REQUIRE(m->SaveMap(after).ok());
  REQUIRE(after.bytes == Apartment().bytes);
  CHECK(m->counters().relocalisations >= 3);  // the start and both kidnaps
  REQUIRE(placed > 600);
  INFO("mean error while placed " << sum_m / placed << " m over " << placed << " scans");
  CHECK(sum_m / placed < 0.15);
}

TEST_CASE("Started at an unknown pose that matches nothing: stays lost, changes nothing, never guesses") {
  const dpcr::sim::SimConfig sim_config = SimConfigFor(1, 1.0);
  dpcr::MapperConfig config = MapperConfigFor(sim_config);
  config.localisation.unknown_start = true;
  auto m = Loaded(config);
  const std::vector<std::int16_t> before = Render(*m);
  // A place that is nowhere in the apartment: a round room (so the scans track each other and
  // search rounds run to their end), with still wheels.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> range(1.19f, 1.21f);
  for (int s = 0; s < 300; ++s) {
    const std::int64_t stamp = static_cast<std::int64_t>(s) * 100000 + 100000;
    for (int k = 0; k < 10; ++k) {
      dpcr::OdometrySample o;
      o.stamp_us = stamp - 100000 + k * 10000;
      m->AddOdometry(o);
    }
    M::ScanType scan;
    scan.stamp_us = stamp;
    for (int b = 0; b < 450; ++b) {
      dpcr::Beam beam;
      beam.angle_rad = -dpcr::kPi + 2.0f * dpcr::kPi * static_cast<float>(b) / 450.0f;
      beam.range_m = range(rng);
      (void)scan.beams.push_back(beam);
    }
    (void)m->AddScan(scan);
    REQUIRE(m->status() == dpcr::MapperStatus::kLost);
  }
  CHECK(m->counters().relocalisations == 0);
  INFO("failed rounds " << m->counters().relocalisation_failures);
  CHECK(m->counters().relocalisation_failures >= 3);  // rounds ran and found nothing sure
  CHECK(Render(*m) == before);
}

// A robot started 0.8 m and 34 deg off in a loaded map (the slip: a turn past what a second
// registration may correct, PlicpConfig::max_correction_rad; a 20 deg slip it corrects itself since
// it registers about the submap's centroid, pivot_frame.hpp), with the lidar alone or with a
// gyro's samples but no wheels, and the slip rule after `slipped_after` rejected second
// registrations (0: off): its relocalisations and its final error.
namespace {
std::pair<std::uint32_t, double> RunSlipped(int slipped_after, bool gyro) {
  const dpcr::sim::SimConfig sim_config = SimConfigFor(1, 0.75);
  dpcr::MapperConfig config = MapperConfigFor(sim_config);
  config.front_end.lidar_only_lost_after_second_rejections = slipped_after;
  auto m = Loaded(config, dpcr::Pose2{0.8f, 0.0f, 0.6f});
  dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
  dpcr::sim::SimEvent e;
  double error_m = 1e9;
  while (sim.Step(&e)) {
    if (e.type == dpcr::sim::SimEventType::kOdometry && gyro) {
      dpcr::OdometrySample gyro_only = e.odometry;  // the simulated gyro's rate, no wheels
      gyro_only.pose = dpcr::Pose2::Identity();
      gyro_only.has_wheels = false;
      REQUIRE(gyro_only.has_gyro);
      m->AddOdometry(gyro_only);
    }
    if (e.type != dpcr::sim::SimEventType::kScan) continue;
    (void)m->AddScan(e.scan);
    error_m = ErrorM(m->pose(), e.truth.ToPose2());
  }
  return std::make_pair(m->counters().relocalisations, error_m);
}
}  // namespace

// Without wheels or a gyro nothing measures a turn: a submap the first registration let slip
// still matches every new scan, and only the regional map disagrees. Here the slip is the start
// pose itself: the robot must call itself lost on the regional map's rejections
// (FrontEndConfig::lidar_only_lost_after_second_rejections) and be found again.
TEST_CASE("A lidar-only robot whose submap the regional map keeps rejecting is lost and found again") {
  const auto [found, error_m] = RunSlipped(3, false);
  INFO("relocalisations " << found << ", final error " << error_m << " m");
  CHECK(found >= 1);
  CHECK(error_m < 0.3);
  // The rule off: the robot stays where the slip put it.
  const auto [found_off, error_off_m] = RunSlipped(0, false);
  INFO("without the rule: relocalisations " << found_off << ", final error " << error_off_m << " m");
  CHECK(error_off_m > 0.5);
}

// The same slip with a gyro but no wheel translation (a gyro alone, or wheel ticks set aside by
// the wheel check: the real XV-11 recordings' heading-only ticks): nothing measures where the robot
// went, and the regional map's rejections must send it lost as well. With wheels such a streak is
// drift the back end reconciles (intel).
TEST_CASE("A robot with a gyro and no wheel translation whose submap the regional map keeps rejecting is lost and found again") {
  const auto [found, error_m] = RunSlipped(3, true);
  INFO("relocalisations " << found << ", final error " << error_m << " m");
  CHECK(found >= 1);
  CHECK(error_m < 0.3);
  const auto [found_off, error_off_m] = RunSlipped(0, true);
  INFO("without the rule: relocalisations " << found_off << ", final error " << error_off_m << " m");
  CHECK(error_off_m > 0.5);
}

// Without a heading sensor (LocalisationConfig::near_window_m, clear_min_score): the robot lost
// nearby is searched for around its believed pose first (not aligned by the second registration
// from there), and a fix that is not clear is taken only when a later round agrees with it.
TEST_CASE("A lidar-only robot takes an unclear fix only when a second round agrees with it") {
  const dpcr::sim::SimConfig sim_config = SimConfigFor(1, 0.75);
  const dpcr::Pose2 wrong_start{0.8f, 0.0f, 0.35f};
  struct Outcome {
    std::uint32_t found = 0, failures = 0;
    double first_fix_s = -1.0, error_m = 1e9, worst_after_fix_m = 0.0;
  };
  const auto run = [&](float clear_min_score, float near_window_m) {
    dpcr::MapperConfig config = MapperConfigFor(sim_config);
    config.localisation.clear_min_score = clear_min_score;
    config.localisation.near_window_m = near_window_m;
    auto m = Loaded(config, wrong_start);
    dpcr::sim::Simulation sim(dpcr::sim::LoadBuiltinWorld("apartment"), sim_config);
    dpcr::sim::SimEvent e;
    Outcome o;
    while (sim.Step(&e)) {
      if (e.type != dpcr::sim::SimEventType::kScan) continue;  // no odometry at all
      (void)m->AddScan(e.scan);
      o.error_m = ErrorM(m->pose(), e.truth.ToPose2());
      if (m->counters().relocalisations > 0 && o.first_fix_s < 0.0) o.first_fix_s = static_cast<double>(e.scan.stamp_us) * 1e-6;
      if (o.first_fix_s >= 0.0 && m->status() != dpcr::MapperStatus::kLost && o.error_m > o.worst_after_fix_m) {
        o.worst_after_fix_m = o.error_m;
      }
    }
    o.found = m->counters().relocalisations;
    o.failures = m->counters().relocalisation_failures;
    return o;
  };
  const Outcome usual = run(0.85f, 0.3f);
  // No fix is clear: each is held until a second round places the robot within 0.25 m of it.
  const Outcome held = run(1.0f, 0.3f);
  INFO("usual: first fix at " << usual.first_fix_s << " s, worst " << usual.worst_after_fix_m << " m; all held: first fix at "
                              << held.first_fix_s << " s, worst " << held.worst_after_fix_m << " m");
  for (const Outcome& o : {usual, held}) {
    CHECK(o.found >= 1);
    CHECK(o.worst_after_fix_m < 0.3);
    CHECK(o.error_m < 0.3);
  }
  CHECK(held.first_fix_s > usual.first_fix_s);  // it waited for the agreeing round
  // The rules off (every verified fix taken, the near second registration): found as well.
  const Outcome off = run(0.0f, 0.0f);
  CHECK(off.found >= 1);
  CHECK(off.error_m < 0.3);
}
