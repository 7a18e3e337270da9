#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "core/geometry/pose2.hpp"
#include "hal/ld06_decoder.hpp"
#include "hal/scan_assembler.hpp"
#include "hal/xv11_decoder.hpp"
#include "lidar_stream_helpers.hpp"

using dpcr::LidarPacket;
using dpcr::ScanAssembler;

namespace {

using BigScan = dpcr::Scan<512>;

// XV-11 style packets: 4 points at 1 degree, 90 per turn, 5 Hz.
LidarPacket XvPacket(int index, std::int64_t t0_us) {
  LidarPacket p;
  p.start_deg = static_cast<float>(4 * index);
  p.step_deg = 1.0f;
  p.point_dt_us = 200000.0f / 360.0f;
  p.stamp_us = t0_us + static_cast<std::int64_t>(4 * index * 200000 / 360);
  p.count = 4;
  for (int i = 0; i < 4; ++i) p.range_mm[i] = static_cast<std::uint16_t>(1000 + 4 * index + i);
  return p;
}

}  // namespace

TEST_CASE("assembler splits revolutions at the wrap with interpolated times") {
  auto a = std::make_unique<ScanAssembler>();
  auto scan = std::make_unique<BigScan>();
  int ready = 0;
  for (int rev = 0; rev < 3; ++rev) {
    for (int k = 0; k < 90; ++k) {
      if (a->Add(XvPacket(k, rev * 200000))) {
        ++ready;
        CHECK(k == 0);  // the first packet of the next turn closes the previous one
        dpcr::RevolutionInfo info;
        a->TakeScan(scan.get(), &info);
        REQUIRE(scan->beams.size() == 360);
        CHECK(scan->stamp_us == (rev - 1) * 200000);
        CHECK(scan->beams[1].offset_us == 556);   // 200 ms / 360, rounded
        CHECK(scan->beams[359].offset_us == Approx(359 * 200000 / 360).margin(2));
        CHECK(scan->beams[0].range_m == Approx(1.0f));
        CHECK(scan->beams[90].range_m == Approx(1.09f));
        // Clockwise device angle 90 deg is -90 deg in the scan frame.
        CHECK(scan->beams[90].angle_rad == Approx(-dpcr::kPi / 2));
        CHECK(info.gaps == 0);
        CHECK_FALSE(info.decimated);
      }
    }
  }
  CHECK(ready == 2);
  CHECK(a->counters().revolutions == 2);
}

TEST_CASE("assembler records a dropped-packet gap") {
  auto a = std::make_unique<ScanAssembler>();
  auto scan = std::make_unique<BigScan>();
  for (int k = 0; k < 90; ++k) {
    if (k == 40 || k == 41) continue;  // two packets lost
    static_cast<void>(a->Add(XvPacket(k, 0)));
  }
  REQUIRE(a->Add(XvPacket(0, 200000)));
  dpcr::RevolutionInfo info;
  a->TakeScan(scan.get(), &info);
  CHECK(scan->beams.size() == 352);
  CHECK(info.gaps == 1);
  CHECK(info.missing_deg == Approx(8.0f));
  CHECK(a->counters().gaps == 1);
}

TEST_CASE("assembler counts a silence of whole turns as a dropout and drops the turn it cuts") {
  auto a = std::make_unique<ScanAssembler>();
  auto scan = std::make_unique<BigScan>();
  int ready = 0;
  for (int rev = 0; rev < 6; ++rev) {
    for (int k = 0; k < 90; ++k) {
      if (rev == 2 && k >= 45) continue;       // the lidar stops mid-turn for 3 turns (0.6 s):
      if (rev == 3 || rev == 4) continue;      // it comes back at the same angle one turn later
      if (rev == 5 && k < 45) continue;
      if (a->Add(XvPacket(k, rev * 200000))) {
        ++ready;
        a->TakeScan(scan.get());
      }
    }
  }
  CHECK_FALSE(a->Add(XvPacket(0, 6 * 200000)));  // closes the cut turn: dropped
  CHECK(a->counters().dropouts == 1);
  CHECK(a->counters().gaps == 0);               // angles alone see nothing missing
  CHECK(a->counters().partial_dropped == 1);    // turn 2 + half of turn 5: never a scan
  CHECK(ready == 2);                            // turns 0 and 1
}

