// Registration reference: the nearest-obstacle table against a plain oracle of the same vector
// distance transform (every cell visited, every neighbour bounds-checked), on random grids.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <vector>

#include "registration_fixtures.hpp"

using dpcr::Point2;
using dpcr_test::GridFixture;
using dpcr_test::Segment;

namespace {

// The transform as first written: two raster passes (forward + right, backward + left) over the
// whole window, first neighbour wins on ties, then the cut at the bound.
std::vector<std::uint16_t> OracleTable(const dpcr::RegistrationReference& ref, int w, int h, float bound_cells) {
  std::vector<std::uint16_t> t(static_cast<std::size_t>(w * h), dpcr::kNoCell);
  const auto d2 = [&](std::uint16_t k, int x, int y) {
    const int dx = ref.cell(k).x - x, dy = ref.cell(k).y - y;
    return dx * dx + dy * dy;
  };
  for (std::uint16_t i = 0; i < ref.cell_count(); ++i) t[static_cast<std::size_t>(ref.cell(i).y * w + ref.cell(i).x)] = i;
  const auto visit = [&](int x, int y, const std::vector<std::pair<int, int>>& offsets) {
    std::uint16_t& cur = t[static_cast<std::size_t>(y * w + x)];
    int cur_d = cur == dpcr::kNoCell ? INT32_MAX : d2(cur, x, y);
    if (cur_d == 0) return;
    for (const auto& o : offsets) {
      const int nx = x + o.first, ny = y + o.second;
      if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
      const std::uint16_t cand = t[static_cast<std::size_t>(ny * w + nx)];
      if (cand == dpcr::kNoCell || cand == cur) continue;
      const int d = d2(cand, x, y);
      if (d < cur_d) cur = cand, cur_d = d;
    }
  };
  const std::vector<std::pair<int, int>> forward{{-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  const std::vector<std::pair<int, int>> backward{{1, 0}, {1, 1}, {0, 1}, {-1, 1}};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) visit(x, y, forward);
    for (int x = w - 1; x >= 0; --x) visit(x, y, {{1, 0}});
  }
  for (int y = h - 1; y >= 0; --y) {
    for (int x = w - 1; x >= 0; --x) visit(x, y, backward);
    for (int x = 0; x < w; ++x) visit(x, y, {{-1, 0}});
  }
  const int bound2 = static_cast<int>(bound_cells * bound_cells);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::uint16_t& k = t[static_cast<std::size_t>(y * w + x)];
      if (k != dpcr::kNoCell && d2(k, x, y) > bound2) k = dpcr::kNoCell;
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

TEST_CASE("The nearest-obstacle table equals the plain two-pass transform (random walls, clutter, window edges)") {
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
