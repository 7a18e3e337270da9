// Inserts one scan's rays into a tiled grid: each ray's cells become misses and its endpoint
// a hit, with at most one update per cell per scan. Hit cells are reserved first, so a cell
// both crossed by one ray and hit by another counts as a hit (a thin wall seen at a grazing
// angle survives); then misses are applied, then the hits.
#pragma once

#include <cstdint>

#include "core/cell.hpp"
#include "core/config.hpp"
#include "core/pose2.hpp"
#include "core/span.hpp"
#include "core/tiled_grid.hpp"

namespace dpcr {

struct InsertionStats {
  int hit_cells = 0;
  int miss_cells = 0;
  int out_of_box = 0;         // updates that fell outside the grid's box
  int dropped_pool_full = 0;  // updates lost because no tile was free
};

// `hits`: endpoints of beams with a return; `free_ends`: where beams without a return stop
// clearing. Both in the grid's frame. `scratch` holds at least hits.size() cells.
// `stamp` identifies the scan (non-zero, different from the previous scan's).
// `miss_range_m` > 0: a ray to a hit clears only its last miss_range_m metres (free ends: whole).
InsertionStats InsertRays(TiledGrid& grid, Point2 origin, Span<const Point2> hits,
                          Span<const Point2> free_ends, const GridConfig& config,
                          std::uint32_t stamp, Span<CellIndex> scratch, float miss_range_m = 0.0f);

// Visits the cells of the segment a -> b (Bresenham), excluding b; stops early when the
// visitor returns false. Header-only so the per-cell call inlines.
template <typename Visitor>
void TraceCells(CellIndex a, CellIndex b, Visitor&& visit) {
  std::int32_t dx = b.x - a.x;
  std::int32_t dy = b.y - a.y;
  const std::int32_t sx = dx >= 0 ? 1 : -1;
  const std::int32_t sy = dy >= 0 ? 1 : -1;
  dx = dx >= 0 ? dx : -dx;
  dy = dy >= 0 ? dy : -dy;
  std::int32_t err = dx - dy;
  CellIndex c = a;
  while (c != b) {
    if (!visit(c)) return;
    const std::int32_t e2 = 2 * err;
    if (e2 > -dy) {
      err -= dy;
      c.x += sx;
    }
    if (e2 < dx) {
      err += dx;
      c.y += sy;
    }
  }
}

}  // namespace dpcr
