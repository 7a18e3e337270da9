// Never smear (FrontEndConfig::uncertain_turn_rad): a scan whose first registration was rejected
// while the prediction was uncertain goes into no map; a long streak reports lost, is counted,
// and the submap restarts so that tracking can come back.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "core/mapper.hpp"
#include "tests/budget/synthetic_run.hpp"

namespace {

using M = dpcr::Mapper<dpcr::VacuumProfile>;

std::vector<std::int16_t> Render(const M& m) {
  const dpcr::CellBox box = m.MapBounds();
  std::vector<std::int16_t> cells(static_cast<std::size_t>(box.width() * box.height()));
  REQUIRE(m.RenderMap(box, dpcr::Span<std::int16_t>(cells.data(), cells.size())) == dpcr::Status::kOk);
  return cells;
}

// Junk: ranges that match nothing (a lidar spinning up or reporting garbage).
M::ScanType Junk(std::int64_t stamp_us, std::mt19937* rng) {
  std::uniform_real_distribution<float> range(0.3f, 3.0f);
  M::ScanType scan;
  scan.stamp_us = stamp_us;
  for (int b = 0; b < 360; ++b) {
    dpcr::Beam beam;
    beam.angle_rad = -dpcr::kPi + 2.0f * dpcr::kPi * static_cast<float>(b) / 360.0f;
    beam.range_m = range(*rng);
    (void)scan.beams.push_back(beam);
  }
  return scan;
}

struct Runner {
  std::unique_ptr<M> m = std::make_unique<M>();
  dpcr::test::SyntheticRun<M> run{8.0f, 120, 450};
  std::size_t odom = 0;
  // Without the global search (a streak would start it: relocalisation_test.cpp): the keep-out
  // path alone.
  Runner() {
    dpcr::MapperConfig config;
    config.localisation.relocalise = false;
    REQUIRE(m->Init(config) == dpcr::Status::kOk);
  }
  void Odometry(std::int64_t up_to_us) {
    while (odom < run.odometry.size() && run.odometry[odom].stamp_us <= up_to_us) m->AddOdometry(run.odometry[odom++]);
  }
  void Scan(int i) {
    Odometry(run.scans[static_cast<std::size_t>(i)].stamp_us);
    (void)m->AddScan(run.scans[static_cast<std::size_t>(i)]);
  }
};

// A gyro alone (no wheels), the robot not turning: a sample every 10 ms.
struct StillGyro {
  std::int64_t next_us = 0;
  void Until(M* m, std::int64_t t_us) {
    for (; next_us <= t_us; next_us += 10000) {
      dpcr::OdometrySample s;
      s.stamp_us = next_us;
      s.has_wheels = false;
      s.has_gyro = true;
      m->AddOdometry(s);
    }
  }
};

// The run's first `count` scans, after the gyro's samples up to each (none without `gyro`).
void TrackFirstScans(M* m, const dpcr::test::SyntheticRun<M>& run, int count, StillGyro* gyro) {
  for (int i = 0; i < count; ++i) {
    const M::ScanType& scan = run.scans[static_cast<std::size_t>(i)];
    if (gyro != nullptr) gyro->Until(m, scan.stamp_us);
    (void)m->AddScan(scan);
  }
}

}  // namespace

