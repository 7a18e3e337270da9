// The loop-closure search: a cloud found far outside the PLICP basin, and ambiguous scenes refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/back_end/correlative_search.hpp"
#include "tests/core/registration_fixtures.hpp"

using dpcr::Point2;
using dpcr::Pose2;
using dpcr_test::Segment;

namespace {

using Grid = dpcr::MatchGridStorage<128, 128>;

// An L-shaped room with a table and a cupboard: no symmetry.
std::vector<Segment> Room() {
  return {{{1, 1}, {9, 1}}, {{9, 1}, {9, 5}}, {{9, 5}, {5, 5}}, {{5, 5}, {5, 9}}, {{5, 9}, {1, 9}},
          {{1, 9}, {1, 1}}, {{2.5f, 3}, {3.5f, 3}}, {{3.5f, 3}, {3.5f, 3.6f}}, {{7, 2}, {7.8f, 2}}};
}

std::vector<Point2> Cloud(const std::vector<Segment>& walls, Pose2 at) {
  return dpcr_test::SimulateScan(walls, at, 360, 0.01f, 3);
}

struct Setup {
  dpcr_test::GridFixture fixture;
  std::unique_ptr<Grid> grid = std::make_unique<Grid>();
  std::vector<dpcr::MatchCell> scratch = std::vector<dpcr::MatchCell>(512);
  explicit Setup(const std::vector<Segment>& walls) {
    for (const Segment& s : walls) fixture.Draw(s);
    grid->Build(*fixture.grid, fixture.grid->box(), 2, 0);
  }
  dpcr::CorrelativeSearchResult Search(const std::vector<Point2>& cloud, Pose2 initial, float window_m, float window_rad) {
    return dpcr::CorrelativeSearch(*grid, dpcr::Span<const Point2>(cloud.data(), cloud.size()), initial, window_m, window_rad,
                                   dpcr::CorrelativeSearchConfig{}, dpcr::Span<dpcr::MatchCell>(scratch.data(), scratch.size()));
  }
};

}  // namespace

TEST_CASE("The correlative search finds a cloud 1 m and 12 degrees from its guess") {
  Setup s(Room());
  REQUIRE(s.grid->obstacle_cells() > 200);
  const Pose2 truth{3.2f, 6.1f, 0.4f};
  const auto cloud = Cloud(Room(), truth);
  const Pose2 guess{truth.x + 0.8f, truth.y - 0.6f, truth.theta - 0.21f};
  const dpcr::CorrelativeSearchResult r = s.Search(cloud, guess, 1.5f, 0.35f);
  REQUIRE(r.verdict == dpcr::Status::kOk);
  REQUIRE(std::hypot(r.pose.x - truth.x, r.pose.y - truth.y) < 0.1f);
  REQUIRE(std::fabs(dpcr::NormalizeAngle(r.pose.theta - truth.theta)) < 0.03f);
  REQUIRE(r.score > 0.7f);
  REQUIRE(r.second_score < r.score);
  // A window that does not reach the truth gives a weak or no answer, never a confident wrong one
  // near the guess.
  const dpcr::CorrelativeSearchResult narrow = s.Search(cloud, guess, 0.3f, 0.05f);
  if (narrow.verdict == dpcr::Status::kOk) {
    REQUIRE(std::hypot(narrow.pose.x - truth.x, narrow.pose.y - truth.y) < 0.1f);
  }
}

