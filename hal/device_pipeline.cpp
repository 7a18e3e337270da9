#include "hal/device_pipeline.hpp"

namespace dpcr {

DevicePipeline::DevicePipeline(const DevicePipelineConfig& config, DeviceSink* sink)
    : sink_(sink), lidar_(config.lidar), odometry_(config.wheels), wheel_time_(config.wheel_clock), wheel_timeout_us_(config.wheel_timeout_us) {}

std::size_t DevicePipeline::FeedLidar(const std::uint8_t* data, std::size_t size, std::int64_t arrival_us) {
  const std::size_t used = lidar_.Feed(data, size, arrival_us);
  if (lidar_.revolution_ready()) {
    lidar_.TakeScan(&scan_);
    ++scans_;
    sink_->AddScan(scan_);
  }
  return used;
}

void DevicePipeline::FlushLidar() {
  if (!lidar_.Flush()) return;
  lidar_.TakeScan(&scan_);
  ++scans_;
  sink_->AddScan(scan_);
}

void DevicePipeline::FeedAllLidar(const std::uint8_t* data, std::size_t size, std::int64_t arrival_us) {
  std::size_t used = 0;
  while (used < size) used += FeedLidar(data + used, size - used, arrival_us);
}

void DevicePipeline::FeedCan(const CanFrame& frame, std::int64_t received_us) {
  const CanDecodeResult decoded = wheels_.Feed(frame);
  if (decoded == CanDecodeResult::kStatus) {
    const RobotStatus& status = wheels_.status();
    if (status.lifted && !last_status_lifted_) ++lifts_;
    last_status_lifted_ = status.lifted;
    lift_.Observe(status);
    return;
  }
  if (decoded == CanDecodeResult::kGyro) {
    gyro_ = wheels_.gyro();
    have_gyro_ = true;
    // Two gyro frames without a ticks frame between them, and none ever: no wheel encoders. (A
    // robot with wheels sends its ticks frame right after the gyro frame of the same instant.)
    if (wheels_.counters().ticks_frames == 0 && ++gyro_frames_without_ticks_ >= 2) {
      // No wheel encoders (yet): a gyro-only sample, so that the mapper still gets the turn.
      OdometrySample sample;
      sample.stamp_us = wheel_time_.ToHostUs(gyro_.device_time_us, received_us);
      sample.has_wheels = false;
      sample.has_gyro = true;
      sample.gyro_yaw_rate = gyro_.yaw_rate_rad_s;
      sample.lifted = lift_.LiftedAt(gyro_.device_time_us);
      Send(sample);
    }
    return;
  }
  if (decoded != CanDecodeResult::kTicks) return;
  gyro_frames_without_ticks_ = 0;
  if (last_ticks_us_ != INT64_MIN && received_us - last_ticks_us_ > wheel_timeout_us_) {
    odometry_.Resume();
    ++wheel_gaps_;
  }
  last_ticks_us_ = received_us;
  const std::int64_t stamp_us = wheel_time_.ToHostUs(wheels_.ticks().device_time_us, received_us);
  OdometrySample sample = odometry_.Update(wheels_.ticks(), stamp_us);
  sample.has_gyro = have_gyro_;
  sample.gyro_yaw_rate = gyro_.yaw_rate_rad_s;
  sample.lifted = lift_.LiftedAt(wheels_.ticks().device_time_us);
  Send(sample);
}

void DevicePipeline::Send(const OdometrySample& sample) {
  ++odometry_samples_;
  if (sample.lifted) ++lifted_samples_;
  sink_->AddOdometry(sample);
}

DevicePipelineCounters DevicePipeline::counters() const {
  DevicePipelineCounters c;
  c.lidar = lidar_.counters();
  c.can = wheels_.counters();
  c.scans = scans_;
  c.odometry = odometry_samples_;
  c.wheel_gaps = wheel_gaps_;
  c.lifts = lifts_;
  c.lifted_samples = lifted_samples_;
  return c;
}

}  // namespace dpcr
