// Line features from synthetic int16 grids: rooms, noisy walls, gaps, corners, short furniture.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/capacity.hpp"
#include "core/config.hpp"
#include "core/front_end/reference_for_noise.hpp"
#include "registration_fixtures.hpp"

using dpcr::Point2;
using dpcr_test::GridFixture;
using dpcr_test::InsertScan;
using dpcr_test::SimulateScan;
using dpcr_test::Segment;

namespace {

float Dist(Point2 a, Point2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

float DistanceToSegment(Point2 p, Segment s) {
  const float ex = s.b.x - s.a.x, ey = s.b.y - s.a.y;
  const float t = std::clamp(((p.x - s.a.x) * ex + (p.y - s.a.y) * ey) / (ex * ex + ey * ey), 0.0f, 1.0f);
  return Dist(p, Point2{s.a.x + t * ex, s.a.y + t * ey});
}

// The extracted line matching a true segment with both endpoints within `tol` metres, or -1.
int FindLine(const dpcr::RegistrationReference& ref, Segment s, float tol) {
  for (std::uint16_t i = 0; i < ref.line_count(); ++i) {
    const dpcr::LineFeature& l = ref.line(i);
    if ((Dist(l.a, s.a) <= tol && Dist(l.b, s.b) <= tol) || (Dist(l.a, s.b) <= tol && Dist(l.b, s.a) <= tol)) {
      return i;
    }
  }
  for (std::uint16_t i = 0; i < ref.line_count(); ++i) {
    const dpcr::LineFeature& l = ref.line(i);
    UNSCOPED_INFO("line " << i << ": (" << l.a.x << ", " << l.a.y << ") - (" << l.b.x << ", " << l.b.y
                          << ") support " << l.support << " rms " << l.rms);
  }
  return -1;
}

constexpr float kCell = 0.05f;
// Endpoint accuracy target: one cell. Walls are drawn through cell centres' lattice at arbitrary
// offsets, so this is the quantisation of the grid plus the fit.
constexpr float kTol = kCell + 1e-4f;

}  // namespace

TEST_CASE("A rectangular room yields its four walls with endpoints within one cell") {
  GridFixture f;
  const Point2 c0{1.02f, 1.03f}, c1{5.01f, 1.03f}, c2{5.01f, 4.02f}, c3{1.02f, 4.02f};
  const Segment walls[] = {{c0, c1}, {c1, c2}, {c2, c3}, {c3, c0}};
  for (const Segment& w : walls) f.Draw(w);
  dpcr::ReferenceBuildStats stats;
  REQUIRE(f.Build(&stats) == dpcr::Status::kOk);
  CHECK(f.ref->line_count() == 4);
  for (const Segment& w : walls) CHECK(FindLine(*f.ref, w, kTol) >= 0);
  // Every obstacle cell of a clean room belongs to a line, and its line passes within a cell.
  for (std::uint16_t i = 0; i < f.ref->cell_count(); ++i) {
    const std::uint16_t id = f.ref->cell(i).line;
    REQUIRE(id != dpcr::kNoLine);
    const dpcr::LineFeature& l = f.ref->line(id);
    const Point2 p = f.ref->ObstaclePoint(i);
    CHECK(std::fabs(l.normal.x * p.x + l.normal.y * p.y - l.offset) <= kCell);
  }
}

TEST_CASE("Noisy walls are still single lines with a small fit residual") {
  GridFixture f;
  const Segment wall{{0.5f, 2.0f}, {6.5f, 2.6f}};  // slanted, 6 m
  f.Draw(wall, 0.015f, 7);
  REQUIRE(f.Build() == dpcr::Status::kOk);
  const int id = FindLine(*f.ref, wall, kTol);
  REQUIRE(id >= 0);
  CHECK(f.ref->line(static_cast<std::uint16_t>(id)).rms < 0.03f);
  CHECK(f.ref->line_count() <= 2);
}

TEST_CASE("A wall with a door gap gives two lines, an L corner gives two lines meeting at the corner") {
  GridFixture f;
  // Coordinates off the cell lattice: a point exactly on a cell border falls in the upper cell.
  f.Draw(Segment{{1.01f, 1.01f}, {7.01f, 1.01f}}, 0.0f, 1, 2.0f, 2.9f);  // door from x = 3.01 to 3.91
  f.Draw(Segment{{1.01f, 5.01f}, {6.01f, 5.01f}});
  f.Draw(Segment{{6.01f, 5.01f}, {6.01f, 9.01f}});
  REQUIRE(f.Build() == dpcr::Status::kOk);
  CHECK(FindLine(*f.ref, Segment{{1.01f, 1.01f}, {3.01f, 1.01f}}, kTol) >= 0);
  CHECK(FindLine(*f.ref, Segment{{3.91f, 1.01f}, {7.01f, 1.01f}}, kTol) >= 0);
  CHECK(FindLine(*f.ref, Segment{{1.01f, 5.01f}, {6.01f, 5.01f}}, kTol) >= 0);
  CHECK(FindLine(*f.ref, Segment{{6.01f, 5.01f}, {6.01f, 9.01f}}, kTol) >= 0);
  CHECK(f.ref->line_count() == 4);
}

TEST_CASE("Short furniture edges become lines, chair legs stay clutter with no line") {
  GridFixture f;
  const Segment table_edge{{2.0f, 2.0f}, {2.6f, 2.0f}};  // 12 cells
  f.Draw(table_edge);
  f.Mark(Point2{4.01f, 4.01f});  // chair legs: single cells
  f.Mark(Point2{4.41f, 4.01f});
  f.Mark(Point2{4.01f, 4.41f});
  REQUIRE(f.Build() == dpcr::Status::kOk);
  CHECK(FindLine(*f.ref, table_edge, kTol) >= 0);
  CHECK(f.ref->line_count() == 1);
  const std::uint16_t leg = f.ref->ObstacleAt(80, 80);
  REQUIRE(leg != dpcr::kNoCell);
  CHECK(f.ref->cell(leg).line == dpcr::kNoLine);
}

TEST_CASE("The nearest-obstacle table answers the true nearest cell within its bound") {
  GridFixture f;
  f.Draw(Segment{{1.0f, 1.0f}, {5.0f, 1.0f}});
  f.Mark(Point2{3.02f, 3.02f});
  dpcr::ReferenceConfig config;
  config.max_distance_m = 1.0f;
  REQUIRE(f.Build(nullptr, config) == dpcr::Status::kOk);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 6.0f);
  for (int k = 0; k < 2000; ++k) {
    const Point2 p{u(rng), u(rng)};
    const Point2 centre{(std::floor(p.x / kCell) + 0.5f) * kCell, (std::floor(p.y / kCell) + 0.5f) * kCell};
    float best = 1e9f;
    for (std::uint16_t i = 0; i < f.ref->cell_count(); ++i) best = std::fmin(best, Dist(centre, f.ref->ObstaclePoint(i)));
    const std::uint16_t got = f.ref->Nearest(p);
    if (best > 1.0f + kCell) {
      CHECK(got == dpcr::kNoCell);
    } else if (best < 1.0f - kCell) {
      REQUIRE(got != dpcr::kNoCell);
      CHECK(Dist(centre, f.ref->ObstaclePoint(got)) <= best + 1e-4f);
    }
  }
}

