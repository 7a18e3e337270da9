#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <memory>

#include "hal/lidar_stream.hpp"
#include "lidar_stream_helpers.hpp"

// Stand-in for a user-recorded LD06 dump (none can be downloaded here): partial packets at
// both ends, line-noise bursts, bit flips, and a motor-speed change from 10 Hz to 6 Hz.
TEST_CASE("noisy LD06 capture decodes with the bad parts counted") {
  const dpcr_test::NoisyCapture capture = dpcr_test::MakeNoisyLd06Capture(1234);
  REQUIRE(capture.corrupted_packets > 0);
  REQUIRE(capture.garbage_bursts > 0);
  for (std::size_t chunk : {1u, 7u, 64u, 4096u}) {
    dpcr::Ld06Decoder d;
    const auto packets = dpcr_test::DecodeAll(&d, capture.bytes, chunk);
    CHECK(packets.size() == static_cast<std::size_t>(capture.good_packets));
    CHECK(d.counters().packets == static_cast<std::uint32_t>(capture.good_packets));
    CHECK(d.counters().crc_failures >= static_cast<std::uint32_t>(capture.corrupted_packets));
    CHECK(d.counters().resyncs >= static_cast<std::uint32_t>(capture.garbage_bursts + capture.corrupted_packets));
  }
  // Through the assembler: the speed change shows as more points per revolution, and the
  // corrupted packets as gaps, never as bad beams.
  auto stream = std::make_unique<dpcr::LidarStream>();
  auto scan = std::make_unique<dpcr::Scan<512>>();
  std::size_t used = 0;
  int revolutions = 0;
  std::uint32_t max_points = 0;
  std::uint32_t min_points = 100000;
  while (used < capture.bytes.size()) {
    used += stream->Feed(capture.bytes.data() + used, capture.bytes.size() - used, 0);
    if (stream->revolution_ready()) {
      dpcr::RevolutionInfo info;
      stream->TakeScan(scan.get(), &info);
      ++revolutions;
      max_points = info.points_in > max_points ? info.points_in : max_points;
      min_points = info.points_in < min_points ? info.points_in : min_points;
      for (const dpcr::Beam& b : scan->beams) REQUIRE((b.range_m > 1.0f && b.range_m < 3.0f));
    }
  }
  // 3 turns at 10 Hz, 2 at 6 Hz; the first closes at the first wrap, the last never closes.
  CHECK(revolutions == 4);
  CHECK(min_points < 460);   // 4500 points/s at 10 Hz = 450 (fewer when packets were lost)
  CHECK(max_points > 700);   // at 6 Hz = 750
  const dpcr::LidarStreamCounters c = stream->counters();
  CHECK(c.gaps >= static_cast<std::uint32_t>(capture.corrupted_packets) - 1);
  CHECK(c.bad_packets >= static_cast<std::uint32_t>(capture.corrupted_packets));
}

TEST_CASE("decode rate of LD06 packets (informational)") {
  const auto bytes = dpcr_test::EncodeAll(dpcr_test::MakeLd06Packets(200, 3600, 0));
  dpcr::Ld06Decoder d;
  const auto start = std::chrono::steady_clock::now();
  const auto packets = dpcr_test::DecodeAll(&d, bytes, 256);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  REQUIRE(packets.size() > 7000);
  std::printf("LD06 decode: %zu packets in %.4f s = %.0f packets/s\n", packets.size(), s,
              static_cast<double>(packets.size()) / s);
}
