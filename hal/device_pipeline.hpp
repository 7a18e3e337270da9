// The device path from received bytes and frames to mapper inputs, one for the firmware and the
// host replay: lidar bytes -> LidarStream (LD06/XV-11 decoder + ScanAssembler) -> scans; CAN
// frames -> WheelCanDecoder -> DiffDriveOdometry -> odometry samples carrying the last gyro
// rate, stamped in host time through the wheel board's clock (DeviceTimeBase: minimum latency,
// drift followed), and marked lifted while the status frames say the wheels are off the floor
// (hal/wheel_lift_state.hpp). Both go to a DeviceSink: the mapper, or a wrapper that also counts
// or times.
// Allocation-free: all state lives in the object (~71 KiB with the vacuum scan: build it once, at
// start-up, off the stack).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/capacity.hpp"
#include "core/front_end/odometry.hpp"
#include "core/geometry/scan.hpp"
#include "hal/can_frame.hpp"
#include "hal/device_time_base.hpp"
#include "hal/diff_drive_odometry.hpp"
#include "hal/lidar_stream.hpp"
#include "hal/wheel_can_protocol.hpp"
#include "hal/wheel_lift_state.hpp"

namespace dpcr {

// A revolution of the robot's lidar: the vacuum profile's scan (every profile but `tiny` takes it).
using DeviceScan = Scan<VacuumProfile::kMaxBeams>;

// Mapper-like receiver of the pipeline's outputs, in the order the devices delivered them.
class DeviceSink {
 public:
  virtual ~DeviceSink() = default;
  virtual void AddOdometry(const OdometrySample& sample) = 0;
  virtual void AddScan(const DeviceScan& scan) = 0;
};

struct DevicePipelineConfig {
  LidarStreamConfig lidar;
  DiffDriveConfig wheels;
  // A ticks frame received this long after the previous one ends a wheel gap (the bus down, the
  // wheel board silent): the odometry resumes from the pose it had, the gap's motion not added
  // (the lidar alone tracked it; added at once it would be a jump in the odometry prior).
  std::int64_t wheel_timeout_us = 500000;
  // How the wheel board's clock is mapped to host time (kFirstFrame: only to measure the difference).
  DeviceTimeBase::Mode wheel_clock = DeviceTimeBase::Mode::kTracked;
};

struct DevicePipelineCounters {
  LidarStreamCounters lidar;
  WheelCanCounters can;
  std::uint32_t scans = 0;
  std::uint32_t odometry = 0;
  std::uint32_t wheel_gaps = 0;  // wheel gaps the odometry resumed after
  std::uint32_t lifts = 0;           // status frames that said "lifted" after one that did not
  std::uint32_t lifted_samples = 0;  // odometry samples sent marked lifted
};

class DevicePipeline {
 public:
  // `sink` must outlive the pipeline.
  DevicePipeline(const DevicePipelineConfig& config, DeviceSink* sink);

  // Consumes lidar bytes that arrived at host time `arrival_us`, up to the end of at most one
  // revolution, which goes to the sink; returns the bytes consumed (feed the rest next, so that
  // frames received meanwhile can go first).
  std::size_t FeedLidar(const std::uint8_t* data, std::size_t size, std::int64_t arrival_us);
  // Feeds every byte (any number of revolutions).
  void FeedAllLidar(const std::uint8_t* data, std::size_t size, std::int64_t arrival_us);
  // The lidar stream has ended (a recording's end): its last revolution goes to the sink when it
  // is nearly complete (no wrap will come to close it).
  void FlushLidar();

  // One CAN frame received at host time `received_us`. A ticks frame becomes an odometry sample
  // stamped on the wheel board's clock (in host time: hal/device_time_base.hpp); a gyro frame
  // updates the rate the next samples carry, and once two have come without a ticks frame, none
  // ever (a robot without wheel encoders), each is a sample of its own (has_wheels false). A
  // status frame sets whether the samples from its device time on are lifted. Other frames are
  // counted and ignored.
  void FeedCan(const CanFrame& frame, std::int64_t received_us);

  DevicePipelineCounters counters() const;
  // Host time of the last lidar packet decoded (0 before the first): for "lidar silent" checks.
  std::int64_t last_lidar_packet_us() const { return lidar_.last_packet_us(); }
  // Host time a ticks frame was last received (INT64_MIN before the first): "wheels silent".
  std::int64_t last_ticks_us() const { return last_ticks_us_; }
  const DeviceTimeBase& wheel_time() const { return wheel_time_; }

 private:
  void Send(const OdometrySample& sample);

  DeviceSink* sink_;
  LidarStream lidar_;
  WheelCanDecoder wheels_;
  DiffDriveOdometry odometry_;
  DeviceTimeBase wheel_time_;
  GyroRate gyro_;
  WheelLiftState lift_;
  bool last_status_lifted_ = false;
  bool have_gyro_ = false;
  std::uint32_t gyro_frames_without_ticks_ = 0;
  DeviceScan scan_;
  std::int64_t wheel_timeout_us_;
  std::int64_t last_ticks_us_ = INT64_MIN;
  std::uint32_t scans_ = 0;
  std::uint32_t odometry_samples_ = 0;
  std::uint32_t wheel_gaps_ = 0;
  std::uint32_t lifts_ = 0;
  std::uint32_t lifted_samples_ = 0;
};

}  // namespace dpcr
