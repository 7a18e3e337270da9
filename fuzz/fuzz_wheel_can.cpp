// CAN frames -> WheelCanDecoder -> DiffDriveOdometry: no crash, time never runs backwards (each
// stream), the counters add up, and the integrated pose stays finite.
// Input: 13 bytes per frame (4-byte id little-endian, DLC, 8 data bytes).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz/fuzz_check.hpp"
#include "hal/diff_drive_odometry.hpp"
#include "hal/wheel_can_protocol.hpp"
#include "hal/wheel_lift_state.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  dpcr::WheelCanDecoder decoder;
  dpcr::DiffDriveOdometry odometry;
  std::int64_t last_ticks_time = INT64_MIN, last_gyro_time = INT64_MIN, last_status_time = INT64_MIN;
  std::uint32_t frames = 0;
  for (std::size_t i = 0; i + 13 <= size; i += 13) {
    dpcr::CanFrame frame;
    frame.id = static_cast<std::uint32_t>(data[i]) | static_cast<std::uint32_t>(data[i + 1]) << 8 |
               static_cast<std::uint32_t>(data[i + 2]) << 16 | static_cast<std::uint32_t>(data[i + 3]) << 24;
    frame.dlc = data[i + 4];
    std::memcpy(frame.data, &data[i + 5], 8);
    ++frames;
    switch (decoder.Feed(frame)) {
      case dpcr::CanDecodeResult::kTicks: {
        const dpcr::WheelTicks& t = decoder.ticks();
        FUZZ_CHECK(t.device_time_us >= last_ticks_time);
        last_ticks_time = t.device_time_us;
        const dpcr::OdometrySample s = odometry.Update(t, t.device_time_us);
        FUZZ_CHECK(std::isfinite(s.pose.x) && std::isfinite(s.pose.y) && std::isfinite(s.pose.theta));
        break;
      }
      case dpcr::CanDecodeResult::kGyro:
        FUZZ_CHECK(decoder.gyro().device_time_us >= last_gyro_time);
        last_gyro_time = decoder.gyro().device_time_us;
        FUZZ_CHECK(std::fabs(decoder.gyro().yaw_rate_rad_s) <= 32.768f);
        break;
      case dpcr::CanDecodeResult::kStatus:
        FUZZ_CHECK(decoder.status().device_time_us >= last_status_time);
        last_status_time = decoder.status().device_time_us;
        {  // the lift state's comparison across streams stays within half the wrap
          const std::int64_t bound = dpcr::kWheelTimeWrapUnits / 2 * dpcr::kWheelTimeUnitUs;
          const std::int64_t d = dpcr::DeviceTimeDifferenceUs(last_status_time, last_ticks_time == INT64_MIN ? 0 : last_ticks_time);
          FUZZ_CHECK(d >= -bound && d < bound);
        }
        break;
      default:
        break;
    }
  }
  const dpcr::WheelCanCounters& c = decoder.counters();
  FUZZ_CHECK(c.ticks_frames + c.gyro_frames + c.status_frames + c.foreign + c.error_frames + c.bad_dlc + c.duplicated +
                 c.reordered ==
             frames);
  FUZZ_CHECK(c.reserved_flags <= c.status_frames);
  return 0;
}
