// The global map on demand: regional maps fused by summing log-odds (clamped) into a
// caller-provided buffer. Never the only copy of the data.
#pragma once

#include <cstdint>

#include "core/geometry/pose2.hpp"
#include "core/base/span.hpp"
#include "core/base/status.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr {

// A regional map placed in the world: its cells are in the frame of `anchor`.
struct PlacedGrid {
  const TiledGrid* grid = nullptr;
  Pose2 anchor;
};

// World-frame cell box covering every allocated tile of every grid (empty box if none).
CellBox FusedBounds(Span<const PlacedGrid> grids, float resolution_m);

// Fills `out` (row-major, row 0 = box.min.y, width box.width()) with the fused log-odds,
// kUnknownCell where no grid observed a cell. kInvalidArgument if `out` is too small.
Status FuseInto(Span<const PlacedGrid> grids, CellBox box, float resolution_m, std::int16_t clamp_min,
                std::int16_t clamp_max, Span<std::int16_t> out);

}  // namespace dpcr
