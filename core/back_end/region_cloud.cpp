#include "core/back_end/region_cloud.hpp"

#include "core/grid/cell.hpp"
#include "core/grid/tile_pool.hpp"

namespace dpcr {
namespace {

// Calls visit(cell) for each obstacle cell of the grid, in tile order.
template <typename Visitor>
void ForEachObstacleCell(const TiledGrid& grid, std::int16_t threshold, Visitor&& visit) {
  const CellBox box = grid.box();
  for (int ty = 0; ty < grid.tiles_y(); ++ty) {
    for (int tx = 0; tx < grid.tiles_x(); ++tx) {
      const TileId id = grid.tile_at(tx, ty);
      if (id == kNoTile) continue;
      const std::int16_t* values = grid.pool()[id].cells;
      for (int i = 0; i < kTileCells; ++i) {
        if (values[i] <= threshold) continue;  // kUnknownCell included
        visit(CellIndex{box.min.x + tx * kTileSide + (i % kTileSide), box.min.y + ty * kTileSide + (i / kTileSide)});
      }
    }
  }
}

}  // namespace

std::size_t CountObstacleCells(const TiledGrid& grid, std::int16_t threshold) {
  std::size_t n = 0;
  ForEachObstacleCell(grid, threshold, [&](CellIndex) { ++n; });
  return n;
}

std::size_t CollectObstacleCloud(const TiledGrid& grid, std::int16_t threshold, std::size_t total, Span<Point2> out) {
  if (out.empty() || total == 0) return 0;
  const std::size_t stride = (total + out.size() - 1) / out.size();
  const float res = grid.resolution_m();
  std::size_t seen = 0, n = 0;
  ForEachObstacleCell(grid, threshold, [&](CellIndex c) {
    if (seen++ % stride != 0 || n == out.size()) return;
    out[n++] = Point2{CellCentreX(c, res), CellCentreY(c, res)};
  });
  return n;
}

}  // namespace dpcr
