#include <catch2/catch.hpp>

#include "golden_packets.hpp"
#include "hal/crc8.hpp"

TEST_CASE("crc8 table matches the LDROBOT SDK table") {
  // First row of CrcTable in ldlidar_driver/src/dataprocess/lipkg.cpp.
  const std::uint8_t first[16] = {0x00, 0x4d, 0x9a, 0xd7, 0x79, 0x34, 0xe3, 0xae,
                                  0xf2, 0xbf, 0x68, 0x25, 0x8b, 0xc6, 0x11, 0x5c};
  for (int i = 0; i < 16; ++i) {
    CHECK(dpcr::Crc8LdTableEntry(static_cast<std::uint8_t>(i)) == first[i]);
  }
}

TEST_CASE("crc8 of the LD06 datasheet packet is its last byte") {
  CHECK(dpcr::Crc8Ld(dpcr_test::kLd06DatasheetPacket, 46) == 0x50);
  // Incremental computation gives the same result.
  const std::uint8_t head = dpcr::Crc8Ld(dpcr_test::kLd06DatasheetPacket, 10);
  CHECK(dpcr::Crc8Ld(dpcr_test::kLd06DatasheetPacket + 10, 36, head) == 0x50);
}
