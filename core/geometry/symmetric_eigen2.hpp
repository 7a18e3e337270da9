// The eigenvalues of a symmetric 2x2 matrix [a b; b c] in closed form, and the unit eigenvector of
// the smaller one: a line fit's normal (return_smoothing.cpp), a registration's least-fixed
// direction (core/registration/weak_direction_hold.hpp).
#pragma once

#include <cmath>

#include "core/geometry/pose2.hpp"

namespace dpcr {

struct SymmetricEigen2 {
  float lambda_min = 0.0f;
  float lambda_max = 0.0f;
  Point2 minor{1.0f, 0.0f};  // unit eigenvector of lambda_min
};

inline SymmetricEigen2 EigenOfSymmetric2(float a, float b, float c) {
  const float half_diff = 0.5f * (a - c);
  const float root = std::sqrt(half_diff * half_diff + b * b);
  SymmetricEigen2 e;
  e.lambda_min = 0.5f * (a + c) - root;
  e.lambda_max = 0.5f * (a + c) + root;
  // (b, l - a) and (l - c, b) both solve (M - l I) v = 0; the longer one is the better
  // conditioned (with b = 0 one of them vanishes). Both vanish only for an isotropic matrix: any
  // axis will do (x).
  const Point2 v1{b, e.lambda_min - a}, v2{e.lambda_min - c, b};
  const float n1 = v1.x * v1.x + v1.y * v1.y, n2 = v2.x * v2.x + v2.y * v2.y;
  const Point2 v = n1 >= n2 ? v1 : v2;
  const float norm = std::sqrt(n1 >= n2 ? n1 : n2);
  if (norm > 0.0f) e.minor = Point2{v.x / norm, v.y / norm};
  return e;
}

}  // namespace dpcr
