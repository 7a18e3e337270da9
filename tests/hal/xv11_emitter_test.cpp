// The XV-11 emitter (dpcr-sim --lidar xv11 --emit-device) through the XV-11 decoder and stream.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/geometry/pose2.hpp"
#include "hal/lidar_stream.hpp"
#include "hal/xv11_emitter.hpp"

TEST_CASE("an XV-11 revolution emitted as packets decodes to the same readings") {
  auto scan = std::make_unique<dpcr::Scan<512>>();
  scan->stamp_us = 1000000;
  for (int i = 0; i < 360; ++i) {
    dpcr::Beam b;
    b.angle_rad = dpcr::NormalizeAngle(static_cast<float>(i) * dpcr::kPi / 180.0f);
    b.range_m = i % 7 == 0 ? 0.0f : (i == 5 ? 7.5f : 1.0f + 0.01f * static_cast<float>(i));  // 7.5 m: past 6 m
    b.offset_us = i * 555;
    (void)scan->beams.push_back(b);
  }
  const dpcr::LidarAngleMap map{1.0f, 0.0f};
  dpcr::Xv11EmittedPacket packets[dpcr::kXv11PacketsPerRevolution];
  dpcr::EncodeXv11Revolution(scan->beams.data(), scan->beams.size(), scan->stamp_us, map, 5.0f, packets);
  CHECK(packets[0].bytes[0] == dpcr::kXv11Start);
  CHECK(packets[89].bytes[1] == dpcr::kXv11LastIndex);
  CHECK(packets[89].arrival_us == scan->stamp_us + 199444);  // reading 359 of a 200 ms turn

  dpcr::LidarStreamConfig config;
  config.kind = dpcr::LidarKind::kXv11;
  config.assembler.angle_map = map;
  auto stream = std::make_unique<dpcr::LidarStream>(config);
  for (const auto& p : packets) {
    std::size_t used = 0;
    while (used < sizeof(p.bytes)) used += stream->Feed(p.bytes + used, sizeof(p.bytes) - used, p.arrival_us);
  }
  REQUIRE(stream->Flush());  // the last (here: only) revolution of the stream
  auto out = std::make_unique<dpcr::Scan<512>>();
  stream->TakeScan(out.get());
  REQUIRE(out->beams.size() == 360);
  CHECK(std::llabs(out->stamp_us - scan->stamp_us) <= 1);
  for (std::size_t i = 0; i < 360; ++i) {
    const float expected = (i % 7 == 0 || i == 5) ? 0.0f : scan->beams[i].range_m;
    REQUIRE(out->beams[i].range_m == Approx(expected).margin(1e-3));
    REQUIRE(std::fabs(dpcr::NormalizeAngle(out->beams[i].angle_rad - scan->beams[i].angle_rad)) < 1e-4f);
  }
  CHECK(stream->counters().invalid_points > 50);
}
