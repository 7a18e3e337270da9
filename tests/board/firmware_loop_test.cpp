// The firmware's loop (RunFirmwareLoop) on fake ports: recorded streams delivered on a replay
// clock (tests/board/replay_waiter.hpp), an in-memory map store, a fake service manager. No
// sleeps and no wall time: the fake clock runs the timers.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "board/atomic_file.hpp"
#include "board/firmware_loop.hpp"
#include "core/persistence/map_stream.hpp"
#include "hal/wheel_can_protocol.hpp"
#include "host_sim/drivers/replay_clock.hpp"
#include "tests/board/memory_store.hpp"
#include "tests/board/office_streams.hpp"
#include "tests/board/read_log.hpp"
#include "tests/board/replay_waiter.hpp"

namespace {

using dpcr::test::MemoryStore;
using dpcr::test::OfficeStreams;
using dpcr::test::ReadLog;

dpcr::board::FirmwareConfig ConfigFor(const OfficeStreams& o) {
  dpcr::board::FirmwareConfig c;
  c.angle_map = o.files.angle_map;
  c.wheels = o.files.wheels;
  c.autosave_s = 0;
  return c;
}

struct FakeNotifier : dpcr::ServiceNotifier {
  explicit FakeNotifier(const dpcr::Clock* c, std::int64_t period_us) : clock(c), period(period_us) {}
  void Ready() override { ++ready; }
  void Alive() override { kicks.push_back(clock->NowUs()); }
  void Stopping() override { ++stopping; }
  std::int64_t watchdog_period_us() const override { return period; }
  const dpcr::Clock* clock;
  std::int64_t period;
  int ready = 0;
  int stopping = 0;
  std::vector<std::int64_t> kicks;
};

// The CAN bus failing at `down_us` (a read error: the interface went down) and back at `up_us`
// (Reopen succeeds from then on); frames sent while it was down are lost.
class OutageCan : public dpcr::CanSource {
 public:
  OutageCan(dpcr::CandumpSource* inner, const dpcr::Clock* clock, std::int64_t down_us, std::int64_t up_us)
      : inner_(inner), clock_(clock), down_us_(down_us), up_us_(up_us) {}
  dpcr::CanRead Read() override {
    dpcr::CanRead r;
    if (!open_ || (!failed_ && clock_->NowUs() >= down_us_)) {
      failed_ = true;
      open_ = false;
      r.status = dpcr::IoStatus::kIoError;
      errno = ENETDOWN;
      return r;
    }
    return inner_->Read();
  }
  dpcr::IoStatus Reopen() override {
    ++reopen_tries;
    if (clock_->NowUs() < up_us_) return dpcr::IoStatus::kIoError;
    while (inner_->next_stamp_us() < up_us_) (void)inner_->Read();  // lost on the wire
    open_ = true;
    return dpcr::IoStatus::kOk;
  }
  std::int64_t next_stamp_us() const { return open_ ? inner_->next_stamp_us() : INT64_MAX; }
  int reopen_tries = 0;

 private:
  dpcr::CandumpSource* inner_;
  const dpcr::Clock* clock_;
  std::int64_t down_us_;
  std::int64_t up_us_;
  bool open_ = true;
  bool failed_ = false;
};

// One loop run over the office streams (optionally some wheel frames left out), stopped half a
// second after the recording ends.
struct LoopRun {
  explicit LoopRun(const OfficeStreams& o, std::vector<dpcr::CandumpRecord> records)
      : clock(o.start_us()), uart(o.chunks, &clock), can(std::move(records), &clock) {}
  dpcr::ReplayClock clock;
  dpcr::UartCaptureSource uart;
  dpcr::CandumpSource can;
};

// Runs `firmware` (started, over `run`'s ports) until half a second after the recording ends and
// finishes it; returns what it logged (`log` is closed).
std::string RunToEnd(dpcr::board::Firmware* firmware, LoopRun* run, const OfficeStreams& o, std::FILE* log) {
  dpcr::test::ReplayWaiter waiter(
      &run->clock, [&] { return run->uart.next_stamp_us(); }, [&] { return run->can.next_stamp_us(); }, o.end_us() + 500000);
  CHECK(dpcr::board::RunFirmwareLoop(firmware, &waiter, run->clock) == 0);
  CHECK(firmware->Finish(0) == 0);
  const std::string text = ReadLog(log);
  std::fclose(log);
  return text;
}

// A firmware with the office's configuration on `run`'s ports and an in-memory store, started
// and run to the end (RunToEnd); `text` is what it logged.
struct FinishedRun {
  FinishedRun(const OfficeStreams& o, LoopRun* run, std::FILE* log = std::tmpfile())
      : firmware(ConfigFor(o), dpcr::board::FirmwarePorts{&run->uart, &run->can, &run->clock, &store, nullptr}, log) {
    REQUIRE(firmware.Start());
    text = RunToEnd(&firmware, run, o, log);
  }
  MemoryStore store;
  dpcr::board::Firmware firmware;
  std::string text;
};

// The robot ends where the device replay of the office's clean streams does.
void CheckEndsWithCleanRun(const dpcr::board::Firmware& firmware, const OfficeStreams& o) {
  const dpcr::Pose2 a = firmware.mapper().pose();
  INFO("end " << a.x << " " << a.y << " " << a.theta << ", clean run " << o.pose.x << " " << o.pose.y << " " << o.pose.theta);
  CHECK(std::hypot(a.x - o.pose.x, a.y - o.pose.y) < 0.10f);
  CHECK(std::fabs(dpcr::NormalizeAngle(a.theta - o.pose.theta)) < 0.05f);
}

}  // namespace

