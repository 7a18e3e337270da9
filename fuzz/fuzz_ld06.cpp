// LD06 UART bytes -> Ld06Decoder, fed in chunks whose sizes the input chooses: no crash, every
// byte consumed, every accepted packet in range, and an accepted packet re-encodes to 47 bytes
// that decode to the same packet.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz/fuzz_check.hpp"
#include "hal/ld06_decoder.hpp"

namespace {

void CheckPacket(const dpcr::Ld06Packet& p) {
  FUZZ_CHECK(p.start_angle_cdeg < 36000 && p.end_angle_cdeg < 36000);
  FUZZ_CHECK(p.timestamp_ms < dpcr::kLd06TimestampWrapMs);
  std::uint8_t bytes[dpcr::kLd06PacketBytes];
  dpcr::EncodeLd06Packet(p, bytes);
  dpcr::Ld06Decoder again;
  FUZZ_CHECK(again.Feed(bytes, sizeof(bytes)) == sizeof(bytes));
  FUZZ_CHECK(again.has_packet());
  const dpcr::Ld06Packet& q = again.packet();
  FUZZ_CHECK(q.speed_deg_s == p.speed_deg_s && q.start_angle_cdeg == p.start_angle_cdeg &&
             q.end_angle_cdeg == p.end_angle_cdeg && q.timestamp_ms == p.timestamp_ms);
  for (int i = 0; i < dpcr::kLd06PointsPerPacket; ++i) {
    FUZZ_CHECK(q.points[i].distance_mm == p.points[i].distance_mm && q.points[i].intensity == p.points[i].intensity);
  }
  const dpcr::LidarPacket lp = dpcr::ToLidarPacket(p, 1000000);
  FUZZ_CHECK(lp.count == dpcr::kLd06PointsPerPacket);
  FUZZ_CHECK(lp.step_deg >= 0.0f && lp.step_deg < 360.0f && lp.point_dt_us >= 0.0f);
  for (int i = 0; i < lp.count; ++i) FUZZ_CHECK(lp.range_mm[i] <= dpcr::kLd06MaxRangeMm);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // The first byte: the chunk size (1..256) the rest arrives in, as a UART read would split it.
  const std::size_t chunk = static_cast<std::size_t>(data[0]) + 1;
  ++data;
  --size;
  dpcr::Ld06Decoder decoder;
  dpcr::Ld06TimeBase time_base;
  std::int64_t arrival_us = 0;
  std::uint32_t packets = 0;
  for (std::size_t offset = 0; offset < size;) {
    const std::size_t n = size - offset < chunk ? size - offset : chunk;
    std::size_t used = 0;
    while (used < n) {
      const std::size_t step = decoder.Feed(data + offset + used, n - used);
      FUZZ_CHECK(step > 0 && step <= n - used);
      used += step;
      if (decoder.has_packet()) {
        ++packets;
        CheckPacket(decoder.packet());
        (void)time_base.ToHostUs(decoder.packet().timestamp_ms, arrival_us);
      }
    }
    offset += n;
    arrival_us += 2000;
  }
  const dpcr::Ld06Counters& c = decoder.counters();
  FUZZ_CHECK(c.packets == packets);
  FUZZ_CHECK(c.discarded_bytes <= size);
  FUZZ_CHECK(static_cast<std::uint64_t>(c.packets) * dpcr::kLd06PacketBytes <= size);
  return 0;
}
