// An occupancy grid over a bounded box of tiles, each tile drawn from a shared TilePool on
// first write, so unobserved space costs two bytes of index per tile and nothing else.
// The box bounds the index, not the memory. Size-erased: TiledGridStorage<W, H> owns the index.
#pragma once

#include <cstdint>

#include "core/grid/cell.hpp"
#include "core/grid/hit_mean.hpp"
#include "core/base/span.hpp"
#include "core/base/status.hpp"
#include "core/geometry/pose2.hpp"
#include "core/grid/tile_pool.hpp"

namespace dpcr {

// A half-open box of cells [min, max).
struct CellBox {
  CellIndex min;
  CellIndex max;
  bool Contains(CellIndex c) const { return c.x >= min.x && c.y >= min.y && c.x < max.x && c.y < max.y; }
  std::int32_t width() const { return max.x - min.x; }
  std::int32_t height() const { return max.y - min.y; }
};

// A Bresenham segment of cells from `from` towards `to` (`to` excluded).
struct CellSegment {
  CellIndex from;
  CellIndex to;
};

class TiledGrid {
 public:
  // `pool` may be attached later (arrays of grids are built before their pool is known).
  TiledGrid(TilePool* pool, Span<TileId> index, int tiles_x, int tiles_y);
  void Attach(TilePool* pool) { pool_ = pool; }
  TiledGrid(const TiledGrid&) = delete;
  TiledGrid& operator=(const TiledGrid&) = delete;
  ~TiledGrid() { Reset(); }

  // Places the box so that its lower-left tile starts at `origin_tile` (in tile units)
  // and releases every tile held so far.
  void Reset(CellIndex origin_tile = CellIndex{0, 0});

  CellBox box() const;
  float resolution_m() const { return resolution_m_; }
  void set_resolution_m(float r) { resolution_m_ = r; }

  // Settled cells: once a cell reaches either clamp bound of an update, later updates leave it
  // there. A regional map is the reference that re-anchors the robot; if confident walls and
  // free space could still move, scans inserted at slightly drifted poses would drag them along
  // and the map would follow the drift it is meant to remove. Off by default.
  void set_settle_at_bounds(bool on) { settle_at_bounds_ = on; }
  bool settle_at_bounds() const { return settle_at_bounds_; }
  // Settled cells that keep being contradicted learn again: a cell settled at the upper bound
  // (occupied) that `occupied_after` scans in a row update downwards (no scan updating it upwards
  // in between) leaves the bound and learns as any other cell; `free_after` likewise at the lower
  // bound; 0 = settled for good. The count needs no storage: a settled cell with s contrary scans
  // holds hi - s (lo + s), and a learning cell that would come within the count's band of a
  // bound stays just outside it (at most occupied_after / 1024 nat lower; it still settles on the
  // update that takes it over the bound, as without the band). The band stays above the
  // reference thresholds, so a cell under contrary evidence keeps anchoring the robot until it
  // leaves the bound. Needs set_settle_at_bounds(true).
  void set_settle_rule(bool settle, std::uint8_t occupied_after, std::uint8_t free_after) {
    settle_at_bounds_ = settle;
    unsettle_occupied_after_ = occupied_after;
    unsettle_free_after_ = free_after;
  }
  std::uint8_t unsettle_occupied_after() const { return unsettle_occupied_after_; }
  // The lowest value a settled occupied cell holds under upper bound `hi`: the bound itself, or
  // the bottom of the band its count of contrary scans lives in.
  std::int32_t SettledOccupiedFloor(std::int32_t hi) const {
    return hi - (unsettle_occupied_after_ > 1 ? unsettle_occupied_after_ - 1 : 0);
  }
  std::uint8_t unsettle_free_after() const { return unsettle_free_after_; }

