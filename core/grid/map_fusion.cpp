#include "core/grid/map_fusion.hpp"

#include <algorithm>

namespace dpcr {
namespace {

template <typename Visitor>
void ForEachAllocatedTile(const TiledGrid& grid, Visitor&& visit) {
  for (int ty = 0; ty < grid.tiles_y(); ++ty) {
    for (int tx = 0; tx < grid.tiles_x(); ++tx) {
      const TileId id = grid.tile_at(tx, ty);
      if (id != kNoTile) visit(id, CellIndex{(grid.origin_tile().x + tx) * kTileSide, (grid.origin_tile().y + ty) * kTileSide});
    }
  }
}

}  // namespace

CellBox FusedBounds(Span<const PlacedGrid> grids, float res) {
  bool any = false;
  CellBox box;
  for (const PlacedGrid& g : grids) {
    ForEachAllocatedTile(*g.grid, [&](TileId, CellIndex corner) {
      for (int k = 0; k < 4; ++k) {
        const float lx = static_cast<float>(corner.x + ((k & 1) != 0 ? kTileSide : 0)) * res;
        const float ly = static_cast<float>(corner.y + ((k & 2) != 0 ? kTileSide : 0)) * res;
        const Point2 w = g.anchor.Apply(Point2{lx, ly});
        const CellIndex c = CellOf(w.x, w.y, res);
        if (!any) {
          box.min = c;
          box.max = CellIndex{c.x + 1, c.y + 1};
          any = true;
        }
        box.min.x = std::min(box.min.x, c.x);
        box.min.y = std::min(box.min.y, c.y);
        box.max.x = std::max(box.max.x, c.x + 1);
        box.max.y = std::max(box.max.y, c.y + 1);
      }
    });
  }
  return box;
}

Status FuseInto(Span<const PlacedGrid> grids, CellBox box, float res, std::int16_t clamp_min,
                std::int16_t clamp_max, Span<std::int16_t> out) {
  if (box.width() <= 0 || box.height() <= 0) return Status::kInvalidArgument;
  const std::size_t w = static_cast<std::size_t>(box.width());
  if (out.size() < w * static_cast<std::size_t>(box.height())) return Status::kInvalidArgument;
  for (std::int16_t& v : out) v = kUnknownCell;
  for (const PlacedGrid& g : grids) {
    const TilePool& pool = g.grid->pool();
    ForEachAllocatedTile(*g.grid, [&](TileId id, CellIndex corner) {
      const Tile& tile = pool[id];
      for (int ly = 0; ly < kTileSide; ++ly) {
        for (int lx = 0; lx < kTileSide; ++lx) {
          const std::int16_t v = tile.cells[ly * kTileSide + lx];
          if (v == kUnknownCell) continue;
          // Forward mapping of cell centres: exact for anchors on the grid without rotation.
          const CellIndex local{corner.x + lx, corner.y + ly};
          const Point2 p = g.anchor.Apply(Point2{CellCentreX(local, res), CellCentreY(local, res)});
          const CellIndex c = CellOf(p.x, p.y, res);
          if (!box.Contains(c)) continue;
          std::int16_t& o = out[static_cast<std::size_t>(c.y - box.min.y) * w + static_cast<std::size_t>(c.x - box.min.x)];
          const int sum = (o == kUnknownCell ? 0 : o) + v;
          o = static_cast<std::int16_t>(std::clamp(sum, static_cast<int>(clamp_min), static_cast<int>(clamp_max)));
        }
      }
    });
  }
  return Status::kOk;
}

}  // namespace dpcr
