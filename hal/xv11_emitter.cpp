#include "hal/xv11_emitter.hpp"

#include <cmath>

#include "core/geometry/pose2.hpp"

namespace dpcr {

void EncodeXv11Revolution(const Beam* beams, std::size_t beam_count, std::int64_t stamp_us,
                          const LidarAngleMap& angle_map, float rate_hz,
                          Xv11EmittedPacket (&out)[kXv11PacketsPerRevolution]) {
  constexpr int kDegrees = kXv11PacketsPerRevolution * kXv11ReadingsPerPacket;
  Xv11Packet packets[kXv11PacketsPerRevolution];
  for (int k = 0; k < kXv11PacketsPerRevolution; ++k) {
    packets[k].index = static_cast<std::uint8_t>(kXv11FirstIndex + k);
    packets[k].speed_rpm_x64 = static_cast<std::uint16_t>(std::lround(rate_hz * 60.0f * 64.0f));
    for (Xv11Reading& r : packets[k].readings) r.invalid = true;
  }
  for (std::size_t i = 0; i < beam_count; ++i) {
    const float deg = (beams[i].angle_rad - angle_map.angle_offset_rad) / angle_map.angle_sign * (180.0f / kPi);
    long d = std::lround(deg) % kDegrees;
    if (d < 0) d += kDegrees;
    Xv11Reading& r = packets[d / kXv11ReadingsPerPacket].readings[d % kXv11ReadingsPerPacket];
    const long mm = beams[i].range_m > 0.0f ? std::lround(beams[i].range_m * 1000.0f) : 0;
    r.invalid = mm <= 0 || mm > kXv11MaxRangeMm;
    r.distance_mm = r.invalid ? 0 : static_cast<std::uint16_t>(mm);
    r.strength = r.invalid ? 0 : 200;
  }
  const double reading_us = 1e6 / (static_cast<double>(rate_hz) * kDegrees);
  for (int k = 0; k < kXv11PacketsPerRevolution; ++k) {
    EncodeXv11Packet(packets[k], out[k].bytes);
    const int last = k * kXv11ReadingsPerPacket + kXv11ReadingsPerPacket - 1;
    out[k].arrival_us = stamp_us + std::llround(reading_us * last);
  }
}

}  // namespace dpcr
