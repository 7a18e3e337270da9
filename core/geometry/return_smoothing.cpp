#include "core/geometry/return_smoothing.hpp"

#include <cmath>

#include "core/geometry/symmetric_eigen2.hpp"

namespace dpcr {
namespace {

constexpr int kMaxHalfWindow = 4;
// A window ending or starting at a return replaces the centred one when its rms is under this share.
constexpr float kCornerRmsRatio = 0.3f;

// The range sigma at range r, for a lidar whose sigma at 3 m is noise_m: a base plus a share of
// the range in an LD06's proportions (1 cm + 0.5 %: 0.4 + 0.2 r of its 2.5 cm at 3 m).
float SigmaAt(float noise_m, float r) { return noise_m * (0.4f + 0.2f * r); }

// Whether b lies within the gap of a's bearing, seen from the origin (both relative to it):
// |a x b| <= sin(gap) |a| |b|, squared.
bool Adjacent(Point2 a, Point2 b, float sin2_gap) {
  const float dot = a.x * b.x + a.y * b.y;
  const float cross = a.x * b.y - a.y * b.x;
  return dot > 0.0f && cross * cross <= sin2_gap * (a.x * a.x + a.y * a.y) * (b.x * b.x + b.y * b.y);
}

// The window's total-least-squares line (centroid and unit normal) and its rms residual.
struct LineFit {
  Point2 centroid;
  Point2 normal;
  float rms = 0.0f;
};

// One pass over the window's points, its sums taken relative to its first point: small numbers,
// so the centred moments lose nothing to cancellation.
template <int kSpan>
LineFit FitLine(const Point2* p) {
  constexpr int span = kSpan;
  const Point2 o = p[0];
  float sx = 0.0f, sy = 0.0f, sxx = 0.0f, sxy = 0.0f, syy = 0.0f;
  for (int k = 1; k < span; ++k) {
    const float dx = p[k].x - o.x, dy = p[k].y - o.y;
    sx += dx;
    sy += dy;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  const float inv = 1.0f / static_cast<float>(span);
  LineFit f;
  f.centroid = Point2{o.x + sx * inv, o.y + sy * inv};
  const float a = sxx - sx * sx * inv, b = sxy - sx * sy * inv, c = syy - sy * sy * inv;
  // The normal: the eigenvector of the smallest eigenvalue of [a b; b c].
  const SymmetricEigen2 e = EigenOfSymmetric2(a, b, c);
  f.normal = e.minor;
  f.rms = std::sqrt(std::fmax(e.lambda_min, 0.0f) * inv);
  return f;
}

// The windows fitted so far: the window of returns s..s+2h in slot s % span.
template <int kSpan>
struct Fits {
  LineFit fit[kSpan];
  bool valid[kSpan] = {};
};

// The window a return takes, from the windows it ends, centres and starts (slots given): the
// centred one, unless one of the others fits far better (at a corner that one lies on the
// return's own wall, where the centred one would round the corner off; otherwise the centred
// one: a return at a window's end moves by a noisier fit).
template <int kSpan>
const LineFit* ChooseWindow(const Fits<kSpan>& fits, int ends, int centres, int starts) {
  const LineFit* best = centres >= 0 && fits.valid[centres] ? &fits.fit[centres] : nullptr;
  const int sides[2] = {ends, starts};
  for (const int slot : sides) {
    if (slot < 0 || !fits.valid[slot]) continue;
    const LineFit* side = &fits.fit[slot];
    if (best == nullptr || side->rms < kCornerRmsRatio * best->rms) best = side;
  }
  return best;
}

// The parameter t that puts return d (relative to the origin) at t * d on the window's line, or
// a negative number when the line may not move it.
float MoveOntoLine(const LineFit& line, Point2 d, const ReturnSmoothingConfig& config) {
  const float r = std::sqrt(d.x * d.x + d.y * d.y);
  const float sigma = SigmaAt(config.noise_m, r);
  if (line.rms > config.max_rms_sigmas * sigma) return -1.0f;
  const float along = line.normal.x * d.x + line.normal.y * d.y;  // n . d
  if (std::fabs(along) < 0.2f * r) return -1.0f;  // grazing: the line says little about the range
  const float t = (line.normal.x * line.centroid.x + line.normal.y * line.centroid.y) / along;
  return std::fabs(t - 1.0f) * r <= config.max_move_sigmas * sigma ? t : -1.0f;
}

// SmoothReturns for a window of 2 * kHalf + 1 returns (a constant: the loops unroll).
template <int kHalf>
std::size_t Smooth(Span<Point2> hits, Point2 origin, float sin2_gap, const ReturnSmoothingConfig& config) {
  constexpr int span = 2 * kHalf + 1, half = kHalf;
  const int n = static_cast<int>(hits.size());
  auto measured = [&](int j) {
    const Point2 h = hits[static_cast<std::size_t>(j)];
    return Point2{h.x - origin.x, h.y - origin.y};
  };
  // Returns i..i+2h as measured, twice over (return j in slots j % span and j % span + span), so
  // that every window lies contiguous; each window is fitted once, at the step of its first
  // return, before any of its returns moves.
  Point2 ring[2 * span];
  int adjacent_run = 0;  // consecutive neighbouring pairs ending at the newest return in the ring
  for (int j = 0; j + 1 < span; ++j) {
    ring[j] = ring[j + span] = measured(j);
    adjacent_run = j > 0 && Adjacent(ring[j - 1], ring[j], sin2_gap) ? adjacent_run + 1 : 0;
  }
  Fits<span> fits;
  std::size_t moved = 0;
  int slot = 0;                // i % span
  int last_slot = span - 1;    // (i + 2h) % span
  for (int i = 0; i < n; ++i) {
    bool complete = false;
    if (i + 2 * half < n) {
      const Point2 q = measured(i + 2 * half);
      adjacent_run = Adjacent(ring[last_slot + span - 1], q, sin2_gap) ? adjacent_run + 1 : 0;
      ring[last_slot] = ring[last_slot + span] = q;
      complete = adjacent_run >= 2 * half;
    }
    fits.valid[slot] = complete;
    if (complete) fits.fit[slot] = FitLine<span>(&ring[slot]);
    const int centres = i >= half ? (slot + span - half) % span : -1;
    const int ends = i >= 2 * half ? (slot + 1) % span : -1;
    const LineFit* line = ChooseWindow(fits, ends, centres, slot);
    slot = slot + 1 == span ? 0 : slot + 1;
    last_slot = last_slot + 1 == span ? 0 : last_slot + 1;
    if (line == nullptr) continue;
    const Point2 d = measured(i);
    const float t = MoveOntoLine(*line, d, config);
    if (t < 0.0f) continue;
    hits[static_cast<std::size_t>(i)] = Point2{origin.x + t * d.x, origin.y + t * d.y};
    ++moved;
  }
  return moved;
}

}  // namespace

std::size_t SmoothReturns(Span<Point2> hits, Point2 origin, float beam_step_rad, const ReturnSmoothingConfig& config) {
  const int half = config.half_window < kMaxHalfWindow ? config.half_window : kMaxHalfWindow;
  if (config.noise_m <= 0.0f || half <= 0 || hits.size() < static_cast<std::size_t>(2 * half + 1)) return 0;
  const float sin_gap = std::sin(config.max_gap_beams * beam_step_rad);
  const float sin2_gap = sin_gap * sin_gap;
  switch (half) {
    case 1: return Smooth<1>(hits, origin, sin2_gap, config);
    case 2: return Smooth<2>(hits, origin, sin2_gap, config);
    case 3: return Smooth<3>(hits, origin, sin2_gap, config);
    default: return Smooth<kMaxHalfWindow>(hits, origin, sin2_gap, config);
  }
}

}  // namespace dpcr
