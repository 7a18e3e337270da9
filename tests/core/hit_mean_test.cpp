// Hit means (core/grid/hit_mean.hpp): where in a settled wall cell its returns fall, kept in the
// cell's own int16; the regional maps' lines fitted there; files, fusion and the settle rule
// reading a code as the clamp it settled at.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/config.hpp"
#include "core/grid/hit_mean.hpp"
#include "core/grid/map_fusion.hpp"
#include "core/grid/tiled_grid.hpp"
#include "core/persistence/map_file_format.hpp"
#include "core/persistence/map_reader.hpp"
#include "registration_fixtures.hpp"
#include "tests/core/map_file_fixtures.hpp"

using dpcr::CellIndex;
using dpcr::Point2;

namespace {

constexpr std::int16_t kHi = 3584, kLo = -3584;
constexpr float kRes = 0.05f;

// A regional-map-like grid: settled at the clamps, with or without hit means.
struct RegionGrid {
  std::unique_ptr<dpcr::TilePoolStorage<64>> pool = std::make_unique<dpcr::TilePoolStorage<64>>();
  std::unique_ptr<dpcr::TiledGridStorage<8, 8>> grid = std::make_unique<dpcr::TiledGridStorage<8, 8>>(pool.get());
  std::uint32_t stamp = 0;
  explicit RegionGrid(bool hit_means, std::uint8_t unsettle_occupied_after = 0) {
    grid->Reset(CellIndex{-4, -4});
    grid->set_resolution_m(kRes);
    grid->set_settle_rule(true, unsettle_occupied_after, 0);
    grid->set_hit_means(hit_means ? kHi : std::int16_t{0});
  }
  // One scan's returns: hit updates of their cells, then their hit means (RegionSet::InsertScan's order).
  void Insert(const std::vector<Point2>& hits) {
    ++stamp;
    std::vector<CellIndex> cells;
    for (const Point2& p : hits) cells.push_back(dpcr::CellOf(p.x, p.y, kRes));
    (void)grid->UpdateCells(dpcr::Span<const CellIndex>(cells.data(), cells.size()), 867, kLo, kHi, stamp);
    grid->AddHitMeans(dpcr::Span<const Point2>(hits.data(), hits.size()), stamp);
  }
};

// A repeatable normal deviate (Box-Muller over an LCG).
struct Noise {
  std::uint32_t s;
  float Uniform() {
    s = s * 1664525u + 1013904223u;
    return (static_cast<float>(s >> 8) + 0.5f) / 16777216.0f;
  }
  float Normal(float sigma) { return sigma * std::sqrt(-2.0f * std::log(Uniform())) * std::cos(6.2831853f * Uniform()); }
};

float MeanX(std::int16_t code) { return static_cast<float>(dpcr::DecodeHitMean(code).qx) / dpcr::kHitMeanLevels; }

}  // namespace

TEST_CASE("Hit-mean codes decode to what was encoded, every one above the clamps") {
  for (int k = 1; k <= dpcr::kHitMeanClasses; ++k) {
    for (int qx = 0; qx < dpcr::kHitMeanLevels; qx += 7) {
      for (int qy = 0; qy < dpcr::kHitMeanLevels; qy += 5) {
        const std::int16_t v = dpcr::EncodeHitMean(dpcr::HitMean{qx, qy, k});
        REQUIRE(dpcr::IsHitMeanCode(v));
        const dpcr::HitMean m = dpcr::DecodeHitMean(v);
        REQUIRE((m.qx == qx && m.qy == qy && m.k == k));
      }
    }
  }
  REQUIRE(dpcr::EncodeHitMean(dpcr::HitMean{63, 63, dpcr::kHitMeanClasses}) == INT16_MAX);
  REQUIRE_FALSE(dpcr::IsHitMeanCode(kHi));
}

