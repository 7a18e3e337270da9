#include "core/back_end/square_sums.hpp"

#include <cstring>

// The vector path needs GCC's or Clang's vector types and a little-endian target (a row's bytes
// are the low bytes of its words first); DPCR_NO_BYTE_VECTORS forces the byte-by-byte one (tests).
#if !defined(DPCR_NO_BYTE_VECTORS) && defined(__GNUC__) && defined(__BYTE_ORDER__) && \
    __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define DPCR_BYTE_VECTORS 1
#else
#define DPCR_BYTE_VECTORS 0
#endif

namespace dpcr {
namespace {

constexpr int kB = MatchGrid::kBlock;

#if DPCR_BYTE_VECTORS
using U32x2 = std::uint32_t __attribute__((vector_size(8)));
using U32x4 = std::uint32_t __attribute__((vector_size(16)));
using U8x8 = std::uint8_t __attribute__((vector_size(8)));
using U16x8 = std::uint16_t __attribute__((vector_size(16)));

template <typename T>
T LoadBytes(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// The eight bytes of two 32-bit rows (copied, not aliased: the compiler keeps them in a register).
U8x8 AsBytes(const U32x2& rows) {
  U8x8 bytes;
  std::memcpy(&bytes, &rows, sizeof bytes);
  return bytes;
}

// A point's 4 x 4 square of adjacent cells (four rows of four bytes), widened to 16-bit lanes
// eight at a time and spilled into 32-bit sums every 256 points, before a lane could overflow
// (256 x 255 < 2^16).
class SquareSums {
 public:
  void Add(const std::uint8_t* p, int row_stride) {
    const U32x2 rows01 = {LoadBytes<std::uint32_t>(p), LoadBytes<std::uint32_t>(p + row_stride)};
    const U32x2 rows23 = {LoadBytes<std::uint32_t>(p + 2 * row_stride), LoadBytes<std::uint32_t>(p + 3 * row_stride)};
    low_ += __builtin_convertvector(AsBytes(rows01), U16x8);
    high_ += __builtin_convertvector(AsBytes(rows23), U16x8);
    if (++pending_ == kSpillEvery) Spill();
  }
  void AddOne(int k, std::uint8_t v) { sums_[k] += v; }
  void Finish(std::uint32_t (&out)[16]) {
    Spill();
    for (int k = 0; k < 16; ++k) out[k] = sums_[k];
  }

 private:
  static constexpr int kSpillEvery = 256;
  void Spill() {
    for (int k = 0; k < 8; ++k) {
      sums_[k] += low_[k];
      sums_[8 + k] += high_[k];
    }
    low_ = U16x8{};
    high_ = U16x8{};
    pending_ = 0;
  }
  U16x8 low_ = {};   // rows 0 and 1
  U16x8 high_ = {};  // rows 2 and 3
  int pending_ = 0;
  std::uint32_t sums_[16] = {};
};
#else
// The same, byte by byte.
class SquareSums {
 public:
  void Add(const std::uint8_t* p, int row_stride) {
    for (int j = 0; j < 4; ++j, p += row_stride) {
      for (int i = 0; i < 4; ++i) sums_[4 * j + i] += p[i];
    }
  }
  void AddOne(int k, std::uint8_t v) { sums_[k] += v; }
  void Finish(std::uint32_t (&out)[16]) {
    for (int k = 0; k < 16; ++k) out[k] = sums_[k];
  }

 private:
  std::uint32_t sums_[16] = {};
};
#endif

// A point whose sixteen look-ups, `step` apart, all fall inside the w x h grid.
bool SquareInside(int x, int y, int step, int w, int h) { return x >= 0 && y >= 0 && x + 3 * step < w && y + 3 * step < h; }

}  // namespace

void SumScoreSquares(const MatchGrid& grid, Span<const MatchCell> cells, int x0, int y0, bool all_inside,
                     std::uint32_t (&out)[16]) {
  const int w = grid.width(), h = grid.height();
  const std::uint8_t* table = grid.cells_data();
  SquareSums sums;
  for (const MatchCell& c : cells) {
    const int x = c.x + x0, y = c.y + y0;
    if (all_inside || SquareInside(x, y, 1, w, h)) {
      sums.Add(table + (y * w + x), w);
    } else if (x < w && y < h && x + 3 >= 0 && y + 3 >= 0) {  // else all read 0
      for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) sums.AddOne(4 * j + i, grid.AtCell(x + i, y + j));
      }
    }
  }
  sums.Finish(out);
}

void SumBoundSquares(const MatchGrid& grid, Span<const MatchCell> cells, int x0, int y0, bool all_inside,
                     std::uint32_t (&out)[16]) {
  const int w = grid.width(), h = grid.height();
  const std::uint8_t* table = grid.bounds_data();
  std::uint32_t sums[16] = {};
#if DPCR_BYTE_VECTORS
  // A row's four bounds, kBlock bytes apart, are the low bytes of the four 32-bit words of 16 bytes
  // read at once (three bytes past the last one: read only where the row holds them).
  static_assert(kB == 4, "a row's four bounds are the low bytes of four words");
  const U32x4 low_byte = {0xFFu, 0xFFu, 0xFFu, 0xFFu};
  U32x4 row0 = {}, row1 = {}, row2 = {}, row3 = {};
  const auto add_rows = [&](const std::uint8_t* p) {
    row0 += LoadBytes<U32x4>(p) & low_byte;
    row1 += LoadBytes<U32x4>(p + kB * w) & low_byte;
    row2 += LoadBytes<U32x4>(p + 2 * kB * w) & low_byte;
    row3 += LoadBytes<U32x4>(p + 3 * kB * w) & low_byte;
  };
  if (all_inside) {
    const int offset = y0 * w + x0;
    for (const MatchCell& c : cells) add_rows(table + (c.y * w + c.x + offset));
  }
#endif
  for (std::size_t k = 0; k < (all_inside && DPCR_BYTE_VECTORS ? 0 : cells.size()); ++k) {
    const int x = cells[k].x + x0, y = cells[k].y + y0;
    if (SquareInside(x, y, kB, w, h)) {
      const std::uint8_t* p = table + (y * w + x);
#if DPCR_BYTE_VECTORS
      if (x + 3 * kB + kBoundSquareSpareBytes < w) {
        add_rows(p);
        continue;
      }
#endif
      for (int j = 0; j < 4; ++j, p += kB * w) {
        for (int i = 0; i < 4; ++i) sums[4 * j + i] += p[i * kB];
      }
    } else if (x < w && y < h && x + 3 * kB > -kB && y + 3 * kB > -kB) {  // else all read 0
      for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) sums[4 * j + i] += grid.BoundAt(x + i * kB, y + j * kB);
      }
    }
  }
#if DPCR_BYTE_VECTORS
  for (int i = 0; i < 4; ++i) {
    sums[i] += row0[i];
    sums[4 + i] += row1[i];
    sums[8 + i] += row2[i];
    sums[12 + i] += row3[i];
  }
#endif
  for (int k = 0; k < 16; ++k) out[k] = sums[k];
}

}  // namespace dpcr
