#include "hal/lidar_stream.hpp"

#include <cmath>

namespace dpcr {

LidarStream::LidarStream(const LidarStreamConfig& config)
    : config_(config), assembler_(config.assembler) {}

std::size_t LidarStream::Feed(const std::uint8_t* data, std::size_t size, std::int64_t arrival_us) {
  std::size_t used = 0;
  while (used < size && !assembler_.revolution_ready()) {
    if (config_.kind == LidarKind::kLd06) {
      used += ld06_.Feed(data + used, size - used);
      if (!ld06_.has_packet()) continue;
      const Ld06Packet& p = ld06_.packet();
      LidarPacket lp = ToLidarPacket(p, 0);
      const auto duration_us = static_cast<std::int64_t>(
          std::lround(lp.point_dt_us * static_cast<float>(kLd06PointsPerPacket - 1)));
      lp.stamp_us = config_.timing == LidarTiming::kDeviceClock
                        ? time_base_.ToHostUs(p.timestamp_ms, arrival_us - duration_us)
                        : arrival_us - duration_us;
      OnPacket(lp);
    } else {
      used += xv11_.Feed(data + used, size - used);
      if (!xv11_.has_packet()) continue;
      LidarPacket lp = ToLidarPacket(xv11_.packet(), 0);
      lp.stamp_us = arrival_us - static_cast<std::int64_t>(std::lround(
                                     lp.point_dt_us * static_cast<float>(kXv11ReadingsPerPacket - 1)));
      OnPacket(lp);
    }
  }
  return used;
}

void LidarStream::OnPacket(const LidarPacket& packet) {
  last_packet_us_ = packet.stamp_us;
  static_cast<void>(assembler_.Add(packet));
}

LidarStreamCounters LidarStream::counters() const {
  LidarStreamCounters c;
  if (config_.kind == LidarKind::kLd06) {
    const Ld06Counters& d = ld06_.counters();
    c.packets = d.packets;
    c.bad_packets = d.crc_failures;
    c.resyncs = d.resyncs;
    c.discarded_bytes = d.discarded_bytes;
    c.out_of_range = d.out_of_range;
  } else {
    const Xv11Counters& d = xv11_.counters();
    c.packets = d.packets;
    c.bad_packets = d.checksum_failures;
    c.resyncs = d.resyncs;
    c.discarded_bytes = d.discarded_bytes;
    c.out_of_range = d.out_of_range;
    c.invalid_points = d.invalid_readings;
  }
  const ScanAssemblerCounters& a = assembler_.counters();
  c.revolutions = a.revolutions;
  c.gaps = a.gaps;
  c.dropouts = a.dropouts;
  c.decimated = a.decimated;
  c.partial_dropped = a.partial_dropped;
  return c;
}

}  // namespace dpcr
