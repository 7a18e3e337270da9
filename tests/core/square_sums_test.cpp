// The sums a correlative search scores blocks by: the same integers as look-up by look-up,
// wherever the points fall (inside the grid, across its edges, outside it) and however many.
#include <catch2/catch.hpp>

#include <memory>
#include <random>
#include <vector>

#include "core/back_end/square_sums.hpp"
#include "tests/core/registration_fixtures.hpp"

namespace {

using Grid = dpcr::MatchGridStorage<128, 128>;
using dpcr::MatchCell;

struct Sums {
  std::uint32_t v[16] = {};
};

Sums Scores(const dpcr::MatchGrid& g, const std::vector<MatchCell>& cells, int x0, int y0) {
  Sums s;
  for (const MatchCell& c : cells) {
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 4; ++i) s.v[4 * j + i] += g.AtCell(c.x + x0 + i, c.y + y0 + j);
    }
  }
  return s;
}

Sums Bounds(const dpcr::MatchGrid& g, const std::vector<MatchCell>& cells, int x0, int y0) {
  constexpr int kB = dpcr::MatchGrid::kBlock;
  Sums s;
  for (const MatchCell& c : cells) {
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 4; ++i) s.v[4 * j + i] += g.BoundAt(c.x + x0 + kB * i, c.y + y0 + kB * j);
    }
  }
  return s;
}

void RequireEqual(const std::uint32_t (&got)[16], const Sums& want) {
  for (int k = 0; k < 16; ++k) REQUIRE(got[k] == want.v[k]);
}

// Random walls on a 12.8 m grid, matched at 10 cm: 128 x 128 match cells.
std::unique_ptr<Grid> RandomMap(unsigned seed) {
  dpcr_test::GridFixture f;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> at(0.2f, 12.6f);
  for (int k = 0; k < 25; ++k) f.Draw(dpcr_test::Segment{{at(rng), at(rng)}, {at(rng), at(rng)}});
  auto g = std::make_unique<Grid>();
  g->Build(*f.grid, f.grid->box(), 2, 0);
  return g;
}

}  // namespace

TEST_CASE("Square sums equal look-up by look-up sums, points inside, across the edges and outside") {
  const auto grid = RandomMap(GENERATE(1u, 2u, 3u));
  REQUIRE(grid->width() == 128);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> cell(-30, 157);
  for (const std::size_t n : {1u, 17u, 255u, 256u, 257u, 700u}) {
    std::vector<MatchCell> cells(n);
    for (MatchCell& c : cells) c = MatchCell{static_cast<std::int16_t>(cell(rng)), static_cast<std::int16_t>(cell(rng))};
    const dpcr::Span<const MatchCell> span(cells.data(), cells.size());
    for (const int offset : {-40, -3, 0, 5, 60}) {
      std::uint32_t got[16];
      dpcr::SumScoreSquares(*grid, span, offset, -offset, false, got);
      RequireEqual(got, Scores(*grid, cells, offset, -offset));
      dpcr::SumBoundSquares(*grid, span, offset, offset, false, got);
      RequireEqual(got, Bounds(*grid, cells, offset, offset));
    }
  }
}

TEST_CASE("Square sums of a cloud wholly inside the grid take its fast path and the same integers") {
  const auto grid = RandomMap(4);
  std::mt19937 rng(9);
  // Bounds read up to 3 * kBlock + 3 cells right of a point and 3 * kBlock above it.
  std::uniform_int_distribution<int> cell(0, 128 - 1 - 3 * dpcr::MatchGrid::kBlock - dpcr::kBoundSquareSpareBytes);
  std::vector<MatchCell> cells(600);
  for (MatchCell& c : cells) c = MatchCell{static_cast<std::int16_t>(cell(rng)), static_cast<std::int16_t>(cell(rng))};
  const dpcr::Span<const MatchCell> span(cells.data(), cells.size());
  std::uint32_t got[16];
  dpcr::SumScoreSquares(*grid, span, 0, 0, true, got);
  RequireEqual(got, Scores(*grid, cells, 0, 0));
  dpcr::SumBoundSquares(*grid, span, 0, 0, true, got);
  RequireEqual(got, Bounds(*grid, cells, 0, 0));
}

TEST_CASE("Square sums do not overflow: 1000 points on cells of the highest likelihood") {
  dpcr_test::GridFixture f;
  for (int k = 0; k < 40; ++k) f.Draw(dpcr_test::Segment{{0.1f, 0.1f + 0.05f * static_cast<float>(k)}, {3.0f, 0.1f + 0.05f * static_cast<float>(k)}});
  Grid grid;
  grid.Build(*f.grid, f.grid->box(), 1, 0);  // 5 cm match cells: a solid block of obstacles
  std::vector<MatchCell> cells(1000, MatchCell{10, 10});
  REQUIRE(grid.AtCell(10, 10) == 255);
  std::uint32_t got[16];
  dpcr::SumScoreSquares(grid, dpcr::Span<const MatchCell>(cells.data(), cells.size()), 0, 0, true, got);
  RequireEqual(got, Scores(grid, cells, 0, 0));
  REQUIRE(got[0] == 255000u);
}
