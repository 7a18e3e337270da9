#include "core/grid/tile_pool.hpp"

#include "core/base/assert.hpp"

namespace dpcr {

TilePool::TilePool(Span<Tile> tiles) : tiles_(tiles) {
  DPCR_ASSERT(tiles.size() < kTileInUse);
  for (std::size_t i = tiles.size(); i-- > 0;) {
    tiles_[i].next_free = free_head_;
    free_head_ = static_cast<TileId>(i);
  }
}

TileId TilePool::Allocate() {
  if (free_head_ == kNoTile) {
    ++failed_allocations_;
    return kNoTile;
  }
  const TileId id = free_head_;
  Tile& tile = tiles_[id];
  free_head_ = tile.next_free;
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
