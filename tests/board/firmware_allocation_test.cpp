// After start-up the firmware allocates nothing: the loop over 15 s of the office (1500 lidar
// reads, 3000 CAN frames, 150 scans), its counters lines, watchdog kicks and the autosaves written by
// the save worker through the real atomic file store, with every malloc and operator new of
// the process counted (both threads).
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

#include "board/atomic_file.hpp"
#include "board/firmware_loop.hpp"
#include "host_sim/drivers/replay_clock.hpp"
#include "tests/board/office_streams.hpp"
#include "tests/board/replay_waiter.hpp"
#include "tests/budget/allocation_counter.hpp"

namespace {

struct CountingNotifier : dpcr::ServiceNotifier {
  void Ready() override {}
  void Alive() override { ++kicks; }
  void Stopping() override {}
  std::int64_t watchdog_period_us() const override { return 1000000; }
  int kicks = 0;
};

}  // namespace

TEST_CASE("firmware loop: no allocation after start-up, saves included") {
  const dpcr::test::OfficeStreams& o = dpcr::test::Office15s();
  dpcr::ReplayClock clock(o.start_us());
  dpcr::UartCaptureSource uart(o.chunks, &clock);
  dpcr::CandumpSource can(o.records, &clock);
  const dpcr::test::ScopedTempDir dir("firmware_allocation");
  dpcr::board::AtomicFileStore store(dir.str());
  CountingNotifier notifier;
  dpcr::board::FirmwareConfig config;
  config.angle_map = o.files.angle_map;
  config.wheels = o.files.wheels;
  config.map_dir = dir.str();
  config.autosave_s = 3;
  config.status_period_ms = 2000;
  std::FILE* log = std::tmpfile();
  REQUIRE(log != nullptr);
  dpcr::board::Firmware firmware(config, dpcr::board::FirmwarePorts{&uart, &can, &clock, &store, &notifier}, log);
  REQUIRE(firmware.Start());
  firmware.Running();
  dpcr::test::ReplayWaiter waiter(
      &clock, [&] { return uart.next_stamp_us(); }, [&] { return can.next_stamp_us(); }, o.end_us() + 500000);

  dpcr::test::ArmAllocationCounter();
  const int code = dpcr::board::RunFirmwareLoop(&firmware, &waiter, clock);
  const std::size_t allocations = dpcr::test::DisarmAllocationCounter();

  CHECK(code == 0);
  CHECK(firmware.Finish(0) == 0);
  std::fclose(log);
  CHECK(allocations == 0);
  // It did the work it was counted over.
  CHECK(firmware.scans() == o.scans);
  // At least the first autosave (3 s) went through the worker during the counted loop; later ones
  // may have waited for a slow fsync (real time runs slower than this fake clock).
  CHECK(firmware.counters().saves_requested >= 2);  // that one and the final save
  CHECK(firmware.counters().saves_ok == firmware.counters().saves_requested);
  CHECK(notifier.kicks >= 25);
  CHECK(waiter.waits > 3000);
}