TEST_CASE("More obstacle cells than capacity are reported, not silently lost") {
  GridFixture f;
  for (int y = 0; y < 80; ++y) f.Draw(Segment{{0.1f, 0.025f + 0.05f * static_cast<float>(y)}, {3.9f, 0.025f + 0.05f * static_cast<float>(y)}});
  dpcr::ReferenceBuildStats stats;
  CHECK(f.Build(&stats) == dpcr::Status::kCapacityExceeded);
  CHECK(stats.dropped_cells > 0);
  CHECK(f.ref->cell_count() == 4096);
}

TEST_CASE("One vacuum-profile reference (256x256 window, 4096 cells, 512 lines) stays within 230 KiB") {
  using VacuumReference = dpcr::RegistrationReferenceStorage<dpcr::VacuumProfile::kSubmapSideCells,
                                                             dpcr::VacuumProfile::kSubmapSideCells, 4096,
                                                             dpcr::VacuumProfile::kMaxLines>;
  INFO("sizeof = " << sizeof(VacuumReference));
  CHECK(sizeof(VacuumReference) <= 230u * 1024u);  // 2 KiB of it: ExtractLines' line scratch, off the stack
}

TEST_CASE("More lines than capacity: the rest stay clutter and the build says so") {
  GridFixture f;
  const Point2 c0{1.02f, 1.03f}, c1{5.01f, 1.03f}, c2{5.01f, 4.02f}, c3{1.02f, 4.02f};
  for (const Segment& w : {Segment{c0, c1}, Segment{c1, c2}, Segment{c2, c3}, Segment{c3, c0}}) f.Draw(w);
  auto small = std::make_unique<dpcr::RegistrationReferenceStorage<256, 256, 4096, 2>>();
  dpcr::ReferenceBuildStats stats;
  CHECK(small->Build(*f.grid, f.grid->box(), dpcr::ReferenceConfig{}, &stats) == dpcr::Status::kCapacityExceeded);
  CHECK(stats.extraction.lines_full);
  CHECK(small->line_count() == 2);
  int clutter = 0;
  for (std::uint16_t i = 0; i < small->cell_count(); ++i) clutter += small->cell(i).line == dpcr::kNoLine;
  CHECK(clutter > 100);
}

