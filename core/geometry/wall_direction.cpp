#include "core/geometry/wall_direction.hpp"

#include <cmath>

namespace dpcr {
namespace {

// The straight-line fit of points[first, first + n): its direction (modulo pi) when the points are
// close neighbours, lie on a line within max_rms_m and span at least min_length_m.
bool FitPiece(Span<const Point2> points, std::size_t first, int n, const WallDirectionConfig& c, float* direction) {
  float mx = 0.0f, my = 0.0f;
  for (int k = 0; k < n; ++k) {
    const Point2& p = points[first + static_cast<std::size_t>(k)];
    if (k > 0) {
      const Point2& q = points[first + static_cast<std::size_t>(k) - 1];
      if (std::hypot(p.x - q.x, p.y - q.y) > c.max_step_m) return false;
    }
    mx += p.x;
    my += p.y;
  }
  mx /= static_cast<float>(n);
  my /= static_cast<float>(n);
  float sxx = 0.0f, sxy = 0.0f, syy = 0.0f;
  for (int k = 0; k < n; ++k) {
    const Point2& p = points[first + static_cast<std::size_t>(k)];
    const float dx = p.x - mx, dy = p.y - my;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  const Point2& a = points[first];
  const Point2& b = points[first + static_cast<std::size_t>(n) - 1];
  if (std::hypot(b.x - a.x, b.y - a.y) < c.min_length_m) return false;
  // Smaller eigenvalue of the scatter: the squared residuals across the fitted line.
  const float half_trace = 0.5f * (sxx + syy);
  const float across = half_trace - std::sqrt(0.25f * (sxx - syy) * (sxx - syy) + sxy * sxy);
  if (across > c.max_rms_m * c.max_rms_m * static_cast<float>(n)) return false;
  *direction = 0.5f * std::atan2(2.0f * sxy, sxx - syy);
  return true;
}

// The pieces' mean direction modulo 90 degrees (the mean of 4a on the circle); with `near`, only
// the pieces within `window_rad` of it (modulo 90 degrees) vote.
WallDirection Vote(Span<const Point2> points, const WallDirectionConfig& c, const float* near, float window_rad) {
  WallDirection d;
  float sum_c = 0.0f, sum_s = 0.0f;
  const int n = c.window;
  for (std::size_t i = 0; i + static_cast<std::size_t>(n) <= points.size(); ++i) {
    float a = 0.0f;
    if (!FitPiece(points, i, n, c, &a)) continue;
    if (near != nullptr && std::fabs(NormalizeAngle(4.0f * (a - *near))) > 4.0f * window_rad) continue;
    sum_c += std::cos(4.0f * a);
    sum_s += std::sin(4.0f * a);
    ++d.pieces;
  }
  if (d.pieces == 0) return d;
  d.agreement = std::hypot(sum_c, sum_s) / static_cast<float>(d.pieces);
  d.angle_rad = 0.25f * std::atan2(sum_s, sum_c);
  if (d.angle_rad >= 0.25f * kPi) d.angle_rad -= 0.5f * kPi;
  return d;
}

}  // namespace

WallDirection DominantWallDirection(Span<const Point2> points, const WallDirectionConfig& config) {
  if (config.window < 3) return WallDirection{};
  const WallDirection all = Vote(points, config, nullptr, 0.0f);
  WallDirection d = all;
  if (all.pieces < config.min_pieces || all.agreement < config.min_agreement) return d;
  // Again with the pieces near the first answer only: clutter and odd walls no longer pull it.
  const WallDirection refined = Vote(points, config, &all.angle_rad, 10.0f * kPi / 180.0f);
  if (refined.pieces >= config.min_pieces) d.angle_rad = refined.angle_rad;
  d.found = true;
  return d;
}

}  // namespace dpcr
