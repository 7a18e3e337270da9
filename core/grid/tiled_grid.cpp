#include "core/grid/tiled_grid.hpp"

#include <cstddef>
#include <type_traits>

#include "core/base/assert.hpp"

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

Tile* TiledGrid::TileForWrite(int slot) {
  TileId& id = index_[static_cast<std::size_t>(slot)];
  if (id == kNoTile) {
    // Checked here, not per call: every tile of a grid comes from its pool, so a grid without
    // one holds none and any write gets here first.
    DPCR_ASSERT(pool_ != nullptr);
    id = pool_->Allocate();
    if (id == kNoTile) return nullptr;
    ++allocated_tiles_;
  }
  return &(*pool_)[id];
}

Span<std::int16_t> TiledGrid::RestoreTile(int tx, int ty) {
  if (pool_ == nullptr || tx < 0 || ty < 0 || tx >= tiles_x_ || ty >= tiles_y_) return Span<std::int16_t>();
  const int slot = ty * tiles_x_ + tx;
  if (index_[static_cast<std::size_t>(slot)] != kNoTile) return Span<std::int16_t>();
  Tile* tile = TileForWrite(slot);
  return tile == nullptr ? Span<std::int16_t>() : Span<std::int16_t>(tile->cells, kTileCells);
}

namespace {

// The tile's "updated" bits belong to the scan `stamp`: cleared when it is a new one.
inline void ClaimForScan(Tile* tile, std::uint32_t stamp) {
  if (tile->stamp != stamp) {
    for (std::uint32_t& word : tile->updated) word = 0;
    tile->stamp = stamp;
  }
}

// Marks `offset` as updated in the scan the tile is claimed for; false if it already was.
inline bool MarkClaimed(Tile* tile, int offset) {
  std::uint32_t& word = tile->updated[offset >> 5];
  const std::uint32_t bit = 1u << (offset & 31);
  if ((word & bit) != 0) return false;
  word |= bit;
  return true;
}

// Marks `offset` as updated in scan `stamp`; false if it already was.
bool MarkOnce(Tile* tile, int offset, std::uint32_t stamp) {
  ClaimForScan(tile, stamp);
  return MarkClaimed(tile, offset);
}

}  // namespace

// An update's delta and bounds with the grid's settle rule, prepared once per batch.
struct TiledGrid::Learning {
  std::int32_t delta;
  std::int32_t lo;
  std::int32_t hi;
  // The settled bands, [lo, lo_top] and [hi_bottom, hi] (a bound alone when its count is 0 or 1),
  // and the counts of contrary scans that unsettle (0: never).
  std::int32_t lo_top;
  std::int32_t hi_bottom;
  std::int32_t free_after;
  std::int32_t occupied_after;
  // Cells holding either value are left as they are: settled, and this update agrees with the
  // bound or cannot unsettle it. The walk's first test (most visits of a regional map end there).
  std::int32_t quiet_a;
  std::int32_t quiet_b;
  // Values above it are left as they are too: hit-mean codes, unless this update may count
  // against them (INT32_MAX then, or when the grid holds no codes).
  std::int32_t quiet_code;
};

TiledGrid::Learning TiledGrid::LearningOf(std::int16_t delta, std::int16_t lo, std::int16_t hi, bool may_unsettle) const {
  Learning l{};
  l.delta = delta;
  l.lo = lo;
  l.hi = hi;
  l.hi_bottom = SettledOccupiedFloor(hi);
  l.lo_top = lo + (unsettle_free_after_ > 1 ? unsettle_free_after_ - 1 : 0);
  // Weak evidence: the bands as they are, but no count moves.
  l.occupied_after = may_unsettle ? unsettle_occupied_after_ : 0;
  l.free_after = may_unsettle ? unsettle_free_after_ : 0;
  const bool up = delta >= 0;
  l.quiet_a = up ? hi : lo;
  const std::int32_t contrary_after = up ? l.free_after : l.occupied_after;
  l.quiet_b = contrary_after == 0 ? (up ? lo : hi) : l.quiet_a;
  l.quiet_code = hit_means_settled_ != 0 && (up || l.occupied_after == 0) ? hi : INT32_MAX;
  return l;
}

