#include "hal/xv11_decoder.hpp"

#include <cstring>

#include "hal/byte_order.hpp"

namespace dpcr {

std::uint16_t Xv11Checksum(const std::uint8_t* first20) {
  std::uint32_t chk32 = 0;
  for (int i = 0; i < 10; ++i) {
    chk32 = (chk32 << 1) + LoadLe16(&first20[2 * i]);
  }
  std::uint32_t checksum = (chk32 & 0x7FFFu) + (chk32 >> 15);
  return static_cast<std::uint16_t>(checksum & 0x7FFFu);
}

void Xv11Decoder::Reset() {
  fill_ = 0;
  in_garbage_ = false;
  has_packet_ = false;
}

void Xv11Decoder::Discard() {
  if (!in_garbage_) ++counters_.resyncs;
  in_garbage_ = true;
  ++counters_.discarded_bytes;
}

std::size_t Xv11Decoder::Feed(const std::uint8_t* data, std::size_t size) {
  has_packet_ = false;
  std::size_t used = 0;
  while (used < size && !has_packet_) PushByte(data[used++]);
  return used;
}

void Xv11Decoder::PushByte(std::uint8_t byte) {
  if (fill_ == 0) {
    if (byte != kXv11Start) {
      Discard();
      return;
    }
  } else if (fill_ == 1 && (byte < kXv11FirstIndex || byte > kXv11LastIndex)) {
    Discard();
    fill_ = 0;
    PushByte(byte);
    return;
  }
  buffer_[fill_++] = byte;
  if (fill_ == kXv11PacketBytes) OnPacketBytes();
}

void Xv11Decoder::OnPacketBytes() {
  if (Xv11Checksum(buffer_) != LoadLe16(&buffer_[20])) {
    ++counters_.checksum_failures;
    std::uint8_t rest[kXv11PacketBytes - 1];
    std::memcpy(rest, &buffer_[1], sizeof(rest));
    fill_ = 0;
    Discard();
    for (std::uint8_t b : rest) PushByte(b);
    return;
  }
  packet_.index = buffer_[1];
  packet_.speed_rpm_x64 = LoadLe16(&buffer_[2]);
  for (int i = 0; i < kXv11ReadingsPerPacket; ++i) {
    const std::uint8_t* q = &buffer_[4 + 4 * i];
    const std::uint16_t raw = LoadLe16(q);
    Xv11Reading& r = packet_.readings[i];
    r.distance_mm = static_cast<std::uint16_t>(raw & 0x3FFFu);
    r.invalid = (raw & 0x8000u) != 0;
    r.strength_warning = (raw & 0x4000u) != 0;
    r.strength = LoadLe16(q + 2);
    if (r.invalid) ++counters_.invalid_readings;
    if (r.strength_warning) ++counters_.strength_warnings;
    if (!r.invalid && r.distance_mm > kXv11MaxRangeMm) ++counters_.out_of_range;
  }
  ++counters_.packets;
  has_packet_ = true;
  in_garbage_ = false;
  fill_ = 0;
}

void EncodeXv11Packet(const Xv11Packet& packet, std::uint8_t out[kXv11PacketBytes]) {
  out[0] = kXv11Start;
  out[1] = packet.index;
  StoreLe16(&out[2], packet.speed_rpm_x64);
  for (int i = 0; i < kXv11ReadingsPerPacket; ++i) {
    const Xv11Reading& r = packet.readings[i];
    auto raw = static_cast<std::uint16_t>(r.distance_mm & 0x3FFFu);
    if (r.invalid) raw = static_cast<std::uint16_t>(raw | 0x8000u);
    if (r.strength_warning) raw = static_cast<std::uint16_t>(raw | 0x4000u);
    StoreLe16(&out[4 + 4 * i], raw);
    StoreLe16(&out[6 + 4 * i], r.strength);
  }
  StoreLe16(&out[20], Xv11Checksum(out));
}

LidarPacket ToLidarPacket(const Xv11Packet& packet, std::int64_t stamp_us) {
  LidarPacket out;
  out.stamp_us = stamp_us;
  out.start_deg = static_cast<float>((packet.index - kXv11FirstIndex) * kXv11ReadingsPerPacket);
  out.step_deg = 1.0f;
  const float rpm = static_cast<float>(packet.speed_rpm_x64) / 64.0f;
  out.point_dt_us = rpm > 0.0f ? 60.0e6f / (rpm * 360.0f) : 0.0f;
  out.count = kXv11ReadingsPerPacket;
  for (int i = 0; i < kXv11ReadingsPerPacket; ++i) {
    const Xv11Reading& r = packet.readings[i];
    out.range_mm[i] = (r.invalid || r.distance_mm > kXv11MaxRangeMm) ? 0 : r.distance_mm;
  }
  return out;
}

}  // namespace dpcr