TEST_CASE("A correlative search run in slices gives the one-shot answer, each slice bounded") {
  Setup s(Room());
  const Pose2 truth{3.2f, 6.1f, 0.4f};
  const auto cloud = Cloud(Room(), truth);
  const dpcr::Span<const Point2> points(cloud.data(), cloud.size());
  const dpcr::Span<dpcr::MatchCell> scratch(s.scratch.data(), s.scratch.size());
  for (const Pose2 guess : {Pose2{truth.x + 0.8f, truth.y - 0.6f, truth.theta - 0.21f}, Pose2{2.0f, 4.0f, 1.5f}}) {
    const dpcr::CorrelativeSearchResult whole = s.Search(cloud, guess, 1.5f, 0.35f);
    dpcr::CorrelativeSearchRun run;
    run.Begin(*s.grid, points, guess, 1.5f, 0.35f, dpcr::CorrelativeSearchConfig{});
    constexpr std::uint32_t kSlice = 500;
    // One coarse block of 16 x 16 offsets is the most a slice can overrun by.
    constexpr std::uint32_t kWorstBlock = 16 * 16 + 4 * 4 + 1;
    int slices = 0;
    std::uint32_t before = 0;
    bool done = false;
    while (!done) {
      done = run.Continue(*s.grid, points, dpcr::CorrelativeSearchConfig{}, scratch, kSlice);
      ++slices;
      const std::uint32_t evaluated = run.result().poses_evaluated - before;
      before = run.result().poses_evaluated;
      REQUIRE(evaluated <= kSlice + kWorstBlock + 1);
    }
    REQUIRE(slices > 3);
    const dpcr::CorrelativeSearchResult& sliced = run.result();
    REQUIRE(sliced.verdict == whole.verdict);
    REQUIRE(sliced.pose.x == whole.pose.x);
    REQUIRE(sliced.pose.y == whole.pose.y);
    REQUIRE(sliced.pose.theta == whole.pose.theta);
    REQUIRE(sliced.score == whole.score);
    REQUIRE(sliced.second_score == whole.second_score);
    REQUIRE(sliced.poses_evaluated == whole.poses_evaluated);
  }
}

TEST_CASE("The correlative search refuses twin rooms and corridors") {
  SECTION("two identical rooms side by side, both inside the window") {
    std::vector<Segment> twins;
    for (const float dx : {0.0f, 5.5f}) {
      for (const Segment& w : std::vector<Segment>{{{1, 2}, {5, 2}}, {{5, 2}, {5, 6}}, {{5, 6}, {1, 6}}, {{1, 6}, {1, 2}},
                                                   {{2, 3}, {2.6f, 3}}, {{2.6f, 3}, {2.6f, 3.5f}}}) {
        twins.push_back(Segment{{w.a.x + dx, w.a.y}, {w.b.x + dx, w.b.y}});
      }
    }
    Setup s(twins);
    // The robot in the left room sees only that room (walls block the other).
    const Pose2 truth{3.0f, 4.5f, 0.1f};
    const auto cloud = Cloud(twins, truth);
    const dpcr::CorrelativeSearchResult r = s.Search(cloud, Pose2{5.5f, 4.5f, 0.1f}, 3.0f, 0.1f);
    REQUIRE(r.verdict == dpcr::Status::kRejected);
    REQUIRE(r.second_score > 0.9f * r.score);
  }
  SECTION("a featureless corridor") {
    const std::vector<Segment> corridor{{{0.2f, 5}, {12.6f, 5}}, {{0.2f, 6.5f}, {12.6f, 6.5f}}};
    Setup s(corridor);
    const Pose2 truth{6.0f, 5.7f, 0.0f};
    const auto cloud = dpcr_test::SimulateScan(corridor, truth, 360, 0.01f, 3, 3.0f);
    const dpcr::CorrelativeSearchResult r = s.Search(cloud, Pose2{6.4f, 5.7f, 0.0f}, 1.5f, 0.1f);
    REQUIRE(r.verdict == dpcr::Status::kRejected);
  }
}

namespace {

// The best summed likelihood over the search's lattice of poses (its angle step rule, whole match
// cells), scored pose by pose; a look-up outside the grid reads 0. `poses`: the lattice's size.
std::uint32_t BruteForceBest(const Setup& s, const std::vector<Point2>& cloud, Pose2 guess, float window_m, float window_rad,
                             std::uint32_t* poses) {
  float max_range = 1.0f;
  for (const Point2& p : cloud) max_range = std::fmax(max_range, std::hypot(p.x, p.y));
  const dpcr::CorrelativeSearchConfig config;
  const float step = std::fmin(std::fmax(s.grid->resolution_m() / max_range, config.min_angle_step_rad), config.max_angle_step_rad);
  const int n_angles = static_cast<int>(window_rad / step), n_offsets = static_cast<int>(window_m / s.grid->resolution_m());
  std::uint32_t best = 0;
  for (int a = -n_angles; a <= n_angles; ++a) {
    const dpcr::PointTransform t(Pose2{guess.x, guess.y, guess.theta + static_cast<float>(a) * step});
    for (int oy = -n_offsets; oy <= n_offsets; ++oy) {
      for (int ox = -n_offsets; ox <= n_offsets; ++ox) {
        std::uint32_t sum = 0;
        for (const Point2& p : cloud) {
          const Point2 w = t(p);
          sum += s.grid->AtCell(dpcr::FloorToInt((w.x - s.grid->origin().x) / s.grid->resolution_m()) + ox,
                                dpcr::FloorToInt((w.y - s.grid->origin().y) / s.grid->resolution_m()) + oy);
        }
        best = sum > best ? sum : best;
      }
    }
  }
  *poses = static_cast<std::uint32_t>((2 * n_angles + 1) * (2 * n_offsets + 1) * (2 * n_offsets + 1));
  return best;
}

}  // namespace

