// Scan insertion: misses along rays, hits at endpoints, one update per cell per scan.
#include <catch2/catch.hpp>

#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "core/grid/ray_caster.hpp"

using dpcr::CellIndex;
using dpcr::Point2;

namespace {
struct Fixture {
  std::unique_ptr<dpcr::TilePoolStorage<16>> pool = std::make_unique<dpcr::TilePoolStorage<16>>();
  std::unique_ptr<dpcr::TiledGridStorage<4, 4>> grid = std::make_unique<dpcr::TiledGridStorage<4, 4>>(pool.get());
  dpcr::GridConfig config;
  CellIndex scratch[64];
  Fixture() {
    grid->Reset(CellIndex{-2, -2});
    config.hit_margin_m = 0.0f;  // the plain update rule; the margin has tests of its own below
  }
  dpcr::InsertionStats Insert(Point2 origin, const std::vector<Point2>& hits, std::uint32_t stamp,
                              const std::vector<Point2>& free_ends = {}) {
    return dpcr::InsertRays(*grid, origin, dpcr::Span<const Point2>(hits.data(), hits.size()),
                            dpcr::Span<const Point2>(free_ends.data(), free_ends.size()), config, stamp,
                            dpcr::Span<CellIndex>(scratch, 64));
  }
};
}  // namespace

TEST_CASE("TraceCells visits a straight, gap-free line excluding the end") {
  std::vector<std::pair<int, int>> cells;
  dpcr::TraceCells(CellIndex{0, 0}, CellIndex{5, 2}, [&](CellIndex c) {
    cells.emplace_back(c.x, c.y);
    return true;
  });
  REQUIRE(cells.size() == 5);
  REQUIRE(cells.front() == std::make_pair(0, 0));
  for (std::size_t i = 1; i < cells.size(); ++i) {
    REQUIRE(std::abs(cells[i].first - cells[i - 1].first) <= 1);
    REQUIRE(std::abs(cells[i].second - cells[i - 1].second) <= 1);
  }
}

TEST_CASE("One beam marks free cells up to the wall and the wall cell occupied") {
  Fixture f;
  const auto stats = f.Insert(Point2{0.025f, 0.025f}, {Point2{1.025f, 0.025f}}, 1);
  REQUIRE(stats.hit_cells == 1);
  REQUIRE(stats.miss_cells == 20);
  REQUIRE(f.grid->Get(CellIndex{20, 0}) == f.config.hit_delta);
  for (int x = 0; x < 20; ++x) REQUIRE(f.grid->Get(CellIndex{x, 0}) == f.config.miss_delta);
  REQUIRE(f.grid->Get(CellIndex{21, 0}) == dpcr::kUnknownCell);
}

TEST_CASE("Crossing rays update a shared cell once, and a hit wins over a miss") {
  Fixture f;
  // Two beams ending in the same cell, and a third ray passing through that cell.
  f.Insert(Point2{0.025f, 0.025f},
           {Point2{0.51f, 0.02f}, Point2{0.52f, 0.03f}, Point2{1.025f, 0.025f}}, 1);
  REQUIRE(f.grid->Get(CellIndex{10, 0}) == f.config.hit_delta);  // hit once, not twice, no miss
  REQUIRE(f.grid->Get(CellIndex{5, 0}) == f.config.miss_delta);  // crossed by three rays, one miss
  // The next scan may update the same cells again.
  f.Insert(Point2{0.025f, 0.025f}, {Point2{1.025f, 0.025f}}, 2);
  REQUIRE(f.grid->Get(CellIndex{10, 0}) == f.config.hit_delta + f.config.miss_delta);
  REQUIRE(f.grid->Get(CellIndex{5, 0}) == 2 * f.config.miss_delta);
}

TEST_CASE("Beams without a return clear space but mark no wall, far points are counted, not lost silently") {
  Fixture f;
  const auto stats = f.Insert(Point2{0.025f, 0.025f}, {Point2{10.0f, 0.0f}}, 1, {Point2{0.025f, 0.5f}});
  REQUIRE(stats.out_of_box > 0);
  REQUIRE(f.grid->Get(CellIndex{0, 10}) == dpcr::kUnknownCell);  // the free end itself is not updated
  REQUIRE(f.grid->Get(CellIndex{0, 9}) == f.config.miss_delta);
}

TEST_CASE("Two beams hitting the same new cell are one hit, not a pool-full drop") {
  Fixture f;
  const auto stats = f.Insert(Point2{0.025f, 0.025f}, {Point2{1.0f, 1.0f}, Point2{1.01f, 1.01f}}, 1);
  REQUIRE(stats.hit_cells == 1);
  REQUIRE(stats.dropped_pool_full == 0);
}

TEST_CASE("An exhausted tile pool is reported as dropped updates") {
  auto pool = std::make_unique<dpcr::TilePoolStorage<1>>();
  auto grid = std::make_unique<dpcr::TiledGridStorage<4, 4>>(pool.get());
  grid->Reset(CellIndex{-2, -2});
  dpcr::GridConfig config;
  config.hit_margin_m = 0.0f;
  CellIndex scratch[4];
  const std::vector<Point2> hits{Point2{2.5f, 0.025f}};  // two tiles away from the origin's tile
  const auto stats = dpcr::InsertRays(*grid, Point2{0.025f, 0.025f}, dpcr::Span<const Point2>(hits.data(), 1),
                                      dpcr::Span<const Point2>(), config, 1, dpcr::Span<CellIndex>(scratch, 4));
  // The hit's tile is taken first; the misses in the origin's tile find the pool empty.
  REQUIRE(stats.hit_cells == 1);
  REQUIRE(stats.dropped_pool_full == 32);
  REQUIRE(stats.miss_cells == 18);
  REQUIRE(pool->used() == 1);
  REQUIRE(pool->failed_allocations() > 0);
}

