// XV-11 UART bytes -> Xv11Decoder, in chunks the input chooses: no crash, every byte consumed,
// accepted packets with a valid index, re-encoded to the same 22 bytes' meaning.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_check.hpp"
#include "hal/xv11_decoder.hpp"

namespace {

void CheckPacket(const dpcr::Xv11Packet& p) {
  FUZZ_CHECK(p.index >= dpcr::kXv11FirstIndex && p.index <= dpcr::kXv11LastIndex);
  std::uint8_t bytes[dpcr::kXv11PacketBytes];
  dpcr::EncodeXv11Packet(p, bytes);
  dpcr::Xv11Decoder again;
  FUZZ_CHECK(again.Feed(bytes, sizeof(bytes)) == sizeof(bytes));
  FUZZ_CHECK(again.has_packet());
  const dpcr::Xv11Packet& q = again.packet();
  FUZZ_CHECK(q.index == p.index && q.speed_rpm_x64 == p.speed_rpm_x64);
  for (int i = 0; i < dpcr::kXv11ReadingsPerPacket; ++i) {
    FUZZ_CHECK(q.readings[i].distance_mm == p.readings[i].distance_mm && q.readings[i].invalid == p.readings[i].invalid &&
               q.readings[i].strength_warning == p.readings[i].strength_warning &&
               q.readings[i].strength == p.readings[i].strength);
  }
  const dpcr::LidarPacket lp = dpcr::ToLidarPacket(p, 1000000);
  FUZZ_CHECK(lp.count == dpcr::kXv11ReadingsPerPacket);
  FUZZ_CHECK(lp.start_deg >= 0.0f && lp.start_deg < 360.0f && lp.point_dt_us >= 0.0f);
  for (int i = 0; i < lp.count; ++i) FUZZ_CHECK(lp.range_mm[i] <= dpcr::kXv11MaxRangeMm);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = static_cast<std::size_t>(data[0]) + 1;
  ++data;
  --size;
  dpcr::Xv11Decoder decoder;
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
      }
    }
    offset += n;
  }
  FUZZ_CHECK(decoder.counters().packets == packets);
  FUZZ_CHECK(decoder.counters().discarded_bytes <= size);
  return 0;
}
