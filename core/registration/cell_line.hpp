// The cells of a straight segment on the grid (Bresenham): what a lidar ray crosses.
#pragma once

#include <cstdint>

#include "core/grid/cell.hpp"

namespace dpcr {

// Bresenham's integer walk from a towards b: each Step moves one cell, along the major axis
// always and along the minor one when the error says so; b is reached after steps() steps.
struct BresenhamWalk {
  std::int32_t dx, dy, sx, sy, err;
  BresenhamWalk(CellIndex a, CellIndex b)
      : dx(b.x >= a.x ? b.x - a.x : a.x - b.x),
        dy(b.y >= a.y ? b.y - a.y : a.y - b.y),
        sx(b.x >= a.x ? 1 : -1),
        sy(b.y >= a.y ? 1 : -1),
        err(dx - dy) {}
  std::int32_t steps() const { return dx > dy ? dx : dy; }
  void Step(std::int32_t* x, std::int32_t* y) {
    const std::int32_t e2 = 2 * err;
    if (e2 > -dy) {
      err -= dy;
      *x += sx;
    }
    if (e2 < dx) {
      err += dx;
      *y += sy;
    }
  }
};

// Visits the cells of the segment a -> b (Bresenham), excluding b; stops early when the
// visitor returns false. Header-only so the per-cell call inlines.
template <typename Visitor>
void TraceCells(CellIndex a, CellIndex b, Visitor&& visit) {
  BresenhamWalk walk(a, b);
  CellIndex c = a;
  while (c != b) {
    if (!visit(c)) return;
    walk.Step(&c.x, &c.y);
  }
}

}  // namespace dpcr
