// Registration reference: the nearest-obstacle table (searched cell by cell on first query)
// against a brute-force oracle over every obstacle cell, on random grids.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <vector>

#include "registration_fixtures.hpp"

using dpcr::Point2;
using dpcr_test::GridFixture;
using dpcr_test::Segment;

namespace {

// Every cell against every obstacle cell: the smallest squared distance within the bound; among
// equally near cells the one with more evidence (weight), then the smaller index.
std::vector<std::uint16_t> OracleTable(const dpcr::RegistrationReference& ref, int w, int h, float bound_cells) {
  const int bound2 = static_cast<int>(bound_cells * bound_cells), reach = static_cast<int>(bound_cells) + 1;
  std::vector<std::uint16_t> t(static_cast<std::size_t>(w * h), dpcr::kNoCell);
  std::vector<int> best_d2(t.size(), bound2 + 1);
  // Obstacle cells in index order, each over the square its bound can reach.
  for (std::uint16_t i = 0; i < ref.cell_count(); ++i) {
    const dpcr::ObstacleCell& c = ref.cell(i);
    for (int y = c.y - reach; y <= c.y + reach; ++y) {
      for (int x = c.x - reach; x <= c.x + reach; ++x) {
        if (x < 0 || y < 0 || x >= w || y >= h) continue;
        const std::size_t j = static_cast<std::size_t>(y * w + x);
        const int d2 = (c.x - x) * (c.x - x) + (c.y - y) * (c.y - y);
        if (d2 > bound2) continue;
        // Equal weight: the first (smaller) index stays.
        if (d2 < best_d2[j] || (d2 == best_d2[j] && c.weight > ref.cell(t[j]).weight)) t[j] = i, best_d2[j] = d2;
      }
    }
  }
  return t;
}

void RequireOracleTable(const GridFixture& f, float max_distance_m) {
  constexpr int kSide = 256;
  const std::vector<std::uint16_t> oracle = OracleTable(*f.ref, kSide, kSide, max_distance_m / 0.05f);
  int near_cells = 0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const Point2 p{(static_cast<float>(x) + 0.5f) * 0.05f, (static_cast<float>(y) + 0.5f) * 0.05f};
      const std::uint16_t got = f.ref->Nearest(p);
      REQUIRE(got == oracle[static_cast<std::size_t>(y * kSide + x)]);
      near_cells += got != dpcr::kNoCell;
    }
  }
  REQUIRE(near_cells > 0);
}

}  // namespace

TEST_CASE("The nearest-obstacle table equals a brute-force search (random walls, clutter, window edges)") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> pos(0.0f, 12.8f);
  for (int trial = 0; trial < 6; ++trial) {
    GridFixture f;
    for (int i = 0; i < 4 + trial * 3; ++i) f.Draw(Segment{{pos(rng), pos(rng)}, {pos(rng), pos(rng)}}, 0.02f, 10u + static_cast<unsigned>(i));
    for (int i = 0; i < 40; ++i) f.Mark(Point2{pos(rng), pos(rng)});
    // Obstacles on the window's border rows and columns (the unchecked fast path must not reach past them).
    f.Draw(Segment{{0.01f, 0.01f}, {12.79f, 0.01f}});
    f.Draw(Segment{{12.79f, 0.3f}, {12.79f, 12.79f}});
    f.Mark(Point2{0.01f, 12.79f});
    const float max_distance_m = trial % 2 == 0 ? 1.0f : 0.6f;
    dpcr::ReferenceConfig config;
    config.max_distance_m = max_distance_m;
    (void)f.Build(nullptr, config);
    RequireOracleTable(f, max_distance_m);
  }
}

TEST_CASE("A rebuilt reference answers as a fresh one (a build clears what the last one and its searches wrote)") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> pos(0.0f, 12.8f);
  auto reused = std::make_unique<dpcr_test::Reference>();
  for (int trial = 0; trial < 6; ++trial) {
    GridFixture f;
    for (int i = 0; i < 3 + trial * 2; ++i) f.Draw(Segment{{pos(rng), pos(rng)}, {pos(rng), pos(rng)}});
    for (int i = 0; i < 30; ++i) f.Mark(Point2{pos(rng), pos(rng)});
    // Windows of different sizes in turn: the last build's indices differ from this one's.
    const dpcr::CellBox window = trial % 2 == 0 ? f.grid->box()
                                                : dpcr::CellBox{dpcr::CellIndex{20, 10}, dpcr::CellIndex{220, 190}};
    dpcr::ReferenceConfig config;
    config.max_distance_m = trial % 3 == 0 ? 1.0f : 0.6f;
    (void)reused->Build(*f.grid, window, config, nullptr);
    (void)f.ref->Build(*f.grid, window, config, nullptr);
    for (int y = -2; y < 258; ++y) {
      for (int x = -2; x < 258; ++x) {
        const Point2 p{(static_cast<float>(x) + 0.5f) * 0.05f, (static_cast<float>(y) + 0.5f) * 0.05f};
        REQUIRE(reused->Nearest(p) == f.ref->Nearest(p));
      }
    }
  }
}