TEST_CASE("assembler drops a partial first revolution") {
  auto a = std::make_unique<ScanAssembler>();
  for (int k = 45; k < 90; ++k) CHECK_FALSE(a->Add(XvPacket(k, 0)));
  CHECK_FALSE(a->Add(XvPacket(0, 200000)));
  CHECK(a->counters().partial_dropped == 1);
  for (int k = 1; k < 90; ++k) static_cast<void>(a->Add(XvPacket(k, 200000)));
  CHECK(a->Add(XvPacket(0, 400000)));
}

TEST_CASE("assembler decimates evenly instead of truncating") {
  // 1500 points per turn (slow LD06) into a 512-beam scan: the scan must still span the turn.
  auto a = std::make_unique<ScanAssembler>();
  auto scan = std::make_unique<BigScan>();
  const auto packets = dpcr_test::MakeLd06Packets(2, 1080, 0);
  bool got = false;
  dpcr::RevolutionInfo info;
  for (const auto& p : packets) {
    if (a->Add(dpcr::ToLidarPacket(p, p.timestamp_ms * 1000))) {
      a->TakeScan(scan.get(), &info);
      got = true;
    }
  }
  REQUIRE(got);
  CHECK(info.points_in == Approx(1500).margin(12));
  CHECK(info.decimated);
  CHECK(scan->beams.size() == 512);
  // First beam near device 0 deg, last near device 360 deg (scan angle just above 0 again).
  CHECK(scan->beams[0].angle_rad == Approx(0.0f).margin(0.01));
  CHECK(std::fabs(scan->beams[511].angle_rad) < 0.02f);
  CHECK(std::fabs(scan->beams[256].angle_rad) == Approx(dpcr::kPi).margin(0.02));
  // Evenly spaced: consecutive beams about 360/512 degrees apart.
  for (std::size_t i = 1; i < 511; ++i) {
    const float d = std::remainder(scan->beams[i - 1].angle_rad - scan->beams[i].angle_rad, 2 * dpcr::kPi);
    REQUIRE(d == Approx(2 * dpcr::kPi / 512).margin(0.005));
  }
  CHECK(a->counters().decimated == 1);
}

TEST_CASE("assembler decimates in place past its raw capacity") {
  // 3000 points per turn overflow the 2048-point raw buffer.
  auto a = std::make_unique<ScanAssembler>();
  auto scan = std::make_unique<BigScan>();
  const int n = 3000;
  for (int rev = 0; rev < 2; ++rev) {
    for (int k = 0; k < n / 12; ++k) {
      LidarPacket p;
      p.start_deg = 360.0f * static_cast<float>(12 * k) / n;
      p.step_deg = 360.0f / n;
      p.count = 12;
      p.stamp_us = rev * 100000 + k * 400;
      for (auto& r : p.range_mm) r = 1500;
      static_cast<void>(a->Add(p));
    }
  }
  REQUIRE(a->revolution_ready());
  dpcr::RevolutionInfo info;
  a->TakeScan(scan.get(), &info);
  CHECK(info.points_in == 3000);
  CHECK(scan->beams.size() == 512);
  CHECK(std::fabs(scan->beams[511].angle_rad) < 0.03f);
}

TEST_CASE("at the end of a stream the last revolution is flushed when nearly complete") {
  auto a = std::make_unique<ScanAssembler>();
  auto scan = std::make_unique<BigScan>();
  CHECK_FALSE(a->Flush());  // nothing yet
  for (int rev = 0; rev < 2; ++rev) {
    for (int k = 0; k < 90; ++k) {
      if (a->Add(XvPacket(k, rev * 200000))) a->TakeScan(scan.get());
    }
  }
  REQUIRE(a->Flush());  // the second turn reached 359 deg: kept
  a->TakeScan(scan.get());
  CHECK(scan->beams.size() == 360);
  CHECK(scan->stamp_us == 200000);
  CHECK(a->counters().revolutions == 2);
  CHECK_FALSE(a->Flush());  // once
  // A turn cut short at the end is not a revolution.
  for (int k = 0; k < 45; ++k) (void)a->Add(XvPacket(k, 400000));
  CHECK_FALSE(a->Flush());
}
