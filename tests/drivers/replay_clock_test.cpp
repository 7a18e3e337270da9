// Capture-file ports on a replay clock behave as live ports: what was recorded after the clock's
// now is not there yet (kWouldBlock), and the clock never steps back.
#include <catch2/catch.hpp>

#include <vector>

#include "host_sim/drivers/candump_log.hpp"
#include "host_sim/drivers/replay_clock.hpp"
#include "host_sim/drivers/uart_capture.hpp"

TEST_CASE("replay clock: moves forward only") {
  dpcr::ReplayClock clock(100);
  CHECK(clock.NowUs() == 100);
  clock.AdvanceTo(250);
  CHECK(clock.NowUs() == 250);
  clock.AdvanceTo(200);
  CHECK(clock.NowUs() == 250);
}

TEST_CASE("replay clock: a UART capture delivers the chunks recorded up to the clock") {
  dpcr::ReplayClock clock(1000);
  dpcr::UartCaptureSource uart({{1000, {0x54, 0x2C}}, {2000, {0x01}}}, &clock);
  std::uint8_t buffer[8];
  dpcr::ByteRead r = uart.Read(buffer, sizeof(buffer));
  REQUIRE(r.status == dpcr::IoStatus::kOk);
  CHECK(r.size == 2);
  CHECK(r.stamp_us == 1000);
  CHECK(uart.Read(buffer, sizeof(buffer)).status == dpcr::IoStatus::kWouldBlock);
  clock.AdvanceTo(2000);
  r = uart.Read(buffer, sizeof(buffer));
  REQUIRE(r.status == dpcr::IoStatus::kOk);
  CHECK(buffer[0] == 0x01);
  CHECK(uart.Read(buffer, sizeof(buffer)).status == dpcr::IoStatus::kEndOfStream);
}

TEST_CASE("replay clock: a candump log delivers the frames recorded up to the clock") {
  dpcr::ReplayClock clock(0);
  std::vector<dpcr::CandumpRecord> records(2);
  records[0].stamp_us = 500;
  records[0].frame.id = 0x120;
  records[1].stamp_us = 900;
  records[1].frame.id = 0x121;
  dpcr::CandumpSource can(records, &clock);
  CHECK(can.Read().status == dpcr::IoStatus::kWouldBlock);
  clock.AdvanceTo(900);
  dpcr::CanRead r = can.Read();
  REQUIRE(r.status == dpcr::IoStatus::kOk);
  CHECK(r.frame.id == 0x120);
  CHECK(r.stamp_us == 500);
  CHECK(can.Read().frame.id == 0x121);
  CHECK(can.Read().status == dpcr::IoStatus::kEndOfStream);
}
