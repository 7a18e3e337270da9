#include "core/front_end/start_scans.hpp"

#include <cmath>

namespace dpcr {

namespace {

constexpr float kRadPerUnit = 1e-7f;        // the header's heading less turn
constexpr float kMaxPointM = 32.0f;         // int16 millimetres
constexpr std::uint16_t kLow = 0xFFFF;

std::int16_t FromBits(std::uint32_t bits) {
  const std::int32_t v = static_cast<std::int32_t>(bits & kLow);
  return static_cast<std::int16_t>(v >= 0x8000 ? v - 0x10000 : v);
}

std::uint32_t ToBits(std::int16_t word) { return static_cast<std::uint32_t>(static_cast<std::uint16_t>(word)); }

std::int16_t Millimetres(float m) { return static_cast<std::int16_t>(std::lround(m * 1000.0f)); }

}  // namespace

void StartScans::Reset(TilePool* pool) {
  if (pool != nullptr && first_tile_ != kNoTile) {
    for (int i = kTiles - 1; i >= 0; --i) pool->Free(TileOf(*pool, i * (kMaxKept / kTiles)));
  }
  *this = StartScans();
}

void StartScans::Release(TilePool* pool) {
  const std::int64_t start_us = start_us_;
  Reset(pool);
  start_us_ = start_us;
}

bool StartScans::Begin(TilePool* pool, std::int64_t stamp_us, float yaw_rad, bool wheel_turns) {
  Reset(pool);
  if (pool->capacity() < kMinPoolTiles) return false;
  TileId borrowed[kTiles];
  for (int i = 0; i < kTiles; ++i) {
    borrowed[i] = pool->Allocate();
    if (borrowed[i] != kNoTile) continue;
    for (int j = 0; j < i; ++j) pool->Free(borrowed[j]);
    return false;
  }
  first_tile_ = borrowed[0];
  for (int i = 1; i < kTiles; ++i) (*pool)[first_tile_].updated[i - 1] = borrowed[i];
  keeping_ = true;
  start_us_ = stamp_us;
  last_yaw_ = yaw_rad;
  wheel_turns_ = wheel_turns;
  return true;
}

void StartScans::Track(std::int64_t stamp_us, bool have_yaw, float yaw_rad, const StartScansConfig& config) {
  if (!keeping_) return;
  if (!have_yaw || static_cast<float>(stamp_us - start_us_) * 1e-6f > config.window_s) {
    keeping_ = false;
    return;
  }
  turn_ += NormalizeAngle(yaw_rad - last_yaw_);
  last_yaw_ = yaw_rad;
}

bool StartScans::Due(const TilePool& pool, std::int64_t stamp_us, const StartScansConfig& config) const {
  if (!keeping_ || n_ >= kMaxKept) return false;
  if (n_ == 0) return true;
  const float since_start_s = static_cast<float>(stamp_us - start_us_) * 1e-6f;
  return since_start_s - kept(pool, n_ - 1).t_s >= config.every_s;
}

void StartScans::Keep(TilePool* pool, std::int64_t stamp_us, const Pose2& in_map, Span<const Point2> hits) {
  if (!keeping_ || n_ >= kMaxKept || hits.empty()) return;
  std::int16_t* w = Words(pool, n_);
  const float t_ms = static_cast<float>(stamp_us - start_us_) * 1e-3f;
  w[0] = static_cast<std::int16_t>(std::lround(t_ms));  // the window is at most 30 s (Validate)
  const float less_turn = NormalizeAngle(NormalizeAngle(in_map.theta) - NormalizeAngle(turn_));
  const std::uint32_t bits = static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(less_turn / kRadPerUnit)));
  w[2] = FromBits(bits);
  w[3] = FromBits(bits >> 16);
  const std::size_t stride = (hits.size() + kMaxPoints - 1) / kMaxPoints;
  const PointTransform to_map(in_map);
  int count = 0;
  for (std::size_t i = 0; i < hits.size(); i += stride) {
    const Point2 p = to_map(hits[i]);
    if (!(std::fabs(p.x) < kMaxPointM && std::fabs(p.y) < kMaxPointM)) continue;
    w[kHeaderWords + 2 * count] = Millimetres(p.x);
    w[kHeaderWords + 2 * count + 1] = Millimetres(p.y);
    ++count;
  }
  w[1] = static_cast<std::int16_t>(count);
  ++n_;
}

