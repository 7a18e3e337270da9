// What fuzz/fuzz_mapper_scans.cpp found, kept as regression tests: stamps at the int64 extremes
// (signed overflow in the odometry buffer), a beam time offset near INT32_MAX (overflow when a
// waiting scan was packed), a NaN beam angle (a NaN hit inserted into the maps) and a gyro rate of
// 1e30 (an infinite heading). Each bad input is refused and counted, and the run around it goes
// on as it would have without it.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>

#include "core/mapper.hpp"
#include "tests/budget/synthetic_run.hpp"

namespace {

using Tiny = dpcr::Mapper<dpcr::TinyProfile>;
using Run = dpcr::test::SyntheticRun<Tiny>;

std::unique_ptr<Tiny> MakeMapper() {
  auto m = std::make_unique<Tiny>();
  dpcr::MapperConfig config;
  config.front_end.submap_scans = dpcr::TinyProfile::kSubmapMaxScans;
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  return m;
}

// Scans [first, last) with the odometry up to each (none when `odometry` is false).
void Feed(Tiny& m, const Run& run, std::size_t first, std::size_t last, bool odometry = true) {
  for (std::size_t i = first; i < last; ++i) {
    if (odometry) {
      for (const auto& s : run.odometry) {
        if (s.stamp_us > run.scans[i].stamp_us) break;
        if (i == 0 || s.stamp_us > run.scans[i - 1].stamp_us) m.AddOdometry(s);
      }
    }
    (void)m.AddScan(run.scans[i]);
  }
}

// A 40-scan room run mapped whole (`clean`), and a mapper that has taken its first 20 scans.
struct Halfway {
  Run run{6.0f, 40, 180};
  std::unique_ptr<Tiny> clean = MakeMapper();
  std::unique_ptr<Tiny> mapper = MakeMapper();
  Halfway() {
    Feed(*clean, run, 0, 40);
    Feed(*mapper, run, 0, 20);
  }
};

bool SamePose(const dpcr::Pose2& a, const dpcr::Pose2& b) { return a.x == b.x && a.y == b.y && a.theta == b.theta; }

}  // namespace

TEST_CASE("A scan stamped before 1970 or past 2 to the 56 us is refused and changes nothing") {
  const Halfway h;
  const Run& run = h.run;
  Tiny* m = h.mapper.get();
  const dpcr::Pose2 before = m->pose();
  for (const std::int64_t stamp : {std::numeric_limits<std::int64_t>::min(), std::int64_t{-1},
                                   std::numeric_limits<std::int64_t>::max(), dpcr::kMaxStampUs + 1}) {
    Tiny::ScanType scan = run.scans[20];
    scan.stamp_us = stamp;
    CHECK(m->AddScan(scan) == dpcr::Status::kInvalidArgument);
  }
  CHECK(SamePose(m->pose(), before));
  Feed(*m, run, 20, 40);
  CHECK(m->counters().scans_bad_stamp == 4);
  CHECK(m->counters().scans == 44);
  CHECK(h.clean->counters().scans_bad_stamp == 0);
  CHECK(SamePose(m->pose(), h.clean->pose()));  // the same run, bit for bit
}

TEST_CASE("Odometry stamped at the int64 extremes or turning past any gyro is dropped and counted") {
  const Halfway h;
  const Run& run = h.run;
  Tiny* m = h.mapper.get();
  dpcr::OdometrySample bad = run.odometry[199];
  for (const std::int64_t stamp : {std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max()}) {
    bad.stamp_us = stamp;
    m->AddOdometry(bad);
  }
  bad = run.odometry[199];
  bad.has_gyro = true;
  bad.gyro_yaw_rate = 1e30f;  // finite, and integrated to an infinite heading
  m->AddOdometry(bad);
  Feed(*m, run, 20, 40);
  CHECK(m->counters().odometry_rejected == 3);
  CHECK(SamePose(m->pose(), h.clean->pose()));
}

TEST_CASE("Beams with a wild angle or time offset count as invalid and place nothing") {
  const bool odometry = GENERATE(true, false);  // false: the lidar-only path, whose scans wait packed
  INFO("odometry " << odometry);
  const Run run(6.0f, 40, 180);
  auto clean = MakeMapper();
  Feed(*clean, run, 0, 40, odometry);
  Run hostile = run;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (std::size_t i = 10; i < 40; i += 3) {
    auto& beams = hostile.scans[i].beams;
    beams[0].angle_rad = nan;
    beams[30].angle_rad = inf;
    beams[60].angle_rad = -1e9f;
    beams[90].offset_us = std::numeric_limits<std::int32_t>::max();
    beams[120].offset_us = std::numeric_limits<std::int32_t>::min();
  }
  auto m = MakeMapper();
  Feed(*m, hostile, 0, 40, odometry);
  CHECK(m->counters().beams_invalid == clean->counters().beams_invalid + 10 * 5);
  // Lidar alone in a bare square room, 3 % fewer beams in a third of the scans move the end by
  // 1.4 cm; with wheels by less than a millimetre.
  const float margin = odometry ? 0.005f : 0.025f;
  CHECK(m->pose().x == Approx(clean->pose().x).margin(margin));
  CHECK(m->pose().y == Approx(clean->pose().y).margin(margin));
  CHECK(m->pose().theta == Approx(clean->pose().theta).margin(0.01));
}