TEST_CASE("firmware loop on fake ports maps as the device replay does, the map file saved once, loadable") {
  const OfficeStreams& o = dpcr::test::Office15s();
  LoopRun run(o, o.records);
  MemoryStore store;
  FakeNotifier notifier(&run.clock, 2000000);
  dpcr::board::FirmwareConfig config = ConfigFor(o);
  config.autosave_s = 4;
  config.status_period_ms = 5000;
  std::FILE* log = std::tmpfile();
  dpcr::board::Firmware firmware(config, dpcr::board::FirmwarePorts{&run.uart, &run.can, &run.clock, &store, &notifier}, log);
  REQUIRE(firmware.Start());
  firmware.Running();
  const std::string text = RunToEnd(&firmware, &run, o, log);
  INFO(text);

  REQUIRE(o.scans > 100);
  CHECK(firmware.scans() == o.scans);
  const dpcr::Pose2 a = firmware.mapper().pose();
  CHECK(a.x == o.pose.x);  // the same inputs in the same order: bit-identical
  CHECK(a.y == o.pose.y);
  CHECK(a.theta == o.pose.theta);
  CHECK(firmware.mapper().counters().odometry_samples == o.odometry_samples);
  // Autosaves every 4 s of a 15 s run, through the worker, and the final one.
  CHECK(firmware.counters().saves_ok >= 4);
  CHECK(firmware.counters().saves_failed == 0);
  // The one map file; the exports are derived from it (dpcr-map export), never written beside it.
  REQUIRE(store.blobs.count("map.dpcr") == 1);
  CHECK(store.blobs.size() == 1);
  CHECK(store.blobs["map.dpcr"].size() == firmware.mapper().map_file_bytes());
  CHECK(text.find("wheels on CAN can0") != std::string::npos);
  CHECK(text.find("scan_rate=") != std::string::npos);  // the counters line
  CHECK(text.find("warning") == std::string::npos);
  // The service manager heard: ready, a kick at least every half watchdog period of fake time, stopping.
  CHECK(notifier.ready == 1);
  CHECK(notifier.stopping == 1);
  REQUIRE(notifier.kicks.size() >= 15);
  for (std::size_t i = 1; i < notifier.kicks.size(); ++i) CHECK(notifier.kicks[i] - notifier.kicks[i - 1] <= 1000000 + 100000);

  // The next start loads it: the same maps.
  std::FILE* restart_log = std::tmpfile();
  dpcr::board::Firmware next(config, dpcr::board::FirmwarePorts{&run.uart, &run.can, &run.clock, &store, nullptr},
                             restart_log);
  REQUIRE(next.Start());
  const std::string restart_text = ReadLog(restart_log);
  std::fclose(restart_log);
  CHECK(restart_text.find("map loaded from ./map.dpcr") != std::string::npos);
  CHECK(next.mapper().region_count() == firmware.mapper().region_count());
}

