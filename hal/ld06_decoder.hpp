// LDROBOT LD06/LD19 UART packet decoder and encoder (230400 8N1).
// Packet (47 bytes, little-endian): 0x54 header, 0x2C ver/len (12 points), speed (deg/s, u16),
// start angle (0.01 deg, u16), 12 x {distance mm u16, intensity u8}, end angle (0.01 deg, u16),
// timestamp (ms, u16, wraps at 30000), CRC-8 (hal/crc8.hpp) over the 46 bytes before it.
// The decoder is a byte-wise state machine: it resynchronises on the next 0x54 after garbage or
// a CRC failure (re-scanning the rejected bytes, so a packet hidden inside is not lost).
#pragma once

#include <cstddef>
#include <cstdint>

#include "hal/device_time_base.hpp"
#include "hal/lidar_packet.hpp"

namespace dpcr {

constexpr std::uint8_t kLd06Header = 0x54;
constexpr std::uint8_t kLd06VerLen = 0x2C;
constexpr int kLd06PointsPerPacket = 12;
constexpr std::size_t kLd06PacketBytes = 47;
constexpr std::uint16_t kLd06TimestampWrapMs = 30000;
constexpr std::uint16_t kLd06MaxRangeMm = 12000;  // LD06 datasheet range 0.02..12 m

struct Ld06Point {
  std::uint16_t distance_mm = 0;
  std::uint8_t intensity = 0;
};

struct Ld06Packet {
  std::uint16_t speed_deg_s = 0;
  std::uint16_t start_angle_cdeg = 0;  // 0.01 degree
  std::uint16_t end_angle_cdeg = 0;
  std::uint16_t timestamp_ms = 0;
  Ld06Point points[kLd06PointsPerPacket];
};

struct Ld06Counters {
  std::uint32_t packets = 0;          // accepted packets
  std::uint32_t crc_failures = 0;
  std::uint32_t resyncs = 0;          // runs of discarded bytes before a header
  std::uint32_t discarded_bytes = 0;
  std::uint32_t out_of_range = 0;     // packets with a bad angle/speed (rejected) or points past max range (zeroed)
};

class Ld06Decoder {
 public:
  // Consumes bytes until one packet is complete (then has_packet() is true) or all are used.
  // Returns the number of bytes consumed; call again with the rest.
  std::size_t Feed(const std::uint8_t* data, std::size_t size);
  bool has_packet() const { return has_packet_; }
  // The packet completed by the last Feed; valid until the next Feed.
  const Ld06Packet& packet() const { return packet_; }
  const Ld06Counters& counters() const { return counters_; }
  void Reset();

 private:
  void PushByte(std::uint8_t byte);
  void OnPacketBytes();
  void Discard(std::size_t n);

  std::uint8_t buffer_[kLd06PacketBytes] = {};
  std::size_t fill_ = 0;
  bool in_garbage_ = false;
  bool has_packet_ = false;
  Ld06Packet packet_;
  Ld06Counters counters_;
};

// Writes the 47 bytes of `packet` (CRC included) to `out`.
void EncodeLd06Packet(const Ld06Packet& packet, std::uint8_t out[kLd06PacketBytes]);

// The device-independent form; `stamp_us` is the host time of point 0. Points past the
// LD06 range are given as 0 (no return).
LidarPacket ToLidarPacket(const Ld06Packet& packet, std::int64_t stamp_us);

// Maps the LD06's 16-bit millisecond timestamp (wrapping at 30000) to host microseconds: each
// packet's stamp is unwrapped against the last, then mapped as below.
class Ld06TimeBase {
 public:
  // The packet's millisecond stamp (15 bits, wrapping) in host time: unwrapped, then mapped by
  // the minimum-latency, drift-following estimate of hal/device_time_base.hpp (a late packet,
  // a starved reader, the lidar's crystal drifting: none moves the stamps).
  std::int64_t ToHostUs(std::uint16_t device_ms, std::int64_t host_arrival_us);
  void Reset() { *this = Ld06TimeBase(); }

 private:
  bool started_ = false;
  std::uint16_t last_ms_ = 0;
  std::int64_t unwrapped_ms_ = 0;
  DeviceTimeBase clock_;
};

}  // namespace dpcr
