// Tiled grid: lazy tiles, bounds, clamping, once-per-scan rule, pool exhaustion.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/registration/cell_line.hpp"
#include "core/grid/tiled_grid.hpp"

using dpcr::CellIndex;
using dpcr::Status;

namespace {

// Two small grids on pools of 12 tiles (a full pool is easy to reach), for walks compared against
// an oracle walk.
struct TwinGrids {
  std::unique_ptr<dpcr::TilePoolStorage<12>> pool_a = std::make_unique<dpcr::TilePoolStorage<12>>();
  std::unique_ptr<dpcr::TilePoolStorage<12>> pool_b = std::make_unique<dpcr::TilePoolStorage<12>>();
  dpcr::TiledGridStorage<4, 4> a{pool_a.get()};
  dpcr::TiledGridStorage<4, 4> b{pool_b.get()};
  explicit TwinGrids(bool settle) {
    for (dpcr::TiledGrid* g : {static_cast<dpcr::TiledGrid*>(&a), static_cast<dpcr::TiledGrid*>(&b)}) {
      g->Reset(CellIndex{-2, -2});
      g->set_settle_at_bounds(settle);
    }
  }
};

// A repeatable integer in [lo, hi] (an LCG: the same sequence on every platform).
struct Lcg {
  std::uint32_t seed;
  int operator()(int lo, int hi) {
    seed = seed * 1664525u + 1013904223u;
    return lo + static_cast<int>((seed >> 8) % static_cast<std::uint32_t>(hi - lo + 1));
  }
};

}  // namespace

TEST_CASE("CellOf floors negative coordinates") {
  REQUIRE(dpcr::CellOf(0.01f, 0.01f, 0.05f) == CellIndex{0, 0});
  REQUIRE(dpcr::CellOf(-0.01f, 0.07f, 0.05f) == CellIndex{-1, 1});
  REQUIRE(dpcr::CellCentreX(CellIndex{-1, 0}, 0.05f) == Approx(-0.025f));
}

TEST_CASE("FloorToInt is std::floor for every float of the grid's range") {
  // Whole numbers, halves, the floats either side of them, and a sweep of quotients like CellOf's.
  const float samples[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 1e-7f, -1e-7f, 123456.0f, -123456.0f,
                           16777216.0f, -16777216.0f, 1e9f, -1e9f};
  for (const float v : samples) {
    for (const float w : {std::nextafter(v, -2e9f), v, std::nextafter(v, 2e9f)}) {
      REQUIRE(dpcr::FloorToInt(w) == static_cast<std::int32_t>(std::floor(w)));
    }
  }
  for (int i = -200000; i <= 200000; ++i) {
    const float v = static_cast<float>(i) * 0.0137f / 0.05f;
    REQUIRE(dpcr::FloorToInt(v) == static_cast<std::int32_t>(std::floor(v)));
  }
}

TEST_CASE("Tiles are allocated on first write only, and released on reset") {
  auto pool = std::make_unique<dpcr::TilePoolStorage<8>>();
  dpcr::TiledGridStorage<4, 4> grid(pool.get());
  grid.Reset(CellIndex{-2, -2});
  REQUIRE(grid.box().min == CellIndex{-64, -64});
  REQUIRE(grid.box().max == CellIndex{64, 64});
  REQUIRE(grid.Get(CellIndex{0, 0}) == dpcr::kUnknownCell);
  REQUIRE(pool->used() == 0);

  REQUIRE(grid.Update(CellIndex{-1, -1}, 100, -500, 500, 0) == Status::kOk);
  REQUIRE(grid.Get(CellIndex{-1, -1}) == 100);
  REQUIRE(grid.Get(CellIndex{-2, -1}) == dpcr::kUnknownCell);  // same tile, never written
  REQUIRE(pool->used() == 1);
  REQUIRE(grid.Update(CellIndex{0, 0}, 100, -500, 500, 0) == Status::kOk);  // next tile
  REQUIRE(pool->used() == 2);

  REQUIRE(grid.Update(CellIndex{64, 0}, 100, -500, 500, 0) == Status::kOutOfBounds);
  REQUIRE(grid.Get(CellIndex{64, 0}) == dpcr::kUnknownCell);

  grid.Reset(CellIndex{0, 0});
  REQUIRE(pool->used() == 0);
  REQUIRE(grid.Get(CellIndex{0, 0}) == dpcr::kUnknownCell);
}