TEST_CASE("A reference over two grids shifts the second one's cells and merges shared cells") {
  GridFixture a, b;
  // A wall at x = 1 m in both frames, one hit per cell in a's (Draw samples each cell 4 times).
  for (int i = 0; i <= 100; ++i) a.Mark(Point2{1.01f, 1.01f + 0.05f * static_cast<float>(i)});
  b.Draw(Segment{{1.01f, 1.01f}, {1.01f, 6.01f}});
  b.Draw(Segment{{3.01f, 2.01f}, {3.01f, 5.01f}});  // and a wall of b's own
  dpcr::ReferenceBuildStats single, both;
  REQUIRE(a.Build(&single) == dpcr::Status::kOk);
  const std::size_t a_cells = a.ref->cell_count();

  // b's frame is 40 cells (2 m) left of a's: its x = 3 m wall lands on a's x = 1 m cells, its
  // x = 1 m wall falls outside a's window, a's x = 1 m wall gains b's heavier evidence.
  dpcr::RegistrationReference& ref = *a.ref;
  ref.BeginBuild(a.grid->box(), 0.05f);
  ref.AddGrid(*a.grid, dpcr::CellIndex{0, 0}, dpcr::ReferenceConfig{}, &both);
  const dpcr::CellIndex wall_cell = dpcr::CellOf(1.01f, 3.01f, 0.05f);
  const std::uint16_t before = ref.ObstacleAt(wall_cell.x, wall_cell.y);
  REQUIRE(before != dpcr::kNoCell);
  const std::uint16_t a_weight = ref.cell(before).weight;
  ref.AddGrid(*b.grid, dpcr::CellIndex{-40, 0}, dpcr::ReferenceConfig{}, &both);
  REQUIRE(ref.FinishBuild(dpcr::ReferenceConfig{}, &both) == dpcr::Status::kOk);

  // b's x = 3 m wall (y 2..5 m) is a's x = 1 m wall's middle: no new cells there, only more weight.
  REQUIRE(ref.cell_count() == a_cells);
  REQUIRE(ref.ObstacleAt(wall_cell.x, wall_cell.y) != dpcr::kNoCell);
  REQUIRE(ref.cell(ref.ObstacleAt(wall_cell.x, wall_cell.y)).weight > a_weight);
  const dpcr::CellIndex end_cell = dpcr::CellOf(1.01f, 5.81f, 0.05f);  // only a's wall reaches y = 5.8 m
  REQUIRE(ref.cell(ref.ObstacleAt(end_cell.x, end_cell.y)).weight == a_weight);
  REQUIRE(both.dropped_cells == 0);
  REQUIRE(ref.line_count() == static_cast<std::size_t>(single.lines));

  // Shifted the other way (b 2 m right of a), b's walls land at x = 3 m and x = 5 m: new lines.
  ref.BeginBuild(a.grid->box(), 0.05f);
  dpcr::ReferenceBuildStats apart;
  ref.AddGrid(*a.grid, dpcr::CellIndex{0, 0}, dpcr::ReferenceConfig{}, &apart);
  ref.AddGrid(*b.grid, dpcr::CellIndex{40, 0}, dpcr::ReferenceConfig{}, &apart);
  (void)ref.FinishBuild(dpcr::ReferenceConfig{}, &apart);
  const dpcr::CellIndex moved = dpcr::CellOf(3.01f, 3.01f, 0.05f);
  REQUIRE(ref.ObstacleAt(moved.x, moved.y) != dpcr::kNoCell);
  REQUIRE(ref.cell_count() > a_cells);
  REQUIRE(ref.line_count() == static_cast<std::size_t>(single.lines) + 2);
}

TEST_CASE("A reference over a rotated grid carries its walls into the window's frame") {
  GridFixture a, b;
  a.Draw(Segment{{2.0f, 1.0f}, {2.0f, 6.0f}});
  // b holds a wall along its own x axis (y = 3 m, x from 1 to 6 m); placed at 90 degrees about
  // (8, 0) it becomes a vertical wall at x = 8 - 3 = 5 m, y from 1 to 6 m in a's frame.
  b.Draw(Segment{{1.0f, 3.0f}, {6.0f, 3.0f}});
  dpcr::RegistrationReference& ref = *a.ref;
  dpcr::ReferenceBuildStats st;
  ref.BeginBuild(a.grid->box(), 0.05f);
  ref.AddPlacedGrid(*a.grid, dpcr::Pose2{}, dpcr::ReferenceConfig{}, &st);
  const std::size_t a_cells = ref.cell_count();
  ref.AddPlacedGrid(*b.grid, dpcr::Pose2{8.0f, 0.0f, dpcr::kPi / 2}, dpcr::ReferenceConfig{}, &st);
  REQUIRE(ref.FinishBuild(dpcr::ReferenceConfig{}, &st) == dpcr::Status::kOk);
  REQUIRE(ref.cell_count() > a_cells + 80);
  REQUIRE(ref.line_count() == 2);
  bool found_vertical_at_5 = false;
  for (std::uint16_t i = 0; i < ref.line_count(); ++i) {
    const dpcr::LineFeature& l = ref.line(i);
    if (std::fabs(std::fabs(l.normal.x) - 1.0f) < 0.01f && std::fabs(std::fabs(l.offset) - 4.975f) < 0.04f) {
      found_vertical_at_5 = true;
    }
  }
  REQUIRE(found_vertical_at_5);
  // A whole-cell shift without rotation takes AddGrid's exact path: the same cells as AddGrid.
  dpcr::ReferenceBuildStats s1, s2;
  ref.BeginBuild(a.grid->box(), 0.05f);
  ref.AddPlacedGrid(*b.grid, dpcr::Pose2{0.5f, -0.25f, 0.0f}, dpcr::ReferenceConfig{}, &s1);
  const std::size_t placed = ref.cell_count();
  ref.BeginBuild(a.grid->box(), 0.05f);
  ref.AddGrid(*b.grid, dpcr::CellIndex{10, -5}, dpcr::ReferenceConfig{}, &s2);
  REQUIRE(ref.cell_count() == placed);
}
