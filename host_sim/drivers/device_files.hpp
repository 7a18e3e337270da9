// The device path on the host: write a run as device files (LD06 UART capture + candump log of
// the wheel protocol), and replay such files through the firmware's DevicePipeline.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/front_end/odometry.hpp"
#include "hal/device_options.hpp"
#include "hal/device_pipeline.hpp"
#include "hal/diff_drive_odometry.hpp"
#include "hal/lidar_stream.hpp"
#include "host_sim/drivers/candump_log.hpp"
#include "host_sim/drivers/uart_capture.hpp"

namespace dpcr {

struct DeviceFilesConfig {
  // Device 0 deg = scan angle 0, sweeping counter-clockwise: matches dpcr-sim, whose
  // revolutions start at angle 0, so a device revolution is the simulator's revolution.
  // A real upright LD06 needs angle_sign = -1 (clockwise).
  LidarAngleMap angle_map{1.0f, 0.0f};
  DiffDriveConfig wheels{0.035f, 0.235f, 4096.0f};
  std::string can_interface = "can0";
  // Written into DIR/device.json with the above (the lidar's range limit and mount).
  float max_range_m = LidarConfig{}.max_range_m;
  float laser_offset_m = 0.0f;
  // The lidar's packets: LD06, or XV-11 (hal/xv11_emitter.hpp) turning at xv11_rate_hz (or at
  // the rate a revolution's beam times give, when it has more than one beam).
  LidarKind lidar = LidarKind::kLd06;
  float xv11_rate_hz = 5.0f;
  // The wheel board's clock and the bus, as the firmware meets them (hal/device_time_base.hpp):
  // the frames' device time runs `wheel_clock_ppm` fast against the host's, starting at
  // `wheel_clock_start_us`; each frame arrives (candump stamp) `can_latency_us` after its device
  // time was taken, plus an exponential jitter of mean `can_jitter_us`, plus, for a fraction
  // `can_spike_fraction` of frames, up to `can_spike_us` more (a loaded SoC); frames stay in
  // order. All zero: an ideal bus (arrival = device time), the default; dpcr-sim --emit-device
  // models a real one (RealisticBus).
  double wheel_clock_ppm = 0.0;
  std::int64_t wheel_clock_start_us = 0;
  std::int64_t can_latency_us = 0;
  double can_jitter_us = 0.0;
  double can_spike_fraction = 0.0;
  double can_spike_us = 0.0;
  std::uint32_t bus_seed = 1;
  // Status frames (0x122: the wheels' lift flag) on every change and at least this often, in
  // device time; 0: none (a robot without them, as in logs from before the frame existed).
  std::int64_t status_period_us = 100000;
};

// A wheel board 35 ppm fast with its clock started 5 s before the host's run, 0.2 ms bus latency,
// 0.5 ms mean jitter and 1 % of frames up to 20 ms late.
inline void RealisticBus(DeviceFilesConfig* c, std::uint32_t seed, double ppm = 35.0) {
  c->wheel_clock_ppm = ppm;
  c->wheel_clock_start_us = 5000000;
  c->can_latency_us = 200;
  c->can_jitter_us = 500.0;
  c->can_spike_fraction = 0.01;
  c->can_spike_us = 20000.0;
  c->bus_seed = seed;
}

// DIR/device.json: the device options a recording was made with (hal/device_options.hpp) and
// its lidar ("ld06" / "xv11"). Read: fields present override `options` / `lidar`; false with
// `error` when the file is unreadable or malformed (a missing file is no error: nothing changes).
bool WriteDeviceDescription(const std::string& path, const DeviceOptions& options, const std::string& lidar,
                            std::string* error);
bool ReadDeviceDescription(const std::string& path, DeviceOptions* options, std::string* lidar, std::string* error);

// Writes DIR/lidar.uart, DIR/wheels.log and DIR/device.json (DeviceEmitter::Open/Close). Scans
// become LD06 or XV-11 packets, one capture chunk per packet at its arrival time; odometry poses
// become wheel ticks (inverse diff-drive on each increment, cumulative rounding) plus a gyro frame
// when present; a sample without wheels (has_wheels false) only its gyro frame. The samples' lift
// flag becomes status frames (on each change and every status_period_us), each sent first among
// the frames of its instant and arriving with the first of them: its state holds for them.
class DeviceEmitter {
 public:
  explicit DeviceEmitter(const DeviceFilesConfig& config = DeviceFilesConfig())
      : config_(config), bus_random_(config.bus_seed) {}
  bool Open(const std::string& dir, std::string* error);
  bool AddScan(const DeviceScan& scan);
  void AddOdometry(const OdometrySample& sample);
  bool Close(std::string* error);

 private:
  void AddGyro(const OdometrySample& sample);
  // A status frame before the frames from `first_frame` on (the sample's), when one is due.
  void AddStatusIfDue(const OdometrySample& sample, std::size_t first_frame);
  // The wheel board's clock at host time `stamp_us`, and a frame's arrival (in order).
  std::int64_t DeviceTimeUs(std::int64_t stamp_us);
  std::int64_t ArrivalUs(std::int64_t stamp_us);
  DeviceFilesConfig config_;
  std::mt19937 bus_random_;
  std::int64_t last_arrival_us_ = INT64_MIN;
  std::int64_t first_stamp_us_ = INT64_MIN;
  std::string dir_;
  UartCaptureWriter uart_;
  std::vector<CandumpRecord> can_;
  bool started_ = false;
  Pose2 last_pose_;
  double left_m_ = 0.0;
  double right_m_ = 0.0;
  std::uint8_t ticks_seq_ = 0;
  std::uint8_t gyro_seq_ = 0;
  std::uint8_t status_seq_ = 0;
  bool status_sent_ = false;
  bool status_lifted_ = false;
  std::int64_t status_device_us_ = 0;  // device time of the last status frame
};

// Replays a UART capture + candump log in time order through a DevicePipeline into `sink`: a
// scan comes after every odometry sample recorded up to the time its revolution closed; at the
// end, the last revolution is flushed (DevicePipeline::FlushLidar).
class DeviceReplay {
 public:
  DeviceReplay(const DeviceFilesConfig& files, const LidarStreamConfig& lidar, DeviceSink* sink);
  // Either path may be empty (that stream is absent). Lines that do not parse are skipped and
  // counted (uart_skipped, can_skipped); false when a file cannot be read, has no valid header,
  // or when most of its lines are bad (a file that is not a recording).
  bool Open(const std::string& uart_path, const std::string& candump_path, std::string* error);
  const SkippedLines& uart_skipped() const { return uart_skipped_; }
  const SkippedLines& can_skipped() const { return can_skipped_; }
  // Replays both files to their end.
  void Run();
  DevicePipelineCounters counters() const { return pipeline_->counters(); }

 private:
  std::unique_ptr<DevicePipeline> pipeline_;
  std::unique_ptr<UartCaptureSource> uart_;
  std::unique_ptr<CandumpSource> can_;
  std::int64_t uart_end_us_ = INT64_MIN;  // the capture's "# end" stamp, if any
  SkippedLines uart_skipped_;
  SkippedLines can_skipped_;
};

}  // namespace dpcr