TEST_CASE("Updates clamp and happen at most once per cell per scan") {
  auto pool = std::make_unique<dpcr::TilePoolStorage<2>>();
  dpcr::TiledGridStorage<2, 2> grid(pool.get());
  const CellIndex c{3, 5};
  for (int i = 0; i < 10; ++i) REQUIRE(grid.Update(c, 300, -1000, 1000, 0) == Status::kOk);
  REQUIRE(grid.Get(c) == 1000);
  for (int i = 0; i < 3; ++i) REQUIRE(grid.Update(c, -400, -1000, 1000, 7) == Status::kOk);
  REQUIRE(grid.Get(c) == 600);  // only the first update of scan 7 counted
  REQUIRE(grid.Update(c, -400, -1000, 1000, 8) == Status::kOk);
  REQUIRE(grid.Get(c) == 200);
}

TEST_CASE("Settled cells keep their value once they reach a bound") {
  auto pool = std::make_unique<dpcr::TilePoolStorage<2>>();
  dpcr::TiledGridStorage<2, 2> grid(pool.get());
  const CellIndex wall{3, 5}, floor{4, 5};
  for (int i = 0; i < 4; ++i) REQUIRE(grid.Update(wall, 300, -1000, 1000, 0) == Status::kOk);
  REQUIRE(grid.Get(wall) == 1000);
  // Without settling a clamped cell is unlearnt.
  REQUIRE(grid.Update(wall, -400, -1000, 1000, 0) == Status::kOk);
  REQUIRE(grid.Get(wall) == 600);
  grid.set_settle_at_bounds(true);
  REQUIRE(grid.Update(wall, 300, -1000, 1000, 0) == Status::kOk);
  REQUIRE(grid.Get(wall) == 900);  // below the bound: still learning
  REQUIRE(grid.Update(wall, 300, -1000, 1000, 0) == Status::kOk);
  REQUIRE(grid.Get(wall) == 1000);  // settled
  for (int i = 0; i < 5; ++i) REQUIRE(grid.Update(wall, -400, -1000, 1000, 0) == Status::kOk);
  REQUIRE(grid.Get(wall) == 1000);
  // Free space settles at the lower bound the same way, also along a segment.
  for (int i = 0; i < 3; ++i) static_cast<void>(grid.UpdateSegment(floor, CellIndex{8, 5}, -400, -1000, 1000, 0));
  REQUIRE(grid.Get(floor) == -1000);
  static_cast<void>(grid.UpdateSegment(floor, CellIndex{8, 5}, 300, -1000, 1000, 0));
  REQUIRE(grid.Get(floor) == -1000);
  REQUIRE(grid.Get(CellIndex{8, 5}) == dpcr::kUnknownCell);  // the segment's end is excluded
}

