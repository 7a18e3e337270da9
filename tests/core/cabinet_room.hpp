// A 6 m x 4 m room with a cabinet in one corner (so that it is not symmetric), for tests that
// cast a lidar's beams by hand.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/geometry/pose2.hpp"
#include "core/geometry/scan.hpp"

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

// One revolution of a rotating lidar at (x, y) in the room, stamped at `t_scan_s`: `beams` beams
// spread over `revolution_s`, each at its own time, while the robot's heading follows
// `heading(t)` (so a turning robot's revolution is bent as a real one is).
template <class Scan, class Heading>
Scan CabinetRoomRevolution(float x, float y, float t_scan_s, float revolution_s, int beams, Heading heading) {
  Scan scan;
  scan.stamp_us = static_cast<std::int64_t>(std::lround(t_scan_s * 1e6f));
  for (int b = 0; b < beams; ++b) {
    const float offset = revolution_s * static_cast<float>(b) / static_cast<float>(beams);
    Beam beam;
    beam.angle_rad = NormalizeAngle(2.0f * kPi * static_cast<float>(b) / static_cast<float>(beams));
    beam.offset_us = static_cast<std::int32_t>(std::lround(offset * 1e6f));
    beam.range_m = CabinetRoomRange(x, y, heading(t_scan_s + offset) + beam.angle_rad);
    (void)scan.beams.push_back(beam);
  }
  return scan;
}

}  // namespace dpcr::test