TEST_CASE("A rejected scan under an uncertain prediction goes into no map, a streak is lost and counted") {
  Runner r;
  std::mt19937 rng(7);
  for (int i = 0; i < 20; ++i) r.Scan(i);
  REQUIRE(r.m->status() == dpcr::MapperStatus::kTracking);
  REQUIRE(r.m->counters().scans_rejected == 0);
  // One rejection with good odometry and no turn: fused at the prediction (the map changes).
  r.Odometry(r.run.scans[20].stamp_us);
  (void)r.m->AddScan(Junk(r.run.scans[20].stamp_us, &rng));
  REQUIRE(r.m->counters().scans_fused_at_prediction == 1);
  REQUIRE(r.m->counters().scans_kept_out_rejected == 0);
  // Rejections in a row: the prediction is uncertain, nothing more goes into any map.
  const std::vector<std::int16_t> before = Render(*r.m);
  const std::size_t tiles = r.m->tiles_used();
  for (int i = 21; i < 36; ++i) {
    r.Odometry(r.run.scans[static_cast<std::size_t>(i)].stamp_us);
    (void)r.m->AddScan(Junk(r.run.scans[static_cast<std::size_t>(i)].stamp_us, &rng));
  }
  REQUIRE(r.m->tiles_used() == tiles);
  REQUIRE(Render(*r.m) == before);
  const dpcr::MapperCounters& c = r.m->counters();
  REQUIRE(c.scans_kept_out_rejected == 15);
  REQUIRE(c.scans_not_inserted == 15);
  REQUIRE(c.scans_rejected == 16);
  REQUIRE(r.m->front_end_counters().first_rejected == 16);
  REQUIRE(c.streak_scans == 16);
  REQUIRE(c.longest_streak_scans == 16);
  REQUIRE(c.streak_us == 16 * 100000);
  REQUIRE(c.longest_streak_us == 16 * 100000);
  // At every submap_restart_after_rejections-th rejection in a row (5: the 5th, 10th and 15th).
  REQUIRE(c.submap_restarts == 16 / static_cast<std::uint32_t>(dpcr::FrontEndConfig{}.submap_restart_after_rejections));
  // A run that ends in a streak says lost.
  REQUIRE(r.m->status() == dpcr::MapperStatus::kLost);
  REQUIRE(c.lost_scans == 7);  // rejections 10 to 16
  REQUIRE(c.lost_us == 7 * 100000);
  // Good scans again: the submap restarts from one of them and tracking comes back.
  for (int i = 36; i < 80; ++i) r.Scan(i);
  REQUIRE(r.m->status() == dpcr::MapperStatus::kTracking);
  REQUIRE(r.m->counters().longest_streak_scans >= 16);
  REQUIRE(r.m->counters().scans_not_inserted < 40);
}

TEST_CASE("Without odometry a rejected scan is never fused") {
  auto m = std::make_unique<M>();
  dpcr::MapperConfig config;
  config.front_end.lidar_only_fixed_lag = false;  // below: the same one revolution late
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  const dpcr::test::SyntheticRun<M> run(8.0f, 10, 450);
  (void)m->AddScan(run.scans[0]);
  const std::vector<std::int16_t> before = Render(*m);
  std::mt19937 rng(3);
  (void)m->AddScan(Junk(run.scans[1].stamp_us, &rng));
  REQUIRE(m->counters().scans_rejected == 1);
  REQUIRE(m->counters().scans_kept_out_rejected == 1);
  REQUIRE(m->counters().scans_fused_at_prediction == 0);
  REQUIRE(Render(*m) == before);
}

TEST_CASE("Without odometry, scans going into the maps a revolution late, a rejected scan is never fused") {
  // FrontEndConfig::lidar_only_fixed_lag: each scan goes in once the next one is registered.
  auto m = std::make_unique<M>();
  REQUIRE(m->Init(dpcr::MapperConfig{}) == dpcr::Status::kOk);
  const dpcr::test::SyntheticRun<M> run(8.0f, 10, 450);
  (void)m->AddScan(run.scans[0]);
  REQUIRE(m->tiles_used() == 0);  // the first scan waits (in the submap only)
  (void)m->AddScan(run.scans[1]);
  REQUIRE(m->tiles_used() > 0);  // the first scan is in
  std::mt19937 rng(3);
  (void)m->AddScan(Junk(run.scans[2].stamp_us, &rng));  // rejected; the second scan goes in
  REQUIRE(m->counters().scans_kept_out_rejected == 1);
  const std::vector<std::int16_t> before = Render(*m);
  (void)m->AddScan(run.scans[3]);  // the rejected scan's turn: it stays out
  REQUIRE(m->counters().scans_rejected == 1);
  REQUIRE(m->counters().scans_fused_at_prediction == 0);
  REQUIRE(m->front_end_counters().lag_reregistered == 1);  // the second scan; not the rejected one
  REQUIRE(Render(*m) == before);
}