namespace {

// A learning cell's new value: settled at a bound it reaches (the clamp), kept out of the bands
// otherwise (a value there would read as settled). Moved towards 0, out of the band: the cell
// settles on the same update as it would without the bands (the next hit takes a value that
// close to the bound over it), so settling keeps its pace.
inline std::int32_t Learnt(std::int32_t v, const TiledGrid::Learning& l) {
  if (v >= l.hi) return l.hi;
  if (v <= l.lo) return l.lo;
  if (v >= l.hi_bottom) return l.hi_bottom - 1;
  if (v <= l.lo_top) return l.lo_top + 1;
  return v;
}

// The settle rule (TiledGrid::set_settle_rule): a settled cell holds its bound minus (plus) the
// contrary scans counted; an agreeing update restarts the count, the last contrary one makes the
// cell learn again from the band's edge.
inline std::int32_t SettledValue(std::int32_t old, const TiledGrid::Learning& l) {
  if (old != kUnknownCell) {
    // Above hi: a hit mean, a cell settled at hi. It keeps its code, unless a contrary scan
    // starts its count (the mean is dropped then).
    if (old > l.hi) {
      if (l.delta >= 0 || l.occupied_after == 0) return old;
      old = l.hi;
    }
    if (old >= l.hi_bottom) {
      if (l.delta >= 0) return l.hi;
      if (l.occupied_after == 0) return old;
      if (l.hi - old + 1 < l.occupied_after) return old - 1;
      return Learnt(l.hi_bottom - 1 + l.delta, l);
    }
    if (old <= l.lo_top) {
      if (l.delta <= 0) return l.lo;
      if (l.free_after == 0) return old;
      if (old - l.lo + 1 < l.free_after) return old + 1;
      return Learnt(l.lo_top + 1 + l.delta, l);
    }
  }
  return Learnt((old == kUnknownCell ? 0 : old) + l.delta, l);
}

// Adds a log-odds delta, clamped; an unknown cell starts from 0 (p = 0.5). With `settle`, the
// settle rule.
void ApplyDelta(std::int16_t* cell, const TiledGrid::Learning& l, bool settle) {
  std::int32_t v;
  if (settle) {
    v = SettledValue(*cell, l);
  } else {
    v = (*cell == kUnknownCell ? 0 : *cell) + l.delta;
    v = v < l.lo ? l.lo : v;
    v = v > l.hi ? l.hi : v;
  }
  *cell = static_cast<std::int16_t>(v);
}


// Updates cell `i` of a tile (row-major, 32 cells a row), once per scan when kStamped: bit i & 31
// of updated[i >> 5] marks it. A quiet settled cell is tested first and left unmarked: nothing in
// this scan can change it, so a later visit that finds it unmarked skips it all the same (on the
// regional maps most visits end here). A settled cell that this update contradicts is marked: it
// counts one contrary scan, not one per ray.
template <bool kStamped, bool kSettle>
inline void UpdateCell(Tile* tile, std::ptrdiff_t i, const TiledGrid::Learning& l) {
  std::int16_t* cell = &tile->cells[i];
  const std::int32_t old = *cell;
  if (kSettle && (old == l.quiet_a || old == l.quiet_b || old > l.quiet_code)) return;
  if (kStamped) {
    const std::uint32_t bit = 1u << (i & 31), word = tile->updated[i >> 5];
    if ((word & bit) != 0) return;
    tile->updated[i >> 5] = word | bit;
  }
  std::int32_t v;
  if (kSettle) {
    v = SettledValue(old, l);
  } else {
    v = (old == kUnknownCell ? 0 : old) + l.delta;
    v = v < l.lo ? l.lo : v;
    v = v > l.hi ? l.hi : v;
  }
  *cell = static_cast<std::int16_t>(v);
}

}  // namespace

