// One lidar revolution as the core takes it: per-beam angle, range and time offset.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/base/static_vector.hpp"

namespace dpcr {

struct Beam {
  float angle_rad = 0.0f;    // in the sensor frame, counter-clockwise from the sensor's x axis
  float range_m = 0.0f;      // <= 0, NaN or past max range: no return
  std::int32_t offset_us = 0;  // time of this beam relative to Scan::stamp_us (motion de-skew)
};

// Stamps (of scans and odometry samples) are microseconds of a clock that started at or after
// 1970 (a boot clock, Unix time) and reads less than 2^56 us (2283 years): the difference of any
// two never overflows. The front end refuses any other.
constexpr std::int64_t kMaxStampUs = std::int64_t{1} << 56;
inline bool PlausibleStamp(std::int64_t stamp_us) { return stamp_us >= 0 && stamp_us <= kMaxStampUs; }

// A beam a lidar could have measured: a finite angle within two turns either way of the sensor's
// x axis, and a time offset within a second of the scan's stamp (a revolution of the slowest
// lidar, an XV-11 at 3.5 Hz, takes 0.29 s). Any other is counted invalid and used for nothing,
// not even as free space: a NaN angle once put a NaN hit into the maps.
constexpr float kMaxBeamAngleRad = 2.0f * 6.28318530718f;
constexpr std::int32_t kMaxBeamOffsetUs = 1000000;
inline bool PlausibleBeam(const Beam& b) {
  return std::fabs(b.angle_rad) <= kMaxBeamAngleRad && b.offset_us >= -kMaxBeamOffsetUs && b.offset_us <= kMaxBeamOffsetUs;
}

// A beam in 8 bytes, for a scan kept until the next one (FrontEnd's fixed-lag de-skew): the range
// as it came, the angle in 1/65536 of a turn (0.0055 deg: 1.2 mm at 12 m) and the time offset in
// steps of 16 us (up to +-0.52 s; a revolution of the slowest lidar, an XV-11 at 3.5 Hz, is 0.29 s).
struct PackedBeam {
  float range_m = 0.0f;
  std::int16_t angle = 0;
  std::int16_t offset_16us = 0;

  static PackedBeam Pack(const Beam& b);
  Beam Unpack() const;
};

template <int kMaxBeams>
struct Scan {
  std::int64_t stamp_us = 0;  // time of the first beam (or the revolution's reference)
  StaticVector<Beam, kMaxBeams> beams;
};

inline PackedBeam PackedBeam::Pack(const Beam& b) {
  constexpr float kStepsPerRad = 65536.0f / 6.28318530718f;
  PackedBeam p;
  p.range_m = b.range_m;
  // The angle modulo a turn: the low 16 bits of the step count, read as signed.
  const std::int32_t steps = static_cast<std::int32_t>(std::lround(std::fmod(b.angle_rad, 6.28318530718f) * kStepsPerRad));
  const std::int32_t low = steps & 0xFFFF;
  p.angle = static_cast<std::int16_t>(low >= 0x8000 ? low - 0x10000 : low);
  const std::int64_t us = b.offset_us;  // in 64 bits: an offset near INT32_MAX must not overflow
  std::int64_t offset = us >= 0 ? (us + 8) / 16 : -((8 - us) / 16);
  if (offset > INT16_MAX) offset = INT16_MAX;
  if (offset < INT16_MIN) offset = INT16_MIN;
  p.offset_16us = static_cast<std::int16_t>(offset);
  return p;
}

inline Beam PackedBeam::Unpack() const {
  constexpr float kRadPerStep = 6.28318530718f / 65536.0f;
  Beam b;
  b.angle_rad = static_cast<float>(angle) * kRadPerStep;
  b.range_m = range_m;
  b.offset_us = static_cast<std::int32_t>(offset_16us) * 16;
  return b;
}

}  // namespace dpcr
