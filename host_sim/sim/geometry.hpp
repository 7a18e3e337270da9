// Double-precision 2D geometry for the world simulator: points, poses, and the analytic
// ray-segment / ray-circle intersections the lidar model is built on.
#pragma once

#include <cmath>

#include "core/geometry/pose2.hpp"

namespace dpcr::sim {

constexpr double kPiD = 3.14159265358979323846;

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return Vec2{a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return Vec2{a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return Vec2{s * a.x, s * a.y}; }
inline double Dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double Cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double Norm(Vec2 a) { return std::sqrt(Dot(a, a)); }

// Wraps to (-pi, pi].
inline double WrapAngle(double a) {
  const double two_pi = 2.0 * kPiD;
  a = std::fmod(a + kPiD, two_pi);
  if (a <= 0.0) a += two_pi;
  return a - kPiD;
}

// Ground-truth pose in the world frame (metres, radians), double so a 70-minute run does not
// accumulate float rounding into the truth itself.
struct Pose2d {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  Vec2 Apply(Vec2 p) const {
    const double c = std::cos(theta);
    const double s = std::sin(theta);
    return Vec2{c * p.x - s * p.y + x, s * p.x + c * p.y + y};
  }
  friend Pose2d operator*(const Pose2d& a, const Pose2d& b) {
    const Vec2 t = a.Apply(Vec2{b.x, b.y});
    return Pose2d{t.x, t.y, WrapAngle(a.theta + b.theta)};
  }
  Pose2 ToPose2() const {
    return Pose2{static_cast<float>(x), static_cast<float>(y), NormalizeAngle(static_cast<float>(theta))};
  }
};

// Distance along the unit-direction ray origin + t*dir to segment [a, b]; negative when missed.
inline double RaySegment(Vec2 origin, Vec2 dir, Vec2 a, Vec2 b) {
  const Vec2 e = b - a;
  const double denom = Cross(dir, e);
  if (std::fabs(denom) < 1e-12) return -1.0;  // parallel: grazing hits are not returns
  const Vec2 w = a - origin;
  const double t = Cross(w, e) / denom;
  const double u = Cross(w, dir) / denom;
  if (t < 0.0 || u < 0.0 || u > 1.0) return -1.0;
  return t;
}

// Distance along the unit-direction ray to the first crossing of a circle; negative when missed
// or when the origin is inside the circle (a sensor inside an obstacle sees nothing of it).
inline double RayCircle(Vec2 origin, Vec2 dir, Vec2 centre, double radius) {
  const Vec2 oc = origin - centre;
  const double b = Dot(oc, dir);
  const double c = Dot(oc, oc) - radius * radius;
  if (c < 0.0) return -1.0;
  const double disc = b * b - c;
  if (disc < 0.0) return -1.0;
  const double t = -b - std::sqrt(disc);
  return t >= 0.0 ? t : -1.0;
}

// Euclidean distance from p to segment [a, b].
inline double PointSegmentDistance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 e = b - a;
  const double len2 = Dot(e, e);
  double u = len2 > 0.0 ? Dot(p - a, e) / len2 : 0.0;
  u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
  return Norm(p - (a + u * e));
}

}  // namespace dpcr::sim