// A segment with both ends in one tile (most of a submap's): its cells lie in the box of its
// ends, so it is one run of cells in that tile, and the minor axis needs no test against the
// tile's edge. WalkSegment's Bresenham steps.
template <bool kXMajor, int kMajorS, bool kStamped, bool kSettle>
__attribute__((always_inline)) inline void TiledGrid::WalkInOneTile(CellSegment s, const Learning& l,
                                                                    std::uint32_t stamp, SegmentStats* st) {
  const CellIndex a = s.from, b = s.to;
  const std::int32_t dx = b.x >= a.x ? b.x - a.x : a.x - b.x, dy = b.y >= a.y ? b.y - a.y : a.y - b.y;
  const std::int32_t major_n = kXMajor ? dx : dy, minor_n = kXMajor ? dy : dx;
  if (major_n == 0) return;  // b excluded: no cell
  const std::int32_t tx = (a.x >> 5) - origin_tile_.x, ty = (a.y >> 5) - origin_tile_.y;
  if (static_cast<std::uint32_t>(tx) >= static_cast<std::uint32_t>(tiles_x_) ||
      static_cast<std::uint32_t>(ty) >= static_cast<std::uint32_t>(tiles_y_)) {
    ++st->out_of_box;
    return;
  }
  Tile* tile = TileForWrite(ty * tiles_x_ + tx);
  if (tile == nullptr) {
    st->dropped_pool_full += major_n;
    return;
  }
  if (kStamped) ClaimForScan(tile, stamp);
  const std::int32_t minor_s = kXMajor ? (b.y >= a.y ? 1 : -1) : (b.x >= a.x ? 1 : -1);
  const std::int32_t major_step = kXMajor ? kMajorS : 32 * kMajorS, minor_step = kXMajor ? 32 * minor_s : minor_s;
  const std::int32_t two_major = 2 * major_n, two_minor = 2 * minor_n;
  std::int32_t g = two_minor - major_n;
  std::ptrdiff_t cell = ((a.y & 31) << 5) | (a.x & 31);
  std::int32_t k = major_n;
  do {
    UpdateCell<kStamped, kSettle>(tile, cell, l);
    cell += major_step;
    if (g > 0) {
      g += two_minor - two_major;
      cell += minor_step;
    } else {
      g += two_minor;
    }
  } while (--k != 0);
  st->applied += major_n;
}

