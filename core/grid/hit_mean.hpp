// Where in a settled wall cell its returns fall: the cell's hit mean, kept in the cell's own int16.
//
// A regional map's lines are fitted to its obstacle cells. Fitted to cell centres, a wall becomes a
// staircase of 5 cm steps, and its line is off by up to a few tenths of a degree; the second
// registration and every later visit then measure against that error (docs/back-end.md, "Walls
// fitted where the returns fell"). A settled occupied cell (TiledGrid::set_settle_at_bounds) holds
// its clamp and nothing else, so its value can carry more: a code at or above kHitMeanCodeBase is a
// settled occupied cell whose log-odds is the clamp, with the mean position of the returns that fell
// in it since it settled (1/64 cell on each axis) and how many it has averaged (a class k: the last
// update's gain was 1/2^k, so the mean is over about 2^k returns, up to 128).
//
// No storage beyond the cells: every value above any permitted clamp (GridConfig::clamp_max <
// kHitMeanCodeBase) is a code. A running mean in 6 bits needs unbiased rounding: each update
// rounds up or down at random (a hash of the scan and the return's index), so that small steps still move
// the mean on average instead of sticking.
#pragma once

#include <cstdint>

#include "core/grid/cell.hpp"

namespace dpcr {

constexpr std::int16_t kHitMeanCodeBase = 4096;
constexpr int kHitMeanLevels = 64;   // per axis, per cell
constexpr int kHitMeanClasses = 7;   // gains 1/2 .. 1/128
static_assert(kHitMeanCodeBase + kHitMeanClasses * kHitMeanLevels * kHitMeanLevels - 1 == INT16_MAX,
              "the codes fill the values above the base exactly");

inline bool IsHitMeanCode(std::int16_t v) { return v >= kHitMeanCodeBase; }

// The cell's log-odds: a code reads as `settled`, the clamp it settled at.
inline std::int16_t LogOddsOf(std::int16_t v, std::int16_t settled) { return IsHitMeanCode(v) ? settled : v; }

struct HitMean {
  int qx = 0;  // 0..63: the mean at qx / 64 of the cell along x
  int qy = 0;
  int k = 1;  // 1..7: the next update's gain is 1 / 2^k
};

inline HitMean DecodeHitMean(std::int16_t v) {
  const int c = v - kHitMeanCodeBase;
  return HitMean{(c >> 6) & (kHitMeanLevels - 1), c & (kHitMeanLevels - 1), 1 + c / (kHitMeanLevels * kHitMeanLevels)};
}

inline std::int16_t EncodeHitMean(const HitMean& m) {
  return static_cast<std::int16_t>(kHitMeanCodeBase + (m.k - 1) * kHitMeanLevels * kHitMeanLevels + m.qx * kHitMeanLevels + m.qy);
}

// Where in its cell (fractions of the cell) the obstacle of a cell with value `v` lies: its hit
// mean when `has_mean` (TiledGrid::HasHitMean), else the centre.
inline void ObstacleOffsetInCell(std::int16_t v, bool has_mean, float* fx, float* fy) {
  if (has_mean) {
    const HitMean m = DecodeHitMean(v);
    *fx = static_cast<float>(m.qx) * (1.0f / kHitMeanLevels);
    *fy = static_cast<float>(m.qy) * (1.0f / kHitMeanLevels);
  } else {
    *fx = *fy = 0.5f;
  }
}

// A cheap integer hash (lowbias32): the deterministic randomness of the rounding.
inline std::uint32_t HitMeanHash(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

// Level (0..63) of a position `f` in [0, 1) of the cell.
inline int HitMeanLevel(float f) {
  const int q = static_cast<int>(f * static_cast<float>(kHitMeanLevels));
  return q < 0 ? 0 : (q >= kHitMeanLevels ? kHitMeanLevels - 1 : q);
}

// The first return of a cell that has just settled starts its mean.
inline HitMean StartHitMean(float fx, float fy) { return HitMean{HitMeanLevel(fx), HitMeanLevel(fy), 1}; }

// One more return at (fx, fy) of the cell; `random` is 32 uniform bits. The class goes up with
// probability 1/2^k, so it stays about 2^k updates at gain 1/2^k: a mean over all returns so far,
// until the last class.
inline HitMean UpdateHitMean(HitMean m, float fx, float fy, std::uint32_t random) {
  const float gain = 1.0f / static_cast<float>(1 << m.k);
  const float ux = static_cast<float>(random & 0x3ff) * (1.0f / 1024.0f);
  const float uy = static_cast<float>((random >> 10) & 0x3ff) * (1.0f / 1024.0f);
  const float levels = static_cast<float>(kHitMeanLevels);
  const auto step = [&](int q, float f, float u) {
    const int s = FloorToInt((f * levels - static_cast<float>(q)) * gain + u);
    const int n = q + s;
    return n < 0 ? 0 : (n >= kHitMeanLevels ? kHitMeanLevels - 1 : n);
  };
  m.qx = step(m.qx, fx, ux);
  m.qy = step(m.qy, fy, uy);
  if (m.k < kHitMeanClasses && ((random >> 20) & ((1u << m.k) - 1u)) == 0) ++m.k;
  return m;
}

}  // namespace dpcr
