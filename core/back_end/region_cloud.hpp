// A regional map's obstacle cloud (paper §3.5: the vertex's point cloud C_n): the centres of its
// cells above a log-odds threshold, evenly thinned to a capacity, in the map's own frame.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/base/span.hpp"
#include "core/geometry/pose2.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr {

// Obstacle cells of `grid` (above `threshold`).
std::size_t CountObstacleCells(const TiledGrid& grid, std::int16_t threshold);

// Writes at most out.size() obstacle-cell centres, every k-th of the grid's obstacle cells in
// tile order (k chosen from `total`, CountObstacleCells' answer); returns how many.
std::size_t CollectObstacleCloud(const TiledGrid& grid, std::int16_t threshold, std::size_t total, Span<Point2> out);

}  // namespace dpcr
