// The whole device path (hal/device_pipeline.hpp) on interleaved lidar bytes and CAN frames, as
// the firmware and dpcr-replay feed it: LidarStream (LD06 or XV-11 decoder, packet timing,
// ScanAssembler) and WheelCanDecoder + DiffDriveOdometry. No crash, and what reaches the sink is
// sane: at most the scan's capacity of beams with finite angles and ranges, finite poses.
// Input: byte 0 picks the lidar (bit 0: XV-11) and its timing (bit 1: the LD06's clock); then
// records: tag byte (bit 0: CAN frame, else lidar bytes), a time step byte (x 1 ms, the
// high bit x 1 s: silences), then for lidar a length byte and that many bytes, for CAN a 4-byte
// id, a DLC byte and 8 data bytes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz/fuzz_check.hpp"
#include "hal/device_pipeline.hpp"

namespace {

class CheckingSink final : public dpcr::DeviceSink {
 public:
  void AddOdometry(const dpcr::OdometrySample& s) override {
    FUZZ_CHECK(std::isfinite(s.pose.x) && std::isfinite(s.pose.y) && std::isfinite(s.pose.theta));
    FUZZ_CHECK(!s.has_gyro || std::isfinite(s.gyro_yaw_rate));
    ++odometry;
    if (s.lifted) ++lifted;
  }
  void AddScan(const dpcr::DeviceScan& scan) override {
    FUZZ_CHECK(scan.beams.size() <= static_cast<std::size_t>(dpcr::VacuumProfile::kMaxBeams));
    for (const dpcr::Beam& b : scan.beams) {
      FUZZ_CHECK(std::isfinite(b.angle_rad) && std::fabs(b.angle_rad) <= 8.0f);
      FUZZ_CHECK(std::isfinite(b.range_m) && b.range_m >= 0.0f && b.range_m <= 20.0f);
    }
    ++scans;
  }
  std::uint32_t odometry = 0;
  std::uint32_t lifted = 0;
  std::uint32_t scans = 0;
};

std::uint32_t LoadLe32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  dpcr::DevicePipelineConfig config;
  config.lidar.kind = (data[0] & 1) != 0 ? dpcr::LidarKind::kXv11 : dpcr::LidarKind::kLd06;
  config.lidar.timing = (data[0] & 2) != 0 && config.lidar.kind == dpcr::LidarKind::kLd06 ? dpcr::LidarTiming::kDeviceClock
                                                                                          : dpcr::LidarTiming::kArrival;
  // ~71 KiB, built per input (on the heap) so that no state carries over from one input to the next.
  CheckingSink sink;
  auto* pipeline = new dpcr::DevicePipeline(config, &sink);
  std::int64_t now_us = 1000000;
  std::size_t i = 1;
  while (i + 2 <= size) {
    const std::uint8_t tag = data[i];
    const std::uint8_t step = data[i + 1];
    i += 2;
    now_us += static_cast<std::int64_t>(step & 0x7F) * 1000 + ((step & 0x80) != 0 ? 1000000 : 0);
    if ((tag & 1) != 0) {
      if (i + 13 > size) break;
      dpcr::CanFrame frame;
      frame.id = LoadLe32(&data[i]);
      frame.dlc = data[i + 4];
      std::memcpy(frame.data, &data[i + 5], 8);
      i += 13;
      pipeline->FeedCan(frame, now_us);
    } else {
      if (i >= size) break;
      std::size_t n = data[i++];
      if (n > size - i) n = size - i;
      pipeline->FeedAllLidar(&data[i], n, now_us);
      i += n;
    }
  }
  const dpcr::DevicePipelineCounters c = pipeline->counters();
  FUZZ_CHECK(c.odometry == sink.odometry && c.lifted_samples == sink.lifted && c.lifts <= c.can.status_frames);
  delete pipeline;
  return 0;
}
