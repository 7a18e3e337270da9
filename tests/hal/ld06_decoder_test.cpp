#include <catch2/catch.hpp>

#include <vector>

#include "golden_packets.hpp"
#include "hal/ld06_decoder.hpp"
#include "lidar_stream_helpers.hpp"

using dpcr::Ld06Decoder;
using dpcr::Ld06Packet;
using dpcr_test::kLd06DatasheetPacket;

namespace {
std::vector<std::uint8_t> Golden() {
  return std::vector<std::uint8_t>(kLd06DatasheetPacket, kLd06DatasheetPacket + 47);
}
}  // namespace

TEST_CASE("ld06 decodes the datasheet packet fields") {
  Ld06Decoder d;
  const auto packets = dpcr_test::DecodeAll(&d, Golden(), 47);
  REQUIRE(packets.size() == 1);
  const Ld06Packet& p = packets[0];
  CHECK(p.speed_deg_s == 0x0868);
  CHECK(p.start_angle_cdeg == 0x7EAB);
  CHECK(p.end_angle_cdeg == 0x82BE);
  CHECK(p.timestamp_ms == 0x1A3A);
  CHECK(p.points[0].distance_mm == 0x00E0);
  CHECK(p.points[0].intensity == 0xE4);
  CHECK(p.points[11].distance_mm == 0x00C0);
  CHECK(d.counters().packets == 1);
  CHECK(d.counters().crc_failures == 0);
  CHECK(d.counters().resyncs == 0);
}

TEST_CASE("ld06 decodes byte by byte the same as in one chunk") {
  const auto bytes = dpcr_test::EncodeAll(dpcr_test::MakeLd06Packets(1, 3600, 0));
  Ld06Decoder a;
  Ld06Decoder b;
  const auto pa = dpcr_test::DecodeAll(&a, bytes, 1);
  const auto pb = dpcr_test::DecodeAll(&b, bytes, bytes.size());
  REQUIRE(pa.size() == pb.size());
  REQUIRE(pa.size() > 30);
  for (std::size_t i = 0; i < pa.size(); ++i) CHECK(pa[i].start_angle_cdeg == pb[i].start_angle_cdeg);
}

TEST_CASE("ld06 encoder reproduces the datasheet bytes") {
  Ld06Decoder d;
  const auto packets = dpcr_test::DecodeAll(&d, Golden(), 47);
  REQUIRE(packets.size() == 1);
  std::uint8_t out[47];
  dpcr::EncodeLd06Packet(packets[0], out);
  CHECK(std::vector<std::uint8_t>(out, out + 47) == Golden());
}

TEST_CASE("ld06 resynchronises after garbage and a false header") {
  std::vector<std::uint8_t> bytes = {0x00, 0x54, 0x11, 0x54, 0x54, 0x2C, 0x01, 0x02};
  const auto g = Golden();
  bytes.insert(bytes.end(), g.begin(), g.end());
  bytes.insert(bytes.end(), g.begin(), g.end());
  Ld06Decoder d;
  const auto packets = dpcr_test::DecodeAll(&d, bytes, 5);
  CHECK(packets.size() == 2);
  // The false header 0x54 0x2C locks for 47 bytes and fails its CRC; the real packet inside is kept.
  CHECK(d.counters().crc_failures == 1);
  CHECK(d.counters().resyncs >= 1);
  CHECK(d.counters().discarded_bytes == 8);
}

TEST_CASE("ld06 rejects a packet with any single flipped bit") {
  for (int byte = 2; byte < 47; ++byte) {
    for (int bit = 0; bit < 8; bit += 3) {
      auto bytes = Golden();
      bytes[static_cast<std::size_t>(byte)] ^= static_cast<std::uint8_t>(1u << bit);
      const auto g = Golden();
      bytes.insert(bytes.end(), g.begin(), g.end());
      Ld06Decoder d;
      const auto packets = dpcr_test::DecodeAll(&d, bytes, 47);
      REQUIRE(packets.size() == 1);  // only the intact second packet
      CHECK(d.counters().crc_failures == 1);
    }
  }
}

TEST_CASE("ld06 counts out-of-range angles and distances") {
  Ld06Packet p;
  p.speed_deg_s = 3600;
  p.start_angle_cdeg = 36500;  // past a full turn
  p.end_angle_cdeg = 100;
  std::uint8_t both[94];
  dpcr::EncodeLd06Packet(p, both);
  Ld06Packet q;
  q.speed_deg_s = 3600;
  q.start_angle_cdeg = 100;
  q.end_angle_cdeg = 1000;
  q.points[3].distance_mm = 15000;  // past 12 m
  dpcr::EncodeLd06Packet(q, both + 47);
  const std::vector<std::uint8_t> bytes(both, both + 94);
  Ld06Decoder d;
  const auto packets = dpcr_test::DecodeAll(&d, bytes, 47);
  REQUIRE(packets.size() == 1);
  CHECK(d.counters().out_of_range == 2);
  CHECK(d.counters().crc_failures == 0);
  const dpcr::LidarPacket lp = dpcr::ToLidarPacket(packets[0], 0);
  CHECK(lp.range_mm[3] == 0);  // given as no return
}

TEST_CASE("ld06 packet to lidar packet handles the wrap inside a packet") {
  Ld06Packet p;
  p.speed_deg_s = 3600;
  p.start_angle_cdeg = 35900;
  p.end_angle_cdeg = 0 + 110 - 100;  // 359.00 + 11 x 0.1 = 360.10 -> 0.10
  const dpcr::LidarPacket lp = dpcr::ToLidarPacket(p, 1000);
  CHECK(lp.start_deg == Approx(359.0f));
  CHECK(lp.step_deg == Approx(0.1f).margin(1e-5));
  CHECK(lp.point_dt_us == Approx(0.1f / 3600.0f * 1e6f));
}

TEST_CASE("ld06 time base unwraps the 30 s millisecond counter") {
  dpcr::Ld06TimeBase tb;
  CHECK(tb.ToHostUs(29990, 5000000) == 5000000);
  // Later packets arrive later than their stamps say (latency): the least delayed one sets the offset.
  CHECK(tb.ToHostUs(29999, 5009500) == 5009000);
  CHECK(tb.ToHostUs(10, 5020300) == 5020000);  // wrapped
  CHECK(tb.ToHostUs(20, 5030000) == 5030000);
}