TEST_CASE("Settled cells learn again after enough contrary scans in a row") {
  auto pool = std::make_unique<dpcr::TilePoolStorage<2>>();
  dpcr::TiledGridStorage<2, 2> grid(pool.get());
  grid.set_settle_rule(true, 3, 2);  // occupied: 3 contrary scans, free: 2
  const CellIndex wall{3, 5}, floor{4, 5}, near{3, 20};
  for (std::uint32_t scan = 1; scan <= 4; ++scan) REQUIRE(grid.Update(wall, 300, -1000, 1000, scan) == Status::kOk);
  REQUIRE(grid.Get(wall) == 1000);
  REQUIRE(grid.Update(wall, -400, -1000, 1000, 5) == Status::kOk);
  REQUIRE(grid.Get(wall) == 999);  // settled, one contrary scan counted
  REQUIRE(grid.Update(wall, -400, -1000, 1000, 6) == Status::kOk);
  REQUIRE(grid.Get(wall) == 998);
  REQUIRE(grid.Update(wall, 300, -1000, 1000, 7) == Status::kOk);
  REQUIRE(grid.Get(wall) == 1000);  // a hit restarts the count
  REQUIRE(grid.Update(wall, -400, -1000, 1000, 8) == Status::kOk);
  REQUIRE(grid.Update(wall, -400, -1000, 1000, 9) == Status::kOk);
  REQUIRE(grid.Update(wall, -400, -1000, 1000, 9) == Status::kOk);  // the same scan counts once
  REQUIRE(grid.Get(wall) == 998);
  REQUIRE(grid.Update(wall, -400, -1000, 1000, 10) == Status::kOk);
  REQUIRE(grid.Get(wall) == 997 - 400);  // the third: learning again, from the band's edge
  REQUIRE(grid.Update(wall, -400, -1000, 1000, 11) == Status::kOk);
  REQUIRE(grid.Get(wall) == 197);

  // Free space: two scans that hit it in a row, along segments as a scan's rays go.
  for (std::uint32_t scan = 12; scan <= 14; ++scan) static_cast<void>(grid.UpdateSegment(floor, CellIndex{8, 5}, -400, -1000, 1000, scan));
  REQUIRE(grid.Get(floor) == -1000);
  static_cast<void>(grid.UpdateSegment(floor, CellIndex{8, 5}, 300, -1000, 1000, 15));
  REQUIRE(grid.Get(floor) == -999);
  static_cast<void>(grid.UpdateSegment(floor, CellIndex{8, 5}, -400, -1000, 1000, 16));
  REQUIRE(grid.Get(floor) == -1000);  // a miss restarts the count
  static_cast<void>(grid.UpdateSegment(floor, CellIndex{8, 5}, 300, -1000, 1000, 17));
  static_cast<void>(grid.UpdateSegment(floor, CellIndex{8, 5}, 300, -1000, 1000, 18));
  REQUIRE(grid.Get(floor) == -998 + 300);

  // A learning cell stays out of a count's band (its values always mean "settled, so many
  // contrary scans"), and settles on the update that takes it over the bound.
  REQUIRE(grid.Update(near, 499, -1000, 1000, 19) == Status::kOk);
  REQUIRE(grid.Update(near, 499, -1000, 1000, 20) == Status::kOk);
  REQUIRE(grid.Get(near) == 997);  // 998 is in the band [998, 1000]
  REQUIRE(grid.Update(near, 2, -1000, 1000, 21) == Status::kOk);
  REQUIRE(grid.Get(near) == 997);  // 999, still below the bound: out of the band again
  REQUIRE(grid.Update(near, 3, -1000, 1000, 22) == Status::kOk);
  REQUIRE(grid.Get(near) == 1000);  // over it: settled

  // Count 0: settled for good (the rule of set_settle_at_bounds).
  grid.set_settle_rule(true, 0, 0);
  for (std::uint32_t scan = 23; scan <= 32; ++scan) REQUIRE(grid.Update(near, -400, -1000, 1000, scan) == Status::kOk);
  REQUIRE(grid.Get(near) == 1000);
}

