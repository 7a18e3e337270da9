// Neato XV-11 lidar UART packet decoder and encoder (115200 8N1).
// Packet (22 bytes, little-endian): 0xFA start, index 0xA0..0xF9 (packet i covers degrees
// 4i..4i+3), speed (rpm x 64, u16), 4 readings of 4 bytes {distance 14 bits with bit 15 =
// invalid data and bit 14 = strength warning, signal strength u16}, checksum u16 over the
// first 20 bytes (the algorithm of the XV-11 hacking wiki, see Xv11Checksum).
#pragma once

#include <cstddef>
#include <cstdint>

#include "hal/lidar_packet.hpp"

namespace dpcr {

constexpr std::uint8_t kXv11Start = 0xFA;
constexpr std::uint8_t kXv11FirstIndex = 0xA0;
constexpr std::uint8_t kXv11LastIndex = 0xF9;
constexpr int kXv11ReadingsPerPacket = 4;
constexpr std::size_t kXv11PacketBytes = 22;
constexpr std::uint16_t kXv11MaxRangeMm = 6000;

struct Xv11Reading {
  std::uint16_t distance_mm = 0;  // 14 bits
  bool invalid = false;           // bit 15: no valid distance
  bool strength_warning = false;  // bit 14: reflectivity lower than expected
  std::uint16_t strength = 0;
};

struct Xv11Packet {
  std::uint8_t index = kXv11FirstIndex;
  std::uint16_t speed_rpm_x64 = 0;
  Xv11Reading readings[kXv11ReadingsPerPacket];
};

struct Xv11Counters {
  std::uint32_t packets = 0;
  std::uint32_t checksum_failures = 0;
  std::uint32_t resyncs = 0;
  std::uint32_t discarded_bytes = 0;
  std::uint32_t invalid_readings = 0;     // bit 15 set
  std::uint32_t strength_warnings = 0;    // bit 14 set
  std::uint32_t out_of_range = 0;         // readings past kXv11MaxRangeMm (given as no return)
};

// The checksum of the first 20 bytes of a packet.
std::uint16_t Xv11Checksum(const std::uint8_t* first20);

class Xv11Decoder {
 public:
  // As Ld06Decoder::Feed: stops after a complete packet; returns bytes consumed.
  std::size_t Feed(const std::uint8_t* data, std::size_t size);
  bool has_packet() const { return has_packet_; }
  const Xv11Packet& packet() const { return packet_; }
  const Xv11Counters& counters() const { return counters_; }
  void Reset();

 private:
  void PushByte(std::uint8_t byte);
  void OnPacketBytes();
  void Discard();

  std::uint8_t buffer_[kXv11PacketBytes] = {};
  std::size_t fill_ = 0;
  bool in_garbage_ = false;
  bool has_packet_ = false;
  Xv11Packet packet_;
  Xv11Counters counters_;
};

void EncodeXv11Packet(const Xv11Packet& packet, std::uint8_t out[kXv11PacketBytes]);

// The device-independent form. The XV-11 sends no timestamp: `stamp_us` is the host time of
// reading 0 (e.g. arrival time minus the packet's duration). Invalid readings become 0.
LidarPacket ToLidarPacket(const Xv11Packet& packet, std::int64_t stamp_us);

}  // namespace dpcr
