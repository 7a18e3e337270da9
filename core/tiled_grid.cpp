#include "core/tiled_grid.hpp"

#include "core/assert.hpp"
#include "core/cell_line.hpp"

namespace dpcr {
TiledGrid::TiledGrid(TilePool* pool, Span<TileId> index, int tiles_x, int tiles_y)
    : pool_(pool), index_(index), tiles_x_(tiles_x), tiles_y_(tiles_y) {
  DPCR_ASSERT(tiles_x > 0 && tiles_y > 0);
  DPCR_ASSERT(index.size() == static_cast<std::size_t>(tiles_x * tiles_y));
  for (TileId& id : index_) id = kNoTile;
}

void TiledGrid::Reset(CellIndex origin_tile) {
  for (TileId& id : index_) {
    if (id != kNoTile && pool_ != nullptr) pool_->Free(id);
    id = kNoTile;
  }
  allocated_tiles_ = 0;
  origin_tile_ = origin_tile;
}

CellBox TiledGrid::box() const {
  return CellBox{CellIndex{origin_tile_.x * kTileSide, origin_tile_.y * kTileSide},
                 CellIndex{(origin_tile_.x + tiles_x_) * kTileSide, (origin_tile_.y + tiles_y_) * kTileSide}};
}

int TiledGrid::SlotOf(CellIndex c, int* offset) const {
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

std::int16_t TiledGrid::Get(CellIndex c) const {
  int offset = 0;
  const int slot = SlotOf(c, &offset);
  if (slot < 0) return kUnknownCell;
  const TileId id = index_[static_cast<std::size_t>(slot)];
  return id == kNoTile ? kUnknownCell : (*pool_)[id].cells[offset];
}

bool TiledGrid::HasTile(CellIndex c) const {
  int offset = 0;
  const int slot = SlotOf(c, &offset);
  return slot >= 0 && index_[static_cast<std::size_t>(slot)] != kNoTile;
}

Tile* TiledGrid::TileForWrite(int slot) {
  DPCR_ASSERT(pool_ != nullptr);
  TileId& id = index_[static_cast<std::size_t>(slot)];
  if (id == kNoTile) {
    id = pool_->Allocate();
    if (id == kNoTile) return nullptr;
    ++allocated_tiles_;
  }
  return &(*pool_)[id];
}

namespace {

// Marks `offset` as updated in scan `stamp`; false if it already was.
bool MarkOnce(Tile* tile, int offset, std::uint32_t stamp) {
  if (tile->stamp != stamp) {
    for (std::uint32_t& word : tile->updated) word = 0;
    tile->stamp = stamp;
  }
  std::uint32_t& word = tile->updated[offset >> 5];
  const std::uint32_t bit = 1u << (offset & 31);
  if ((word & bit) != 0) return false;
  word |= bit;
  return true;
}

// Adds a log-odds delta, clamped; an unknown cell starts from 0 (p = 0.5). With `settle`, a
// cell already at a bound stays there.
void ApplyDelta(std::int16_t* cell, std::int16_t delta, std::int16_t lo, std::int16_t hi, bool settle) {
  if (settle && (*cell == lo || *cell == hi)) return;
  int v = (*cell == kUnknownCell ? 0 : *cell) + delta;
  v = v < lo ? lo : v;
  v = v > hi ? hi : v;
  *cell = static_cast<std::int16_t>(v);
}

}  // namespace

bool TiledGrid::Reserve(CellIndex c, std::uint32_t stamp) {
  int offset = 0;
  const int slot = SlotOf(c, &offset);
  if (slot < 0) return false;
  Tile* tile = TileForWrite(slot);
  return tile != nullptr && MarkOnce(tile, offset, stamp);
}

namespace {

// ApplyDelta with the settle rule fixed at compile time (the hot loop below).
template <bool kSettle>
void ApplyDeltaTo(std::int16_t* cell, std::int32_t delta, std::int32_t lo, std::int32_t hi) {
  const std::int32_t old = *cell;
  if (kSettle && (old == lo || old == hi)) return;
  std::int32_t v = (old == kUnknownCell ? 0 : old) + delta;
  v = v < lo ? lo : v;
  v = v > hi ? hi : v;
  *cell = static_cast<std::int16_t>(v);
}

// Updates one cell (once per scan when kStamped: bit lx of updated[ly] marks it).
template <bool kStamped, bool kSettle>
void UpdateCell(Tile* tile, std::int32_t lx, std::int32_t ly, std::int32_t delta, std::int32_t lo, std::int32_t hi) {
  if (kStamped) {
    const std::uint32_t bit = 1u << lx, word = tile->updated[ly];
    if ((word & bit) != 0) return;
    tile->updated[ly] = word | bit;
  }
  ApplyDeltaTo<kSettle>(&tile->cells[(ly << 5) | lx], delta, lo, hi);
}

// Walks the segment's cells inside one tile from tile-local (lx, ly), at most `left` of them,
// updating each; returns how many it walked. Every step moves along the major axis (kXMajor: x),
// so the run ends after a known number of steps unless the minor axis leaves the tile first,
// which is checked only when it moves. The walk's state lives in locals
// so that the loop keeps it in registers. tile == nullptr (pool full): walk only.
template <bool kXMajor, bool kStamped, bool kSettle>
std::int32_t WalkRun(Tile* tile, BresenhamWalk* walk, std::int32_t* lx_io, std::int32_t* ly_io, std::int32_t left,
                     std::int32_t delta, std::int32_t lo, std::int32_t hi) {
  // BresenhamWalk::Step with e2 = 2 err: x moves when e2 > -dy (err -= dy), y when e2 < dx
  // (err += dx); along the major axis the test always passes.
  const std::int32_t dx = walk->dx, dy = walk->dy;
  const std::int32_t major_s = kXMajor ? walk->sx : walk->sy, minor_s = kXMajor ? walk->sy : walk->sx;
  std::int32_t err = walk->err;
  std::int32_t major = kXMajor ? *lx_io : *ly_io, minor = kXMajor ? *ly_io : *lx_io;
  const std::int32_t to_edge = major_s > 0 ? 32 - major : major + 1;
  const std::int32_t n = left < to_edge ? left : to_edge;
  std::int32_t i = 0;
  while (i < n) {
    if (tile != nullptr) {
      UpdateCell<kStamped, kSettle>(tile, kXMajor ? major : minor, kXMajor ? minor : major, delta, lo, hi);
    }
    ++i;
    const std::int32_t e2 = 2 * err;
    err += kXMajor ? -dy : dx;
    major += major_s;
    if (kXMajor ? e2 < dx : e2 > -dy) {
      err += kXMajor ? dx : -dy;
      minor += minor_s;
      if (static_cast<std::uint32_t>(minor) >= 32u) break;
    }
  }
  walk->err = err;
  *lx_io = kXMajor ? major : minor;
  *ly_io = kXMajor ? minor : major;
  return i;
}

template <bool kStamped, bool kSettle>
std::int32_t WalkRun(Tile* tile, BresenhamWalk* walk, std::int32_t* lx, std::int32_t* ly, std::int32_t left,
                     std::int32_t delta, std::int32_t lo, std::int32_t hi) {
  return walk->dx >= walk->dy ? WalkRun<true, kStamped, kSettle>(tile, walk, lx, ly, left, delta, lo, hi)
                              : WalkRun<false, kStamped, kSettle>(tile, walk, lx, ly, left, delta, lo, hi);
}

}  // namespace

TiledGrid::SegmentStats TiledGrid::UpdateSegment(CellIndex a, CellIndex b, std::int16_t delta, std::int16_t lo,
                                                  std::int16_t hi, std::uint32_t stamp) {
  // TraceCells' Bresenham walk (same cells, same order), cut into runs of cells in one tile: the
  // tile lookup, allocation and stamp check happen once per run, and inside a run the walk moves
  // tile-local coordinates (a row of "updated" bits is one word: bit lx of updated[ly]).
  static_assert(kTileSide == 32, "one 32-bit word of updated bits per tile row");
  SegmentStats st;
  BresenhamWalk walk(a, b);
  // Every Bresenham step moves one cell along the major axis: max(dx, dy) cells, b excluded.
  std::int32_t left = walk.steps();
  CellIndex c = a;
  while (left > 0) {
    const std::int32_t tx = (c.x >> 5) - origin_tile_.x;
    const std::int32_t ty = (c.y >> 5) - origin_tile_.y;
    if (static_cast<std::uint32_t>(tx) >= static_cast<std::uint32_t>(tiles_x_) ||
        static_cast<std::uint32_t>(ty) >= static_cast<std::uint32_t>(tiles_y_)) {
      ++st.out_of_box;  // the box is convex: the ray never comes back
      break;
    }
    Tile* tile = TileForWrite(ty * tiles_x_ + tx);
    if (tile != nullptr && stamp != 0 && tile->stamp != stamp) {
      for (std::uint32_t& word : tile->updated) word = 0;
      tile->stamp = stamp;
    }
    const std::int32_t base_x = c.x - (c.x & 31), base_y = c.y - (c.y & 31);
    std::int32_t lx = c.x & 31, ly = c.y & 31;
    std::int32_t run = 0;
    if (stamp != 0) {
      run = settle_at_bounds_ ? WalkRun<true, true>(tile, &walk, &lx, &ly, left, delta, lo, hi)
                              : WalkRun<true, false>(tile, &walk, &lx, &ly, left, delta, lo, hi);
    } else {
      run = settle_at_bounds_ ? WalkRun<false, true>(tile, &walk, &lx, &ly, left, delta, lo, hi)
                              : WalkRun<false, false>(tile, &walk, &lx, &ly, left, delta, lo, hi);
    }
    left -= run;
    if (tile != nullptr) {
      st.applied += run;
    } else {
      st.dropped_pool_full += run;  // nothing is freed while a scan is inserted: no retry
    }
    c = CellIndex{base_x + lx, base_y + ly};
  }
  return st;
}

Status TiledGrid::Update(CellIndex c, std::int16_t delta, std::int16_t lo, std::int16_t hi,
                         std::uint32_t stamp) {
  int offset = 0;
  const int slot = SlotOf(c, &offset);
  if (slot < 0) return Status::kOutOfBounds;
  Tile* tile = TileForWrite(slot);
  if (tile == nullptr) return Status::kPoolFull;
  // At most one update per cell per scan (stamp 0: no such rule); a repeat is legal and ignored.
  if (stamp == 0 || MarkOnce(tile, offset, stamp)) ApplyDelta(&tile->cells[offset], delta, lo, hi, settle_at_bounds_);
  return Status::kOk;
}

}  // namespace dpcr
