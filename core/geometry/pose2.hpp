// SE(2) rigid transform / robot pose: (x, y) in metres, theta in radians, kept in (-pi, pi].
// a * b applies b first, then a (b expressed in a's frame), as for homogeneous matrices.
#pragma once

#include <cmath>

namespace dpcr {

constexpr float kPi = 3.14159265358979323846f;

// Wraps an angle to (-pi, pi].
inline float NormalizeAngle(float a) {
  a = std::fmod(a + kPi, 2.0f * kPi);
  if (a <= 0.0f) a += 2.0f * kPi;
  return a - kPi;
}

struct Point2 {
  float x = 0.0f;
  float y = 0.0f;
};

struct PointTransform;

struct Pose2 {
  float x = 0.0f;
  float y = 0.0f;
  float theta = 0.0f;

  static Pose2 Identity() { return Pose2{}; }

  inline Point2 Apply(Point2 p) const;

  Pose2 Inverse() const {
    const float c = std::cos(theta);
    const float s = std::sin(theta);
    return Pose2{-(c * x + s * y), s * x - c * y, NormalizeAngle(-theta)};
  }

  friend Pose2 operator*(const Pose2& a, const Pose2& b) {
    const float c = std::cos(a.theta);
    const float s = std::sin(a.theta);
    return Pose2{c * b.x - s * b.y + a.x, s * b.x + c * b.y + a.y, NormalizeAngle(a.theta + b.theta)};
  }
};

// Pose2::Apply with the cosine and sine taken once, for many points (the same floats as Apply;
// a loop over Apply recomputes them: its stores may alias the pose).
struct PointTransform {
  explicit PointTransform(const Pose2& pose) : c(std::cos(pose.theta)), s(std::sin(pose.theta)), x(pose.x), y(pose.y) {}
  Point2 operator()(Point2 p) const { return Point2{c * p.x - s * p.y + x, s * p.x + c * p.y + y}; }
  float c, s, x, y;
};

inline Point2 Pose2::Apply(Point2 p) const { return PointTransform(*this)(p); }

// The pose of `to` expressed in the frame of `from`: from.Inverse() * to.
inline Pose2 Between(const Pose2& from, const Pose2& to) { return from.Inverse() * to; }

}  // namespace dpcr
