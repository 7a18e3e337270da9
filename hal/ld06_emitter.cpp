#include "hal/ld06_emitter.hpp"

#include <cmath>

#include "core/geometry/pose2.hpp"

namespace dpcr {
namespace {

constexpr float kRadToDeg = 180.0f / kPi;

float DeviceDeg(const Beam& beam, const LidarAngleMap& map) {
  float deg = (beam.angle_rad - map.angle_offset_rad) / map.angle_sign * kRadToDeg;
  deg = std::fmod(deg, 360.0f);
  return deg < 0.0f ? deg + 360.0f : deg;
}

std::uint16_t ToCdeg(float deg) {
  long cdeg = std::lround(deg * 100.0f) % 36000;
  if (cdeg < 0) cdeg += 36000;
  return static_cast<std::uint16_t>(cdeg);
}

std::uint16_t ToMm(float range_m) {
  if (!(range_m > 0.0f)) return 0;  // no return, NaN
  const long mm = std::lround(range_m * 1000.0f);
  return mm > kLd06MaxRangeMm ? 0 : static_cast<std::uint16_t>(mm);
}

}  // namespace

std::size_t Ld06PacketCount(std::size_t beam_count) {
  return (beam_count + kLd06PointsPerPacket - 1) / kLd06PointsPerPacket;
}

Ld06EmittedPacket EncodeLd06ScanPacket(const Beam* beams, std::size_t beam_count,
                                       std::int64_t stamp_us, std::size_t index,
                                       const LidarAngleMap& angle_map) {
  constexpr std::size_t kPoints = kLd06PointsPerPacket;
  // The last packet is shifted back to end at the last beam (overlap instead of padding).
  std::size_t first = index * kPoints;
  if (first + kPoints > beam_count) first = beam_count >= kPoints ? beam_count - kPoints : 0;
  const std::size_t real = beam_count - first < kPoints ? beam_count - first : kPoints;

  const float start_deg = DeviceDeg(beams[first], angle_map);
  float step_deg = 0.0f;
  float dt_us = 0.0f;
  if (real >= 2) {
    float span = DeviceDeg(beams[first + real - 1], angle_map) - start_deg;
    if (span < 0.0f) span += 360.0f;
    step_deg = span / static_cast<float>(real - 1);
    dt_us = static_cast<float>(beams[first + real - 1].offset_us - beams[first].offset_us) /
            static_cast<float>(real - 1);
  }
  Ld06Packet p;
  p.start_angle_cdeg = ToCdeg(start_deg);
  p.end_angle_cdeg = ToCdeg(start_deg + step_deg * static_cast<float>(kPoints - 1));
  p.speed_deg_s = dt_us > 0.0f ? static_cast<std::uint16_t>(std::lround(step_deg / dt_us * 1e6f)) : 0;
  const std::int64_t t0_us = stamp_us + beams[first].offset_us;
  p.timestamp_ms = static_cast<std::uint16_t>(((t0_us / 1000) % kLd06TimestampWrapMs + kLd06TimestampWrapMs) %
                                              kLd06TimestampWrapMs);
  for (std::size_t i = 0; i < kPoints; ++i) {
    if (i < real) {
      p.points[i].distance_mm = ToMm(beams[first + i].range_m);
      p.points[i].intensity = p.points[i].distance_mm > 0 ? 200 : 0;
    }
  }
  Ld06EmittedPacket out;
  EncodeLd06Packet(p, out.bytes);
  out.arrival_us = t0_us + std::lround(dt_us * static_cast<float>(kPoints - 1));
  return out;
}

}  // namespace dpcr