TEST_CASE("Branch and bound scores the same best pose as scoring every pose") {
  Setup s(Room());
  const Pose2 truth{6.2f, 3.1f, -0.3f};
  const auto cloud = Cloud(Room(), truth);
  const Pose2 guess{truth.x - 0.45f, truth.y + 0.3f, truth.theta + 0.05f};
  const dpcr::CorrelativeSearchResult r = s.Search(cloud, guess, 0.8f, 0.1f);
  std::uint32_t lattice = 0;
  const std::uint32_t best = BruteForceBest(s, cloud, guess, 0.8f, 0.1f, &lattice);
  REQUIRE(r.score == Approx(static_cast<float>(best) / (255.0f * static_cast<float>(cloud.size()))).epsilon(1e-5));
  // And it scored far fewer poses than the lattice holds.
  REQUIRE(r.poses_evaluated < lattice);
}

TEST_CASE("Branch and bound scores every pose's best also where the window leaves the grid") {
  // The room drawn against the grid's lower-left corner, or its upper-right one, or partly beyond
  // it (its far walls off the grid, as a scan that sees past the map), and a window of 1.5 m: many
  // offsets move part of the cloud (a few hundred points, past the search's 256-point batches)
  // off the grid, where the bounds and scores take their edge paths.
  const float shift = GENERATE(-0.9f, 3.7f, 4.6f);
  std::vector<Segment> walls = Room();
  for (Segment& w : walls) {
    w.a = Point2{w.a.x + shift, w.a.y + shift};
    w.b = Point2{w.b.x + shift, w.b.y + shift};
  }
  Setup s(walls);
  const Pose2 truth{2.1f + shift, 1.9f + shift, 0.4f};
  const auto cloud = Cloud(walls, truth);
  REQUIRE(cloud.size() > 256);
  const Pose2 guess{truth.x + 0.3f, truth.y - 0.2f, truth.theta - 0.04f};
  const dpcr::CorrelativeSearchResult r = s.Search(cloud, guess, 1.5f, 0.08f);
  std::uint32_t lattice = 0;
  const std::uint32_t best = BruteForceBest(s, cloud, guess, 1.5f, 0.08f, &lattice);
  REQUIRE(r.score == Approx(static_cast<float>(best) / (255.0f * static_cast<float>(cloud.size()))).epsilon(1e-5));
}

TEST_CASE("A best pose on the window's border is refused: the peak may lie outside") {
  Setup s(Room());
  const Pose2 truth{3.2f, 6.1f, 0.4f};
  const auto cloud = Cloud(Room(), truth);
  // The truth 0.8 m away in x, the window 0.6 m: the best the search can score is on its edge.
  const Pose2 off_x{truth.x + 0.8f, truth.y, truth.theta};
  const dpcr::CorrelativeSearchResult x = s.Search(cloud, off_x, 0.6f, 0.1f);
  CHECK(x.on_border);
  CHECK(x.verdict == dpcr::Status::kRejected);
  // 0.3 rad off, a window of 0.2 rad.
  const Pose2 off_theta{truth.x, truth.y, truth.theta - 0.3f};
  const dpcr::CorrelativeSearchResult t = s.Search(cloud, off_theta, 0.5f, 0.2f);
  CHECK(t.on_border);
  CHECK(t.verdict == dpcr::Status::kRejected);
  // The same offsets inside wider windows: found, and not on the border.
  const dpcr::CorrelativeSearchResult wide = s.Search(cloud, Pose2{truth.x + 0.8f, truth.y, truth.theta - 0.3f}, 1.2f, 0.35f);
  CHECK_FALSE(wide.on_border);
  REQUIRE(wide.verdict == dpcr::Status::kOk);
  CHECK(std::hypot(wide.pose.x - truth.x, wide.pose.y - truth.y) < 0.1f);
}
