// The regional maps' life cycle: one map per region, current and previous, a full pool that
// stops growth, scans inserted in the map's frame, seeding from the submap.
#include <catch2/catch.hpp>

#include <memory>
#include <vector>

#include "core/front_end/region_set.hpp"

using dpcr::CellIndex;
using dpcr::Point2;
using dpcr::Pose2;
using dpcr::RegionKey;
using dpcr::RegionSet;

namespace {
// Two maps of 2 x 2 tiles (3.2 m at 5 cm) on one tile pool.
struct TwoMaps {
  TwoMaps() {
    for (int i = 0; i < 2; ++i) {
      grids[i].Attach(&tiles);
      maps[i].grid = &grids[i];
    }
    set.Reset(dpcr::GridConfig{}, 0.0f);
  }
  dpcr::TilePoolStorage<16> tiles;
  dpcr::TiledGridStorage<2, 2> grids[2];
  dpcr::RegionalMap maps[2];
  CellIndex scratch[64];
  RegionSet set{dpcr::Span<dpcr::RegionalMap>(maps, 2), dpcr::Span<CellIndex>(scratch, 64)};
};

std::int16_t CellAt(const dpcr::TiledGrid& g, Point2 p) { return g.Get(dpcr::CellOf(p.x, p.y, g.resolution_m())); }
}  // namespace

TEST_CASE("A region gets a map on first entry, anchored at its centre, re-entry finds it") {
  auto m = std::make_unique<TwoMaps>();
  RegionSet& set = m->set;
  REQUIRE(set.Enter(RegionKey{0, 0}, Point2{1.0f, 2.0f}) == RegionSet::Entry::kCreated);
  REQUIRE(set.size() == 1);
  REQUIRE(set.current() == 0);
  REQUIRE(set.previous() == -1);
  REQUIRE(set[0].anchor.x == 1.0f);
  REQUIRE(set[0].anchor.y == 2.0f);
  // The anchor is the box centre.
  REQUIRE(set[0].grid->box().min == CellIndex{-32, -32});
  REQUIRE(set.Enter(RegionKey{1, 0}, Point2{5.0f, 2.0f}) == RegionSet::Entry::kCreated);
  REQUIRE(set.current() == 1);
  REQUIRE(set.previous() == 0);
  REQUIRE(set.Enter(RegionKey{0, 0}, Point2{1.0f, 2.0f}) == RegionSet::Entry::kKnown);
  REQUIRE(set.size() == 2);
  REQUIRE(set.current() == 0);
  REQUIRE(set.previous() == 1);
  // Entering the current region again keeps the previous one.
  REQUIRE(set.Enter(RegionKey{0, 0}, Point2{1.0f, 2.0f}) == RegionSet::Entry::kKnown);
  REQUIRE(set.previous() == 1);
  REQUIRE(set.Find(RegionKey{1, 0}) == 1);
  REQUIRE(set.Find(RegionKey{2, 0}) == -1);
  REQUIRE_FALSE(set.pool_full());
}

TEST_CASE("A full region pool leaves no map current, keeps the last one as previous, and says so") {
  auto m = std::make_unique<TwoMaps>();
  RegionSet& set = m->set;
  (void)set.Enter(RegionKey{0, 0}, Point2{0.0f, 0.0f});
  (void)set.Enter(RegionKey{1, 0}, Point2{4.0f, 0.0f});
  REQUIRE(set.Enter(RegionKey{2, 0}, Point2{8.0f, 0.0f}) == RegionSet::Entry::kPoolFull);
  REQUIRE(set.size() == 2);
  REQUIRE(set.current() == -1);
  REQUIRE(set.previous() == 1);
  REQUIRE(set.pool_full());
  // Back into a known region: it is current, and the previous one stays.
  REQUIRE(set.Enter(RegionKey{0, 0}, Point2{0.0f, 0.0f}) == RegionSet::Entry::kKnown);
  REQUIRE(set.current() == 0);
  REQUIRE(set.previous() == 1);
  // Reset forgets the maps and the full pool.
  set.Reset(dpcr::GridConfig{}, 0.0f);
  REQUIRE(set.size() == 0);
  REQUIRE(set.current() == -1);
  REQUIRE_FALSE(set.pool_full());
}