// TraceCells' Bresenham walk (same cells, same order), cut into runs of cells in one tile: the
// tile lookup, allocation and stamp check happen once per run, and inside a run the walk moves
// the cell's index in the tile (+-1 along x, +-32 along y), which also names its "updated" bit.
// BresenhamWalk::Step always moves the major axis (x when kXMajor: dx >= dy) and moves the
// minor one when its error term says so. Here the error is kept as in the classic integer line:
// g = 2 * minor extent - major extent at the start (g = dx - 2 err when x is major, 2 err + dy
// when y is); the minor axis moves when g > 0 (then g -= 2 * major extent), and g += 2 * minor
// extent at every step. So a run is a counted loop to the tile edge along the major axis, and
// the minor axis is tested against the tile only when it moves. From run to run the walk keeps
// its place in tile terms (the tile's slot coordinates, the index in it, the steps to the tile's
// edge on each axis): the next run starts in the neighbouring tile with no set-up from global
// cells (a ray crosses a tile every ~25 cells).
// Always inlined into the batch's loop (GCC would call it otherwise, and reload the batch's
// state per segment).
template <bool kXMajor, int kMajorS, bool kStamped, bool kSettle>
__attribute__((always_inline)) inline void TiledGrid::WalkSegment(CellSegment s, const Learning& l,
                                                                  std::uint32_t stamp, SegmentStats* st) {
  static_assert(kTileSide == 32, "one 32-bit word of updated bits per tile row");
  if (((static_cast<std::uint32_t>(s.from.x ^ s.to.x) | static_cast<std::uint32_t>(s.from.y ^ s.to.y)) >> 5) == 0) {
    WalkInOneTile<kXMajor, kMajorS, kStamped, kSettle>(s, l, stamp, st);
    return;
  }
  const CellIndex a = s.from, b = s.to;  // in different tiles: at least one step
  const std::int32_t dx = b.x >= a.x ? b.x - a.x : a.x - b.x, dy = b.y >= a.y ? b.y - a.y : a.y - b.y;
  const std::int32_t major_n = kXMajor ? dx : dy, minor_n = kXMajor ? dy : dx;
  // The major axis's direction (kMajorS) is a template argument: one register less in the run.
  const std::int32_t major_s = kMajorS;
  const std::int32_t minor_s = kXMajor ? (b.y >= a.y ? 1 : -1) : (b.x >= a.x ? 1 : -1);
  std::int32_t g = 2 * minor_n - major_n, left = major_n;  // every step moves the major axis; b excluded
  const std::int32_t two_major = 2 * major_n, two_minor = 2 * minor_n;
  // A step's move of the index in a tile: 1 along x, 32 along y.
  const std::int32_t major_step = kXMajor ? major_s : 32 * major_s, minor_step = kXMajor ? 32 * minor_s : minor_s;
  // The walk's place: its tile's slot coordinates, `cell` its index in the tile, the major axis's
  // steps to the tile's edge (n >= 1) and the minor axis's moves left in the tile.
  std::int32_t tx = (a.x >> 5) - origin_tile_.x, ty = (a.y >> 5) - origin_tile_.y;
  std::int32_t &major_tile = kXMajor ? tx : ty, &minor_tile = kXMajor ? ty : tx;
  const std::int32_t start = (kXMajor ? a.x : a.y) & 31, lminor = (kXMajor ? a.y : a.x) & 31;
  std::ptrdiff_t cell = ((a.y & 31) << 5) | (a.x & 31);
  std::int32_t to_edge = major_s > 0 ? 32 - start : start + 1;
  std::int32_t room = minor_s > 0 ? 31 - lminor : lminor;
  for (;;) {
    if (static_cast<std::uint32_t>(tx) >= static_cast<std::uint32_t>(tiles_x_) ||
        static_cast<std::uint32_t>(ty) >= static_cast<std::uint32_t>(tiles_y_)) {
      ++st->out_of_box;  // the box is convex: the ray never comes back
      return;
    }
    Tile* tile = TileForWrite(ty * tiles_x_ + tx);
    if (kStamped && tile != nullptr) ClaimForScan(tile, stamp);
    // The run ends at the tile edge along the major axis or when the minor axis has used up its
    // `room`. Compiled with and without a tile (pool full: cells only counted): no test per cell.
    const std::int32_t n = left < to_edge ? left : to_edge;
    const auto run = [&](auto has_tile) {
      std::int32_t k = n;
      do {
        if (decltype(has_tile)::value) UpdateCell<kStamped, kSettle>(tile, cell, l);
        cell += major_step;
        if (g > 0) {
          g += two_minor - two_major;
          cell += minor_step;
          if (--room < 0) {
            --k;
            break;
          }
        } else {
          g += two_minor;
        }
      } while (--k != 0);
      return k;
    };
    const std::int32_t k = tile != nullptr ? run(std::true_type{}) : run(std::false_type{});
    const std::int32_t walked = n - k;
    left -= walked;
    // A full pool frees nothing while a scan is inserted: no retry.
    (tile != nullptr ? st->applied : st->dropped_pool_full) += walked;
    if (left == 0) return;
    // Into the next tile along the axis (or both) that left this one: the index wraps on that axis.
    if (room < 0) {
      minor_tile += minor_s;
      cell -= 32 * minor_step;
      room = 31;
    }
    to_edge -= walked;
    if (to_edge == 0) {
      major_tile += major_s;
      cell -= 32 * major_step;
      to_edge = 32;
    }
  }
}

template <bool kStamped, bool kSettle>
TiledGrid::SegmentStats TiledGrid::WalkSegments(Span<const CellSegment> segments, const Learning& learning,
                                                std::uint32_t stamp) {
  // A local copy: the walk's stores to a tile's updated bits (uint32) could alias the caller's
  // int32 fields, and would make the compiler reload them for every cell.
  const Learning l = learning;
  SegmentStats st;
  for (const CellSegment& s : segments) {
    const std::int32_t dx = s.to.x >= s.from.x ? s.to.x - s.from.x : s.from.x - s.to.x;
    const std::int32_t dy = s.to.y >= s.from.y ? s.to.y - s.from.y : s.from.y - s.to.y;
    if (dx >= dy) {
      if (s.to.x >= s.from.x) {
        WalkSegment<true, 1, kStamped, kSettle>(s, l, stamp, &st);
      } else {
        WalkSegment<true, -1, kStamped, kSettle>(s, l, stamp, &st);
      }
    } else if (s.to.y >= s.from.y) {
      WalkSegment<false, 1, kStamped, kSettle>(s, l, stamp, &st);
    } else {
      WalkSegment<false, -1, kStamped, kSettle>(s, l, stamp, &st);
    }
  }
  return st;
}