TEST_CASE("A hit mean settles on where the returns fall, within two millimetres") {
  // 200 cells, each hit 300 times by returns 1 cm about a point of its own; the code's position
  // against that point. A cell centre would be 6.5 mm off on average here.
  Noise noise{7};
  double sum = 0.0, sum2 = 0.0;
  for (int cell = 0; cell < 200; ++cell) {
    const float truth = 0.2f + 0.6f * static_cast<float>(cell) / 200.0f;  // fraction of the cell
    dpcr::HitMean m = dpcr::StartHitMean(truth, 0.5f);
    for (int i = 0; i < 300; ++i) {
      float f = truth + noise.Normal(0.01f / kRes);
      f = f < 0.0f ? 0.0f : (f > 0.999f ? 0.999f : f);
      m = dpcr::UpdateHitMean(m, f, 0.5f, dpcr::HitMeanHash(static_cast<std::uint32_t>(cell * 1000 + i)));
    }
    REQUIRE(m.k >= dpcr::kHitMeanClasses - 2);  // the class rises at random: about 2^k updates each
    const double e = (static_cast<double>(m.qx) / dpcr::kHitMeanLevels - truth) * kRes;
    sum += e, sum2 += e * e;
  }
  INFO("bias " << sum / 200 * 1e3 << " mm, rms " << std::sqrt(sum2 / 200) * 1e3 << " mm");
  CHECK(std::fabs(sum / 200) < 0.0005);
  CHECK(std::sqrt(sum2 / 200) < 0.002);
}

TEST_CASE("Steps smaller than a level move a hit mean on average: the rounding is unbiased") {
  // Returns always 0.3 of a level above the stored mean, at the last class's gain of 1/128: a
  // rounding to the nearest level would never move it.
  dpcr::HitMean m{10, 10, dpcr::kHitMeanClasses};
  const float f = 10.3f / dpcr::kHitMeanLevels;
  double levels = 0.0;
  for (int i = 0; i < 20000; ++i) {
    m = dpcr::UpdateHitMean(m, f, f, dpcr::HitMeanHash(static_cast<std::uint32_t>(i)));
    if (i >= 10000) levels += m.qx;
  }
  CHECK(levels / 10000 == Approx(10.3).margin(0.1));
}

TEST_CASE("A settled wall cell keeps its hit mean under hits and misses and reads as the clamp") {
  RegionGrid g(true);
  const Point2 p{1.013f, 0.511f};  // in cell (20, 10), at (0.26, 0.22) of it
  const CellIndex c = dpcr::CellOf(p.x, p.y, kRes);
  for (int i = 0; i < 4; ++i) g.Insert({p});
  REQUIRE(g.grid->Get(c) < kHi);  // four hits from 0: 3468, still learning, no mean
  g.Insert({p});
  const std::int16_t code = g.grid->Get(c);
  REQUIRE(g.grid->HasHitMean(code));
  REQUIRE(g.grid->LogOdds(code) == kHi);
  CHECK(MeanX(code) == Approx(0.26f).margin(1.0f / dpcr::kHitMeanLevels));
  // A miss through it (a ray's cells) and more hits: still settled, still a mean.
  (void)g.grid->UpdateSegment(CellIndex{10, 10}, CellIndex{30, 10}, -415, kLo, kHi, ++g.stamp);
  REQUIRE(g.grid->HasHitMean(g.grid->Get(c)));
  for (int i = 0; i < 50; ++i) g.Insert({Point2{1.0105f, 0.511f}});  // returns at 0.21 of the cell
  CHECK(MeanX(g.grid->Get(c)) == Approx(0.21f).margin(2.0f / dpcr::kHitMeanLevels));
}

TEST_CASE("A hit mean that contrary scans start to count against is dropped, not corrupted") {
  RegionGrid g(true, 3);
  const Point2 p{1.013f, 0.511f};
  const CellIndex c = dpcr::CellOf(p.x, p.y, kRes);
  for (int i = 0; i < 6; ++i) g.Insert({p});
  REQUIRE(g.grid->HasHitMean(g.grid->Get(c)));
  (void)g.grid->UpdateSegment(CellIndex{10, 10}, CellIndex{30, 10}, -415, kLo, kHi, ++g.stamp);
  CHECK(g.grid->Get(c) == kHi - 1);  // settled, one contrary scan counted
  g.Insert({p});                     // an agreeing scan: back at the clamp, a new mean
  CHECK(g.grid->HasHitMean(g.grid->Get(c)));
}

