#include "core/grid/tile_pool.hpp"

#include "core/base/assert.hpp"

namespace dpcr {

TilePool::TilePool(Span<Tile> tiles) : tiles_(tiles) { DPCR_ASSERT(tiles.size() < kTileInUse); }

TileId TilePool::Allocate() {
  TileId id;
  if (free_head_ != kNoTile) {
    id = free_head_;
    free_head_ = tiles_[id].next_free;
  } else if (never_used_from_ < tiles_.size()) {
    id = never_used_from_++;
  } else {
    ++failed_allocations_;
    return kNoTile;
  }
  Tile& tile = tiles_[id];
  tile.next_free = kTileInUse;
  for (std::int16_t& cell : tile.cells) cell = kUnknownCell;
  tile.stamp = 0;
  for (std::uint32_t& word : tile.updated) word = 0;
  ++used_;
  return id;
}

void TilePool::Free(TileId id) {
  DPCR_ASSERT(id < tiles_.size() && tiles_[id].next_free == kTileInUse);
  tiles_[id].next_free = free_head_;
  free_head_ = id;
  --used_;
}

}  // namespace dpcr
