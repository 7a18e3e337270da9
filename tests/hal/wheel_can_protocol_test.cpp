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

namespace {
dpcr::CanFrame Status(std::uint8_t flags, std::uint8_t seq, std::uint32_t t) {
  dpcr::StatusFrame s;
  s.flags = flags;
  s.sequence = seq;
  s.time_10us = t;
  return dpcr::EncodeStatusFrame(s);
}
}  // namespace

TEST_CASE("can status frame layout is as documented, and decodes back") {
  const dpcr::CanFrame f = Status(0x01, 3, 0x123456);
  CHECK(f.id == 0x122);
  CHECK(f.dlc == 5);
  const std::uint8_t expect[5] = {0x01, 0x03, 0x56, 0x34, 0x12};
  for (int i = 0; i < 5; ++i) CHECK(f.data[i] == expect[i]);
  WheelCanDecoder d;
  REQUIRE(d.Feed(f) == CanDecodeResult::kStatus);
  CHECK(d.status().lifted);
  CHECK(d.status().device_time_us == 0x123456 * 10LL);
  REQUIRE(d.Feed(Status(0x00, 4, 0x123456 + 10000)) == CanDecodeResult::kStatus);
  CHECK_FALSE(d.status().lifted);
  CHECK(d.status().device_time_us == (0x123456 + 10000) * 10LL);
  CHECK(d.counters().status_frames == 2);
  CHECK(d.counters().reserved_flags == 0);
  CHECK(d.counters().foreign == 0);
}

TEST_CASE("can status frame with a wrong dlc is counted and changes nothing") {
  WheelCanDecoder d;
  REQUIRE(d.Feed(Status(0x00, 0, 100)) == CanDecodeResult::kStatus);
  dpcr::CanFrame f = Status(0x01, 1, 200);
  f.dlc = 4;
  CHECK(d.Feed(f) == CanDecodeResult::kBadDlc);
  f.dlc = 8;
  CHECK(d.Feed(f) == CanDecodeResult::kBadDlc);
  CHECK_FALSE(d.status().lifted);
  CHECK(d.counters().bad_dlc == 2);
  CHECK(d.counters().status_frames == 1);
}

TEST_CASE("can status frame with reserved flags set is counted, bit 0 still holds") {
  WheelCanDecoder d;
  REQUIRE(d.Feed(Status(0xFE, 0, 100)) == CanDecodeResult::kStatus);
  CHECK_FALSE(d.status().lifted);
  REQUIRE(d.Feed(Status(0x81, 1, 200)) == CanDecodeResult::kStatus);
  CHECK(d.status().lifted);
  REQUIRE(d.Feed(Status(0x01, 2, 300)) == CanDecodeResult::kStatus);
  CHECK(d.counters().reserved_flags == 2);
  CHECK(d.counters().status_frames == 3);
}

TEST_CASE("can status stream: own sequence, lost, duplicated and late frames as the others") {
  WheelCanDecoder d;
  REQUIRE(d.Feed(Ticks(0, 0, 40, 0)) == CanDecodeResult::kTicks);
  REQUIRE(d.Feed(Status(0x00, 200, 0)) == CanDecodeResult::kStatus);  // its own sequence: no gap
  CHECK(d.counters().lost == 0);
  CHECK(d.Feed(Status(0x00, 200, 0)) == CanDecodeResult::kDuplicate);
  // 201 (the lift) lost; 202 says lifted (the periodic resend).
  REQUIRE(d.Feed(Status(0x01, 202, 20000)) == CanDecodeResult::kStatus);
  CHECK(d.counters().lost == 1);
  CHECK(d.status().lifted);
  REQUIRE(d.Feed(Status(0x00, 203, 30000)) == CanDecodeResult::kStatus);  // put down
  // 201 arrives late: dropped, it does not lift the robot again.
  CHECK(d.Feed(Status(0x01, 201, 10000)) == CanDecodeResult::kReordered);
  CHECK_FALSE(d.status().lifted);
  CHECK(d.status().device_time_us == 300000);
  CHECK(d.counters().lost == 0);
  CHECK(d.counters().duplicated == 1);
  CHECK(d.counters().reordered == 1);
  CHECK(d.counters().status_frames == 3);
  REQUIRE(d.Feed(Ticks(1, 1, 41, 1000)) == CanDecodeResult::kTicks);  // the ticks stream unaffected
  CHECK(d.counters().lost == 0);
}