TEST_CASE("A grid without hit means keeps every value as log-odds") {
  // A submap's unclamped sums go past the code base: they are not codes there.
  RegionGrid g(false);
  const CellIndex c{20, 10};
  (void)g.grid->Update(c, 5000, kLo, INT16_MAX, 0);
  g.grid->AddHitMeans(dpcr::Span<const Point2>(std::vector<Point2>{{1.013f, 0.511f}}.data(), 1), 1);
  CHECK(g.grid->Get(c) == 5000);
  CHECK_FALSE(g.grid->HasHitMean(5000));
  CHECK(g.grid->LogOdds(5000) == 5000);
}

TEST_CASE("A wall along a cell row: its line lies where the returns fell, not on the cell centres") {
  // A 2.5 m wall at y = 1.013 m (0.26 into its row of cells) seen 40 times with 1 cm noise. Fitted
  // to cell centres its line is 1.2 cm off; to the hit means, within 2 mm.
  float offset_error[2];
  for (const bool means : {false, true}) {
    RegionGrid g(means);
    Noise noise{3};
    for (int scan = 0; scan < 40; ++scan) {
      std::vector<Point2> hits;
      for (float x = -1.0f; x < 1.5f; x += 0.01f) hits.push_back(Point2{x, 1.013f + noise.Normal(0.01f)});
      g.Insert(hits);
    }
    auto ref = std::make_unique<dpcr_test::Reference>();
    dpcr::ReferenceConfig config;
    config.obstacle_threshold = 3000;
    REQUIRE(ref->Build(*g.grid, g.grid->box(), config, nullptr) != dpcr::Status::kInvalidArgument);
    REQUIRE(ref->line_count() >= 1);
    const dpcr::LineFeature* longest = &ref->line(0);
    for (std::uint16_t i = 1; i < ref->line_count(); ++i) {
      if (ref->line(i).support > longest->support) longest = &ref->line(i);
    }
    REQUIRE(std::fabs(longest->normal.y) > 0.999f);
    offset_error[means ? 1 : 0] = std::fabs(longest->offset / longest->normal.y - 1.013f);
  }
  INFO("line offset error: cell centres " << offset_error[0] << " m, hit means " << offset_error[1] << " m");
  CHECK(offset_error[0] > 0.008f);
  CHECK(offset_error[1] < 0.002f);
}

TEST_CASE("Fusion and the map file read a hit mean as the clamp it settled at") {
  RegionGrid g(true);
  const Point2 p{1.013f, 0.511f};
  for (int i = 0; i < 6; ++i) g.Insert({p});
  const CellIndex c = dpcr::CellOf(p.x, p.y, kRes);
  REQUIRE(g.grid->HasHitMean(g.grid->Get(c)));
  // A second map sees the cell free: the fused value is the sum of log-odds, 0, not code - 3584.
  RegionGrid free_map(true);
  (void)free_map.grid->Update(c, kLo, kLo, kHi, 0);
  const dpcr::PlacedGrid grids[2] = {{g.grid.get(), dpcr::Pose2{}}, {free_map.grid.get(), dpcr::Pose2{}}};
  const dpcr::CellBox box{c, CellIndex{c.x + 1, c.y + 1}};
  std::int16_t one = 0;
  REQUIRE(dpcr::FuseInto(dpcr::Span<const dpcr::PlacedGrid>(grids, 1), box, kRes, kLo, kHi, dpcr::Span<std::int16_t>(&one, 1)) ==
          dpcr::Status::kOk);
  CHECK(one == kHi);
  std::int16_t both = 0;
  REQUIRE(dpcr::FuseInto(dpcr::Span<const dpcr::PlacedGrid>(grids, 2), box, kRes, kLo, kHi, dpcr::Span<std::int16_t>(&both, 1)) ==
          dpcr::Status::kOk);
  CHECK(both == 0);
  // A tile with hit means codes exactly as the same tile at the clamp.
  std::int16_t with_means[dpcr::kTileCells], at_clamp[dpcr::kTileCells];
  for (int i = 0; i < dpcr::kTileCells; ++i) {
    with_means[i] = static_cast<std::int16_t>(i % 5 == 0 ? dpcr::EncodeHitMean(dpcr::HitMean{i % 64, (i / 3) % 64, 1 + i % 7})
                                                         : (i % 5 == 1 ? kLo : (i % 5 == 2 ? dpcr::kUnknownCell : i)));
    at_clamp[i] = i % 5 == 0 ? kHi : with_means[i];
  }
  REQUIRE(dpcr::TileRunBytes(with_means, kLo, kHi) == dpcr::TileRunBytes(at_clamp, kLo, kHi));
  for (int i = 0; i < dpcr::kTileCells;) {
    const dpcr::TileToken a = dpcr::NextTileToken(with_means, i, kLo, kHi), b = dpcr::NextTileToken(at_clamp, i, kLo, kHi);
    REQUIRE((a.code == b.code && a.cells == b.cells && a.values == b.values));
    i += a.cells;
  }
}