  // Hit means (core/grid/hit_mean.hpp): a cell settled at the upper bound `settled` learns where in
  // it the returns fall, in codes above the bound. 0: off. Needs set_settle_at_bounds(true).
  void set_hit_means(std::int16_t settled) { hit_means_settled_ = settled; }
  std::int16_t hit_means_settled() const { return hit_means_settled_; }
  // Whether cell value `v` is a hit-mean code (in a grid without hit means, such as the submap's
  // unclamped sums, values above the base are log-odds).
  bool HasHitMean(std::int16_t v) const { return hit_means_settled_ != 0 && IsHitMeanCode(v); }
  // A cell value as log-odds: a hit-mean code reads as the bound it settled at.
  std::int16_t LogOdds(std::int16_t v) const { return HasHitMean(v) ? hit_means_settled_ : v; }
  // Adds each return (grid frame, metres) to the hit mean of the cell it falls in, if that cell is
  // settled occupied (one that has just settled starts its mean). `seed` (the scan's stamp) and the
  // return's index make the rounding's randomness. Nothing when hit means are off.
  void AddHitMeans(Span<const Point2> hits, std::uint32_t seed);

  // kUnknownCell outside the box or in a tile never written. Inline: insertion screens its hits
  // with it (InsertRays).
  std::int16_t Get(CellIndex c) const {
    int offset = 0;
    const int slot = SlotOf(c, &offset);
    if (slot < 0) return kUnknownCell;
    const TileId id = index_[static_cast<std::size_t>(slot)];
    return id == kNoTile ? kUnknownCell : (*pool_)[id].cells[offset];
  }

  // Adds `delta` clamped to [lo, hi] if the cell was not yet updated in scan `stamp`
  // (stamp 0 = no once-per-scan rule); a settled cell (see set_settle_at_bounds) keeps its value
  // or counts a contrary scan (set_settle_rule).
  // kOutOfBounds outside the box, kPoolFull when the tile
  // cannot be allocated (the update is dropped), kOk otherwise (also when skipped as a repeat).
  Status Update(CellIndex c, std::int16_t delta, std::int16_t lo, std::int16_t hi, std::uint32_t stamp);

  // What UpdateSegment(s) did: updates applied (repeats within the scan included), whether the
  // segment left the box (tracing stops there), updates lost to a full pool. Also UpdateCells'.
  struct SegmentStats {
    int applied = 0;
    int out_of_box = 0;
    int dropped_pool_full = 0;
  };
  // Update(c, delta, lo, hi, stamp) for every cell of the Bresenham segment a -> b (b excluded,
  // the cells of TraceCells in its order), stopping at the first cell outside the box. Same result
  // as the per-cell calls; the tile is looked up once per tile crossed, not once per cell.
  SegmentStats UpdateSegment(CellIndex a, CellIndex b, std::int16_t delta, std::int16_t lo, std::int16_t hi,
                             std::uint32_t stamp);
  // UpdateSegment for each segment in turn, the stats summed. A scan's rays go in batches: the
  // walk (stamp rule, settle rule) is chosen once per batch, not once per ray. With
  // `may_unsettle` false, a settled cell that the update contradicts is left as it is, its count
  // too (weak evidence: the part of a ray just before its return, InsertRays).
  SegmentStats UpdateSegments(Span<const CellSegment> segments, std::int16_t delta, std::int16_t lo, std::int16_t hi,
                              std::uint32_t stamp, bool may_unsettle = true);

  // Update(c, delta, lo, hi, stamp) for each cell (stamp != 0), the stats summed: `applied`
  // counts the cells updated (not the repeats), the others the cells out of the box or lost to a
  // full pool. InsertRays applies a scan's hits so, before its misses.
  SegmentStats UpdateCells(Span<const CellIndex> cells, std::int16_t delta, std::int16_t lo, std::int16_t hi,
                           std::uint32_t stamp);

  int tiles_x() const { return tiles_x_; }
  int tiles_y() const { return tiles_y_; }
  CellIndex origin_tile() const { return origin_tile_; }
  // The tile at box slot (tx, ty), or kNoTile.
  TileId tile_at(int tx, int ty) const { return index_[static_cast<std::size_t>(ty * tiles_x_ + tx)]; }
  std::size_t allocated_tiles() const { return static_cast<std::size_t>(allocated_tiles_); }
  // Loading a saved map (core/persistence): takes a tile from the pool for box slot (tx, ty) and
  // returns its cells (all unknown) to fill; empty when the slot is outside the box or already
  // holds a tile, or the pool is exhausted.
  Span<std::int16_t> RestoreTile(int tx, int ty);
  const TilePool& pool() const { return *pool_; }
  TilePool& pool() { return *pool_; }

