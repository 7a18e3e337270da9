// The submap ring: what a scan adds, its removal takes away exactly.
#include <catch2/catch.hpp>

#include <memory>
#include <random>
#include <vector>

#include "core/front_end/submap.hpp"

using dpcr::CellIndex;
using dpcr::Point2;
using dpcr::Pose2;

namespace {
using SmallSubmap = dpcr::SubmapStorage<4, 64, 128>;

std::vector<Point2> RoomScan(const Pose2& pose, std::mt19937& rng) {
  // A 6 m x 6 m room centred at the origin, seen from `pose`, with noise.
  std::normal_distribution<float> noise(0.0f, 0.01f);
  std::vector<Point2> pts;
  for (int b = 0; b < 64; ++b) {
    const float a = -dpcr::kPi + 2.0f * dpcr::kPi * static_cast<float>(b) / 64.0f;
    const float wa = pose.theta + a, c = std::cos(wa), s = std::sin(wa);
    float r = 1e9f;
    if (c > 1e-6f) r = std::fmin(r, (3.0f - pose.x) / c);
    if (c < -1e-6f) r = std::fmin(r, (-3.0f - pose.x) / c);
    if (s > 1e-6f) r = std::fmin(r, (3.0f - pose.y) / s);
    if (s < -1e-6f) r = std::fmin(r, (-3.0f - pose.y) / s);
    r += noise(rng);
    pts.push_back(Point2{r * std::cos(a), r * std::sin(a)});
  }
  return pts;
}

std::vector<std::int16_t> Snapshot(const dpcr::TiledGrid& g) {
  std::vector<std::int16_t> v;
  const dpcr::CellBox b = g.box();
  for (int y = b.min.y; y < b.max.y; ++y)
    for (int x = b.min.x; x < b.max.x; ++x) {
      const std::int16_t c = g.Get(CellIndex{x, y});
      v.push_back(c == dpcr::kUnknownCell ? 0 : c);  // a cell back at 0 equals one never touched
    }
  return v;
}
}  // namespace

TEST_CASE("The submap keeps the last N scans and removes the oldest exactly") {
  std::mt19937 rng(11);
  auto a = std::make_unique<SmallSubmap>();
  auto b = std::make_unique<SmallSubmap>();
  dpcr::GridConfig config;
  a->Reset(config, 4);
  b->Reset(config, 4);
  std::vector<std::pair<Pose2, std::vector<Point2>>> scans;
  for (int i = 0; i < 10; ++i) {
    const Pose2 p{0.1f * static_cast<float>(i), 0.05f * static_cast<float>(i), 0.02f * static_cast<float>(i)};
    scans.emplace_back(p, RoomScan(p, rng));
  }
  for (const auto& [p, pts] : scans) (void)a->Add(p, dpcr::Span<const Point2>(pts.data(), pts.size()));
  for (int i = 6; i < 10; ++i) (void)b->Add(scans[i].first, dpcr::Span<const Point2>(scans[i].second.data(), scans[i].second.size()));
  REQUIRE(a->size() == 4);
  REQUIRE(a->scan(0).pose.x == Approx(0.6f));
  REQUIRE(a->grid().box().min == b->grid().box().min);
  REQUIRE(Snapshot(a->grid()) == Snapshot(b->grid()));
  // The wall at x = 3 m: noise puts its cells on either side of the cell border x = 60.
  const auto& g = a->grid();
  int wall_cells = 0;
  for (int y = -60; y < 60; ++y) wall_cells += dpcr::IsOccupied(g.Get(CellIndex{59, y})) || dpcr::IsOccupied(g.Get(CellIndex{60, y}));
  REQUIRE(wall_cells >= 8);
  REQUIRE(dpcr::IsFree(g.Get(dpcr::CellOf(2.0f, 0.45f, 0.05f))));
}

TEST_CASE("The submap box follows the robot and keeps its scans") {
  std::mt19937 rng(5);
  auto s = std::make_unique<SmallSubmap>();  // 128 cells = 6.4 m box
  s->Reset(dpcr::GridConfig{}, 4);
  const Pose2 far{2.5f, 0.0f, 0.0f};
  const auto pts = RoomScan(far, rng);
  (void)s->Add(Pose2{}, dpcr::Span<const Point2>(pts.data(), pts.size()));
  (void)s->Add(far, dpcr::Span<const Point2>(pts.data(), pts.size()));
  REQUIRE(s->recentres() == 1);
  REQUIRE(s->grid().box().Contains(dpcr::CellOf(2.5f, 0.0f, 0.05f)));
  REQUIRE(s->size() == 2);
}
