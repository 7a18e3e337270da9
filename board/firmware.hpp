// The firmware's work on its ports (hal/ports.hpp), whatever waits on them: start-up (the mapper,
// the device pipeline, the save worker and its buffer: every allocation of the run), lidar bytes
// and CAN frames into the DevicePipeline -> Mapper, degraded devices (no CAN: the lidar alone,
// the wheels taken back when they return), the counters line, the watchdog kick, autosaves handed
// to the save worker, and the final save. The loop that drives it is RunFirmwareLoop
// (firmware_loop.hpp): poll() over the board's devices, or a test's fake ports and clock.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "board/save_worker.hpp"
#include "core/capacity.hpp"
#include "core/mapper.hpp"
#include "hal/device_options.hpp"
#include "hal/device_pipeline.hpp"
#include "hal/diff_drive_odometry.hpp"
#include "hal/lidar_stream.hpp"
#include "hal/ports.hpp"

namespace dpcr::board {

struct FirmwareConfig {
  std::string uart_device = "/dev/ttyS1";
  int baud = 230400;
  LidarKind lidar = LidarKind::kLd06;
  LidarAngleMap angle_map;                 // upright LD06: clockwise (angle_sign -1)
  LidarTiming lidar_timing = LidarTiming::kArrival;  // kDeviceClock: LD06 packet stamps
  std::string can_interface = "can0";
  int can_fd = -1;                         // an already-open fd carrying struct can_frame (tests)
  // Wheel geometry; the encoder's ticks per revolution have no default (0: not stated, Start
  // refuses): a wrong count loses the robot within seconds (dpcr-sim's device files use 4096).
  DiffDriveConfig wheels{DiffDriveConfig{}.wheel_radius_m, DiffDriveConfig{}.track_width_m, 0.0f};
  float max_range_m = DeviceOptions{}.max_range_m;  // the device options (hal/device_options.hpp)
  float laser_offset_m = 0.0f;
  // The robot's largest acceleration (FrontEndConfig::max_acceleration_mps2): without wheel
  // translation (a gyro alone) the constant-velocity guess changes by no more. 0: no limit.
  float max_accel_mps2 = FrontEndConfig{}.max_acceleration_mps2;
  // The prediction's heading: "model" (the lidar's: ModelGyroHeading), "wheels" or "gyro" (the
  // CAN gyro's); FrontEndConfig::gyro_heading is GyroHeadingFor(heading, lidar), as in dpcr-replay.
  std::string heading = "model";
  std::string map_dir = ".";               // loads map.dpcr from there and saves it there
  int autosave_s = 60;                     // 0: only on exit
  int lidar_timeout_ms = 2000;             // no packet for this long: reported, exit 2
  int wheel_timeout_ms = 500;              // no ticks frame for this long: mapping from the lidar alone
  int can_retry_ms = 2000;                 // without the bus: the next try to open it
  int status_period_ms = 60000;            // the counters line
  // Tests: the per-scan trajectory, written as TUM at exit with the final map anchors (room for
  // `trajectory_capacity` scans, reserved at start-up); the received streams, recorded as device
  // files with their device.json (board/stream_recorder.hpp). Empty: off.
  std::string trajectory_path;
  std::size_t trajectory_capacity = 72000;  // two hours at 10 Hz
  std::string record_dir;
};

// What the firmware runs on; none is owned. `notifier` may be null (no service manager).
struct FirmwarePorts {
  ByteSource* lidar = nullptr;
  CanSource* can = nullptr;
  const Clock* clock = nullptr;
  BlobStore* storage = nullptr;  // holds "map.dpcr": loaded at start, replaced by each save
  ServiceNotifier* notifier = nullptr;
};

using BoardMapper = Mapper<VacuumProfile>;

// What the firmware has done, for the counters line and tests.
struct FirmwareCounters {
  std::uint32_t scans = 0;
  std::uint32_t saves_requested = 0;
  std::uint32_t saves_ok = 0;
  std::uint32_t saves_failed = 0;
  std::uint32_t saves_deferred = 0;   // due while the previous one was still being written
  std::uint32_t can_failures = 0;     // the bus lost (read error, closed) or not there at start
  std::uint32_t wheel_silences = 0;   // stretches without ticks frames past the timeout
  std::uint32_t watchdog_kicks = 0;
};

class Firmware {
 public:
  // Status and errors go to `log`, each line prefixed "dpcr-firmware: ".
  Firmware(const FirmwareConfig& config, const FirmwarePorts& ports, std::FILE* log);
  ~Firmware();
  Firmware(const Firmware&) = delete;
  Firmware& operator=(const Firmware&) = delete;

