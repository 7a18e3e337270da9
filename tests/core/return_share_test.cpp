// The share of a lidar's returns where it sees anything (ProjectedScan::beams_in_returning_sectors,
// core/front_end/return_share.hpp) and the submap threshold it scales.
#include "core/front_end/return_share.hpp"

#include <catch2/catch.hpp>

#include <vector>

#include "core/config.hpp"
#include "core/front_end/odometry_buffer.hpp"
#include "core/front_end/scan_motion.hpp"
#include "core/geometry/scan.hpp"
#include "core/geometry/scan_projection.hpp"

namespace {

// `n` beams at 1 degree; beam i returns at 2 m when returns(i), else reads 0 (no return).
template <class Returns>
dpcr::ProjectedScan Project(int n, Returns returns) {
  std::vector<dpcr::Beam> beams;
  for (int i = 0; i < n; ++i) beams.push_back(dpcr::Beam{0.0174533f * static_cast<float>(i), returns(i) ? 2.0f : 0.0f, 0});
  dpcr::LidarConfig lidar;
  lidar.max_range_m = 6.0f;
  const dpcr::OdometryBuffer none;
  const dpcr::ScanMotion still(none, false, dpcr::Pose2::Identity(), 0);
  std::vector<dpcr::Point2> hits(beams.size()), free_ends(beams.size());
  return dpcr::ProjectScan(dpcr::Span<const dpcr::Beam>(beams.data(), beams.size()), lidar, still,
                           dpcr::Span<dpcr::Point2>(hits.data(), hits.size()),
                           dpcr::Span<dpcr::Point2>(free_ends.data(), free_ends.size()));
}

}  // namespace

TEST_CASE("Beams count where their sector of eight holds a return") {
  // A wall across the first quarter, 40 % of its beams returning; nothing in range elsewhere.
  const dpcr::ProjectedScan wall = Project(360, [](int i) { return i < 90 && i % 5 < 2; });
  CHECK(wall.hits == 36);
  CHECK(wall.beams_in_returning_sectors == 88);  // sectors 0-7 ... 80-87 (beam 86 the last returning): eleven
  // Every beam returning: every beam counts, the last sector's three (83 = 10 x 8 + 3) too.
  const dpcr::ProjectedScan full = Project(83, [](int) { return true; });
  CHECK(full.hits == 83);
  CHECK(full.beams_in_returning_sectors == 83);
  const dpcr::ProjectedScan last_only = Project(83, [](int i) { return i == 82; });
  CHECK(last_only.beams_in_returning_sectors == 3);
  CHECK(Project(83, [](int) { return false; }).beams_in_returning_sectors == 0);
}

TEST_CASE("The return share follows the scans and a blind scan leaves it") {
  dpcr::ProjectedScan sparse;
  sparse.hits = 40;
  sparse.beams_in_returning_sectors = 100;
  float share = 1.0f;
  for (int k = 0; k < 100; ++k) share = dpcr::UpdateReturnShare(share, sparse);
  CHECK(share == Approx(0.4f).margin(0.01f));
  const dpcr::ProjectedScan blind;  // no returning sector: a lidar facing nothing in range
  CHECK(dpcr::UpdateReturnShare(share, blind) == share);
  // One scan moves it by a twentieth of the difference.
  dpcr::ProjectedScan full;
  full.hits = 100;
  full.beams_in_returning_sectors = 100;
  CHECK(dpcr::UpdateReturnShare(0.4f, full) == Approx(0.43f));
}

TEST_CASE("The submap threshold scales with a share below the full one") {
  const dpcr::ReferenceConfig base = dpcr::FrontEndConfig{}.submap_reference;
  REQUIRE(base.obstacle_threshold == 2000);
  CHECK(dpcr::ReferenceForReturnShare(base, 0.3f, 0.6f).obstacle_threshold == 1000);
  CHECK(dpcr::ReferenceForReturnShare(base, 0.6f, 0.6f).obstacle_threshold == 2000);
  CHECK(dpcr::ReferenceForReturnShare(base, 0.9f, 0.6f).obstacle_threshold == 2000);
  CHECK(dpcr::ReferenceForReturnShare(base, 0.3f, 0.0f).obstacle_threshold == 2000);  // off
  // The rest of the reference's configuration is the base's.
  CHECK(dpcr::ReferenceForReturnShare(base, 0.3f, 0.6f).lines.max_rms_cells == base.lines.max_rms_cells);
}
