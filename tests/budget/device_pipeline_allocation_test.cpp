// The firmware's device path after start-up allocates nothing: LD06 bytes and wheel CAN frames
// through the DevicePipeline into the vacuum mapper, with the heap counter armed.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/mapper.hpp"
#include "hal/device_pipeline.hpp"
#include "hal/ld06_emitter.hpp"
#include "tests/budget/allocation_counter.hpp"

namespace {

using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;

class MapperSink : public dpcr::DeviceSink {
 public:
  explicit MapperSink(MapperType* mapper) : mapper_(mapper) {}
  void AddOdometry(const dpcr::OdometrySample& sample) override { mapper_->AddOdometry(sample); }
  void AddScan(const dpcr::DeviceScan& scan) override { (void)mapper_->AddScan(scan); }

 private:
  MapperType* mapper_;
};

// A robot standing in a 4 m x 3 m room: `revolutions` LD06 turns at 10 Hz.
std::vector<dpcr::Ld06EmittedPacket> RoomPackets(int revolutions) {
  std::vector<dpcr::Ld06EmittedPacket> packets;
  auto scan = std::make_unique<dpcr::DeviceScan>();
  for (int k = 0; k < revolutions; ++k) {
    scan->stamp_us = 100000 * k;
    scan->beams.clear();
    for (int i = 0; i < 450; ++i) {
      const float a = 2.0f * dpcr::kPi * static_cast<float>(i) / 450.0f;
      const float c = std::fabs(std::cos(a)), s = std::fabs(std::sin(a));
      dpcr::Beam b;
      b.angle_rad = dpcr::NormalizeAngle(a);
      b.range_m = std::min(c > 1e-6f ? 2.0f / c : 1e6f, s > 1e-6f ? 1.5f / s : 1e6f);
      b.offset_us = static_cast<std::int32_t>(std::lround(100000.0 * i / 450));
      (void)scan->beams.push_back(b);
    }
    dpcr::EmitLd06Revolution(*scan, dpcr::LidarAngleMap{1.0f, 0.0f},
                             [&packets](const dpcr::Ld06EmittedPacket& p) { packets.push_back(p); });
  }
  return packets;
}

}  // namespace

TEST_CASE("The device pipeline into the mapper makes zero heap allocations after start-up") {
  const std::vector<dpcr::Ld06EmittedPacket> packets = RoomPackets(30);
  auto mapper = std::make_unique<MapperType>();  // start-up: the allocations a host test may make
  REQUIRE(mapper->Init(dpcr::MapperConfig{}) == dpcr::Status::kOk);
  MapperSink sink(mapper.get());
  dpcr::DevicePipelineConfig config;
  config.lidar.assembler.angle_map = dpcr::LidarAngleMap{1.0f, 0.0f};
  auto pipeline = std::make_unique<dpcr::DevicePipeline>(config, &sink);

  dpcr::test::ArmAllocationCounter();
  std::uint8_t sequence = 0;
  std::int64_t next_ticks_us = 0;
  for (const dpcr::Ld06EmittedPacket& p : packets) {
    for (; next_ticks_us <= p.arrival_us; next_ticks_us += 10000, ++sequence) {  // 100 Hz, standing still
      dpcr::WheelTicksFrame ticks;
      ticks.sequence = sequence;
      ticks.time_10us = static_cast<std::uint32_t>(next_ticks_us / dpcr::kWheelTimeUnitUs);
      pipeline->FeedCan(dpcr::EncodeWheelFrame(ticks), next_ticks_us);
    }
    pipeline->FeedAllLidar(p.bytes, sizeof(p.bytes), p.arrival_us);
  }
  const std::size_t allocations = dpcr::test::DisarmAllocationCounter();
  const dpcr::DevicePipelineCounters c = pipeline->counters();
  INFO("scans " << c.scans << ", odometry samples " << c.odometry);
  REQUIRE(c.scans >= 28);
  REQUIRE(mapper->counters().scans == c.scans);
  REQUIRE(c.odometry > 250);
  CHECK(allocations == 0);
}
