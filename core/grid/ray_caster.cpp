#include "core/grid/ray_caster.hpp"

#include <cmath>

#include "core/base/assert.hpp"

namespace dpcr {

InsertionStats InsertRays(TiledGrid& grid, Point2 origin, Span<const Point2> hits, Span<const Point2> free_ends,
                          const GridConfig& config, std::uint32_t stamp, Span<CellIndex> scratch, float miss_range_m) {
  DPCR_ASSERT(stamp != 0 && scratch.size() >= hits.size());
  InsertionStats stats;
  const float res = config.resolution_m;
  const CellIndex start = CellOf(origin.x, origin.y, res);

  // 1. The hits, each distinct cell once. They are marked as updated in this scan, so no ray of
  // this scan can clear them (a miss would be skipped as a repeat).
  for (std::size_t i = 0; i < hits.size(); ++i) scratch[i] = CellOf(hits[i].x, hits[i].y, res);
  const TiledGrid::SegmentStats h = grid.UpdateCells(Span<const CellIndex>(scratch.data(), hits.size()), config.hit_delta,
                                                     config.clamp_min, config.clamp_max, stamp);
  stats.hit_cells = h.applied;
  stats.out_of_box += h.out_of_box;
  stats.dropped_pool_full += h.dropped_pool_full;

  // 2. Misses along every ray, each cell once. The box is convex and rays start inside it:
  // a ray that leaves it never comes back, so tracing stops there (one out_of_box per ray).
  // Rays go to the grid in batches (the walk is set up once per batch, and the cells of a batch's
  // rays, a chain of square root and divisions each, are computed back to back).
  constexpr std::size_t kBatch = 32;
  CellSegment batch[kBatch];
  std::size_t queued = 0;
  const auto flush = [&]() {
    const TiledGrid::SegmentStats s = grid.UpdateSegments(Span<const CellSegment>(batch, queued), config.miss_delta,
                                                          config.clamp_min, config.clamp_max, stamp);
    stats.miss_cells += s.applied;
    stats.out_of_box += s.out_of_box;
    stats.dropped_pool_full += s.dropped_pool_full;
    queued = 0;
  };
  const auto queue = [&](CellIndex from, CellIndex to) {
    batch[queued++] = CellSegment{from, to};
    if (queued == kBatch) flush();
  };
  const float range2 = miss_range_m * miss_range_m;
  const float margin2 = config.hit_margin_m * config.hit_margin_m;
  // The cells a ray to hit p clears: from `start` (or miss_range_m before the hit) up to
  // hit_margin_m before it; none when the hit is within the margin.
  for (const Point2& p : hits) {
    const float dx = p.x - origin.x, dy = p.y - origin.y;
    const float d2 = dx * dx + dy * dy;
    if (d2 <= margin2) continue;
    const float d = std::sqrt(d2);
    const float end_k = 1.0f - config.hit_margin_m / d;
    const CellIndex to = config.hit_margin_m > 0.0f ? CellOf(origin.x + end_k * dx, origin.y + end_k * dy, res)
                                                    : CellOf(p.x, p.y, res);  // exactly the hit's cell
    if (miss_range_m <= 0.0f || d2 <= range2) {
      queue(start, to);
    } else {
      // Start miss_range_m before the hit (a cell of the full ray's neighbourhood, not always on it).
      const float k = 1.0f - miss_range_m / d;
      queue(CellOf(origin.x + k * dx, origin.y + k * dy, res), to);
    }
  }
  for (const Point2& p : free_ends) queue(start, CellOf(p.x, p.y, res));
  flush();
  return stats;
}

}  // namespace dpcr
