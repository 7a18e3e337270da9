// The sums a correlative search scores a block of poses by (correlative_search.cpp): for each
// point of a cloud in match cells, sixteen look-ups in a 4 x 4 square, summed over the cloud.
// Most of a loop-closure search's time; with the compiler's vector types (SSE2, NEON) four or
// eight look-ups are added at once, giving the same integers as one by one.
#pragma once

#include <cstdint>

#include "core/back_end/correlative_search.hpp"
#include "core/base/span.hpp"

namespace dpcr {

// out[4 j + i] = the sum over the cells c of grid.AtCell(c.x + x0 + i, c.y + y0 + j), i, j < 4
// (the scores of the sixteen offsets of a block; 0 outside the grid). `all_inside`: every look-up
// falls inside the grid (a promise; it skips the per-point test).
void SumScoreSquares(const MatchGrid& grid, Span<const MatchCell> cells, int x0, int y0, bool all_inside,
                     std::uint32_t (&out)[16]);

// out[4 j + i] = the sum over the cells c of grid.BoundAt(c.x + x0 + kBlock i, c.y + y0 + kBlock j)
// (the bounds of the sixteen blocks of a coarse block). `all_inside`: every look-up falls inside
// the grid with kBoundSquareSpareBytes more along its row (a row's bounds are read 16 bytes at once).
constexpr int kBoundSquareSpareBytes = 3;
void SumBoundSquares(const MatchGrid& grid, Span<const MatchCell> cells, int x0, int y0, bool all_inside,
                     std::uint32_t (&out)[16]);

}  // namespace dpcr