TiledGrid::SegmentStats TiledGrid::UpdateSegments(Span<const CellSegment> segments, std::int16_t delta, std::int16_t lo,
                                                   std::int16_t hi, std::uint32_t stamp, bool may_unsettle) {
  // The stamp and settle rules are fixed for the batch: the walk is chosen once.
  const Learning l = LearningOf(delta, lo, hi, may_unsettle);
  if (stamp != 0) {
    return settle_at_bounds_ ? WalkSegments<true, true>(segments, l, stamp) : WalkSegments<true, false>(segments, l, stamp);
  }
  return settle_at_bounds_ ? WalkSegments<false, true>(segments, l, stamp) : WalkSegments<false, false>(segments, l, stamp);
}

TiledGrid::SegmentStats TiledGrid::UpdateSegment(CellIndex a, CellIndex b, std::int16_t delta, std::int16_t lo,
                                                  std::int16_t hi, std::uint32_t stamp) {
  const CellSegment s{a, b};
  return UpdateSegments(Span<const CellSegment>(&s, 1), delta, lo, hi, stamp);
}

TiledGrid::SegmentStats TiledGrid::UpdateCells(Span<const CellIndex> cells, std::int16_t delta, std::int16_t lo,
                                               std::int16_t hi, std::uint32_t stamp) {
  // Update() per cell, with its lookups inlined and repeats not counted.
  DPCR_ASSERT(stamp != 0);
  const Learning l = LearningOf(delta, lo, hi);
  SegmentStats st;
  // A scan's hits come in beam order, mostly several to a tile: the last tile is kept.
  int last_slot = -1;
  Tile* tile = nullptr;
  for (const CellIndex c : cells) {
    int offset = 0;
    const int slot = SlotOf(c, &offset);
    if (slot < 0) {
      ++st.out_of_box;
      continue;
    }
    if (slot != last_slot) {
      tile = TileForWrite(slot);
      last_slot = tile != nullptr ? slot : -1;  // a full pool is asked again, as before
      if (tile != nullptr) ClaimForScan(tile, stamp);  // once per tile looked up, not per hit
    }
    if (tile == nullptr) {
      ++st.dropped_pool_full;
    } else if (MarkClaimed(tile, offset)) {
      ApplyDelta(&tile->cells[offset], l, settle_at_bounds_);
      ++st.applied;
    }
  }
  return st;
}

void TiledGrid::AddHitMeans(Span<const Point2> hits, std::uint32_t seed) {
  if (hit_means_settled_ == 0 || !settle_at_bounds_) return;
  const float inv_res = 1.0f / resolution_m_;
  std::uint32_t index = 0;
  for (const Point2& p : hits) {
    ++index;
    // Times the inverse, not divided as the ray caster's CellOf: the rare return within a rounding
    // error of a cell's edge may count for the neighbour's mean, at that edge.
    const float gx = p.x * inv_res, gy = p.y * inv_res;
    const CellIndex c{FloorToInt(gx), FloorToInt(gy)};
    int offset = 0;
    const int slot = SlotOf(c, &offset);
    if (slot < 0) continue;
    const TileId id = index_[static_cast<std::size_t>(slot)];
    if (id == kNoTile) continue;
    std::int16_t& v = (*pool_)[id].cells[offset];
    const float fx = gx - static_cast<float>(c.x), fy = gy - static_cast<float>(c.y);
    if (v == hit_means_settled_) {
      v = EncodeHitMean(StartHitMean(fx, fy));
    } else if (IsHitMeanCode(v)) {
      v = EncodeHitMean(UpdateHitMean(DecodeHitMean(v), fx, fy, HitMeanHash(seed * 0x9e3779b9U ^ index)));
    }
  }
}

Status TiledGrid::Update(CellIndex c, std::int16_t delta, std::int16_t lo, std::int16_t hi,
                         std::uint32_t stamp) {
  int offset = 0;
  const int slot = SlotOf(c, &offset);
  if (slot < 0) return Status::kOutOfBounds;
  Tile* tile = TileForWrite(slot);
  if (tile == nullptr) return Status::kPoolFull;
  // At most one update per cell per scan (stamp 0: no such rule); a repeat is legal and ignored.
  if (stamp == 0 || MarkOnce(tile, offset, stamp)) ApplyDelta(&tile->cells[offset], LearningOf(delta, lo, hi), settle_at_bounds_);
  return Status::kOk;
}

}  // namespace dpcr
