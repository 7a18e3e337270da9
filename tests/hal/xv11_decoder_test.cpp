#include <catch2/catch.hpp>

#include <vector>

#include "golden_packets.hpp"
#include "hal/xv11_decoder.hpp"
#include "lidar_stream_helpers.hpp"

using dpcr::Xv11Decoder;
using dpcr_test::kXv11Packet;

namespace {
std::vector<std::uint8_t> Golden() { return std::vector<std::uint8_t>(kXv11Packet, kXv11Packet + 22); }
}  // namespace

TEST_CASE("xv11 checksum of the golden packet") {
  CHECK(dpcr::Xv11Checksum(kXv11Packet) == 0x608B);
}

TEST_CASE("xv11 decodes readings and flags") {
  Xv11Decoder d;
  const auto packets = dpcr_test::DecodeAll(&d, Golden(), 22);
  REQUIRE(packets.size() == 1);
  const dpcr::Xv11Packet& p = packets[0];
  CHECK(p.index == 0xA0);
  CHECK(p.speed_rpm_x64 == 300 * 64);
  CHECK(p.readings[0].distance_mm == 1000);
  CHECK(p.readings[0].strength == 500);
  CHECK_FALSE(p.readings[0].invalid);
  CHECK(p.readings[1].invalid);
  CHECK(p.readings[2].strength_warning);
  CHECK(p.readings[2].distance_mm == 2000);
  CHECK(p.readings[3].distance_mm == 6500);
  CHECK(d.counters().invalid_readings == 1);
  CHECK(d.counters().strength_warnings == 1);
  CHECK(d.counters().out_of_range == 1);
  const dpcr::LidarPacket lp = dpcr::ToLidarPacket(p, 0);
  CHECK(lp.range_mm[0] == 1000);
  CHECK(lp.range_mm[1] == 0);
  CHECK(lp.range_mm[2] == 2000);
  CHECK(lp.range_mm[3] == 0);
  CHECK(lp.point_dt_us == Approx(60.0e6f / (300.0f * 360.0f)));
  std::uint8_t out[22];
  dpcr::EncodeXv11Packet(p, out);
  CHECK(std::vector<std::uint8_t>(out, out + 22) == Golden());
}

TEST_CASE("xv11 resynchronises and rejects bad checksums") {
  std::vector<std::uint8_t> bytes = {0x12, 0xFA, 0x05, 0xFA, 0xFA};  // bad index after 0xFA
  auto bad = Golden();
  bad[9] ^= 0x10;
  bytes.insert(bytes.end(), bad.begin(), bad.end());
  const auto g = Golden();
  bytes.insert(bytes.end(), g.begin(), g.end());
  bytes.insert(bytes.end(), g.begin(), g.begin() + 10);  // partial packet at the end
  Xv11Decoder d;
  const auto packets = dpcr_test::DecodeAll(&d, bytes, 3);
  CHECK(packets.size() == 1);
  CHECK(d.counters().checksum_failures == 1);
  CHECK(d.counters().resyncs == 1);  // one garbage run: nothing valid in between
  CHECK(d.counters().discarded_bytes == 27);  // 5 leading bytes + the 22 rejected ones
  CHECK(d.counters().packets == 1);
}

TEST_CASE("xv11 full revolution of 90 packets decodes") {
  std::vector<std::uint8_t> bytes;
  for (int i = 0; i < 90; ++i) {
    dpcr::Xv11Packet p;
    p.index = static_cast<std::uint8_t>(0xA0 + i);
    p.speed_rpm_x64 = 250 * 64;
    for (auto& r : p.readings) r.distance_mm = static_cast<std::uint16_t>(500 + i);
    std::uint8_t b[22];
    dpcr::EncodeXv11Packet(p, b);
    bytes.insert(bytes.end(), b, b + 22);
  }
  Xv11Decoder d;
  const auto packets = dpcr_test::DecodeAll(&d, bytes, 64);
  REQUIRE(packets.size() == 90);
  CHECK(packets[89].index == 0xF9);
  CHECK(d.counters().resyncs == 0);
}
