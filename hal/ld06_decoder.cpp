#include "hal/ld06_decoder.hpp"

#include <cstring>

#include "hal/byte_order.hpp"
#include "hal/crc8.hpp"

namespace dpcr {
namespace {

constexpr std::uint16_t kFullTurnCdeg = 36000;
// The LD06 turns at 10 Hz nominal (3600 deg/s); anything past 30 Hz is a corrupted field.
constexpr std::uint16_t kMaxSpeedDegS = 10800;

}  // namespace

void Ld06Decoder::Reset() {
  fill_ = 0;
  in_garbage_ = false;
  has_packet_ = false;
}

void Ld06Decoder::Discard(std::size_t n) {
  if (!in_garbage_) ++counters_.resyncs;
  in_garbage_ = true;
  counters_.discarded_bytes += static_cast<std::uint32_t>(n);
}

std::size_t Ld06Decoder::Feed(const std::uint8_t* data, std::size_t size) {
  has_packet_ = false;
  std::size_t used = 0;
  while (used < size && !has_packet_) PushByte(data[used++]);
  return used;
}

void Ld06Decoder::PushByte(std::uint8_t byte) {
  if (fill_ == 0) {
    if (byte != kLd06Header) {
      Discard(1);
      return;
    }
  } else if (fill_ == 1 && byte != kLd06VerLen) {
    // The header byte was garbage; this byte may itself start a packet.
    Discard(1);
    fill_ = 0;
    PushByte(byte);
    return;
  }
  buffer_[fill_++] = byte;
  if (fill_ == kLd06PacketBytes) OnPacketBytes();
}

void Ld06Decoder::OnPacketBytes() {
  const bool crc_ok = Crc8Ld(buffer_, kLd06PacketBytes - 1) == buffer_[kLd06PacketBytes - 1];
  Ld06Packet p;
  if (crc_ok) {
    p.speed_deg_s = LoadLe16(&buffer_[2]);
    p.start_angle_cdeg = LoadLe16(&buffer_[4]);
    for (int i = 0; i < kLd06PointsPerPacket; ++i) {
      const std::uint8_t* q = &buffer_[6 + 3 * i];
      p.points[i].distance_mm = LoadLe16(q);
      p.points[i].intensity = q[2];
    }
    p.end_angle_cdeg = LoadLe16(&buffer_[42]);
    p.timestamp_ms = LoadLe16(&buffer_[44]);
  }
  const bool in_range = crc_ok && p.start_angle_cdeg < kFullTurnCdeg &&
                        p.end_angle_cdeg < kFullTurnCdeg && p.speed_deg_s <= kMaxSpeedDegS &&
                        p.timestamp_ms < kLd06TimestampWrapMs;
  if (in_range) {
    packet_ = p;
    has_packet_ = true;
    in_garbage_ = false;
    ++counters_.packets;
    for (const Ld06Point& point : packet_.points) {
      if (point.distance_mm > kLd06MaxRangeMm) {
        ++counters_.out_of_range;
        break;
      }
    }
    fill_ = 0;
    return;
  }
  if (crc_ok) {
    ++counters_.out_of_range;
  } else {
    ++counters_.crc_failures;
  }
  // Re-scan the rejected bytes after the header: a real packet may start inside them.
  std::uint8_t rest[kLd06PacketBytes - 1];
  const std::size_t rest_size = kLd06PacketBytes - 1;
  std::memcpy(rest, &buffer_[1], rest_size);
  fill_ = 0;
  Discard(1);
  for (std::size_t i = 0; i < rest_size; ++i) PushByte(rest[i]);
}

void EncodeLd06Packet(const Ld06Packet& packet, std::uint8_t out[kLd06PacketBytes]) {
  out[0] = kLd06Header;
  out[1] = kLd06VerLen;
  StoreLe16(&out[2], packet.speed_deg_s);
  StoreLe16(&out[4], packet.start_angle_cdeg);
  for (int i = 0; i < kLd06PointsPerPacket; ++i) {
    std::uint8_t* q = &out[6 + 3 * i];
    StoreLe16(q, packet.points[i].distance_mm);
    q[2] = packet.points[i].intensity;
  }
  StoreLe16(&out[42], packet.end_angle_cdeg);
  StoreLe16(&out[44], packet.timestamp_ms);
  out[46] = Crc8Ld(out, kLd06PacketBytes - 1);
}

LidarPacket ToLidarPacket(const Ld06Packet& packet, std::int64_t stamp_us) {
  LidarPacket out;
  out.stamp_us = stamp_us;
  out.start_deg = static_cast<float>(packet.start_angle_cdeg) * 0.01f;
  // The end angle may have wrapped past 360 within the packet.
  const int span_cdeg = (packet.end_angle_cdeg + kFullTurnCdeg - packet.start_angle_cdeg) % kFullTurnCdeg;
  out.step_deg = static_cast<float>(span_cdeg) * 0.01f / static_cast<float>(kLd06PointsPerPacket - 1);
  out.point_dt_us = packet.speed_deg_s > 0
                        ? out.step_deg / static_cast<float>(packet.speed_deg_s) * 1e6f
                        : 0.0f;
  out.count = kLd06PointsPerPacket;
  for (int i = 0; i < kLd06PointsPerPacket; ++i) {
    const std::uint16_t d = packet.points[i].distance_mm;
    out.range_mm[i] = d > kLd06MaxRangeMm ? 0 : d;
  }
  return out;
}

std::int64_t Ld06TimeBase::ToHostUs(std::uint16_t device_ms, std::int64_t host_arrival_us) {
  if (!started_) {
    started_ = true;
    unwrapped_ms_ = device_ms;
  } else {
    int delta = static_cast<int>(device_ms) - static_cast<int>(last_ms_);
    if (delta < -kLd06TimestampWrapMs / 2) delta += kLd06TimestampWrapMs;
    unwrapped_ms_ += delta;
  }
  last_ms_ = device_ms;
  return clock_.ToHostUs(unwrapped_ms_ * 1000, host_arrival_us);
}

}  // namespace dpcr
