// The shared store of 32x32 cell tiles that every tiled grid draws from on first write.
// Overflow policy: Allocate on an empty free list returns kNoTile; the caller counts the
// dropped update and reports kPoolFull. Nothing is evicted.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/capacity.hpp"
#include "core/grid/cell.hpp"
#include "core/base/span.hpp"

namespace dpcr {

using TileId = std::uint16_t;
constexpr TileId kNoTile = 0xFFFF;
constexpr TileId kTileInUse = 0xFFFE;  // next_free of an allocated tile

struct Tile {
  std::int16_t cells[kTileCells];
  // "Updated in scan `stamp`" bits, one per cell: at most one update per cell per scan.
  // Valid only while stamp equals the current scan's stamp (lazy reset, no per-scan sweep).
  std::uint32_t stamp;
  std::uint32_t updated[kTileCells / 32];
  TileId next_free;
};

// Size-erased pool over caller-owned tiles (TilePoolStorage<N> owns them). Freed tiles are
// reused first (last freed, first reused); then the never-used ones in index order. Those are
// not touched before their first allocation: a mapper in static storage does not fault in the
// pages of tiles it never uses.
class TilePool {
 public:
  explicit TilePool(Span<Tile> tiles);
  TilePool(const TilePool&) = delete;
  TilePool& operator=(const TilePool&) = delete;

  // A tile with every cell unknown, or kNoTile when the pool is exhausted.
  TileId Allocate();
  void Free(TileId id);

  Tile& operator[](TileId id) { return tiles_[id]; }
  const Tile& operator[](TileId id) const { return tiles_[id]; }

  std::size_t capacity() const { return tiles_.size(); }
  std::size_t used() const { return used_; }
  std::size_t failed_allocations() const { return failed_allocations_; }

 private:
  Span<Tile> tiles_;
  TileId free_head_ = kNoTile;  // the freed tiles, a list through next_free
  TileId never_used_from_ = 0;  // tiles from here on have never been allocated (in free_head_'s padding)
  std::size_t used_ = 0;
  std::size_t failed_allocations_ = 0;
};

template <std::size_t N>
class TilePoolStorage : public TilePool {
  static_assert(N < kTileInUse, "tile ids are 16-bit");

 public:
  TilePoolStorage() : TilePool(Span<Tile>(storage_, N)) {}

 private:
  Tile storage_[N];
};

}  // namespace dpcr
