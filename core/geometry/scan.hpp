// One lidar revolution as the core takes it: per-beam angle, range and time offset.
#pragma once

#include <cstdint>

#include "core/base/static_vector.hpp"

namespace dpcr {

struct Beam {
  float angle_rad = 0.0f;    // in the sensor frame, counter-clockwise from the sensor's x axis
  float range_m = 0.0f;      // <= 0, NaN or past max range: no return
  std::int32_t offset_us = 0;  // time of this beam relative to Scan::stamp_us (motion de-skew)
};

template <int kMaxBeams>
struct Scan {
  std::int64_t stamp_us = 0;  // time of the first beam (or the revolution's reference)
  StaticVector<Beam, kMaxBeams> beams;
};

}  // namespace dpcr
