// The cells of a straight segment on the grid (Bresenham): what a lidar ray crosses.
#pragma once

#include <cstdint>

#include "core/cell.hpp"

namespace dpcr {

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