TEST_CASE("A ray clears nothing within the hit margin before its return") {
  Fixture f;
  f.config.hit_margin_m = 0.05f;
  const auto stats = f.Insert(Point2{0.025f, 0.025f}, {Point2{1.025f, 0.025f}}, 1);
  REQUIRE(stats.hit_cells == 1);
  REQUIRE(stats.miss_cells == 19);
  for (int x = 0; x < 19; ++x) REQUIRE(f.grid->Get(CellIndex{x, 0}) == f.config.miss_delta);
  REQUIRE(f.grid->Get(CellIndex{19, 0}) == dpcr::kUnknownCell);  // inside the margin
  REQUIRE(f.grid->Get(CellIndex{20, 0}) == f.config.hit_delta);
  // A return closer than the margin marks its cell and clears nothing.
  const auto near = f.Insert(Point2{0.025f, 0.025f}, {Point2{0.025f, 0.06f}}, 2);
  REQUIRE(near.hit_cells == 1);
  REQUIRE(near.miss_cells == 0);
}

TEST_CASE("A return behind a settled wall along its ray is dropped with its ray, one at the wall is kept") {
  Fixture f;
  f.grid->set_settle_at_bounds(true);
  f.config.drop_hits_behind_settled_cells = 5;
  const Point2 origin{0.025f, 0.025f};
  std::uint32_t stamp = 1;
  // Settle the wall cell (50, 0), 2.5 m away (nearer returns are not screened).
  for (int i = 0; i < 5; ++i) f.Insert(origin, {Point2{2.525f, 0.025f}}, stamp++);
  REQUIRE(f.grid->Get(CellIndex{50, 0}) == f.config.clamp_max);
  // Three cells behind it: range noise through the wall, dropped (no hit, no misses, no out-of-box).
  const auto behind = f.Insert(origin, {Point2{2.675f, 0.025f}}, stamp++);
  CHECK(behind.hit_cells == 0);
  CHECK(behind.miss_cells == 0);
  CHECK(behind.out_of_box == 0);
  CHECK(f.grid->Get(CellIndex{53, 0}) == dpcr::kUnknownCell);
  CHECK(f.grid->Get(CellIndex{52, 0}) == dpcr::kUnknownCell);
  // The cell just behind the wall's cell is the wall's own thickness: kept.
  CHECK(f.Insert(origin, {Point2{2.575f, 0.025f}}, stamp++).hit_cells == 1);
  CHECK(f.grid->Get(CellIndex{51, 0}) == f.config.hit_delta);
  // Farther behind than the screen looks: kept (something seen past a wall's end).
  CHECK(f.Insert(origin, {Point2{2.875f, 0.025f}}, stamp++).hit_cells == 1);
  // Screen off: kept.
  f.config.drop_hits_behind_settled_cells = 0;
  CHECK(f.Insert(origin, {Point2{2.675f, 0.025f}}, stamp++).hit_cells == 1);
  CHECK(f.grid->Get(CellIndex{53, 0}) > 0);
  // Nearer than 2 m (40 cells) the noise cannot carry a return through a wall: not screened.
  Fixture near;
  near.grid->set_settle_at_bounds(true);
  near.config.drop_hits_behind_settled_cells = 5;
  for (std::uint32_t i = 1; i <= 5; ++i) near.Insert(origin, {Point2{1.025f, 0.025f}}, i);
  REQUIRE(near.grid->Get(CellIndex{20, 0}) == near.config.clamp_max);
  CHECK(near.Insert(origin, {Point2{1.175f, 0.025f}}, 6).hit_cells == 1);
}

TEST_CASE("A return on a settled wall seen at a grazing angle is kept with its ray") {
  // Along a grazing ray the cells before the return lie on the wall itself: they are settled
  // too, but the return is the wall, not noise carried through it.
  Fixture f;
  f.grid->set_settle_at_bounds(true);
  f.config.drop_hits_behind_settled_cells = 5;
  std::vector<Point2> wall;
  for (int x = 40; x <= 60; ++x) wall.push_back(Point2{0.05f * static_cast<float>(x) + 0.025f, 0.025f});
  for (std::uint32_t stamp = 1; stamp <= 5; ++stamp) f.Insert(Point2{0.025f, 0.025f}, wall, stamp);
  REQUIRE(f.grid->Get(CellIndex{55, 0}) == f.config.clamp_max);
  REQUIRE(f.grid->Get(CellIndex{52, 0}) == f.config.clamp_max);
  // From two rows above the wall, to its cell 55: the ray crosses rows 2 and 1 before it.
  const auto grazing = f.Insert(Point2{0.025f, 0.125f}, {Point2{2.775f, 0.04f}}, 6);
  CHECK(grazing.miss_cells > 0);
  CHECK(f.grid->Get(CellIndex{10, 2}) < 0);
}

TEST_CASE("A grid that does not settle (the submap) drops no return behind its walls") {
  Fixture f;
  f.config.drop_hits_behind_settled_cells = 5;
  const Point2 origin{0.025f, 0.025f};
  for (std::uint32_t stamp = 1; stamp <= 6; ++stamp) f.Insert(origin, {Point2{2.525f, 0.025f}}, stamp);
  REQUIRE(f.grid->Get(CellIndex{50, 0}) == f.config.clamp_max);
  CHECK(f.Insert(origin, {Point2{2.675f, 0.025f}}, 7).hit_cells == 1);
}