TEST_CASE("firmware loop: a corrupt or missing saved map is one line, the run maps from scratch") {
  const OfficeStreams& o = dpcr::test::Office15s();
  LoopRun run(o, o.records);
  MemoryStore store;
  const auto start = [&](const char* expect) {
    std::FILE* log = std::tmpfile();
    dpcr::board::Firmware f(ConfigFor(o), dpcr::board::FirmwarePorts{&run.uart, &run.can, &run.clock, &store, nullptr}, log);
    REQUIRE(f.Start());
    const std::string text = ReadLog(log);
    std::fclose(log);
    INFO(text);
    CHECK(text.find(expect) != std::string::npos);
    CHECK(std::count(text.begin(), text.end(), '\n') == 1);
    return f.mapper().region_count();
  };
  CHECK(start("no saved map at ./map.dpcr") == 0);
  // A map of a few scans, then corrupted.
  {
    LoopRun first(o, o.records);
    std::FILE* log = std::tmpfile();
    dpcr::board::Firmware f(ConfigFor(o), dpcr::board::FirmwarePorts{&first.uart, &first.can, &first.clock, &store, nullptr}, log);
    REQUIRE(f.Start());
    dpcr::test::ReplayWaiter waiter(
        &first.clock, [&] { return first.uart.next_stamp_us(); }, [&] { return first.can.next_stamp_us(); }, o.start_us() + 3000000);
    CHECK(dpcr::board::RunFirmwareLoop(&f, &waiter, first.clock) == 0);
    CHECK(f.Finish(0) == 0);
    std::fclose(log);
  }
  REQUIRE(store.blobs.count("map.dpcr") == 1);
  store.blobs["map.dpcr"][200] ^= 0x10;
  CHECK(start("error: ./map.dpcr: corrupt: CRC-32 mismatch") == 0);
}

TEST_CASE("firmware loop: a slow flash does not stall the scans (saves wait in the worker, not in the loop)") {
  // A store whose writes hang until the run has reached its end: the loop must go on mapping.
  struct StuckStore : MemoryStore {
    std::atomic<bool> release{false};
    std::atomic<int> writes{0};
    dpcr::IoStatus Write(const char* name, const std::uint8_t* data, std::size_t size) override {
      ++writes;
      while (!release.load()) std::this_thread::yield();
      return MemoryStore::Write(name, data, size);
    }
  } store;
  const OfficeStreams& o = dpcr::test::Office15s();
  LoopRun run(o, o.records);
  dpcr::board::FirmwareConfig config = ConfigFor(o);
  config.autosave_s = 2;
  std::FILE* log = std::tmpfile();
  dpcr::board::Firmware firmware(config, dpcr::board::FirmwarePorts{&run.uart, &run.can, &run.clock, &store, nullptr}, log);
  REQUIRE(firmware.Start());
  std::uint32_t scans_when_stuck = 0;
  dpcr::test::ReplayWaiter waiter(
      &run.clock,
      [&] {
        // Once the first autosave is handed over: wait (in this fake device) until the worker is
        // inside the hanging write, and note how far the mapping was.
        if (firmware.counters().saves_requested == 1 && scans_when_stuck == 0) {
          while (store.writes.load() == 0) std::this_thread::yield();
          scans_when_stuck = firmware.scans();
        }
        return run.uart.next_stamp_us();
      },
      [&] { return run.can.next_stamp_us(); }, o.end_us() + 500000);
  CHECK(dpcr::board::RunFirmwareLoop(&firmware, &waiter, run.clock) == 0);
  store.release = true;
  CHECK(firmware.Finish(0) == 0);
  std::fclose(log);
  CHECK(firmware.scans() == o.scans);                   // every scan mapped while the first save hung
  REQUIRE(scans_when_stuck > 0);
  CHECK(scans_when_stuck < o.scans - 100);              // it hung from early on (2 s of 15)
  CHECK(firmware.counters().saves_deferred > 0);        // later autosaves waited their turn
  CHECK(firmware.mapper().pose().x == o.pose.x);
}

