// The firmware on host ports: a simulated run written as device files, played into Firmware
// through capture-file ports on a replay clock, maps exactly as dpcr-replay's device path does.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

#include "board/firmware.hpp"
#include "host_sim/drivers/device_files.hpp"
#include "host_sim/drivers/replay_clock.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "tests/board/memory_store.hpp"

namespace {

using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;

using dpcr::test::MemoryStore;

struct CountingSink : dpcr::DeviceSink {
  explicit CountingSink(MapperType* m) : mapper(m) {}
  void AddOdometry(const dpcr::OdometrySample& sample) override { mapper->AddOdometry(sample); }
  void AddScan(const dpcr::DeviceScan& scan) override {
    (void)mapper->AddScan(scan);
    ++scans;
  }
  MapperType* mapper;
  std::uint32_t scans = 0;
};

void EmitOfficeRun(const std::filesystem::path& dir) {
  dpcr::sim::SimConfig config;
  config.duration_min = 0.25;
  config.seed = 5;
  const dpcr::sim::World world = dpcr::sim::LoadBuiltinWorld("office");
  dpcr::sim::Simulation sim(world, config);
  dpcr::DeviceEmitter emitter;
  std::string error;
  REQUIRE(emitter.Open(dir.string(), &error));
  dpcr::sim::SimEvent e;
  while (sim.Step(&e)) {
    if (e.type == dpcr::sim::SimEventType::kOdometry) {
      emitter.AddOdometry(e.odometry);
    } else {
      REQUIRE(emitter.AddScan(e.scan));
    }
  }
  REQUIRE(emitter.Close(&error));
}

}  // namespace

TEST_CASE("firmware on capture-file ports and a replay clock maps as the device replay does") {
  const auto dir = std::filesystem::temp_directory_path() / ("dpcr_firmware_replay_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  EmitOfficeRun(dir);
  const dpcr::DeviceFilesConfig files;
  std::string error;
  std::vector<dpcr::UartChunk> chunks;
  std::vector<dpcr::CandumpRecord> records;
  REQUIRE(dpcr::ReadUartCapture((dir / "lidar.uart").string(), &chunks, &error));
  REQUIRE(dpcr::ReadCandumpLog((dir / "wheels.log").string(), &records, &error));

  // The oracle: the host's device replay into a mapper.
  auto reference = std::make_unique<MapperType>();
  REQUIRE(reference->Init(dpcr::MapperConfig{}) == dpcr::Status::kOk);
  CountingSink sink(reference.get());
  dpcr::LidarStreamConfig lidar;
  lidar.assembler.angle_map = files.angle_map;
  dpcr::DeviceReplay replay(files, lidar, &sink);
  REQUIRE(replay.Open((dir / "lidar.uart").string(), (dir / "wheels.log").string(), &error));
  replay.Run();
  std::filesystem::remove_all(dir);

  // The firmware, woken whenever the next recorded byte or frame is due.
  dpcr::ReplayClock clock(std::min(chunks.front().stamp_us, records.front().stamp_us));
  dpcr::UartCaptureSource uart(chunks, &clock);
  dpcr::CandumpSource can(records, &clock);
  MemoryStore store;
  dpcr::board::FirmwareConfig config;
  config.angle_map = files.angle_map;
  config.wheels = files.wheels;
  config.autosave_s = 0;
  std::FILE* log = std::tmpfile();
  REQUIRE(log != nullptr);
  dpcr::board::Firmware firmware(config, dpcr::board::FirmwarePorts{&uart, &can, &clock, &store}, log);
  REQUIRE(firmware.Start());
  bool uart_open = true;
  bool can_open = true;
  while (uart.next_stamp_us() != INT64_MAX || can.next_stamp_us() != INT64_MAX) {
    clock.AdvanceTo(std::min(uart.next_stamp_us(), can.next_stamp_us()));
    if (can_open) can_open = firmware.ServiceCan();
    if (uart_open) uart_open = firmware.ServiceLidar();
    REQUIRE((can_open || can.next_stamp_us() == INT64_MAX));  // a port ends only with its file
    REQUIRE((uart_open || uart.next_stamp_us() == INT64_MAX));
    REQUIRE_FALSE(firmware.LidarSilent());
    firmware.ServiceTimers();
  }
  CHECK(firmware.Finish(0) == 0);
  std::fclose(log);

  REQUIRE(sink.scans > 100);
  CHECK(firmware.scans() == sink.scans);
  const dpcr::Pose2 a = firmware.mapper().pose();
  const dpcr::Pose2 b = reference->pose();
  CHECK(a.x == b.x);  // the same inputs in the same order: bit-identical
  CHECK(a.y == b.y);
  CHECK(a.theta == b.theta);
  CHECK(firmware.mapper().counters().odometry_samples == reference->counters().odometry_samples);
  REQUIRE(store.blobs.count("map.pgm") == 1);
  REQUIRE(store.blobs.count("map.yaml") == 1);
  CHECK(store.blobs["map.pgm"].size() > 1000);
  REQUIRE(store.blobs.count("map.dpcr") == 1);
  CHECK(store.blobs["map.dpcr"].size() == firmware.mapper().map_file_bytes());

  // The next start loads it: the same maps, the same graph.
  const auto restart = [&](const char* expect_in_log) {
    std::FILE* restart_log = std::tmpfile();
    dpcr::board::Firmware next(config, dpcr::board::FirmwarePorts{&uart, &can, &clock, &store}, restart_log);
    REQUIRE(next.Start());
    std::rewind(restart_log);
    char line[512] = {};
    std::string text;
    while (std::fgets(line, sizeof(line), restart_log) != nullptr) text += line;
    std::fclose(restart_log);
    INFO(text);
    CHECK(text.find(expect_in_log) != std::string::npos);
    CHECK(std::count(text.begin(), text.end(), '\n') == 1);  // one line
    return next.mapper().region_count();
  };
  CHECK(restart("map loaded from ./map.dpcr") == firmware.mapper().region_count());
  // A corrupt map: one error line, the run maps from scratch.
  store.blobs["map.dpcr"][200] ^= 0x10;
  CHECK(restart("error: ./map.dpcr: corrupt: CRC-32 mismatch") == 0);
  store.blobs.erase("map.dpcr");
  CHECK(restart("no saved map at ./map.dpcr") == 0);
}
