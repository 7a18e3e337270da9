// A short simulated office run as the firmware's device streams (LD06 capture chunks and wheel
// CAN frames, dpcr-sim --emit-device's format), made once per test process, with the host's
// device replay of it (the firmware's oracle: the same inputs in the same order map identically).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/mapper.hpp"
#include "hal/device_options.hpp"
#include "host_sim/drivers/device_files.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "tests/support/temp_dir.hpp"

namespace dpcr::test {

struct OfficeStreams {
  DeviceFilesConfig files;
  std::vector<UartChunk> chunks;
  std::vector<CandumpRecord> records;
  // The device replay's result.
  Pose2 pose;
  std::uint32_t scans = 0;
  std::uint32_t odometry_samples = 0;
  std::uint32_t lost_events = 0;
  std::uint32_t lifted_scans = 0;
  std::int64_t start_us() const { return std::min(chunks.front().stamp_us, records.front().stamp_us); }
  std::int64_t end_us() const { return std::max(chunks.back().stamp_us, records.back().stamp_us); }
};

// `kidnaps`: the robot carried away that many times from the run's fifth second on (the wheels'
// lift flag in status frames).
inline OfficeStreams MakeOfficeStreams(double minutes, int kidnaps = 0) {
  using MapperType = Mapper<VacuumProfile>;
  struct CountingSink : DeviceSink {
    explicit CountingSink(MapperType* m) : mapper(m) {}
    void AddOdometry(const OdometrySample& sample) override { mapper->AddOdometry(sample); }
    void AddScan(const DeviceScan& scan) override {
      (void)mapper->AddScan(scan);
      ++scans;
    }
    MapperType* mapper;
    std::uint32_t scans = 0;
  };
  OfficeStreams o;
  const ScopedTempDir dir("office_streams");
  sim::SimConfig config;
  config.duration_min = minutes;
  config.seed = 5;
  config.kidnaps.count = kidnaps;
  config.kidnaps.from_min = 5.0 / 60.0;
  const sim::World world = sim::LoadBuiltinWorld("office");
  sim::Simulation simulation(world, config);
  DeviceEmitter emitter(o.files);
  std::string error;
  REQUIRE(emitter.Open(dir.str(), &error));
  sim::SimEvent e;
  while (simulation.Step(&e)) {
    if (e.type == sim::SimEventType::kOdometry) {
      emitter.AddOdometry(e.odometry);
    } else {
      REQUIRE(emitter.AddScan(e.scan));
    }
  }
  REQUIRE(emitter.Close(&error));
  const std::string uart = (dir.path() / "lidar.uart").string();
  const std::string can = (dir.path() / "wheels.log").string();
  REQUIRE(ReadUartCapture(uart, &o.chunks, &error));
  REQUIRE(ReadCandumpLog(can, &o.records, &error));
  auto reference = std::make_unique<MapperType>();
  LidarStreamConfig lidar;
  MapperConfig mapper_config;
  ApplyLidarModel(lidar.kind, &mapper_config.lidar);  // as dpcr-firmware and dpcr-replay
  REQUIRE(reference->Init(mapper_config) == Status::kOk);
  CountingSink sink(reference.get());
  lidar.assembler.angle_map = o.files.angle_map;
  DeviceReplay replay(o.files, lidar, &sink);
  REQUIRE(replay.Open(uart, can, &error));
  replay.Run();
  o.pose = reference->pose();
  o.scans = sink.scans;
  o.odometry_samples = reference->counters().odometry_samples;
  o.lost_events = reference->counters().lost_events;
  o.lifted_scans = reference->counters().lifted_scans;
  return o;
}

// 15 s of the office (150 scans), shared by the tests of one process.
inline const OfficeStreams& Office15s() {
  static const OfficeStreams streams = MakeOfficeStreams(0.25);
  return streams;
}

// The same 15 s with one kidnap.
inline const OfficeStreams& Office15sKidnapped() {
  static const OfficeStreams streams = MakeOfficeStreams(0.25, 1);
  return streams;
}

}  // namespace dpcr::test