StartScans::Kept StartScans::kept(const TilePool& pool, int i) const {
  const std::int16_t* w = Words(pool, i);
  Kept k;
  k.t_s = static_cast<float>(w[0]) * 1e-3f;
  k.points = w[1];
  const std::int32_t units = static_cast<std::int32_t>(ToBits(w[2]) | (ToBits(w[3]) << 16));
  k.heading_less_turn_rad = static_cast<float>(units) * kRadPerUnit;
  return k;
}

std::size_t StartScans::Points(const TilePool& pool, int i, Span<Point2> out) const {
  const std::int16_t* w = Words(pool, i);
  std::size_t n = 0;
  for (int j = 0; j < w[1] && n < out.size(); ++j) {
    out[n++] = Point2{static_cast<float>(w[kHeaderWords + 2 * j]) * 1e-3f, static_cast<float>(w[kHeaderWords + 2 * j + 1]) * 1e-3f};
  }
  return n;
}

TileId StartScans::TileOf(const TilePool& pool, int scan) const {
  const int tile = scan / (kMaxKept / kTiles);
  return tile == 0 ? first_tile_ : static_cast<TileId>(pool[first_tile_].updated[tile - 1]);
}

std::int16_t* StartScans::Words(TilePool* pool, int scan) {
  constexpr int kScansPerTile = kMaxKept / kTiles;
  return (*pool)[TileOf(*pool, scan)].cells + (scan % kScansPerTile) * kWordsPerScan;
}

const std::int16_t* StartScans::Words(const TilePool& pool, int scan) const {
  constexpr int kScansPerTile = kMaxKept / kTiles;
  return pool[TileOf(pool, scan)].cells + (scan % kScansPerTile) * kWordsPerScan;
}

bool FitStartOffset(const StartScans& scans, const TilePool& pool, const float* registered_turn, float start_heading_rad,
                    const StartScansConfig& config, StartOffsetFit* fit) {
  float r[StartScans::kMaxKept], t[StartScans::kMaxKept];
  int n = 0;
  for (int i = 0; i < scans.size(); ++i) {
    if (std::isnan(registered_turn[i])) continue;
    const StartScans::Kept k = scans.kept(pool, i);
    r[n] = NormalizeAngle(k.heading_less_turn_rad + registered_turn[i] - start_heading_rad);
    t[n++] = k.t_s;
  }
  *fit = StartOffsetFit();
  fit->scans = n;
  if (n < config.min_scans || n < 3) return false;
  float st = 0.0f, stt = 0.0f, sr = 0.0f, str = 0.0f;
  for (int i = 0; i < n; ++i) st += t[i], stt += t[i] * t[i], sr += r[i], str += t[i] * r[i];
  const float fn = static_cast<float>(n);
  const float det = fn * stt - st * st;
  if (!(det > 1e-6f)) return false;
  fit->offset_rad = (stt * sr - st * str) / det;
  fit->bias_rad_s = -(fn * str - st * sr) / det;
  // The offset's standard error from the residuals about the line (n - 2 degrees of freedom).
  float ss = 0.0f;
  for (int i = 0; i < n; ++i) {
    const float e = r[i] - (fit->offset_rad - fit->bias_rad_s * t[i]);
    ss += e * e;
  }
  fit->offset_se_rad = std::sqrt(ss / (fn - 2.0f) * stt / det);
  return std::fabs(fit->offset_rad) <= config.max_offset_rad && std::fabs(fit->bias_rad_s) <= config.max_bias_rad_s;
}

}  // namespace dpcr
