// Scan -> LD06 packets, for device-file emission (dpcr-sim --emit-device) and tests.
// Beams must be in time order with device angles increasing (see LidarAngleMap). Packets of
// 12 beams; a last packet with fewer beams re-sends the previous beams to fill 12 (the
// ScanAssembler drops points that do not advance the angle, so nothing is duplicated).
// The rotation speed is taken from the beams' time offsets (0 when they are all equal).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/geometry/scan.hpp"
#include "hal/ld06_decoder.hpp"
#include "hal/scan_assembler.hpp"

namespace dpcr {

struct Ld06EmittedPacket {
  std::uint8_t bytes[kLd06PacketBytes] = {};
  std::int64_t arrival_us = 0;  // host time of the packet's last point: when a UART delivers it
};

// Packets needed for `beam_count` beams.
std::size_t Ld06PacketCount(std::size_t beam_count);

// Encodes packet `index` (< Ld06PacketCount) of the beams of a scan stamped `stamp_us`.
// Ranges are rounded to mm (past 12 m or no return: 0), angles to 0.01 degree.
Ld06EmittedPacket EncodeLd06ScanPacket(const Beam* beams, std::size_t beam_count,
                                       std::int64_t stamp_us, std::size_t index,
                                       const LidarAngleMap& angle_map);

// Converts a whole scan; calls sink(const Ld06EmittedPacket&) for each packet, in order.
template <int N, typename Sink>
void EmitLd06Revolution(const Scan<N>& scan, const LidarAngleMap& angle_map, Sink&& sink) {
  const std::size_t count = Ld06PacketCount(scan.beams.size());
  for (std::size_t k = 0; k < count; ++k) {
    sink(EncodeLd06ScanPacket(scan.beams.data(), scan.beams.size(), scan.stamp_us, k, angle_map));
  }
}

}  // namespace dpcr
