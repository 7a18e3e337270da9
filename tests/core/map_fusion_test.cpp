// The global map fused from regional maps: on the lattice cells map one to one; under a moved or
// rotated anchor (after the back end) the footprint is resampled without holes.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/grid/map_fusion.hpp"
#include "registration_fixtures.hpp"

using dpcr::CellIndex;
using dpcr::Point2;
using dpcr::Pose2;

namespace {

// A 3 m x 2 m block of free cells with a wall cell row along its top edge, from (1, 1) m.
void FillBlock(dpcr::TiledGrid& grid) {
  for (int y = 20; y < 60; ++y) {
    for (int x = 20; x < 80; ++x) (void)grid.Update(CellIndex{x, y}, y == 59 ? 2000 : -1000, -3000, 3000, 0);
  }
}

struct Fused {
  dpcr::CellBox box;
  std::vector<std::int16_t> cells;
  std::int16_t At(Point2 p) const {
    const CellIndex c = dpcr::CellOf(p.x, p.y, 0.05f);
    return cells[static_cast<std::size_t>((c.y - box.min.y) * box.width() + (c.x - box.min.x))];
  }
  int Known() const {
    int n = 0;
    for (std::int16_t v : cells) n += v != dpcr::kUnknownCell ? 1 : 0;
    return n;
  }
};

Fused Fuse(const std::vector<dpcr::PlacedGrid>& grids) {
  Fused f;
  const dpcr::Span<const dpcr::PlacedGrid> span(grids.data(), grids.size());
  f.box = dpcr::FusedBounds(span, 0.05f);
  f.cells.resize(static_cast<std::size_t>(f.box.width() * f.box.height()));
  REQUIRE(dpcr::FuseInto(span, f.box, 0.05f, -3584, 3584, dpcr::Span<std::int16_t>(f.cells.data(), f.cells.size())) ==
          dpcr::Status::kOk);
  return f;
}

}  // namespace

TEST_CASE("Fusion on the lattice sums log-odds cell for cell") {
  dpcr_test::GridFixture a;
  FillBlock(*a.grid);
  const Fused f = Fuse({{a.grid.get(), Pose2{}}, {a.grid.get(), Pose2{0.5f, 0.0f, 0.0f}}});
  REQUIRE(f.Known() == 2400 + 2400 - 50 * 40);  // two 60 x 40 blocks overlapping by 50 x 40
  REQUIRE(f.At(Point2{2.02f, 2.02f}) == -2000);  // both blocks: summed
  REQUIRE(f.At(Point2{1.02f, 2.02f}) == -1000);  // the first only
}

TEST_CASE("Fusion under a rotated, moved anchor leaves no holes and puts walls where they belong") {
  dpcr_test::GridFixture a;
  FillBlock(*a.grid);
  const Pose2 anchor{4.013f, -0.71f, 0.5236f};  // 30 degrees, off the lattice
  const Fused f = Fuse({{a.grid.get(), anchor}});
  // The block's area is kept within the rim's resampling (a forward mapping of 2400 cells under
  // rotation would leave ~1/4 of the area as holes or double hits).
  REQUIRE(std::abs(f.Known() - 2400) < 120);
  // The block's centre is free, with no unknown hole anywhere inside it.
  for (float u = 1.2f; u < 3.8f; u += 0.05f) {
    for (float v = 1.2f; v < 2.8f; v += 0.05f) {
      REQUIRE(f.At(anchor.Apply(Point2{u, v})) < 0);
    }
  }
  // The wall row (local y = 2.95..3.0 m) lands on the rotated edge.
  REQUIRE(f.At(anchor.Apply(Point2{2.0f, 2.975f})) == 2000);
}