  // One update's delta, bounds and settle rule, prepared once per batch (tiled_grid.cpp).
  struct Learning;

 private:
  // The tile slot of a cell, -1 outside the box; `offset` gets the cell's place in its tile.
  int SlotOf(CellIndex c, int* offset) const {
    // Tiles are 32 cells: an arithmetic shift is the floor division (GCC and Clang shift signed
    // integers arithmetically), and this is the hottest line of ray casting.
    static_assert(kTileSide == 32, "shift and mask below assume 32-cell tiles");
    const std::int32_t tx = (c.x >> 5) - origin_tile_.x;
    const std::int32_t ty = (c.y >> 5) - origin_tile_.y;
    if (static_cast<std::uint32_t>(tx) >= static_cast<std::uint32_t>(tiles_x_) ||
        static_cast<std::uint32_t>(ty) >= static_cast<std::uint32_t>(tiles_y_)) {
      return -1;
    }
    *offset = ((c.y & 31) << 5) | (c.x & 31);
    return ty * tiles_x_ + tx;
  }
  Tile* TileForWrite(int slot);
  Learning LearningOf(std::int16_t delta, std::int16_t lo, std::int16_t hi, bool may_unsettle = true) const;
  // UpdateSegments with the stamp and settle rules fixed at compile time, and one segment with
  // its major axis (x when kXMajor) and that axis's direction (kMajorS, +-1) fixed too;
  // tiled_grid.cpp.
  template <bool kStamped, bool kSettle>
  SegmentStats WalkSegments(Span<const CellSegment> segments, const Learning& l, std::uint32_t stamp);
  template <bool kXMajor, int kMajorS, bool kStamped, bool kSettle>
  void WalkSegment(CellSegment s, const Learning& l, std::uint32_t stamp, SegmentStats* st);
  // A segment whose ends lie in one tile: one run, no tile edge to watch.
  template <bool kXMajor, int kMajorS, bool kStamped, bool kSettle>
  void WalkInOneTile(CellSegment s, const Learning& l, std::uint32_t stamp, SegmentStats* st);

  TilePool* pool_;
  Span<TileId> index_;
  int tiles_x_;
  int tiles_y_;
  CellIndex origin_tile_;
  float resolution_m_ = 0.05f;
  bool settle_at_bounds_ = false;
  std::uint8_t unsettle_occupied_after_ = 0;
  std::uint8_t unsettle_free_after_ = 0;
  std::int16_t hit_means_settled_ = 0;
  std::int32_t allocated_tiles_ = 0;  // int32, not size_t: the grid's fields fit where they did
};

// Calls visit(cells, corner) for each tile the grid holds: its kTileSide x kTileSide cells
// (row-major) and the grid-frame index of its lower-left cell. Unobserved tiles cost nothing.
template <typename Visitor>
void ForEachTile(const TiledGrid& grid, Visitor&& visit) {
  for (int ty = 0; ty < grid.tiles_y(); ++ty) {
    for (int tx = 0; tx < grid.tiles_x(); ++tx) {
      const TileId id = grid.tile_at(tx, ty);
      if (id == kNoTile) continue;
      visit(static_cast<const std::int16_t*>(grid.pool()[id].cells),
            CellIndex{(grid.origin_tile().x + tx) * kTileSide, (grid.origin_tile().y + ty) * kTileSide});
    }
  }
}

// Calls visit(cell, value) for each cell above `threshold` (kUnknownCell is below any), in tile order.
template <typename Visitor>
void ForEachCellAbove(const TiledGrid& grid, std::int16_t threshold, Visitor&& visit) {
  ForEachTile(grid, [&](const std::int16_t* cells, CellIndex corner) {
    for (int i = 0; i < kTileCells; ++i) {
      if (cells[i] > threshold) visit(CellIndex{corner.x + (i % kTileSide), corner.y + (i / kTileSide)}, cells[i]);
    }
  });
}

template <int kTilesX, int kTilesY>
class TiledGridStorage : public TiledGrid {
 public:
  explicit TiledGridStorage(TilePool* pool = nullptr)
      : TiledGrid(pool, Span<TileId>(index_storage_, kTilesX * kTilesY), kTilesX, kTilesY) {}

 private:
  TileId index_storage_[kTilesX * kTilesY];
};

}  // namespace dpcr
