// The Mapper's contract: configuration checks, regions, scans fused once, full pools reported.
#include <catch2/catch.hpp>

#include <limits>
#include <memory>
#include <string>

#include "core/mapper.hpp"
#include "tests/budget/synthetic_run.hpp"

namespace {
template <class Profile>
std::unique_ptr<dpcr::Mapper<Profile>> MakeMapper() {
  auto m = std::make_unique<dpcr::Mapper<Profile>>();
  dpcr::MapperConfig config;
  config.front_end.submap_scans = Profile::kSubmapMaxScans;
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  return m;
}
template <class M, class Run>
void Feed(M& mapper, const Run& run) {
  std::size_t odom = 0;
  for (const auto& scan : run.scans) {
    while (odom < run.odometry.size() && run.odometry[odom].stamp_us <= scan.stamp_us) mapper.AddOdometry(run.odometry[odom++]);
    (void)mapper.AddScan(scan);
  }
}
}  // namespace

TEST_CASE("Init rejects a configuration the profile cannot hold") {
  auto m = std::make_unique<dpcr::Mapper<dpcr::TinyProfile>>();
  dpcr::MapperConfig config;
  config.front_end.submap_scans = dpcr::TinyProfile::kSubmapMaxScans + 1;
  REQUIRE(m->Init(config) == dpcr::Status::kInvalidArgument);
}

TEST_CASE("A scan without usable beams is rejected and counted") {
  auto m = MakeMapper<dpcr::TinyProfile>();
  dpcr::Mapper<dpcr::TinyProfile>::ScanType scan;
  dpcr::Beam b;
  b.range_m = 0.0f;
  (void)scan.beams.push_back(b);
  REQUIRE(m->AddScan(scan) == dpcr::Status::kNotEnoughData);
  REQUIRE(m->counters().scans_rejected == 1);
  REQUIRE(m->status() == dpcr::MapperStatus::kWaitingForData);
}

TEST_CASE("The odometry pipeline follows odometry exactly") {
  auto m = std::make_unique<dpcr::Mapper<dpcr::VacuumProfile>>();
  dpcr::MapperConfig config;
  config.front_end.enable_registration = false;
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  using M = dpcr::Mapper<dpcr::VacuumProfile>;
  const dpcr::test::SyntheticRun<M> run(8.0f, 400, 450);
  Feed(*m, run);
  const dpcr::Pose2 start = run.Sample(0.095f, 0.25f, 8.0f).pose;
  const dpcr::Pose2 expected = dpcr::Between(start, run.Sample(39.995f, 0.25f, 8.0f).pose);
  REQUIRE(m->pose().x == Approx(expected.x).margin(1e-3));
  REQUIRE(m->pose().y == Approx(expected.y).margin(1e-3));
  REQUIRE(std::string(m->pipeline()) == "odometry");
}

TEST_CASE("The front end tracks a room run and maps the room walls") {
  auto m = MakeMapper<dpcr::VacuumProfile>();
  using M = dpcr::Mapper<dpcr::VacuumProfile>;
  const dpcr::test::SyntheticRun<M> run(8.0f, 400, 450);
  Feed(*m, run);
  // The first scan fixes the world frame at the robot's first pose.
  const dpcr::Pose2 start = run.Sample(0.095f, 0.25f, 8.0f).pose;
  const dpcr::Pose2 expected = dpcr::Between(start, run.Sample(39.995f, 0.25f, 8.0f).pose);
  // Perfect odometry and noiseless walls lying exactly on cell borders, the worst case of
  // quantisation: submap lines are refitted to the raw points, but regional-map lines sit on cell
  // centres (half a cell off) and the second registration's targets are submap cell centres
  // (another half cell at most): the pose may move by up to one cell, not more.
  REQUIRE(m->pose().x == Approx(expected.x).margin(0.05));
  REQUIRE(m->pose().y == Approx(expected.y).margin(0.05));
  REQUIRE(m->status() == dpcr::MapperStatus::kTracking);
  REQUIRE(m->front_end_counters().first_registrations == 399);
  REQUIRE(m->front_end_counters().first_rejected < 20);
  REQUIRE(m->front_end_counters().second_registrations > 0);
  REQUIRE(m->region_count() >= 2);
  // The wall at x = 8 m (world x = 8 - start.x) is occupied in the fused map; the room inside is free.
  const dpcr::CellBox box = m->MapBounds();
  std::vector<std::int16_t> cells(static_cast<std::size_t>(box.width() * box.height()));
  REQUIRE(m->RenderMap(box, dpcr::Span<std::int16_t>(cells.data(), cells.size())) == dpcr::Status::kOk);
  auto at = [&](float x, float y) {
    const dpcr::CellIndex c = dpcr::CellOf(x - start.x, y - start.y, 0.05f);
    return cells[static_cast<std::size_t>((c.y - box.min.y) * box.width() + (c.x - box.min.x))];
  };
  REQUIRE(dpcr::IsOccupied(at(7.99f, 4.0f)));
  REQUIRE(dpcr::IsFree(at(4.0f, 4.0f)));
}

