#include "lidar_stream_helpers.hpp"

#include <cmath>
#include <random>

namespace dpcr_test {

using dpcr::Ld06Packet;

std::uint16_t RoomRangeMm(float deg) {
  return static_cast<std::uint16_t>(2000.0 + 800.0 * std::sin(static_cast<double>(deg) * 0.05));
}

std::vector<Ld06Packet> MakeLd06Packets(int revolutions, std::uint16_t speed_deg_s,
                                        std::uint16_t start_ms, float start_deg) {
  // The LD06 samples at 4500 Hz: point spacing = speed / 4500.
  const double step = speed_deg_s / 4500.0;
  std::vector<Ld06Packet> out;
  double angle = static_cast<double>(start_deg);
  double t_ms = start_ms;
  const double end = angle + 360.0 * revolutions;
  while (angle + 11 * step < end) {
    Ld06Packet p;
    p.speed_deg_s = speed_deg_s;
    p.start_angle_cdeg = static_cast<std::uint16_t>(std::lround(std::fmod(angle, 360.0) * 100.0) % 36000);
    p.end_angle_cdeg =
        static_cast<std::uint16_t>(std::lround(std::fmod(angle + 11 * step, 360.0) * 100.0) % 36000);
    p.timestamp_ms = static_cast<std::uint16_t>(std::lround(t_ms) % 30000);
    for (int i = 0; i < 12; ++i) {
      p.points[i].distance_mm = RoomRangeMm(static_cast<float>(std::fmod(angle + i * step, 360.0)));
      p.points[i].intensity = 200;
    }
    out.push_back(p);
    angle += 12 * step;
    t_ms += 12.0 / 4.5;
  }
  return out;
}

std::vector<std::uint8_t> EncodeAll(const std::vector<Ld06Packet>& packets) {
  std::vector<std::uint8_t> bytes;
  for (const Ld06Packet& p : packets) {
    std::uint8_t b[dpcr::kLd06PacketBytes];
    dpcr::EncodeLd06Packet(p, b);
    bytes.insert(bytes.end(), b, b + sizeof(b));
  }
  return bytes;
}

NoisyCapture MakeNoisyLd06Capture(unsigned seed) {
  std::mt19937 rng(seed);
  NoisyCapture c;
  std::vector<Ld06Packet> packets = MakeLd06Packets(3, 3600, 100);
  const std::vector<Ld06Packet> slow = MakeLd06Packets(2, 2160, 400);
  packets.insert(packets.end(), slow.begin(), slow.end());
  // Starts 20 bytes into a packet (the capture began mid-packet).
  std::vector<std::uint8_t> first = EncodeAll({packets[0]});
  c.bytes.assign(first.begin() + 20, first.end());
  std::uniform_int_distribution<int> pct(0, 99);
  std::uniform_int_distribution<int> byte(0, 255);
  for (std::size_t k = 1; k + 1 < packets.size(); ++k) {
    std::vector<std::uint8_t> b = EncodeAll({packets[k]});
    const int roll = pct(rng);
    if (roll < 3) {
      // Line noise burst between packets (may contain 0x54 bytes).
      const int n = 1 + pct(rng) % 30;
      for (int i = 0; i < n; ++i) c.bytes.push_back(static_cast<std::uint8_t>(byte(rng)));
      ++c.garbage_bursts;
    }
    if (roll >= 3 && roll < 6) {
      // One flipped bit inside the packet body: the CRC must reject it.
      const std::size_t at = 2 + static_cast<std::size_t>(pct(rng)) % 44;
      b[at] = static_cast<std::uint8_t>(b[at] ^ (1u << (pct(rng) % 8)));
      ++c.corrupted_packets;
    } else {
      ++c.good_packets;
    }
    c.bytes.insert(c.bytes.end(), b.begin(), b.end());
  }
  // Ends 30 bytes into the last packet.
  std::vector<std::uint8_t> last = EncodeAll({packets.back()});
  c.bytes.insert(c.bytes.end(), last.begin(), last.begin() + 30);
  return c;
}


}  // namespace dpcr_test
