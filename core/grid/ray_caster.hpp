// Inserts one scan's rays into a tiled grid: each ray's cells become misses and its endpoint
// a hit, with at most one update per cell per scan. Hits are applied first, so a cell both
// crossed by one ray and hit by another counts as a hit (a thin wall seen at a grazing angle
// survives): the misses of the scan skip it as already updated.
#pragma once

#include <cstdint>

#include "core/grid/cell.hpp"
#include "core/registration/cell_line.hpp"
#include "core/config.hpp"
#include "core/geometry/pose2.hpp"
#include "core/base/span.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr {

struct InsertionStats {
  int hit_cells = 0;
  int miss_cells = 0;
  int out_of_box = 0;         // updates that fell outside the grid's box
  int dropped_pool_full = 0;  // updates lost because no tile was free
};

// `hits`: endpoints of beams with a return; `free_ends`: where beams without a return stop
// clearing. Both in the grid's frame. `scratch` holds at least hits.size() cells.
// `stamp` identifies the scan (ScanMarker: non-zero, different from the previous scan's).
// `miss_range_m` > 0: a ray to a hit clears only its last miss_range_m metres (free ends: whole).
// A ray to a hit stops clearing config.hit_margin_m before it (GridConfig::hit_margin_m).
InsertionStats InsertRays(TiledGrid& grid, Point2 origin, Span<const Point2> hits,
                          Span<const Point2> free_ends, const GridConfig& config,
                          std::uint32_t stamp, Span<CellIndex> scratch, float miss_range_m = 0.0f);

}  // namespace dpcr