TEST_CASE("firmware loop: without CAN the lidar maps alone, said in the log, the wheels are taken back") {
  const OfficeStreams& o = dpcr::test::Office15s();
  LoopRun run(o, o.records);
  const std::int64_t down = o.start_us() + 5000000;
  const std::int64_t up = o.start_us() + 8000000;
  OutageCan can(&run.can, &run.clock, down, up);
  MemoryStore store;
  dpcr::board::FirmwareConfig config = ConfigFor(o);
  config.can_retry_ms = 1000;
  std::FILE* log = std::tmpfile();
  dpcr::board::Firmware firmware(config, dpcr::board::FirmwarePorts{&run.uart, &can, &run.clock, &store, nullptr}, log);
  REQUIRE(firmware.Start());
  dpcr::test::ReplayWaiter waiter(
      &run.clock, [&] { return run.uart.next_stamp_us(); },
      [&] { return can.next_stamp_us(); },
      o.end_us() + 500000);
  CHECK(dpcr::board::RunFirmwareLoop(&firmware, &waiter, run.clock) == 0);
  CHECK(firmware.Finish(0) == 0);
  const std::string text = ReadLog(log);
  std::fclose(log);
  INFO(text);
  CHECK(text.find("error: CAN can0: read: ENETDOWN (Network is down): mapping from the lidar alone") != std::string::npos);
  CHECK(text.find("CAN can0 open again") != std::string::npos);
  CHECK(text.find("no wheel ticks on CAN can0 for 500 ms: mapping from the lidar alone") != std::string::npos);
  CHECK(text.find("wheels back on CAN can0 after") != std::string::npos);
  CHECK(can.reopen_tries >= 3);
  CHECK(firmware.counters().can_failures >= 1);  // the outage (and the recording's end: "closed")
  std::size_t outages = 0;
  for (std::size_t at = text.find("ENETDOWN"); at != std::string::npos; at = text.find("ENETDOWN", at + 1)) ++outages;
  CHECK(outages == 1);
  CHECK(firmware.device_counters().wheel_gaps == 1);
  CHECK(firmware.scans() == o.scans);
  // Three seconds of lidar alone, then the wheels again: the robot ends where the clean run does.
  CheckEndsWithCleanRun(firmware, o);
}

TEST_CASE("firmware loop: wheels silent (frames missing) -> lidar alone, their return resumes the odometry without a jump") {
  const OfficeStreams& o = dpcr::test::Office15s();
  std::vector<dpcr::CandumpRecord> records;
  const std::int64_t from = o.start_us() + 4000000;
  const std::int64_t to = o.start_us() + 7000000;
  for (const dpcr::CandumpRecord& r : o.records) {
    if (r.stamp_us < from || r.stamp_us >= to) records.push_back(r);
  }
  LoopRun run(o, records);
  const FinishedRun f(o, &run);
  INFO(f.text);
  CHECK(f.text.find("no wheel ticks on CAN can0 for 500 ms: mapping from the lidar alone") != std::string::npos);
  CHECK(f.text.find("wheels back on CAN can0 after 2.") != std::string::npos);
  CHECK(f.firmware.counters().wheel_silences == 1);
  CHECK(f.firmware.device_counters().wheel_gaps == 1);
  CheckEndsWithCleanRun(f.firmware, o);
}

// The office's ticks frames rewritten to carry the heading alone (each wheel's count replaced by
// half the difference of the two, opposite signs): what a recorder that turned its IMU's yaw into
// ticks sends. The gyro frames are dropped with them.
std::vector<dpcr::CandumpRecord> HeadingOnlyTicks(const std::vector<dpcr::CandumpRecord>& records) {
  std::vector<dpcr::CandumpRecord> out;
  std::int64_t left = 0, right = 0;
  std::uint16_t last_left = 0, last_right = 0;
  bool first = true;
  for (dpcr::CandumpRecord r : records) {
    if (r.frame.id == dpcr::kGyroCanId) continue;
    if (r.frame.id == dpcr::kWheelTicksCanId) {
      const auto u16 = [&r](int at) { return static_cast<std::uint16_t>(r.frame.data[at] | (r.frame.data[at + 1] << 8)); };
      const std::uint16_t l = u16(0), rt = u16(2);
      if (!first) {
        left += static_cast<std::int16_t>(static_cast<std::uint16_t>(l - last_left));
        right += static_cast<std::int16_t>(static_cast<std::uint16_t>(rt - last_right));
      }
      first = false;
      last_left = l;
      last_right = rt;
      const auto put = [&r](int at, std::int64_t v) {
        const std::uint16_t w = static_cast<std::uint16_t>(v & 0xFFFF);
        r.frame.data[at] = static_cast<std::uint8_t>(w & 0xFF);
        r.frame.data[at + 1] = static_cast<std::uint8_t>(w >> 8);
      };
      put(0, (left - right) / 2);
      put(2, (right - left) / 2);
    }
    out.push_back(r);
  }
  return out;
}

TEST_CASE("firmware loop: ticks that carry only the heading are noticed, their translation ignored, said in the log") {
  const OfficeStreams& o = dpcr::test::Office15s();
  LoopRun run(o, HeadingOnlyTicks(o.records));
  const FinishedRun f(o, &run);
  INFO(f.text);
  CHECK(f.text.find("wheel ticks on CAN can0 miss the motion the lidar sees: their translation is ignored (their heading is kept)") !=
        std::string::npos);
  CHECK(f.firmware.mapper().counters().odometry_without_wheel_translation > 0);
  // The robot ends where the run with its true wheels does.
  CheckEndsWithCleanRun(f.firmware, o);
}