TEST_CASE("Odometry samples that are not finite or lie past any floor are dropped and counted") {
  using M = dpcr::Mapper<dpcr::VacuumProfile>;
  const dpcr::test::SyntheticRun<M> run(8.0f, 400, 450);
  auto clean = MakeMapper<dpcr::VacuumProfile>();
  Feed(*clean, run);
  // The same run with corrupt samples among the good ones (a CARMEN pose of 1e6 m once opened a
  // region 1000 km away and ended the replay in std::bad_alloc).
  auto corrupt_run = run;
  const float bad[] = {1e6f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), -2e5f};
  for (std::size_t k = 0; k < 4; ++k) {
    dpcr::OdometrySample s = corrupt_run.odometry[100 + 50 * k];
    (k % 2 == 0 ? s.pose.x : s.pose.y) = bad[k];
    corrupt_run.odometry.insert(corrupt_run.odometry.begin() + static_cast<std::ptrdiff_t>(101 + 50 * k), s);
  }
  auto m = MakeMapper<dpcr::VacuumProfile>();
  Feed(*m, corrupt_run);
  CHECK(m->counters().odometry_rejected == 4);
  CHECK(clean->counters().odometry_rejected == 0);
  CHECK(m->counters().odometry_samples == clean->counters().odometry_samples);
  CHECK(m->region_count() == clean->region_count());
  CHECK(m->pose().x == Approx(clean->pose().x).margin(0.02));
  CHECK(m->pose().y == Approx(clean->pose().y).margin(0.02));
}

TEST_CASE("A full region pool stops map growth, keeps the pose, and says so") {
  auto m = MakeMapper<dpcr::TinyProfile>();  // 4 regions of 4 m
  using M = dpcr::Mapper<dpcr::TinyProfile>;
  const dpcr::test::SyntheticRun<M> run(30.0f, 3000, 180);  // a 30 m hall: many regions
  Feed(*m, run);
  REQUIRE(m->region_count() == dpcr::TinyProfile::kMaxRegions);
  REQUIRE(m->counters().region_pool_full > 0);
  REQUIRE(m->status() == dpcr::MapperStatus::kPoolFull);
  REQUIRE(m->counters().scans == 3000);
  const dpcr::Pose2 start = run.Sample(0.095f, 0.25f, 30.0f).pose;
  const dpcr::Pose2 expected = dpcr::Between(start, run.Sample(299.995f, 0.25f, 30.0f).pose);
  // 5 cm (was 1 cm; 10 cm below) after 75 m: the hall's walls are mostly beyond the tiny 6.4 m submap, so most
  // matches are weak (inlier ratio < 0.6) and rebuild the reference early with the lower threshold
  // (FrontEndConfig::weak_match_*); the pose drifts 2.1 cm along the lanes, the weak direction, and
  // 4.8 cm since a rejection streak restarts the submap after 5 rejections instead of 10
  // (FrontEndConfig::submap_restart_after_rejections): the restarted submap forgets the hall.
  // 10 cm (was 5 cm): with the wheels calibrated online the drift is 3.9 cm on x86-64 and 6.0 cm
  // on armhf under qemu, where the floats round otherwise (4.8 cm on both without calibration):
  // a degenerate hall's drift is chaotic. What this checks is that a full pool keeps the pose,
  // not the hall's accuracy; a lost pose is metres off.
  INFO("x " << m->pose().x << " expected " << expected.x << ", first registrations rejected " << m->front_end_counters().first_rejected);
  REQUIRE(m->pose().x == Approx(expected.x).margin(0.1));
}

TEST_CASE("Regional maps learn at the slow rate once they hold the configured scans") {
  // The same room run (6 s) into three mappers: never slow, slow after 20 scans at a quarter, and
  // at a rate so small that the maps stay near what their first 20 scans made them. The evidence
  // in the fused map (the sum of |log-odds|) follows the rate (measured: 66.6 M, 64.6 M, 59.4 M).
  using M = dpcr::Mapper<dpcr::VacuumProfile>;
  const dpcr::test::SyntheticRun<M> run(8.0f, 60, 450);
  const auto evidence = [&](int slow_after, float rate) {
    auto m = std::make_unique<M>();
    dpcr::MapperConfig config;
    config.front_end.submap_scans = dpcr::VacuumProfile::kSubmapMaxScans;
    config.front_end.region_slow_learning_scans = slow_after;
    config.front_end.region_slow_learning_rate = rate;
    REQUIRE(m->Init(config) == dpcr::Status::kOk);
    Feed(*m, run);
    REQUIRE(m->status() == dpcr::MapperStatus::kTracking);
    const dpcr::CellBox box = m->MapBounds();
    std::vector<std::int16_t> cells(static_cast<std::size_t>(box.width() * box.height()));
    REQUIRE(m->RenderMap(box, dpcr::Span<std::int16_t>(cells.data(), cells.size())) == dpcr::Status::kOk);
    long sum = 0;
    for (const std::int16_t v : cells) sum += v == dpcr::kUnknownCell ? 0 : (v < 0 ? -v : v);
    return sum;
  };
  const long full = evidence(1000000, 1.0f), quarter = evidence(20, 0.25f), least = evidence(20, 0.003f);
  REQUIRE(quarter < full);
  REQUIRE(least < quarter);
}
