#include "core/back_end/region_cloud.hpp"

#include "core/grid/cell.hpp"
#include "core/grid/hit_mean.hpp"

namespace dpcr {

std::size_t CountObstacleCells(const TiledGrid& grid, std::int16_t threshold) {
  std::size_t n = 0;
  ForEachCellAbove(grid, threshold, [&](CellIndex, std::int16_t) { ++n; });
  return n;
}

std::size_t CollectObstacleCloud(const TiledGrid& grid, std::int16_t threshold, std::size_t total, Span<Point2> out) {
  if (out.empty() || total == 0) return 0;
  const std::size_t stride = (total + out.size() - 1) / out.size();
  const float res = grid.resolution_m();
  std::size_t seen = 0, n = 0;
  ForEachCellAbove(grid, threshold, [&](CellIndex c, std::int16_t v) {
    if (seen++ % stride != 0 || n == out.size()) return;
    float fx = 0.5f, fy = 0.5f;
    ObstacleOffsetInCell(v, grid.HasHitMean(v), &fx, &fy);  // the hit mean where the cell has one
    out[n++] = Point2{(static_cast<float>(c.x) + fx) * res, (static_cast<float>(c.y) + fy) * res};
  });
  return n;
}

}  // namespace dpcr
