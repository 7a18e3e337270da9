// Tile pool: allocation order, reuse, exhaustion, and no writes to a tile before it is first used.
#include <catch2/catch.hpp>

#include <cstring>
#include <memory>

#include "core/grid/tile_pool.hpp"

namespace {

constexpr unsigned char kUntouched = 0xA5;

bool Untouched(const dpcr::Tile& tile) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(&tile);
  for (std::size_t i = 0; i < sizeof(dpcr::Tile); ++i) {
    if (bytes[i] != kUntouched) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("A pool writes no tile before handing it out, and hands out fresh tiles in index order") {
  auto tiles = std::make_unique<dpcr::Tile[]>(4);
  std::memset(static_cast<void*>(tiles.get()), kUntouched, 4 * sizeof(dpcr::Tile));
  dpcr::TilePool pool(dpcr::Span<dpcr::Tile>(tiles.get(), 4));
  for (int i = 0; i < 4; ++i) REQUIRE(Untouched(tiles[static_cast<std::size_t>(i)]));

  REQUIRE(pool.Allocate() == 0);
  REQUIRE(pool.Allocate() == 1);
  REQUIRE(pool.used() == 2);
  // Only the tiles handed out were written: a mapper in static storage faults in no other page.
  REQUIRE_FALSE(Untouched(tiles[0]));
  REQUIRE_FALSE(Untouched(tiles[1]));
  REQUIRE(Untouched(tiles[2]));
  REQUIRE(Untouched(tiles[3]));
  // Handed out blank: every cell unknown, no cell marked updated.
  for (const std::int16_t cell : tiles[1].cells) REQUIRE(cell == dpcr::kUnknownCell);
  for (const std::uint32_t word : tiles[1].updated) REQUIRE(word == 0);
  REQUIRE(tiles[1].stamp == 0);
}

TEST_CASE("A freed tile is reused before a fresh one, and a full pool says so until a tile is freed") {
  auto pool = std::make_unique<dpcr::TilePoolStorage<3>>();
  REQUIRE(pool->Allocate() == 0);
  REQUIRE(pool->Allocate() == 1);
  (*pool)[1].cells[5] = 42;
  pool->Free(1);
  pool->Free(0);
  REQUIRE(pool->used() == 0);
  REQUIRE(pool->Allocate() == 0);  // the last freed first
  REQUIRE(pool->Allocate() == 1);
  REQUIRE((*pool)[1].cells[5] == dpcr::kUnknownCell);  // blank again
  REQUIRE(pool->Allocate() == 2);  // then the never-used one
  REQUIRE(pool->Allocate() == dpcr::kNoTile);
  REQUIRE(pool->failed_allocations() == 1);
  pool->Free(2);
  REQUIRE(pool->Allocate() == 2);
  REQUIRE(pool->used() == 3);
}