TEST_CASE("Settle rule: UpdateSegments and UpdateCells equal per-cell Update (one direction per scan)") {
  // As a scan goes in: the hits (one direction), then the misses (the other), each cell once.
  const int occupied_after = GENERATE(1, 4, 12), free_after = GENERATE(0, 3);
  TwinGrids twins(true);
  dpcr::TiledGrid& fast = twins.a;
  dpcr::TiledGrid& slow = twins.b;
  for (dpcr::TiledGrid* g : {&fast, &slow}) {
    g->set_settle_rule(true, static_cast<std::uint8_t>(occupied_after), static_cast<std::uint8_t>(free_after));
  }
  Lcg next{4242};
  dpcr::CellSegment segments[24];
  CellIndex cells[24];
  int unsettled = 0;
  for (std::uint32_t scan = 1; scan <= 1500; ++scan) {
    const std::size_t n = static_cast<std::size_t>(next(1, 24));
    for (std::size_t i = 0; i < n; ++i) {
      // Short segments in a small area: cells settle, then get contradicted.
      const CellIndex a{next(-20, 20), next(-20, 20)};
      segments[i] = dpcr::CellSegment{a, CellIndex{a.x + next(-12, 12), a.y + next(-12, 12)}};
      cells[i] = CellIndex{next(-20, 20), next(-20, 20)};
    }
    const std::int16_t hit = static_cast<std::int16_t>(next(200, 900)), miss = static_cast<std::int16_t>(-next(200, 900));
    // Half the scans reversed: the cells wander to both bounds and away again.
    const bool reversed = next(0, 1) == 1;
    const std::int16_t hit_dir = reversed ? miss : hit, miss_dir = reversed ? hit : miss;
    fast.UpdateCells(dpcr::Span<const CellIndex>(cells, n), hit_dir, -3000, 3000, scan);
    for (std::size_t i = 0; i < n; ++i) REQUIRE(slow.Update(cells[i], hit_dir, -3000, 3000, scan) == Status::kOk);
    fast.UpdateSegments(dpcr::Span<const dpcr::CellSegment>(segments, n), miss_dir, -3000, 3000, scan);
    for (std::size_t i = 0; i < n; ++i) {
      dpcr::TraceCells(segments[i].from, segments[i].to, [&](CellIndex c) {
        const std::int16_t before = slow.Get(c);
        REQUIRE(slow.Update(c, miss_dir, -3000, 3000, scan) == Status::kOk);
        const std::int16_t after = slow.Get(c);
        const int band_bottom = 3000 - (occupied_after > 1 ? occupied_after - 1 : 0);
        unsettled += (before >= band_bottom && after < band_bottom && miss_dir < 0) ? 1 : 0;
        return true;
      });
    }
  }
  for (int y = -64; y < 64; ++y) {
    for (int x = -64; x < 64; ++x) REQUIRE(fast.Get(CellIndex{x, y}) == slow.Get(CellIndex{x, y}));
  }
  REQUIRE(unsettled > 0);  // settled cells were unsettled
}

TEST_CASE("A full tile pool drops the update and says so") {
  auto pool = std::make_unique<dpcr::TilePoolStorage<1>>();
  dpcr::TiledGridStorage<2, 2> grid(pool.get());
  REQUIRE(grid.Update(CellIndex{0, 0}, 10, -100, 100, 0) == Status::kOk);
  REQUIRE(grid.Update(CellIndex{40, 0}, 10, -100, 100, 0) == Status::kPoolFull);
  REQUIRE(grid.Get(CellIndex{40, 0}) == dpcr::kUnknownCell);
  REQUIRE(pool->failed_allocations() == 1);
  REQUIRE(grid.Update(CellIndex{1, 1}, 10, -100, 100, 0) == Status::kOk);  // existing tile still works
}