TEST_CASE("A scan goes into the current map, in the map's frame") {
  auto m = std::make_unique<TwoMaps>();
  RegionSet& set = m->set;
  std::vector<Point2> hits{Point2{1.01f, 0.0f}};
  // No current map: nothing is inserted.
  REQUIRE(set.InsertScan(Pose2{}, dpcr::Span<Point2>(hits.data(), 1), dpcr::Span<Point2>(), 1).hit_cells == 0);
  (void)set.Enter(RegionKey{0, 0}, Point2{2.0f, 1.0f});
  // Robot at (2.52, 1) facing +y: the hit ahead is at (2.52, 2.01) in the world, (0.52, 1.01) in the map.
  const dpcr::InsertionStats st =
      set.InsertScan(Pose2{2.52f, 1.0f, dpcr::kPi / 2}, dpcr::Span<Point2>(hits.data(), 1), dpcr::Span<Point2>(), 2);
  REQUIRE(st.hit_cells == 1);
  REQUIRE(hits[0].x == Approx(0.52f).margin(1e-5));
  REQUIRE(hits[0].y == Approx(1.01f).margin(1e-5));
  REQUIRE(dpcr::IsOccupied(CellAt(*set[0].grid, Point2{0.52f, 1.02f})));
  REQUIRE(dpcr::IsFree(CellAt(*set[0].grid, Point2{0.52f, 0.5f})));
  REQUIRE(set[0].scans_inserted == 1);
}

TEST_CASE("A new map is seeded with the submap's scans but the newest, one marker each") {
  auto m = std::make_unique<TwoMaps>();
  RegionSet& set = m->set;
  auto submap = std::make_unique<dpcr::SubmapStorage<4, 64, 128>>();
  submap->Reset(dpcr::GridConfig{}, 4);
  // Three scans, each one hit 1.01 m ahead of a robot that moves 0.5 m along x between them.
  for (int i = 0; i < 3; ++i) {
    const Point2 hit{1.01f, 0.0f};
    (void)submap->Add(Pose2{0.5f * static_cast<float>(i), 0.0f, 0.0f}, dpcr::Span<const Point2>(&hit, 1));
  }
  (void)set.Enter(RegionKey{0, 0}, Point2{1.0f, 0.0f});
  dpcr::ScanMarker marker;
  (void)marker.Next();  // the scan being added
  std::vector<Point2> points(64);
  // The submap frame is 0.26 m up in the world.
  REQUIRE(set.SeedFromSubmap(*submap, Pose2{0.0f, 0.26f, 0.0f}, dpcr::Span<Point2>(points.data(), points.size()), marker) == 0);
  REQUIRE(marker.current() == 4);  // two seeded scans and the scan being added
  const dpcr::TiledGrid& g = *set[0].grid;
  // Map frame = world - (1, 0): the hits of scans 0 and 1 at x = 0.01 and 0.51, y = 0.26; not scan 2's.
  REQUIRE(dpcr::IsOccupied(CellAt(g, Point2{0.02f, 0.27f})));
  REQUIRE(dpcr::IsOccupied(CellAt(g, Point2{0.52f, 0.27f})));
  REQUIRE(CellAt(g, Point2{1.02f, 0.27f}) == dpcr::kUnknownCell);
}

TEST_CASE("A scan inserted at a learning rate moves cells by that share of the deltas") {
  auto m = std::make_unique<TwoMaps>();
  RegionSet& set = m->set;
  const dpcr::GridConfig grid;
  (void)set.Enter(RegionKey{0, 0}, Point2{0.0f, 0.0f});
  const auto insert = [&](Point2 hit, std::uint32_t marker, float rate) {
    std::vector<Point2> hits{hit};
    (void)set.InsertScan(Pose2{}, dpcr::Span<Point2>(hits.data(), 1), dpcr::Span<Point2>(), marker, -1, rate);
  };
  // Three scans at full rate: the hit cell holds three hits, a cell its ray crosses three misses.
  for (std::uint32_t k = 1; k <= 3; ++k) insert(Point2{1.01f, 0.01f}, k, 1.0f);
  const std::int16_t hit3 = CellAt(*set[0].grid, Point2{1.01f, 0.01f});
  const std::int16_t free3 = CellAt(*set[0].grid, Point2{0.51f, 0.01f});
  REQUIRE(hit3 == 3 * grid.hit_delta);
  REQUIRE(free3 == 3 * grid.miss_delta);
  // A quarter of each delta, rounded towards 0, on the old cells and on a new one.
  const dpcr::GridConfig slow = dpcr::ScaledLearning(grid, 0.25f);
  REQUIRE(slow.hit_delta == 216);  // 867 / 4
  REQUIRE(slow.miss_delta == -103);  // -415 / 4
  insert(Point2{1.01f, 0.01f}, 4, 0.25f);
  REQUIRE(CellAt(*set[0].grid, Point2{1.01f, 0.01f}) == hit3 + slow.hit_delta);
  REQUIRE(CellAt(*set[0].grid, Point2{0.51f, 0.01f}) == free3 + slow.miss_delta);
  insert(Point2{0.01f, 1.01f}, 5, 0.25f);
  REQUIRE(CellAt(*set[0].grid, Point2{0.01f, 1.01f}) == slow.hit_delta);
  REQUIRE(dpcr::IsOccupied(CellAt(*set[0].grid, Point2{0.01f, 1.01f})));  // one hit still marks a wall
  REQUIRE(set[0].scans_inserted == 5);
}
