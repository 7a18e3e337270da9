// Scan -> Neato XV-11 packets, for device-file emission (dpcr-sim --lidar xv11 --emit-device) and
// tests; the packet format is xv11_decoder.hpp's (EncodeXv11Packet). A revolution is 90 packets
// of 4 readings at 1 degree, indices 0xA0..0xF9. Each beam goes to the reading of its nearest
// whole device degree (a later beam on the same degree wins); degrees without a beam and beams
// without a return (or past 6 m) are sent with the invalid-data flag, as the sensor does.
// Beams must be in time order with device angles increasing from 0 (see LidarAngleMap).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/geometry/scan.hpp"
#include "hal/scan_assembler.hpp"
#include "hal/xv11_decoder.hpp"

namespace dpcr {

constexpr int kXv11PacketsPerRevolution = 90;

struct Xv11EmittedPacket {
  std::uint8_t bytes[kXv11PacketBytes] = {};
  std::int64_t arrival_us = 0;  // host time of the packet's last reading
};

// All packets of one revolution of `rate_hz` (the speed field; readings 1/360 of a turn apart)
// whose first reading is at `stamp_us`.
void EncodeXv11Revolution(const Beam* beams, std::size_t beam_count, std::int64_t stamp_us,
                          const LidarAngleMap& angle_map, float rate_hz,
                          Xv11EmittedPacket (&out)[kXv11PacketsPerRevolution]);

}  // namespace dpcr