TEST_CASE("With a gyro alone (no wheels) a rejected scan is never fused") {
  auto m = std::make_unique<M>();
  REQUIRE(m->Init(dpcr::MapperConfig{}) == dpcr::Status::kOk);  // gyro_heading off: no wheels, the gyro anyway
  const dpcr::test::SyntheticRun<M> run(8.0f, 10, 450);
  for (int k = 0; k <= 10; ++k) {
    dpcr::OdometrySample s;
    s.stamp_us = run.scans[0].stamp_us - 50000 + k * 10000;
    s.has_wheels = false;
    s.has_gyro = true;
    s.gyro_yaw_rate = 0.0f;
    m->AddOdometry(s);
  }
  (void)m->AddScan(run.scans[0]);
  const std::vector<std::int16_t> before = Render(*m);
  std::mt19937 rng(5);
  (void)m->AddScan(Junk(run.scans[0].stamp_us + 50000, &rng));
  REQUIRE(m->counters().scans_kept_out_rejected == 1);
  REQUIRE(m->counters().scans_fused_at_prediction == 0);
  REQUIRE(Render(*m) == before);
}

TEST_CASE("A sparse first revolution (a spin-up) does not start the submap, the next full one does") {
  Runner r;
  M::ScanType sparse = r.run.scans[0];
  for (std::size_t b = 0; b < sparse.beams.size(); ++b) {
    if (b % 45 != 0) sparse.beams[b].range_m = 0.0f;  // 10 returns of 450
  }
  r.Odometry(sparse.stamp_us);
  REQUIRE(r.m->AddScan(sparse) == dpcr::Status::kNotEnoughData);
  REQUIRE(r.m->counters().scans_too_sparse == 1);
  REQUIRE(r.m->counters().scans_rejected == 1);
  REQUIRE(r.m->tiles_used() == 0);  // in no map
  for (int i = 1; i < 40; ++i) r.Scan(i);
  CHECK(r.m->counters().scans_too_sparse == 1);
  CHECK(r.m->front_end_counters().first_rejected == 0);
  CHECK(r.m->status() == dpcr::MapperStatus::kTracking);
  // Once the submap holds scans, a sparse one is registered like any other (not skipped).
  M::ScanType later = r.run.scans[40];
  for (std::size_t b = 0; b < later.beams.size(); ++b) {
    if (b % 45 != 0) later.beams[b].range_m = 0.0f;
  }
  r.Odometry(later.stamp_us);
  (void)r.m->AddScan(later);
  CHECK(r.m->counters().scans_too_sparse == 1);
}

TEST_CASE("Without wheels a registration that leaps from the constant velocity's guess is rejected once, then caught up") {
  // FrontEnd::kMaxLeapWithoutWheelsM: one scan after a tracked one the robot cannot be 0.35 m from
  // where its velocity says. (A look-alike would pull the pose so; here the robot truly jumps, so
  // that the next scan, in the streak where the gate is off, shows the registration free again.)
  dpcr::MapperConfig config;
  config.localisation.relocalise = false;
  auto m = std::make_unique<M>();
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  const dpcr::test::SyntheticRun<M> run(8.0f, 60, 450);  // 2.5 cm per scan along x
  for (int i = 0; i < 20; ++i) (void)m->AddScan(run.scans[static_cast<std::size_t>(i)]);
  REQUIRE(m->front_end_counters().first_rejected == 0);
  const dpcr::Pose2 before = m->pose();
  // The scan seen 14 scans further on (0.35 m), stamped as the next one.
  M::ScanType leap = run.scans[34];
  leap.stamp_us = run.scans[20].stamp_us;
  (void)m->AddScan(leap);
  CHECK(m->front_end_counters().first_rejected == 1);
  CHECK(std::hypot(m->pose().x - before.x, m->pose().y - before.y) < 0.1f);
  // The next one (15 scans on), in the streak: registered where it is.
  M::ScanType next = run.scans[35];
  next.stamp_us = run.scans[21].stamp_us;
  (void)m->AddScan(next);
  CHECK(m->front_end_counters().first_rejected == 1);
  const dpcr::Pose2 start = run.Sample(0.095f, 0.25f, 8.0f).pose;  // the map's frame is the first scan's pose
  const dpcr::Pose2 truth = run.Sample(3.595f, 0.25f, 8.0f).pose;
  INFO("pose " << m->pose().x << " " << m->pose().y << ", truth " << truth.x - start.x << " " << truth.y - start.y);
  CHECK(std::hypot(m->pose().x - (truth.x - start.x), m->pose().y - (truth.y - start.y)) < 0.03f);
}

