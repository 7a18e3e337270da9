#include "core/grid/map_fusion.hpp"

#include <algorithm>
#include <cmath>

namespace dpcr {
namespace {

// An anchor without rotation, a whole number of cells from the origin: cells map one to one.
bool OnLattice(const Pose2& anchor, float res) {
  const float fx = anchor.x / res, fy = anchor.y / res;
  return anchor.theta == 0.0f && std::fabs(fx - std::round(fx)) < 1e-3f && std::fabs(fy - std::round(fy)) < 1e-3f;
}

// Forward mapping of cell centres: exact on the lattice.
template <typename Add>
void FuseOnLattice(const PlacedGrid& g, CellBox box, float res, Add&& add) {
  ForEachTile(*g.grid, [&](const std::int16_t* cells, CellIndex corner) {
    for (int ly = 0; ly < kTileSide; ++ly) {
      for (int lx = 0; lx < kTileSide; ++lx) {
        const std::int16_t v = cells[ly * kTileSide + lx];
        if (v == kUnknownCell) continue;
        const CellIndex local{corner.x + lx, corner.y + ly};
        const Point2 p = g.anchor.Apply(Point2{CellCentreX(local, res), CellCentreY(local, res)});
        const CellIndex c = CellOf(p.x, p.y, res);
        if (box.Contains(c)) add(c, v);
      }
    }
  });
}

// A moved or rotated anchor: each world cell of the grid's footprint takes the grid cell under
// its centre (inverse mapping: no holes, no cell counted twice, as forward mapping would leave).
template <typename Add>
void FuseResampled(const PlacedGrid& g, CellBox box, float res, Add&& add) {
  const PlacedGrid one[1] = {g};
  CellBox footprint = FusedBounds(Span<const PlacedGrid>(one, 1), res);
  footprint.min.x = std::max(footprint.min.x, box.min.x);
  footprint.min.y = std::max(footprint.min.y, box.min.y);
  footprint.max.x = std::min(footprint.max.x, box.max.x);
  footprint.max.y = std::min(footprint.max.y, box.max.y);
  const PointTransform to_local(g.anchor.Inverse());
  for (std::int32_t y = footprint.min.y; y < footprint.max.y; ++y) {
    for (std::int32_t x = footprint.min.x; x < footprint.max.x; ++x) {
      const CellIndex c{x, y};
      const Point2 p = to_local(Point2{CellCentreX(c, res), CellCentreY(c, res)});
      const std::int16_t v = g.grid->Get(CellOf(p.x, p.y, res));
      if (v != kUnknownCell) add(c, v);
    }
  }
}

}  // namespace

CellBox FusedBounds(Span<const PlacedGrid> grids, float res) {
  bool any = false;
  CellBox box;
  for (const PlacedGrid& g : grids) {
    ForEachTile(*g.grid, [&](const std::int16_t*, CellIndex corner) {
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
  const auto add = [&](CellIndex c, std::int16_t v) {
    std::int16_t& o = out[static_cast<std::size_t>(c.y - box.min.y) * w + static_cast<std::size_t>(c.x - box.min.x)];
    const int sum = (o == kUnknownCell ? 0 : o) + v;
    o = static_cast<std::int16_t>(std::clamp(sum, static_cast<int>(clamp_min), static_cast<int>(clamp_max)));
  };
  for (const PlacedGrid& g : grids) {
    const auto add_log_odds = [&](CellIndex c, std::int16_t v) { add(c, g.grid->LogOdds(v)); };  // hit means too
    if (OnLattice(g.anchor, res)) {
      FuseOnLattice(g, box, res, add_log_odds);
    } else {
      FuseResampled(g, box, res, add_log_odds);
    }
  }
  return Status::kOk;
}

}  // namespace dpcr