TEST_CASE("Line fits weight cells by their evidence: stray weak cells barely tilt a solid wall") {
  // A solid wall along row 40 (y = 2.025 m) and, over its left fifth, weak cells one row above
  // (range noise that reached them once).
  const auto fit = [](bool weighted) {
    GridFixture f;
    for (int x = 20; x < 60; ++x) (void)f.grid->Update(dpcr::CellIndex{x, 40}, 3000, -3000, 3000, 0);
    for (int x = 20; x < 28; ++x) (void)f.grid->Update(dpcr::CellIndex{x, 41}, 200, -3000, 3000, 0);
    dpcr::ReferenceConfig config;
    config.weight_by_evidence = weighted;
    REQUIRE(f.Build(nullptr, config) == dpcr::Status::kOk);
    REQUIRE(f.ref->line_count() == 1);
    return f.ref->line(0);
  };
  const dpcr::LineFeature plain = fit(false), weighted = fit(true);
  const float plain_tilt = std::fabs(plain.normal.x), weighted_tilt = std::fabs(weighted.normal.x);
  // Height of the fitted line at the wall's middle (x = 2 m) against the wall's 2.025 m.
  const auto error_at_middle = [](const dpcr::LineFeature& l) {
    return std::fabs((l.offset - 2.0f * l.normal.x) / l.normal.y - 2.025f);
  };
  const float plain_offset_error = error_at_middle(plain), weighted_offset_error = error_at_middle(weighted);
  INFO("tilt plain " << plain_tilt << " weighted " << weighted_tilt << "; offset error plain " << plain_offset_error
                     << " weighted " << weighted_offset_error);
  CHECK(weighted_tilt < 0.2f * plain_tilt);
  CHECK(weighted_offset_error < 0.2f * plain_offset_error);
  CHECK(weighted_offset_error < 0.002f);
}

namespace {

// The share of the obstacle cells that belong to some line.
float LinedShare(const dpcr::RegistrationReference& ref) {
  int lined = 0;
  for (std::uint16_t i = 0; i < ref.cell_count(); ++i) lined += ref.cell(i).line != dpcr::kNoLine ? 1 : 0;
  return ref.cell_count() == 0 ? 0.0f : static_cast<float>(lined) / static_cast<float>(ref.cell_count());
}

}  // namespace

TEST_CASE("The line fit tolerance grows with the lidar's declared range noise, and only then") {
  dpcr::MapperConfig config;
  const dpcr::ReferenceConfig base = config.front_end.region_reference;
  CHECK(dpcr::ReferenceForNoise(base, config).lines.max_rms_cells == base.lines.max_rms_cells);  // not known
  config.lidar.range_noise_m = 0.025f;  // an LD06 at 3 m
  const float ld06 = dpcr::ReferenceForNoise(base, config).lines.max_rms_cells;
  CHECK(ld06 == Approx(1.0f).margin(0.01f));
  config.lidar.range_noise_m = 0.04f;  // an XV-11
  CHECK(dpcr::ReferenceForNoise(base, config).lines.max_rms_cells == Approx(1.30f).margin(0.01f));
  // The rest of the settings are kept.
  CHECK(dpcr::ReferenceForNoise(base, config).obstacle_threshold == base.obstacle_threshold);
}