TEST_CASE("firmware loop: a kidnap's status frames make the robot lost as in the device replay, and are counted") {
  const OfficeStreams& o = dpcr::test::Office15sKidnapped();
  LoopRun run(o, o.records);
  const FinishedRun f(o, &run);
  INFO(f.text);
  REQUIRE(o.lifted_scans >= 30);  // carried 3-6 s: the replay kept those scans out
  CHECK(f.firmware.mapper().counters().lifted_scans == o.lifted_scans);
  CHECK(f.firmware.mapper().counters().lost_events == o.lost_events);
  CHECK(f.firmware.device_counters().lifts == 1);
  CHECK(f.firmware.device_counters().can.reserved_flags == 0);
  CHECK(f.text.find(" lifts=1 ") != std::string::npos);  // the summary line
  const dpcr::Pose2 a = f.firmware.mapper().pose();
  CHECK(a.x == o.pose.x);  // the same inputs in the same order: bit-identical
  CHECK(a.y == o.pose.y);
}

TEST_CASE("firmware: an unwritable map directory is an error at start, not at the first save") {
  const OfficeStreams& o = dpcr::test::Office15s();
  LoopRun run(o, o.records);
  const dpcr::test::ScopedTempDir tmp("firmware_unwritable");
  dpcr::board::FirmwareConfig config = ConfigFor(o);
  config.map_dir = tmp.str() + "/no-such-dir";
  dpcr::board::AtomicFileStore store(config.map_dir);
  std::FILE* log = std::tmpfile();
  dpcr::board::Firmware firmware(config, dpcr::board::FirmwarePorts{&run.uart, &run.can, &run.clock, &store, nullptr}, log);
  CHECK_FALSE(firmware.Start());
  const std::string text = ReadLog(log);
  std::fclose(log);
  INFO(text);
  CHECK(text.find("error: map directory " + config.map_dir + " is not writable: ENOENT") != std::string::npos);
}

TEST_CASE("firmware: ticks per revolution must be stated") {
  const OfficeStreams& o = dpcr::test::Office15s();
  LoopRun run(o, o.records);
  MemoryStore store;
  dpcr::board::FirmwareConfig config;  // no ticks stated
  CHECK(config.wheels.ticks_per_rev == 0.0f);
  std::FILE* log = std::tmpfile();
  dpcr::board::Firmware firmware(config, dpcr::board::FirmwarePorts{&run.uart, &run.can, &run.clock, &store, nullptr}, log);
  CHECK_FALSE(firmware.Start());
  const std::string text = ReadLog(log);
  std::fclose(log);
  CHECK(text.find("ticks per revolution are not stated") != std::string::npos);
}

TEST_CASE("firmware: the heading choice and the robot's acceleration reach the mapper") {
  const OfficeStreams& o = dpcr::test::Office15s();
  const auto started = [&](dpcr::LidarKind lidar, const std::string& heading, float max_accel_mps2) {
    LoopRun run(o, o.records);
    MemoryStore store;
    dpcr::board::FirmwareConfig config = ConfigFor(o);
    config.lidar = lidar;
    config.heading = heading;
    config.max_accel_mps2 = max_accel_mps2;
    std::FILE* log = std::tmpfile();
    dpcr::board::Firmware firmware(config, dpcr::board::FirmwarePorts{&run.uart, &run.can, &run.clock, &store, nullptr}, log);
    REQUIRE(firmware.Start());
    const dpcr::FrontEndConfig f = firmware.mapper().config().front_end;
    std::fclose(log);
    return f;
  };
  // "model": the lidar's (ModelGyroHeading), as dpcr-replay and dpcr-sim take it.
  CHECK_FALSE(started(dpcr::LidarKind::kLd06, "model", 0.5f).gyro_heading);
  CHECK(started(dpcr::LidarKind::kXv11, "model", 0.5f).gyro_heading);
  CHECK(started(dpcr::LidarKind::kLd06, "gyro", 0.5f).gyro_heading);
  CHECK_FALSE(started(dpcr::LidarKind::kXv11, "wheels", 0.5f).gyro_heading);
  CHECK(started(dpcr::LidarKind::kLd06, "model", 1.5f).max_acceleration_mps2 == 1.5f);
  CHECK(started(dpcr::LidarKind::kLd06, "model", 0.0f).max_acceleration_mps2 == 0.0f);
}