TEST_CASE("A scan hours after the one before it carries no time across the jump") {
  const Run run(6.0f, 40, 180);
  auto clean = MakeMapper();
  Feed(*clean, run, 0, 40);
  // The robot slept for three hours after scan 19: every later stamp, scans and odometry, is later.
  Run slept = run;
  constexpr std::int64_t kThreeHoursUs = 3LL * 3600 * 1000000;
  for (std::size_t i = 20; i < 40; ++i) slept.scans[i].stamp_us += kThreeHoursUs;
  for (auto& s : slept.odometry) {
    if (s.stamp_us > run.scans[19].stamp_us) s.stamp_us += kThreeHoursUs;
  }
  auto m = MakeMapper();
  Feed(*m, slept, 0, 40);
  CHECK(m->counters().scan_stamp_jumps == 1);
  CHECK(clean->counters().scan_stamp_jumps == 0);
  CHECK(m->counters().scans_rejected == clean->counters().scans_rejected);
  CHECK(m->pose().x == Approx(clean->pose().x).margin(0.01));
  CHECK(m->pose().y == Approx(clean->pose().y).margin(0.01));
}

TEST_CASE("A corrupt odometry increment is dropped and the next goes on from the last good pose") {
  auto clean = MakeMapper();
  auto m = MakeMapper();
  const dpcr::Pose2 step{0.01f, 0.0f, 0.002f};
  for (int i = 1; i <= 100; ++i) {
    const std::int64_t t = 10000LL * i;
    clean->AddOdometryIncrement(t, step);
    m->AddOdometryIncrement(t, step);
    if (i == 50) m->AddOdometryIncrement(t + 1, dpcr::Pose2{2e6f, 0.0f, 0.0f});  // 2000 km in 1 us
  }
  CHECK(m->counters().odometry_rejected == 1);
  CHECK(m->counters().odometry_samples == clean->counters().odometry_samples);
  // Both end where 100 steps take the robot: one scan at the end places it.
  Tiny::ScanType scan;
  for (int b = 0; b < 180; ++b) (void)scan.beams.push_back(dpcr::Beam{-3.14159f + 0.0349f * static_cast<float>(b), 2.0f, 0});
  scan.stamp_us = 1000000;
  (void)clean->AddScan(scan);
  (void)m->AddScan(scan);
  scan.stamp_us += 100000;
  clean->AddOdometryIncrement(scan.stamp_us, step);
  m->AddOdometryIncrement(scan.stamp_us, step);
  (void)clean->AddScan(scan);
  (void)m->AddScan(scan);
  CHECK(SamePose(m->pose(), clean->pose()));
}

TEST_CASE("Lidar-only scans stamped at the same time as the one before them are mapped without NaN") {
  // The fixed-lag de-skew divided the motion between two scans by the time between their stamps:
  // 0 / 0 when a recorder stamped two revolutions alike, and a NaN hit reached the maps
  // (fuzz_mapper_scans, under UBSan: FloorToInt(NaN)). The motion is now none.
  const Run run(6.0f, 40, 180);
  auto clean = MakeMapper();
  Feed(*clean, run, 0, 40, false);
  Run twice = run;
  for (std::size_t i = 21; i < 40; i += 4) twice.scans[i].stamp_us = twice.scans[i - 1].stamp_us;
  auto m = MakeMapper();
  Feed(*m, twice, 0, 40, false);
  CHECK(m->counters().scans == 40);
  CHECK(std::isfinite(m->pose().x));
  CHECK(std::isfinite(m->pose().theta));
  CHECK(m->pose().x == Approx(clean->pose().x).margin(0.05));
  CHECK(m->pose().y == Approx(clean->pose().y).margin(0.05));
  const dpcr::CellBox a = clean->MapBounds(), b = m->MapBounds();
  CHECK((std::abs(a.min.x - b.min.x) <= 2 && std::abs(a.max.x - b.max.x) <= 2));
  CHECK((std::abs(a.min.y - b.min.y) <= 2 && std::abs(a.max.y - b.max.y) <= 2));
}

TEST_CASE("Odometry headings of any finite size are angles and never make a pose NaN") {
  // Two wheel samples at -3.3e38 and 3.3e38 rad (finite, so not refused) differed by infinity
  // where the de-skew interpolated between them, and a NaN hit reached the maps
  // (fuzz_mapper_scans, under UBSan: FloorToInt(NaN)). Headings past a half turn are now wrapped
  // on entry. This one is a whole number of turns and 1.7e-6 rad (the run's true heading is 0), so
  // the run must come out as without it.
  const float turns = 0x1.f7b7d2p+127f;
  REQUIRE(std::fabs(dpcr::NormalizeAngle(turns)) < 1e-5f);
  REQUIRE(std::fabs(dpcr::NormalizeAngle(-turns)) < 1e-5f);
  const Halfway h;
  const Run& run = h.run;
  Tiny* m = h.mapper.get();
  Run hostile = run;
  for (std::size_t i = 200; i < hostile.odometry.size(); ++i) {
    REQUIRE(hostile.odometry[i].pose.theta == 0.0f);
    hostile.odometry[i].pose.theta = i % 2 == 0 ? turns : -turns;
  }
  Feed(*m, hostile, 20, 40);
  CHECK(m->counters().scans == 40);
  CHECK(m->counters().odometry_rejected == 0);
  CHECK(m->counters().updates_out_of_box == h.clean->counters().updates_out_of_box);
  CHECK(m->pose().x == Approx(h.clean->pose().x).margin(0.002));
  CHECK(m->pose().y == Approx(h.clean->pose().y).margin(0.002));
  CHECK(m->pose().theta == Approx(h.clean->pose().theta).margin(0.001));
}