TEST_CASE("Without wheels a registration faster than a vacuum drives is rejected") {
  // FrontEnd::kMaxSpeedWithoutWheelsMps (with a heading sensor): a run of registrations that each
  // agree with the constant velocity can still race away where the walls give no hold along the
  // way; past the speed no vacuum drives, the registration is not taken.
  dpcr::MapperConfig config;
  config.localisation.relocalise = false;
  auto m = std::make_unique<M>();
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  const dpcr::test::SyntheticRun<M> run(8.0f, 60, 450);  // 2.5 cm per scan along x (0.25 m/s)
  StillGyro gyro{run.scans[0].stamp_us - 100000};
  TrackFirstScans(m.get(), run, 20, &gyro);
  REQUIRE(m->front_end_counters().first_rejected == 0);
  // The scan seen 3 scans further on, stamped as the next one: 0.075 m in 0.1 s, within the
  // leap allowed from the guess (0.05 m off it) but 0.75 m/s.
  M::ScanType fast = run.scans[22];
  fast.stamp_us = run.scans[20].stamp_us;
  gyro.Until(m.get(), fast.stamp_us);
  (void)m->AddScan(fast);
  CHECK(m->front_end_counters().first_rejected == 1);
}

namespace {

// A robot driving straight at 0.25 m/s meets three scans it cannot register (junk) after 20
// tracked ones; returns how far its pose moved over them. `with_gyro`: a gyro alone (the heading
// known, no wheels); otherwise no odometry at all.
float MoveOverThreeRejectedScans(bool with_gyro) {
  dpcr::MapperConfig config;
  config.localisation.relocalise = false;
  auto m = std::make_unique<M>();
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  const dpcr::test::SyntheticRun<M> run(8.0f, 60, 450);  // 2.5 cm per scan along x
  StillGyro still{run.scans[0].stamp_us - 100000};
  StillGyro* gyro = with_gyro ? &still : nullptr;
  TrackFirstScans(m.get(), run, 20, gyro);
  REQUIRE(m->front_end_counters().first_rejected == 0);
  const dpcr::Pose2 before = m->pose();
  std::mt19937 rng(3);
  for (int i = 20; i < 23; ++i) {
    if (gyro != nullptr) gyro->Until(m.get(), run.scans[static_cast<std::size_t>(i)].stamp_us);
    (void)m->AddScan(Junk(run.scans[static_cast<std::size_t>(i)].stamp_us, &rng));
  }
  REQUIRE(m->front_end_counters().first_rejected == 3);
  return std::hypot(m->pose().x - before.x, m->pose().y - before.y);
}

}  // namespace

TEST_CASE("In a rejection streak a robot with a heading sensor keeps its speed and one without slows down") {
  // FrontEnd::FadeConstantVelocity: the truth moves 7.5 cm over the three scans. With the gyro the
  // translation is held (a robot crossing a room whose far wall is out of reach keeps going).
  // Without any sensor it fades as before: the first rejected scan still moves by the last
  // tracked step, the next two by half and a quarter of it (2.5 + 1.25 + 0.6 cm).
  const float with_gyro = MoveOverThreeRejectedScans(true);
  const float without = MoveOverThreeRejectedScans(false);
  INFO("moved " << with_gyro << " m with a gyro, " << without << " m without odometry");
  CHECK(std::fabs(with_gyro - 0.075f) < 0.01f);
  CHECK(std::fabs(without - 0.044f) < 0.005f);
}