TEST_CASE("Walls mapped from a low-cost lidar's noisy returns are lines with the noise-aware tolerance, clutter without") {
  // A room mapped as the regional maps are: noisy scans from poses around it through the ray
  // inserter, its walls a band of cells three to four thick. The range sigma is an XV-11's (4 cm),
  // an LD06's far walls' (1 cm + 0.5 % of 6 m); at an LD06's 2.5 cm both tolerances fit these walls.
  GridFixture f;
  const Point2 c0{1.02f, 1.03f}, c1{6.01f, 1.53f}, c2{5.51f, 5.02f}, c3{0.52f, 4.02f};
  const std::vector<Segment> walls = {{c0, c1}, {c1, c2}, {c2, c3}, {c3, c0}};
  constexpr float kNoise = 0.04f;
  std::uint32_t stamp = 1;
  for (int k = 0; k < 200; ++k) {
    const float t = static_cast<float>(k) * 0.37f;
    const dpcr::Pose2 pose{3.2f + 1.2f * std::cos(t), 3.0f + 0.9f * std::sin(1.3f * t), 0.1f * t};
    InsertScan(f, SimulateScan(walls, pose, 450, kNoise, stamp), pose, stamp);
    ++stamp;
  }
  dpcr::MapperConfig config;
  config.lidar.range_noise_m = kNoise;
  const dpcr::ReferenceConfig clean = config.front_end.region_reference;
  REQUIRE(f.Build(nullptr, clean) == dpcr::Status::kOk);
  const float clean_share = LinedShare(*f.ref);
  REQUIRE(f.Build(nullptr, dpcr::ReferenceForNoise(clean, config)) == dpcr::Status::kOk);
  const float noisy_share = LinedShare(*f.ref);
  INFO("cells in lines: clean tolerance " << clean_share << ", noise-aware " << noisy_share << " of " << f.ref->cell_count());
  CHECK(clean_share < 0.6f);
  CHECK(noisy_share >= 0.9f);
  // They are pieces of the true walls (a noisy wall is split at its outliers): each one's middle
  // lies within two cells of a wall.
  for (std::uint16_t i = 0; i < f.ref->line_count(); ++i) {
    const dpcr::LineFeature& l = f.ref->line(i);
    const Point2 mid{0.5f * (l.a.x + l.b.x), 0.5f * (l.a.y + l.b.y)};
    float nearest = 1e9f;
    for (const Segment& w : walls) nearest = std::min(nearest, DistanceToSegment(mid, w));
    CHECK(nearest <= 2.0f * kCell);
  }
}

TEST_CASE("Local normals are the principal axis the trigonometric formula gives, to the unit") {
  // 5x5 neighbourhoods around one cell of a 5x5 table. The reference: the angle of the
  // covariance's main axis by atan2, its normal by sin and cos, rounded half away from zero.
  constexpr int kW = 5;
  std::uint64_t seed = 3;
  int compared = 0, exact = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::uint16_t cell_at[kW * kW];
    std::vector<dpcr::ObstacleCell> cells;
    seed = seed * 6364136223846793005u + 1442695040888963407u;
    // Mostly wall-like: the cells near a line through the centre at a random angle and offset,
    // a few others at random.
    const double angle = static_cast<double>(seed >> 40) / 16777216.0 * 3.14159265358979;
    const double offset = static_cast<double>((seed >> 8) & 0xff) / 256.0 - 0.5, width = 0.4 + static_cast<double>((seed >> 16) & 0xff) / 512.0;
    for (int k = 0; k < kW * kW; ++k) {
      const double across = -std::sin(angle) * (k % kW - 2) + std::cos(angle) * (k / kW - 2) - offset;
      const bool occupied = k == 12 || std::fabs(across) < width || ((seed >> (k % 20)) & 0x1fu) == 0;
      cell_at[k] = dpcr::kNoCell;
      if (!occupied) continue;
      dpcr::ObstacleCell c;
      c.x = static_cast<std::uint16_t>(k % kW) & 0x3ffu;  // 10-bit fields
      c.y = static_cast<std::uint16_t>(k / kW) & 0x3ffu;
      cell_at[k] = static_cast<std::uint16_t>(cells.size());
      cells.push_back(c);
    }
    const std::uint16_t centre = cell_at[12];
    dpcr::ComputeLocalNormals(dpcr::Span<dpcr::ObstacleCell>(cells.data(), cells.size()), cell_at, kW, kW);
    double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (const auto& c : cells) {
      const double dx = c.x - 2.0, dy = c.y - 2.0;
      sx += dx, sy += dy, sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
    }
    const double n = static_cast<double>(cells.size()), mx = sx / n, my = sy / n;
    const double cxx = sxx / n - mx * mx, cxy = sxy / n - mx * my, cyy = syy / n - my * my;
    const double hs = 0.5 * (cxx + cyy), root = std::sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
    const auto& got = cells[centre];
    if (cells.size() < 3 || hs - root > 0.25 * (hs + root) + 1e-9) {
      REQUIRE(got.nx == 0);
      REQUIRE(got.ny == 0);
      continue;
    }
    if (hs - root > 0.25 * (hs + root) - 1e-9) continue;  // on the blob test's edge: float decides
    const double phi = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
    const long nx = std::lround(-127.0 * std::sin(phi)), ny = std::lround(127.0 * std::cos(phi));
    ++compared;
    REQUIRE(std::abs(got.nx - nx) <= 1);
    INFO("cxx " << cxx << " cxy " << cxy << " cyy " << cyy << " n " << n << " got " << static_cast<int>(got.nx) << "," << static_cast<int>(got.ny) << " want " << nx << "," << ny);
    REQUIRE(std::abs(got.ny - ny) <= 1);
    exact += (got.nx == nx && got.ny == ny) ? 1 : 0;
  }
  REQUIRE(compared > 5000);
  REQUIRE(exact >= compared * 99 / 100);  // off by one only where the product lies at a half
}
