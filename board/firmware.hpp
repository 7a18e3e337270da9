// The firmware's work on its ports (hal/ports.hpp), whatever waits on them: start-up (the mapper
// and the device pipeline, allocated once), lidar bytes and CAN frames into the DevicePipeline
// -> Mapper, the lidar-silence check, the status line, autosaves and the final map save.
// RunFirmware (firmware_loop.hpp) drives it with poll() over the board's ports; a test can drive
// it with capture files and a replay clock (host_sim/drivers).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "core/capacity.hpp"
#include "core/mapper.hpp"
#include "hal/device_pipeline.hpp"
#include "hal/device_options.hpp"
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
  DiffDriveConfig wheels;
  float max_range_m = DeviceOptions{}.max_range_m;  // the device options (hal/device_options.hpp)
  float laser_offset_m = 0.0f;
  std::string map_dir = ".";               // loads map.dpcr from there; saves map.dpcr, map.pgm + map.yaml
  int autosave_s = 60;                     // 0: only on exit
  int lidar_timeout_ms = 2000;             // no packet for this long: reported, exit 2
  int status_period_ms = 1000;
  // Tests: the per-scan trajectory, written as TUM at exit with the final map anchors (room for
  // `trajectory_capacity` scans, reserved at start-up); the received streams, recorded as device
  // files (board/stream_recorder.hpp). Empty: off.
  std::string trajectory_path;
  std::size_t trajectory_capacity = 72000;  // two hours at 10 Hz
  std::string record_dir;
};

// What the firmware runs on; none is owned.
struct FirmwarePorts {
  ByteSource* lidar = nullptr;
  CanSource* can = nullptr;
  const Clock* clock = nullptr;
  BlobStore* storage = nullptr;  // holds "map.dpcr" (loaded at start), receives it and "map.pgm", "map.yaml"
};

using BoardMapper = Mapper<VacuumProfile>;

class Firmware {
 public:
  // Status and errors go to `log`, each line prefixed "dpcr-firmware: ".
  Firmware(const FirmwareConfig& config, const FirmwarePorts& ports, std::FILE* log);
  ~Firmware();
  Firmware(const Firmware&) = delete;
  Firmware& operator=(const Firmware&) = delete;

  // Validates the configuration and allocates the mapper and the device pipeline: the run's
  // only allocations besides map loads and saves. Loads map.dpcr when the store has one (the robot
  // starts where the saved map's first session started: its origin); a map that cannot be loaded
  // is reported in one line and the run maps from scratch. False (logged) when the configuration
  // is rejected.
  bool Start();
  // One read from the lidar port into the pipeline; false once the port ended or failed (logged).
  bool ServiceLidar();
  // Every frame the CAN port has queued; false once the port closed or failed (logged).
  bool ServiceCan();
  // True (logged) when no lidar packet arrived for longer than the timeout.
  bool LidarSilent();
  // The status line and the autosave, each when due.
  void ServiceTimers();
  // The final save; returns `exit_code`, or 1 for a clean stop whose map could not be saved.
  int Finish(int exit_code);

  const BoardMapper& mapper() const { return *mapper_; }
  std::uint32_t scans() const;
  // The device counters and the peak resident set, one line ("dpcr-firmware: summary ...").
  void PrintSummary();

 private:
  // The lidar stream ended (or the firmware is finishing): its last revolution, once.
  void FlushLidar();
  bool lidar_flushed_ = false;
  class MapperSink;
  struct SaveResult;
  SaveResult SaveMap();
  void LoadSavedMap();
  bool Store(const char* name, const std::uint8_t* data, std::size_t size, std::string* error);
  void PrintStatus(std::int64_t now_us);
  bool WriteTrajectory(std::string* error) const;

  FirmwareConfig config_;
  FirmwarePorts ports_;
  std::FILE* log_;
  std::unique_ptr<BoardMapper> mapper_;
  std::unique_ptr<MapperSink> sink_;
  std::unique_ptr<DevicePipeline> pipeline_;
  std::int64_t start_us_ = 0;
  std::int64_t next_status_us_ = 0;
  std::int64_t next_save_us_ = 0;
  std::int64_t last_lidar_us_ = 0;
  std::uint32_t scans_at_last_status_ = 0;
  std::uint8_t buffer_[4096] = {};
};

}  // namespace dpcr::board
