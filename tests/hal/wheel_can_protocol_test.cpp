#include <catch2/catch.hpp>

#include "hal/wheel_can_protocol.hpp"

using dpcr::CanDecodeResult;
using dpcr::WheelCanDecoder;
using dpcr::WheelTicksFrame;

namespace {
dpcr::CanFrame Ticks(std::uint16_t l, std::uint16_t r, std::uint8_t seq, std::uint32_t t) {
  WheelTicksFrame f;
  f.left_ticks = l;
  f.right_ticks = r;
  f.sequence = seq;
  f.time_10us = t;
  return dpcr::EncodeWheelFrame(f);
}
}  // namespace

TEST_CASE("can ticks frame layout is little-endian as documented") {
  const dpcr::CanFrame f = Ticks(0x1234, 0xABCD, 7, 0x123456);
  CHECK(f.id == 0x120);
  CHECK(f.dlc == 8);
  const std::uint8_t expect[8] = {0x34, 0x12, 0xCD, 0xAB, 0x07, 0x56, 0x34, 0x12};
  for (int i = 0; i < 8; ++i) CHECK(f.data[i] == expect[i]);
}

TEST_CASE("can decoder unwraps tick rollover both ways and device time") {
  WheelCanDecoder d;
  REQUIRE(d.Feed(Ticks(65530, 10, 0, (1 << 24) - 100)) == CanDecodeResult::kTicks);
  REQUIRE(d.Feed(Ticks(4, 65530, 1, 900)) == CanDecodeResult::kTicks);
  CHECK(d.ticks().left_ticks == 65530 + 10);
  CHECK(d.ticks().right_ticks == 10 - 16);
  CHECK(d.ticks().device_time_us == ((1 << 24) - 100) * 10LL + 1000 * 10);
  CHECK(d.counters().lost == 0);
}

TEST_CASE("can decoder counts lost, duplicated and reordered frames") {
  WheelCanDecoder d;
  REQUIRE(d.Feed(Ticks(0, 0, 250, 0)) == CanDecodeResult::kTicks);
  REQUIRE(d.Feed(Ticks(10, 10, 251, 1000)) == CanDecodeResult::kTicks);
  CHECK(d.Feed(Ticks(10, 10, 251, 1000)) == CanDecodeResult::kDuplicate);
  // 252 and 253 missing, sequence wraps to 0..
  REQUIRE(d.Feed(Ticks(40, 40, 254, 4000)) == CanDecodeResult::kTicks);
  CHECK(d.counters().lost == 2);
  // 253 arrives late: reordered, dropped; it is no longer lost.
  CHECK(d.Feed(Ticks(30, 30, 253, 3000)) == CanDecodeResult::kReordered);
  CHECK(d.counters().lost == 1);
  REQUIRE(d.Feed(Ticks(60, 60, 1, 6000)) == CanDecodeResult::kTicks);  // 255, 0 lost
  CHECK(d.counters().lost == 3);
  CHECK(d.counters().duplicated == 1);
  CHECK(d.counters().reordered == 1);
  CHECK(d.ticks().left_ticks == 60);  // absolute counters: nothing lost in the sum
  CHECK(d.counters().ticks_frames == 4);
}

TEST_CASE("can decoder ignores foreign, extended, rtr and error frames and bad dlc") {
  WheelCanDecoder d;
  dpcr::CanFrame f = Ticks(1, 1, 0, 0);
  f.id = 0x200;
  CHECK(d.Feed(f) == CanDecodeResult::kIgnored);
  f.id = 0x120 | dpcr::kCanEffFlag;
  CHECK(d.Feed(f) == CanDecodeResult::kIgnored);
  f.id = 0x120 | dpcr::kCanRtrFlag;
  CHECK(d.Feed(f) == CanDecodeResult::kIgnored);
  f.id = dpcr::kCanErrFlag | 0x4;
  CHECK(d.Feed(f) == CanDecodeResult::kErrorFrame);
  f = Ticks(1, 1, 0, 0);
  f.dlc = 6;
  CHECK(d.Feed(f) == CanDecodeResult::kBadDlc);
  CHECK(d.counters().foreign == 3);
  CHECK(d.counters().error_frames == 1);
  CHECK(d.counters().bad_dlc == 1);
  CHECK(d.counters().ticks_frames == 0);
}

TEST_CASE("can gyro frame round trip") {
  dpcr::GyroFrame g;
  g.yaw_rate_mrad_s = -1234;
  g.sequence = 9;
  g.time_10us = 500;
  WheelCanDecoder d;
  REQUIRE(d.Feed(dpcr::EncodeGyroFrame(g)) == CanDecodeResult::kGyro);
  CHECK(d.gyro().yaw_rate_rad_s == Approx(-1.234f));
  CHECK(d.gyro().device_time_us == 5000);
  // The gyro stream has its own sequence: no interference with the ticks stream.
  REQUIRE(d.Feed(Ticks(0, 0, 0, 0)) == CanDecodeResult::kTicks);
  CHECK(d.counters().lost == 0);
}