TEST_CASE("Hit means need a clamp below the codes") {
  dpcr::MapperConfig c;
  c.grid.clamp_max = dpcr::kHitMeanCodeBase;
  CHECK(dpcr::Validate(c) == dpcr::Status::kInvalidArgument);
  c.grid.hit_means = false;
  CHECK(dpcr::Validate(c) == dpcr::Status::kOk);
}

TEST_CASE("A mapper behind a noisy lidar keeps hit means, saves them as the clamp and loads the same log-odds") {
  using Tiny = dpcr::Mapper<dpcr::TinyProfile>;
  dpcr::MapperConfig config = dpcr::test::TestConfig<dpcr::TinyProfile>();
  config.lidar.range_noise_m = 0.02f;  // declared: hit means on
  auto mapper = dpcr::test::MakeMapper<dpcr::TinyProfile>(config);
  REQUIRE(mapper != nullptr);
  dpcr::test::SyntheticRun<Tiny> run(8.0f, 300, 180);
  dpcr::test::Feed(*mapper, run);
  // Every settled wall cell of every map is a code (returns keep falling in them).
  int codes = 0, clamps = 0;
  const dpcr::MapFileContent saved = mapper->map_file_content();
  for (const dpcr::RegionalMap& r : saved.regions) {
    dpcr::ForEachCellAbove(*r.grid, kHi - 1, [&](CellIndex, std::int16_t v) { ++(r.grid->HasHitMean(v) ? codes : clamps); });
  }
  INFO(codes << " hit means, " << clamps << " cells at the clamp without one");
  CHECK(codes > 100);
  CHECK(clamps == 0);
  // Saved and loaded: each cell as the saved map reads it.
  const std::vector<std::uint8_t> bytes = dpcr::test::SaveToBytes(*mapper);
  REQUIRE(!bytes.empty());
  auto fresh = dpcr::test::MakeMapper<dpcr::TinyProfile>(config);
  dpcr::MemoryMapSource source(dpcr::Span<const std::uint8_t>(bytes.data(), bytes.size()));
  REQUIRE(fresh->LoadMap(source).ok());
  const dpcr::MapFileContent loaded = fresh->map_file_content();
  REQUIRE(loaded.regions.size() == saved.regions.size());
  int compared = 0;
  for (std::size_t i = 0; i < saved.regions.size(); ++i) {
    const dpcr::TiledGrid& a = *saved.regions[i].grid;
    const dpcr::TiledGrid& b = *loaded.regions[i].grid;
    const dpcr::CellBox box = a.box();
    for (int y = box.min.y; y < box.max.y; ++y) {
      for (int x = box.min.x; x < box.max.x; ++x) {
        const std::int16_t v = a.Get(CellIndex{x, y});
        if (v == dpcr::kUnknownCell) continue;
        REQUIRE(b.Get(CellIndex{x, y}) == a.LogOdds(v));
        ++compared;
      }
    }
  }
  CHECK(compared > 1000);
  // Without a declared noise, no codes at all (the public logs' maps).
  config.lidar.range_noise_m = 0.0f;
  auto plain = dpcr::test::MakeMapper<dpcr::TinyProfile>(config);
  dpcr::test::Feed(*plain, run);
  for (const dpcr::RegionalMap& r : plain->map_file_content().regions) {
    dpcr::ForEachCellAbove(*r.grid, kHi - 1, [&](CellIndex, std::int16_t v) { REQUIRE_FALSE(dpcr::IsHitMeanCode(v)); });
  }
}
