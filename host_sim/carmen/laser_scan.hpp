// A CARMEN laser record as a mapper scan: beam i at angle_min + i * increment. A record with
// more beams than the scan holds is decimated (every k-th beam kept), not truncated.
#pragma once

#include <cstddef>

#include "core/geometry/scan.hpp"
#include "host_sim/carmen/carmen_reader.hpp"

namespace dpcr::carmen {

// Overwrites `scan`; true when beams had to be dropped.
template <int N>
bool ToScan(const LaserRecord& laser, Scan<N>* scan) {
  scan->stamp_us = laser.stamp_us;
  scan->beams.clear();
  const std::size_t n = laser.ranges_m.size();
  const std::size_t stride = (n + static_cast<std::size_t>(N) - 1) / static_cast<std::size_t>(N);
  for (std::size_t i = 0; i < n; i += stride) {
    Beam b;
    b.angle_rad = laser.angle_min_rad + static_cast<float>(i) * laser.angle_increment_rad;
    b.range_m = laser.ranges_m[i];
    static_cast<void>(scan->beams.push_back(b));
  }
  return stride > 1;
}

}  // namespace dpcr::carmen