  // Validates the configuration, allocates the mapper, the device pipeline and the save worker
  // (its buffer holds the largest map the profile can write), loads map.dpcr when the store has
  // one (the robot starts where the saved map's first session started; a map that cannot be
  // loaded is one error line, the run maps from scratch) and checks that the store takes a new
  // map.dpcr (an unwritable map directory is an error now, not at the first save). False, logged,
  // when any of it fails.
  bool Start();
  // The CAN port could not be opened at start-up (`reason`): mapping from the lidar alone, the
  // bus tried again every can_retry_ms.
  void CanUnavailable(const char* reason);
  // Says the service is ready (log line, notifier), once the ports are open.
  void Running();
  // A stop request (SIGTERM / SIGINT): logged; the caller then finishes.
  void StopRequested();
  // The loop's wait failed with `error` (errno): logged.
  void WaitFailed(int error);

  // One read from the lidar port into the pipeline; false once the port ended or failed (logged).
  bool ServiceLidar();
  // Every frame the CAN port has queued. A failed port is logged once and retried later; the
  // lidar maps alone meanwhile.
  void ServiceCan();
  // True (logged) when no lidar packet arrived for longer than the timeout.
  bool LidarSilent();
  // The timers: the wheels' silence, the bus retry, the save worker's result and the autosave,
  // the counters line, the watchdog kick. Never waits.
  void ServiceTimers();
  // When the loop should wake at the latest (the next timer), in clock time.
  std::int64_t next_timer_us() const;
  bool can_up() const { return can_up_; }
  bool wheels_up() const { return wheels_up_; }

  // The final save (waits for the save worker); returns `exit_code`, or 1 for a clean stop
  // whose map could not be saved.
  int Finish(int exit_code);

  const BoardMapper& mapper() const { return *mapper_; }
  std::uint32_t scans() const { return counters_.scans; }
  const FirmwareCounters& counters() const { return counters_; }
  DevicePipelineCounters device_counters() const { return pipeline_->counters(); }
  // The device counters and the peak resident set, one line ("dpcr-firmware: summary ...").
  void PrintSummary();

 private:
  class MapperSink;
  void FlushLidar();
  void LoadSavedMap();
  bool CheckMapDirectory();
  void CanDown(const char* what, int error);
  void TryReopenCan(std::int64_t now_us);
  void WatchWheels(std::int64_t now_us);
  // Copies the map file into the save worker's buffer and hands it over (CPU only); false
  // (logged) when the map is empty or does not fit.
  bool SubmitSave();
  void CollectSave();
  void PrintCounters(std::int64_t now_us);
  bool WriteTrajectory(std::string* error) const;

  FirmwareConfig config_;
  FirmwarePorts ports_;
  std::FILE* log_;
  std::unique_ptr<BoardMapper> mapper_;
  std::unique_ptr<MapperSink> sink_;
  std::unique_ptr<DevicePipeline> pipeline_;
  SaveWorker saver_;
  FirmwareCounters counters_;
  bool lidar_flushed_ = false;
  bool can_up_ = true;
  bool wheels_up_ = false;        // ticks frames are coming
  bool wheels_ever_ = false;
  bool wheel_translation_ignored_ = false;  // the mapper's WheelCheck, as last logged
  std::int64_t wheels_lost_us_ = 0;
  std::int64_t start_us_ = 0;
  std::int64_t next_status_us_ = 0;
  std::int64_t next_save_us_ = 0;
  std::int64_t next_can_retry_us_ = INT64_MAX;
  std::int64_t next_kick_us_ = INT64_MAX;
  std::int64_t watchdog_period_us_ = 0;
  std::int64_t last_lidar_us_ = 0;
  std::uint32_t scans_at_last_status_ = 0;
  std::uint8_t buffer_[4096] = {};
};

}  // namespace dpcr::board
