// A wheel board that restarts mid-run counts from another origin: the odometry jumps by metres
// between two samples. No robot moves so; the first registration from that prediction is
// rejected and tried again from the constant velocity (FrontEndConfig::odometry_doubt_*), which
// takes the robot on as if nothing had happened. With that retry off, the same restart opens a
// second region 23 m away and maps the room again there.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <memory>

#include "core/mapper.hpp"
#include "tests/budget/synthetic_run.hpp"

namespace {

using Tiny = dpcr::Mapper<dpcr::TinyProfile>;
using Run = dpcr::test::SyntheticRun<Tiny>;

// The run mapped with every odometry sample from scan `restart_scan` on seen from `restart`
// (restart_scan past the run: as logged).
std::unique_ptr<Tiny> Map(const Run& run, std::size_t restart_scan, const dpcr::Pose2& restart) {
  dpcr::MapperConfig config;
  config.front_end.submap_scans = dpcr::TinyProfile::kSubmapMaxScans;
  auto m = std::make_unique<Tiny>();
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  std::size_t next = 0;
  for (std::size_t i = 0; i < run.scans.size(); ++i) {
    for (; next < run.odometry.size() && run.odometry[next].stamp_us <= run.scans[i].stamp_us; ++next) {
      dpcr::OdometrySample s = run.odometry[next];
      if (i >= restart_scan) s.pose = restart * s.pose;
      m->AddOdometry(s);
    }
    (void)m->AddScan(run.scans[i]);
  }
  return m;
}

}  // namespace

TEST_CASE("Odometry that restarts 24 m away at any scan leaves one room and the pose") {
  const Run run(6.0f, 40, 180);
  const auto clean = Map(run, run.scans.size(), dpcr::Pose2{});
  const dpcr::CellBox a = clean->MapBounds();
  for (std::size_t restart_scan = 1; restart_scan < run.scans.size(); ++restart_scan) {
    CAPTURE(restart_scan);
    const auto m = Map(run, restart_scan, dpcr::Pose2{24.0f, -7.0f, 1.0f});
    CHECK(m->front_end_counters().odometry_overruled >= 1);
    CHECK(m->counters().regions_created == clean->counters().regions_created);
    CHECK(std::hypot(m->pose().x - clean->pose().x, m->pose().y - clean->pose().y) < 0.02f);
    const dpcr::CellBox b = m->MapBounds();
    CHECK((std::abs(a.min.x - b.min.x) <= 2 && std::abs(a.max.x - b.max.x) <= 2));
    CHECK((std::abs(a.min.y - b.min.y) <= 2 && std::abs(a.max.y - b.max.y) <= 2));
  }
}
