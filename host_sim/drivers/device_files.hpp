// The device path on the host: write a run as device files (LD06 UART capture + candump log of
// the wheel protocol), and replay such files through the same decoders as the firmware.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/capacity.hpp"
#include "core/front_end/odometry.hpp"
#include "core/geometry/scan.hpp"
#include "hal/diff_drive_odometry.hpp"
#include "hal/lidar_stream.hpp"
#include "hal/wheel_can_protocol.hpp"
#include "host_sim/drivers/candump_log.hpp"
#include "host_sim/drivers/uart_capture.hpp"

namespace dpcr {

using DeviceScan = Scan<VacuumProfile::kMaxBeams>;

struct DeviceFilesConfig {
  // Device 0 deg = scan angle 0, sweeping counter-clockwise: matches dpcr-sim, whose
  // revolutions start at angle 0, so a device revolution is the simulator's revolution.
  // A real upright LD06 needs angle_sign = -1 (clockwise).
  LidarAngleMap angle_map{1.0f, 0.0f};
  DiffDriveConfig wheels{0.035f, 0.235f, 4096.0f};
  std::string can_interface = "can0";
};

// Writes DIR/lidar.uart and DIR/wheels.log (DeviceEmitter::Open/Close). Scans become LD06
// packets, one capture chunk per packet at its arrival time; odometry poses become wheel ticks
// (inverse diff-drive on each increment, cumulative rounding) plus a gyro frame when present.
class DeviceEmitter {
 public:
  explicit DeviceEmitter(const DeviceFilesConfig& config = DeviceFilesConfig()) : config_(config) {}
  bool Open(const std::string& dir, std::string* error);
  bool AddScan(const DeviceScan& scan);
  void AddOdometry(const OdometrySample& sample);
  bool Close(std::string* error);

 private:
  DeviceFilesConfig config_;
  std::string dir_;
  UartCaptureWriter uart_;
  std::vector<CandumpRecord> can_;
  bool started_ = false;
  Pose2 last_pose_;
  double left_m_ = 0.0;
  double right_m_ = 0.0;
  std::uint8_t ticks_seq_ = 0;
  std::uint8_t gyro_seq_ = 0;
};

struct DeviceReplayCounters {
  LidarStreamCounters lidar;
  WheelCanCounters can;
  std::uint32_t scans = 0;
  std::uint32_t odometry = 0;
};

// Replays a UART capture + candump log in time order through LidarStream, WheelCanDecoder and
// DiffDriveOdometry. Next() yields odometry samples and scans; a scan comes after every
// odometry sample recorded up to the time its revolution closed.
class DeviceReplay {
 public:
  enum class Event { kOdometry, kScan, kEnd };

  DeviceReplay(const DeviceFilesConfig& files, const LidarStreamConfig& lidar);
  // Either path may be empty (that stream is absent).
  bool Open(const std::string& uart_path, const std::string& candump_path, std::string* error);
  Event Next();
  const OdometrySample& odometry() const { return odometry_; }
  const DeviceScan& scan() const { return *scan_; }
  DeviceReplayCounters counters() const;

 private:
  DeviceFilesConfig files_;
  std::unique_ptr<LidarStream> lidar_;
  std::unique_ptr<UartCaptureSource> uart_;
  std::unique_ptr<CandumpSource> can_;
  WheelCanDecoder wheels_;
  DiffDriveOdometry odo_;
  DeviceTimeBase wheel_time_;
  GyroRate last_gyro_;
  bool have_gyro_ = false;
  std::vector<std::uint8_t> pending_;
  std::size_t pending_at_ = 0;
  std::int64_t pending_stamp_ = 0;
  OdometrySample odometry_;
  std::unique_ptr<DeviceScan> scan_;
  std::uint32_t scans_ = 0;
  std::uint32_t odometry_count_ = 0;
};

}  // namespace dpcr
