// Test helpers for line extraction and registration: synthetic grids drawn cell by cell, and
// scans ray-cast against wall segments.
#pragma once

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "core/grid/ray_caster.hpp"
#include "core/registration/registration_reference.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr_test {

using dpcr::CellIndex;
using dpcr::Point2;

struct Segment {
  Point2 a, b;
};

using Reference = dpcr::RegistrationReferenceStorage<256, 256, 4096, 512>;

// Cell-centre coordinates (k * 5 cm + 2.5 cm): walls drawn there give exact line features.
inline float C(int k) { return 0.05f * static_cast<float>(k) + 0.025f; }

inline dpcr::Span<const Point2> SpanOf(const std::vector<Point2>& v) { return dpcr::Span<const Point2>(v.data(), v.size()); }

struct GridFixture {
  std::unique_ptr<dpcr::TilePoolStorage<64>> pool = std::make_unique<dpcr::TilePoolStorage<64>>();
  std::unique_ptr<dpcr::TiledGridStorage<8, 8>> grid = std::make_unique<dpcr::TiledGridStorage<8, 8>>(pool.get());
  std::unique_ptr<Reference> ref = std::make_unique<Reference>();
  GridFixture() { grid->Reset(CellIndex{0, 0}); }

  void Mark(Point2 p) { (void)grid->Update(dpcr::CellOf(p.x, p.y, 0.05f), 1000, -3000, 3000, 0); }
  // Marks the cells along a segment (one sample per 1/4 cell), optionally jittered across it.
  void Draw(Segment s, float jitter_m = 0.0f, unsigned seed = 1, float gap_from = -1.0f, float gap_to = -1.0f) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, jitter_m > 0.0f ? jitter_m : 1e-9f);
    const float len = std::hypot(s.b.x - s.a.x, s.b.y - s.a.y);
    const int n = static_cast<int>(len / 0.0125f) + 1;
    const Point2 nrm{-(s.b.y - s.a.y) / len, (s.b.x - s.a.x) / len};
    for (int i = 0; i <= n; ++i) {
      const float t = static_cast<float>(i) / static_cast<float>(n);
      if (t * len > gap_from && t * len < gap_to) continue;
      const float e = jitter_m > 0.0f ? noise(rng) : 0.0f;
      Mark(Point2{s.a.x + t * (s.b.x - s.a.x) + e * nrm.x, s.a.y + t * (s.b.y - s.a.y) + e * nrm.y});
    }
  }
  dpcr::Status Build(dpcr::ReferenceBuildStats* stats = nullptr, dpcr::ReferenceConfig config = {}) {
    return ref->Build(*grid, grid->box(), config, stats);
  }
};

// Range to the first wall along a ray, or -1.
inline float CastRay(const std::vector<Segment>& walls, Point2 o, float angle, float max_range) {
  const float dx = std::cos(angle), dy = std::sin(angle);
  float best = -1.0f;
  for (const Segment& w : walls) {
    const float ex = w.b.x - w.a.x, ey = w.b.y - w.a.y;
    const float den = dx * ey - dy * ex;
    if (std::fabs(den) < 1e-9f) continue;
    const float t = ((w.a.x - o.x) * ey - (w.a.y - o.y) * ex) / den;
    const float u = ((w.a.x - o.x) * dy - (w.a.y - o.y) * dx) / den;
    if (t > 0.0f && u >= 0.0f && u <= 1.0f && t <= max_range && (best < 0.0f || t < best)) best = t;
  }
  return best;
}

// A 360° scan of `beams` beams from `pose`, endpoints in the sensor frame.
inline std::vector<Point2> SimulateScan(const std::vector<Segment>& walls, dpcr::Pose2 pose, int beams,
                                        float noise_m, unsigned seed, float max_range = 8.0f) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, noise_m > 0.0f ? noise_m : 1e-9f);
  std::vector<Point2> pts;
  for (int i = 0; i < beams; ++i) {
    const float a = -dpcr::kPi + 2.0f * dpcr::kPi * static_cast<float>(i) / static_cast<float>(beams);
    float r = CastRay(walls, Point2{pose.x, pose.y}, pose.theta + a, max_range);
    if (r < 0.0f) continue;
    if (noise_m > 0.0f) r += noise(rng);
    pts.push_back(Point2{r * std::cos(a), r * std::sin(a)});
  }
  return pts;
}

// Inserts a sensor-frame scan taken at `pose` into the fixture's grid.
inline void InsertScan(GridFixture& f, const std::vector<Point2>& scan, dpcr::Pose2 pose, std::uint32_t stamp) {
  std::vector<Point2> world;
  for (const Point2& p : scan) world.push_back(pose.Apply(p));
  std::vector<CellIndex> scratch(world.size() + 1);
  dpcr::GridConfig config;
  (void)dpcr::InsertRays(*f.grid, Point2{pose.x, pose.y}, dpcr::Span<const Point2>(world.data(), world.size()),
                         dpcr::Span<const Point2>(), config, stamp,
                         dpcr::Span<CellIndex>(scratch.data(), scratch.size()));
}

}  // namespace dpcr_test
