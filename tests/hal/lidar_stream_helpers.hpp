// Test helpers: synthetic LD06 / XV-11 byte streams of a turning lidar, and decode-all loops.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "hal/ld06_decoder.hpp"
#include "hal/lidar_packet.hpp"
#include "hal/xv11_decoder.hpp"

namespace dpcr_test {

// Range (mm) of a synthetic room at device angle `deg`: smooth, never 0.
std::uint16_t RoomRangeMm(float deg);

// LD06 packets covering `revolutions` turns at `speed_deg_s`, starting at angle 0 and
// time `start_ms`; 12 points per packet, packet spacing as the real sensor (~0.8 deg at 10 Hz).
std::vector<dpcr::Ld06Packet> MakeLd06Packets(int revolutions, std::uint16_t speed_deg_s,
                                              std::uint16_t start_ms, float start_deg = 0.0f);
std::vector<std::uint8_t> EncodeAll(const std::vector<dpcr::Ld06Packet>& packets);

// A realistic noisy capture: starts mid-packet, 10 Hz then 6 Hz, line noise (random garbage
// bursts, flipped bits) and a truncated packet at the end. Counts what was injected.
struct NoisyCapture {
  std::vector<std::uint8_t> bytes;
  int good_packets = 0;       // intact packets in the stream
  int corrupted_packets = 0;  // packets with a flipped bit
  int garbage_bursts = 0;
};
NoisyCapture MakeNoisyLd06Capture(unsigned seed);

// Decodes everything, feeding in chunks of `chunk` bytes (Ld06Decoder or Xv11Decoder).
template <typename Decoder>
auto DecodeAll(Decoder* decoder, const std::vector<std::uint8_t>& bytes, std::size_t chunk) {
  std::vector<std::decay_t<decltype(decoder->packet())>> out;
  for (std::size_t at = 0; at < bytes.size(); at += chunk) {
    const std::size_t n = bytes.size() - at < chunk ? bytes.size() - at : chunk;
    std::size_t used = 0;
    while (used < n) {
      used += decoder->Feed(bytes.data() + at + used, n - used);
      if (decoder->has_packet()) out.push_back(decoder->packet());
    }
  }
  return out;
}

}  // namespace dpcr_test
