#include "core/ray_caster.hpp"

#include <cmath>

#include "core/assert.hpp"

namespace dpcr {
namespace {

void Count(Status s, InsertionStats* stats, int* applied) {
  if (s == Status::kOk) {
    ++*applied;
  } else if (s == Status::kOutOfBounds) {
    ++stats->out_of_box;
  } else if (s == Status::kPoolFull) {
    ++stats->dropped_pool_full;
  }
}

}  // namespace

InsertionStats InsertRays(TiledGrid& grid, Point2 origin, Span<const Point2> hits,
                          Span<const Point2> free_ends, const GridConfig& config,
                          std::uint32_t stamp, Span<CellIndex> scratch, float miss_range_m) {
  DPCR_ASSERT(stamp != 0 && scratch.size() >= hits.size());
  InsertionStats stats;
  const float res = config.resolution_m;
  const CellIndex start = CellOf(origin.x, origin.y, res);

  // 1. Reserve every distinct hit cell, so no ray of this scan can clear it.
  std::size_t reserved = 0;
  CellIndex next_hit = hits.empty() ? start : CellOf(hits[0].x, hits[0].y, res);
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const CellIndex c = next_hit;
    if (i + 1 < hits.size()) next_hit = CellOf(hits[i + 1].x, hits[i + 1].y, res);  // ahead, as below
    if (grid.Reserve(c, stamp)) {
      scratch[reserved++] = c;
    } else if (!grid.box().Contains(c)) {
      ++stats.out_of_box;
    } else if (!grid.HasTile(c)) {
      // In the box but no tile could be had: the pool is exhausted.
      ++stats.dropped_pool_full;
    }
  }
  // 2. Misses along every ray, each cell once. The box is convex and rays start inside it:
  // a ray that leaves it never comes back, so tracing stops there (one out_of_box per ray).
  const auto miss = [&](CellIndex from, CellIndex to) {
    const TiledGrid::SegmentStats s =
        grid.UpdateSegment(from, to, config.miss_delta, config.clamp_min, config.clamp_max, stamp);
    stats.miss_cells += s.applied;
    stats.out_of_box += s.out_of_box;
    stats.dropped_pool_full += s.dropped_pool_full;
  };
  const float range2 = miss_range_m * miss_range_m;
  const float margin2 = config.hit_margin_m * config.hit_margin_m;
  // The cells a ray to hit p clears: from `start` (or miss_range_m before the hit) up to
  // hit_margin_m before it; none when the hit is within the margin.
  struct RayCells {
    CellIndex from, to;
    bool clears;
  };
  const auto ray_cells = [&](const Point2& p) {
    const float dx = p.x - origin.x, dy = p.y - origin.y;
    const float d2 = dx * dx + dy * dy;
    if (d2 <= margin2) return RayCells{start, start, false};
    const float d = std::sqrt(d2);
    const float end_k = 1.0f - config.hit_margin_m / d;
    const CellIndex to = config.hit_margin_m > 0.0f ? CellOf(origin.x + end_k * dx, origin.y + end_k * dy, res)
                                                    : CellOf(p.x, p.y, res);  // exactly the hit's cell
    if (miss_range_m <= 0.0f || d2 <= range2) return RayCells{start, to, true};
    // Start miss_range_m before the hit (a cell of the full ray's neighbourhood, not always on it).
    const float k = 1.0f - miss_range_m / d;
    return RayCells{CellOf(origin.x + k * dx, origin.y + k * dy, res), to, true};
  };
  // The next ray's cells (a chain of square root and divisions) are computed before this ray is
  // walked, so that they run in the walk's shadow instead of after it.
  RayCells next{start, start, false};
  if (!hits.empty()) next = ray_cells(hits[0]);
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const RayCells ray = next;
    if (i + 1 < hits.size()) next = ray_cells(hits[i + 1]);
    if (ray.clears) miss(ray.from, ray.to);
  }
  for (const Point2& p : free_ends) miss(start, CellOf(p.x, p.y, res));
  // 3. The reserved hits (stamp 0: already marked for this scan).
  for (std::size_t i = 0; i < reserved; ++i) {
    Count(grid.Update(scratch[i], config.hit_delta, config.clamp_min, config.clamp_max, 0), &stats,
          &stats.hit_cells);
  }
  return stats;
}

}  // namespace dpcr