TEST_CASE("UpdateSegment equals per-cell Update along TraceCells (random segments, box exits, full pool)") {
  // Oracle: the tile-run walk must touch the same cells in the same order as TraceCells + Update,
  // with and without settled cells.
  TwinGrids twins(GENERATE(false, true));
  // 0: ends anywhere; 12: short segments, most of them inside one tile (the walk's one-run path).
  const int reach = GENERATE(0, 12);
  dpcr::TiledGrid& fast = twins.a;
  dpcr::TiledGrid& slow = twins.b;
  Lcg next{12345};
  int dropped = 0, exits = 0;
  for (int i = 0; i < 4000; ++i) {
    const std::uint32_t stamp = static_cast<std::uint32_t>(i / 7);  // several segments per "scan"; 0 = no rule
    const CellIndex a = reach == 0 ? CellIndex{next(-64, 63), next(-64, 63)} : CellIndex{next(-80, 80), next(-80, 80)};
    const CellIndex b = reach == 0 ? CellIndex{next(-90, 90), next(-90, 90)}
                                   : CellIndex{a.x + next(-reach, reach), a.y + next(-reach, reach)};
    const std::int16_t delta = static_cast<std::int16_t>(next(-400, 400));
    const dpcr::TiledGrid::SegmentStats s = fast.UpdateSegment(a, b, delta, -3000, 3000, stamp);
    dpcr::TiledGrid::SegmentStats o;
    dpcr::TraceCells(a, b, [&](CellIndex c) {
      const Status r = slow.Update(c, delta, -3000, 3000, stamp);
      if (r == Status::kOutOfBounds) {
        ++o.out_of_box;
        return false;
      }
      if (r == Status::kPoolFull) {
        ++o.dropped_pool_full;
      } else {
        ++o.applied;
      }
      return true;
    });
    REQUIRE(s.applied == o.applied);
    REQUIRE(s.out_of_box == o.out_of_box);
    REQUIRE(s.dropped_pool_full == o.dropped_pool_full);
    dropped += s.dropped_pool_full;
    exits += s.out_of_box;
  }
  REQUIRE(dropped > 0);  // both the full pool and box exits were exercised
  REQUIRE(exits > 0);
  REQUIRE(twins.pool_a->used() == twins.pool_b->used());
  int at_bounds = 0;
  for (int y = -64; y < 64; ++y) {
    for (int x = -64; x < 64; ++x) {
      REQUIRE(fast.Get(CellIndex{x, y}) == slow.Get(CellIndex{x, y}));
      at_bounds += (fast.Get(CellIndex{x, y}) == 3000 || fast.Get(CellIndex{x, y}) == -3000) ? 1 : 0;
    }
  }
  // Settled cells were exercised (the short segments spread too thin to reach the bounds; the
  // settle rule's test walks short ones).
  if (reach == 0) REQUIRE(at_bounds > 0);
}

TEST_CASE("UpdateSegments equals UpdateSegment one segment at a time") {
  TwinGrids twins(GENERATE(false, true));
  dpcr::TiledGrid& batched = twins.a;
  dpcr::TiledGrid& single = twins.b;
  Lcg next{777};
  dpcr::CellSegment segments[40];
  for (std::uint32_t scan = 1; scan <= 300; ++scan) {
    const std::size_t n = static_cast<std::size_t>(next(0, 40));
    for (std::size_t i = 0; i < n; ++i) {
      segments[i] = dpcr::CellSegment{CellIndex{next(-64, 63), next(-64, 63)}, CellIndex{next(-90, 90), next(-90, 90)}};
    }
    const std::int16_t delta = static_cast<std::int16_t>(next(-400, 400));
    const dpcr::TiledGrid::SegmentStats b =
        batched.UpdateSegments(dpcr::Span<const dpcr::CellSegment>(segments, n), delta, -3000, 3000, scan);
    dpcr::TiledGrid::SegmentStats o;
    for (std::size_t i = 0; i < n; ++i) {
      const dpcr::TiledGrid::SegmentStats s = single.UpdateSegment(segments[i].from, segments[i].to, delta, -3000, 3000, scan);
      o.applied += s.applied;
      o.out_of_box += s.out_of_box;
      o.dropped_pool_full += s.dropped_pool_full;
    }
    REQUIRE(b.applied == o.applied);
    REQUIRE(b.out_of_box == o.out_of_box);
    REQUIRE(b.dropped_pool_full == o.dropped_pool_full);
  }
  for (int y = -64; y < 64; ++y) {
    for (int x = -64; x < 64; ++x) REQUIRE(batched.Get(CellIndex{x, y}) == single.Get(CellIndex{x, y}));
  }
}
