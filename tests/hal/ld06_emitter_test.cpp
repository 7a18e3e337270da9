#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/geometry/pose2.hpp"
#include "hal/ld06_emitter.hpp"
#include "hal/lidar_stream.hpp"

namespace {

using TestScan = dpcr::Scan<512>;

// A simulator-like scan: `n` beams CCW from -pi, 10 Hz sweep, stamped at the first beam.
void MakeSimScan(TestScan* scan, int n, std::int64_t stamp_us, int seed) {
  scan->beams.clear();
  scan->stamp_us = stamp_us;
  for (int i = 0; i < n; ++i) {
    dpcr::Beam b;
    b.angle_rad = -dpcr::kPi + 2 * dpcr::kPi * static_cast<float>(i) / static_cast<float>(n);
    b.range_m = (i + seed) % 17 == 0 ? 0.0f : 0.5f + 0.001f * static_cast<float>((i * 37 + seed) % 5000);
    b.offset_us = static_cast<std::int32_t>(std::lround(100000.0 * i / n));
    REQUIRE(b.range_m < 12.0f);
    REQUIRE(scan->beams.push_back(b) == dpcr::Status::kOk);
  }
}

}  // namespace

TEST_CASE("scan -> LD06 bytes -> decoder -> assembler -> same scan within LD06 quantisation") {
  dpcr::LidarStreamConfig config;
  // Device 0 deg at scan angle -pi, sweeping counter-clockwise as the simulator does.
  config.assembler.angle_map.angle_sign = 1.0f;
  config.assembler.angle_map.angle_offset_rad = -dpcr::kPi;
  auto stream = std::make_unique<dpcr::LidarStream>(config);
  auto in = std::make_unique<TestScan>();
  auto out = std::make_unique<TestScan>();
  for (int n : {450, 360, 455}) {
    int compared = 0;
    for (int k = 0; k < 4; ++k) {
      const std::int64_t stamp = 1000000 + 100000 * k + (n == 455 ? 7 : 0);
      MakeSimScan(in.get(), n, stamp, k);
      std::vector<dpcr::Ld06EmittedPacket> packets;
      dpcr::EmitLd06Revolution(*in, config.assembler.angle_map,
                               [&packets](const dpcr::Ld06EmittedPacket& p) { packets.push_back(p); });
      CHECK(packets.size() == dpcr::Ld06PacketCount(static_cast<std::size_t>(n)));
      for (const auto& p : packets) {
        std::size_t used = 0;
        while (used < sizeof(p.bytes)) {
          used += stream->Feed(p.bytes + used, sizeof(p.bytes) - used, p.arrival_us);
          if (!stream->revolution_ready()) continue;
          dpcr::RevolutionInfo info;
          stream->TakeScan(out.get(), &info);
          // Previous scan of this size (the stream closes a revolution at the next one's start).
          if (k == 0) continue;  // the previous size's last scan
          MakeSimScan(in.get(), n, stamp - 100000, k - 1);
          REQUIRE(out->beams.size() == in->beams.size());
          CHECK(out->stamp_us == Approx(in->stamp_us).margin(3));
          CHECK(info.gaps == 0);
          for (std::size_t i = 0; i < in->beams.size(); ++i) {
            const dpcr::Beam& a = in->beams[i];
            const dpcr::Beam& b = out->beams[i];
            REQUIRE(std::fabs(std::remainder(a.angle_rad - b.angle_rad, 2 * dpcr::kPi)) < 0.01f * dpcr::kPi / 180 + 2e-5f);
            REQUIRE(std::fabs(a.range_m - b.range_m) <= 0.0005f + 1e-6f);
            REQUIRE(std::abs(a.offset_us - b.offset_us) <= 3);
          }
          ++compared;
          MakeSimScan(in.get(), n, stamp, k);
        }
      }
    }
    CHECK(compared == 3);
  }
  const dpcr::LidarStreamCounters c = stream->counters();
  CHECK(c.bad_packets == 0);
  CHECK(c.resyncs == 0);
  CHECK(c.gaps == 0);
}
