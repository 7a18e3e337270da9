// A 6 m x 4 m room with a cabinet in one corner (so that it is not symmetric), for tests that
// cast a lidar's beams by hand.
#pragma once

#include <cmath>

namespace dpcr::test {

// The range from (x, y) along the world angle `a` to the first wall or the cabinet.
inline float CabinetRoomRange(float x, float y, float a) {
  constexpr float kRoomX = 6.0f, kRoomY = 4.0f;
  const float c = std::cos(a), s = std::sin(a);
  float r = 1e9f;
  if (c > 1e-6f) r = std::fmin(r, (kRoomX - x) / c);
  if (c < -1e-6f) r = std::fmin(r, -x / c);
  if (s > 1e-6f) r = std::fmin(r, (kRoomY - y) / s);
  if (s < -1e-6f) r = std::fmin(r, -y / s);
  if (c > 1e-6f) {
    const float d = (5.0f - x) / c, hy = y + d * s;
    if (d > 0.0f && hy > 3.0f) r = std::fmin(r, d);
  }
  return r;
}

}  // namespace dpcr::test
