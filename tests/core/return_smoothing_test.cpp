// Range-noise smoothing (core/geometry/return_smoothing.hpp): returns on a straight wall move onto
// it, a corner keeps its returns, a gap or an unknown noise leaves a scan as measured.
#include "core/geometry/return_smoothing.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/pose2.hpp"

using dpcr::Point2;
using dpcr::ReturnSmoothingConfig;
using dpcr::SmoothReturns;
using dpcr::Span;

namespace {

constexpr float kStep = 2.0f * dpcr::kPi / 450.0f;  // an LD06-like revolution

// Returns of beams from the origin at angles first + k * kStep on the wall x = wall_x (ranges
// with Gaussian noise of sigma), or on the corner of the walls x = wall_x and y = wall_y.
std::vector<Point2> Returns(float wall_x, float wall_y, int beams, float sigma, unsigned seed, float first_rad) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  std::vector<Point2> hits;
  for (int k = 0; k < beams; ++k) {
    const float a = first_rad + static_cast<float>(k) * kStep;
    const float c = std::cos(a), s = std::sin(a);
    float r = wall_x / c;
    if (wall_y > 0.0f && s > 0.0f && wall_y / s < r) r = wall_y / s;
    r += sigma * noise(rng);
    hits.push_back(Point2{r * c, r * s});
  }
  return hits;
}

ReturnSmoothingConfig Ld06() {
  ReturnSmoothingConfig c;
  c.noise_m = 0.025f;
  return c;
}

float RmsOffWall(const std::vector<Point2>& hits, float wall_x) {
  float sum = 0.0f;
  for (const Point2& p : hits) sum += (p.x - wall_x) * (p.x - wall_x);
  return std::sqrt(sum / static_cast<float>(hits.size()));
}

}  // namespace

TEST_CASE("Noisy returns on a straight wall move onto it along their rays") {
  // A wall 2 m ahead, 60 beams either side of its normal; the LD06's noise there, 2 cm.
  std::vector<Point2> hits = Returns(2.0f, 0.0f, 120, 0.02f, 7, -60.0f * kStep);
  const std::vector<Point2> measured = hits;
  const float before = RmsOffWall(hits, 2.0f);
  const std::size_t moved = SmoothReturns(Span<Point2>(hits.data(), hits.size()), Point2{}, kStep, Ld06());
  const float after = RmsOffWall(hits, 2.0f);
  CHECK(moved >= 100);  // all but the ends and a few outliers of the noise
  CHECK(after < 0.6f * before);
  for (std::size_t i = 0; i < hits.size(); ++i) {  // along its own ray: the bearing is kept
    const float cross = measured[i].x * hits[i].y - measured[i].y * hits[i].x;
    CHECK(std::fabs(cross) < 1e-4f);
  }
}

TEST_CASE("The returns of a corner stay where they were measured") {
  // Exact returns (no noise) of a right-angle corner 2 m away on both axes.
  std::vector<Point2> hits = Returns(2.0f, 2.0f, 80, 0.0f, 1, 45.0f * dpcr::kPi / 180.0f - 40.0f * kStep);
  const std::vector<Point2> measured = hits;
  (void)SmoothReturns(Span<Point2>(hits.data(), hits.size()), Point2{}, kStep, Ld06());
  float largest = 0.0f;
  for (std::size_t i = 0; i < hits.size(); ++i) {
    largest = std::fmax(largest, std::hypot(hits[i].x - measured[i].x, hits[i].y - measured[i].y));
  }
  CHECK(largest < 0.005f);
}

TEST_CASE("Returns across a gap or of a lidar whose noise is not known are left as measured") {
  std::vector<Point2> hits = Returns(2.0f, 0.0f, 40, 0.02f, 3, -20.0f * kStep);
  const std::vector<Point2> measured = hits;
  ReturnSmoothingConfig unknown = Ld06();
  unknown.noise_m = 0.0f;
  CHECK(SmoothReturns(Span<Point2>(hits.data(), hits.size()), Point2{}, kStep, unknown) == 0);
  // Every other beam missing: no return has an adjacent neighbour.
  std::vector<Point2> sparse;
  for (std::size_t i = 0; i < hits.size(); i += 2) sparse.push_back(hits[i]);
  CHECK(SmoothReturns(Span<Point2>(sparse.data(), sparse.size()), Point2{}, kStep, Ld06()) == 0);
  for (std::size_t i = 0; i < hits.size(); ++i) CHECK((hits[i].x == measured[i].x && hits[i].y == measured[i].y));
}

TEST_CASE("Returns with missing beams between them are smoothed as far as the gap allowed") {
  // An XV-11-like wall: 2 cm of noise, and a third of the beams without a return (seeded).
  const std::vector<Point2> all = Returns(2.0f, 0.0f, 120, 0.02f, 11, -60.0f * kStep);
  std::mt19937 rng(5);
  std::bernoulli_distribution missing(0.33);
  std::vector<Point2> hits;
  for (const Point2& p : all) {
    if (!missing(rng)) hits.push_back(p);
  }
  const float before = RmsOffWall(hits, 2.0f);
  std::vector<Point2> adjacent_only = hits;
  const std::size_t moved_adjacent = SmoothReturns(Span<Point2>(adjacent_only.data(), adjacent_only.size()), Point2{}, kStep, Ld06());
  ReturnSmoothingConfig bridging = Ld06();
  bridging.max_gap_beams = 3.5f;  // up to two missing beams between neighbours
  const std::size_t moved = SmoothReturns(Span<Point2>(hits.data(), hits.size()), Point2{}, kStep, bridging);
  CHECK(moved_adjacent < hits.size() / 4);  // few windows of seven adjacent returns
  CHECK(moved > 2 * moved_adjacent);
  CHECK(moved >= hits.size() / 2);
  CHECK(RmsOffWall(hits, 2.0f) < 0.75f * before);
}
