#include "host_sim/drivers/device_files.hpp"

#include <cmath>

#include <fstream>
#include <nlohmann/json.hpp>

#include "hal/ld06_emitter.hpp"
#include "hal/xv11_emitter.hpp"

namespace dpcr {
namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr std::int64_t kUnitsWrap = kWheelTimeWrapUnits;

}  // namespace

bool DeviceEmitter::Open(const std::string& dir, std::string* error) {
  dir_ = dir;
  const bool xv11 = config_.lidar == LidarKind::kXv11;
  return uart_.Open(dir + "/lidar.uart", xv11 ? "xv11 baud 115200" : "ld06 baud 230400", error);
}

bool DeviceEmitter::AddScan(const DeviceScan& scan) {
  bool ok = true;
  if (config_.lidar == LidarKind::kXv11) {
    Xv11EmittedPacket packets[kXv11PacketsPerRevolution];
    // The revolution's own rate when its beams tell it (a wandering motor: dpcr-sim's XV-11).
    float rate_hz = config_.xv11_rate_hz;
    const std::size_t n = scan.beams.size();
    if (n > 1 && scan.beams[n - 1].offset_us > 0) {
      rate_hz = static_cast<float>(1e6 * static_cast<double>(n - 1) / (static_cast<double>(n) * scan.beams[n - 1].offset_us));
    }
    EncodeXv11Revolution(scan.beams.data(), scan.beams.size(), scan.stamp_us, config_.angle_map, rate_hz, packets);
    for (const Xv11EmittedPacket& p : packets) ok = ok && uart_.Write(p.arrival_us, p.bytes, sizeof(p.bytes));
    return ok;
  }
  EmitLd06Revolution(scan, config_.angle_map, [this, &ok](const Ld06EmittedPacket& p) {
    ok = ok && uart_.Write(p.arrival_us, p.bytes, sizeof(p.bytes));
  });
  return ok;
}

void DeviceEmitter::AddOdometry(const OdometrySample& sample) {
  const std::size_t first_frame = can_.size();
  if (!sample.has_wheels) {
    if (sample.has_gyro) AddGyro(sample);
    AddStatusIfDue(sample, first_frame);
    return;
  }
  if (started_) {
    // Increment in the previous robot frame -> arc length and heading change -> wheel travel.
    const Pose2 d = Between(last_pose_, sample.pose);
    const double dtheta = static_cast<double>(d.theta);
    const double chord = std::hypot(static_cast<double>(d.x), static_cast<double>(d.y));
    double ds = std::fabs(dtheta) < 1e-9 ? chord : chord * (dtheta / 2) / std::sin(dtheta / 2);
    if (d.x < 0.0f) ds = -ds;
    const double half_track = 0.5 * static_cast<double>(config_.wheels.track_width_m);
    left_m_ += ds - dtheta * half_track;
    right_m_ += ds + dtheta * half_track;
  }
  started_ = true;
  last_pose_ = sample.pose;
  const double ticks_per_m = static_cast<double>(config_.wheels.ticks_per_rev) /
                             (kTwoPi * static_cast<double>(config_.wheels.wheel_radius_m));
  WheelTicksFrame f;
  f.left_ticks = static_cast<std::uint16_t>(std::llround(left_m_ * ticks_per_m) & 0xFFFF);
  f.right_ticks = static_cast<std::uint16_t>(std::llround(right_m_ * ticks_per_m) & 0xFFFF);
  f.sequence = ticks_seq_++;
  f.time_10us = static_cast<std::uint32_t>((DeviceTimeUs(sample.stamp_us) / kWheelTimeUnitUs) % kUnitsWrap);
  // The gyro frame before the ticks frame of the same instant, so the odometry sample carries the rate.
  if (sample.has_gyro) AddGyro(sample);
  CandumpRecord r;
  r.stamp_us = ArrivalUs(sample.stamp_us);
  r.interface = config_.can_interface;
  r.frame = EncodeWheelFrame(f);
  can_.push_back(r);
  AddStatusIfDue(sample, first_frame);
}

void DeviceEmitter::AddStatusIfDue(const OdometrySample& sample, std::size_t first_frame) {
  if (config_.status_period_us <= 0 || first_frame >= can_.size()) return;
  const std::int64_t device_us = DeviceTimeUs(sample.stamp_us);
  const bool due = !status_sent_ || sample.lifted != status_lifted_ || device_us - status_device_us_ >= config_.status_period_us;
  if (!due) return;
  StatusFrame s;
  s.flags = sample.lifted ? kStatusLiftedFlag : 0;
  s.sequence = status_seq_++;
  s.time_10us = static_cast<std::uint32_t>((device_us / kWheelTimeUnitUs) % kUnitsWrap);
  // Sent just before the sample's other frames, arriving with the first of them (no draw from the
  // bus's jitter: the other frames arrive as they did before status frames existed).
  CandumpRecord r;
  r.stamp_us = can_[first_frame].stamp_us;
  r.interface = config_.can_interface;
  r.frame = EncodeStatusFrame(s);
  can_.insert(can_.begin() + static_cast<std::ptrdiff_t>(first_frame), r);
  status_sent_ = true;
  status_lifted_ = sample.lifted;
  status_device_us_ = device_us;
}

std::int64_t DeviceEmitter::DeviceTimeUs(std::int64_t stamp_us) {
  if (first_stamp_us_ == INT64_MIN) first_stamp_us_ = stamp_us;
  if (config_.wheel_clock_ppm == 0.0 && config_.wheel_clock_start_us == 0) return stamp_us;  // an ideal bus
  // The board's clock starts with the run (at wheel_clock_start_us) and gains ppm on the host's.
  const double since = static_cast<double>(stamp_us - first_stamp_us_);
  return config_.wheel_clock_start_us + static_cast<std::int64_t>(std::llround(since * (1.0 + config_.wheel_clock_ppm * 1e-6)));
}

std::int64_t DeviceEmitter::ArrivalUs(std::int64_t stamp_us) {
  double late = static_cast<double>(config_.can_latency_us);
  if (config_.can_jitter_us > 0.0) late += std::exponential_distribution<double>(1.0 / config_.can_jitter_us)(bus_random_);
  if (config_.can_spike_fraction > 0.0 && std::uniform_real_distribution<double>(0.0, 1.0)(bus_random_) < config_.can_spike_fraction) {
    late += std::uniform_real_distribution<double>(0.0, config_.can_spike_us)(bus_random_);
  }
  std::int64_t arrival = stamp_us + static_cast<std::int64_t>(std::llround(late));
  if (arrival < last_arrival_us_) arrival = last_arrival_us_;  // a bus delivers in order
  last_arrival_us_ = arrival;
  return arrival;
}

void DeviceEmitter::AddGyro(const OdometrySample& sample) {
  GyroFrame g;
  g.yaw_rate_mrad_s = static_cast<std::int16_t>(std::lround(sample.gyro_yaw_rate * 1000.0f));
  g.sequence = gyro_seq_++;
  g.time_10us = static_cast<std::uint32_t>((DeviceTimeUs(sample.stamp_us) / kWheelTimeUnitUs) % kUnitsWrap);
  CandumpRecord r;
  r.stamp_us = ArrivalUs(sample.stamp_us);
  r.interface = config_.can_interface;
  r.frame = EncodeGyroFrame(g);
  can_.push_back(r);
}

bool WriteDeviceDescription(const std::string& path, const DeviceOptions& o, const std::string& lidar,
                            std::string* error) {
  const nlohmann::json j = {{"lidar", lidar},
                            {"angle_sign", o.angle_sign},
                            {"wheel_radius_m", o.wheels.wheel_radius_m},
                            {"track_width_m", o.wheels.track_width_m},
                            {"ticks_per_rev", o.wheels.ticks_per_rev},
                            {"max_range_m", o.max_range_m},
                            {"laser_offset_m", o.laser_offset_m}};
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) *error = path + ": write failed";
  return static_cast<bool>(out);
}

bool ReadDeviceDescription(const std::string& path, DeviceOptions* o, std::string* lidar, std::string* error) {
  std::ifstream in(path);
  if (!in) return true;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.contains("lidar")) *lidar = j["lidar"].get<std::string>();
    if (j.contains("angle_sign")) o->angle_sign = j["angle_sign"].get<float>() < 0.0f ? -1.0f : 1.0f;
    if (j.contains("wheel_radius_m")) o->wheels.wheel_radius_m = j["wheel_radius_m"].get<float>();
    if (j.contains("track_width_m")) o->wheels.track_width_m = j["track_width_m"].get<float>();
    if (j.contains("ticks_per_rev")) o->wheels.ticks_per_rev = j["ticks_per_rev"].get<float>();
    if (j.contains("max_range_m")) o->max_range_m = j["max_range_m"].get<float>();
    if (j.contains("laser_offset_m")) o->laser_offset_m = j["laser_offset_m"].get<float>();
  } catch (const nlohmann::json::exception& e) {
    *error = path + ": " + e.what();
    return false;
  }
  return true;
}

bool DeviceEmitter::Close(std::string* error) {
  if (!uart_.Close()) {
    *error = dir_ + "/lidar.uart: write failed";
    return false;
  }
  DeviceOptions options;
  options.wheels = config_.wheels;
  options.angle_sign = config_.angle_map.angle_sign;
  options.max_range_m = config_.max_range_m;
  options.laser_offset_m = config_.laser_offset_m;
  const char* lidar = config_.lidar == LidarKind::kXv11 ? "xv11" : "ld06";
  if (!WriteDeviceDescription(dir_ + "/device.json", options, lidar, error)) return false;
  return WriteCandumpLog(dir_ + "/wheels.log", can_, error);
}

DeviceReplay::DeviceReplay(const DeviceFilesConfig& files, const LidarStreamConfig& lidar, DeviceSink* sink)
    : pipeline_(new DevicePipeline(DevicePipelineConfig{lidar, files.wheels}, sink)) {}

bool DeviceReplay::Open(const std::string& uart_path, const std::string& candump_path, std::string* error) {
  std::vector<UartChunk> chunks;
  if (!uart_path.empty() && !ReadUartCapture(uart_path, &chunks, error, &uart_end_us_, &uart_skipped_)) return false;
  std::vector<CandumpRecord> records;
  if (!candump_path.empty() && !ReadCandumpLog(candump_path, &records, error, &can_skipped_)) return false;
  // A bad line here and there is a recording with a flipped byte; mostly bad lines, no recording.
  const auto mostly_bad = [&](const std::string& path, const SkippedLines& s, std::size_t good) {
    if (s.count == 0 || static_cast<std::size_t>(s.count) <= good) return false;
    *error = path + ": " + std::to_string(s.count) + " of " + std::to_string(s.count + static_cast<int>(good)) +
             " lines do not parse (first: " + s.first + ")";
    return true;
  };
  if (mostly_bad(uart_path, uart_skipped_, chunks.size()) || mostly_bad(candump_path, can_skipped_, records.size())) {
    return false;
  }
  uart_.reset(new UartCaptureSource(std::move(chunks)));
  can_.reset(new CandumpSource(std::move(records)));
  return true;
}

void DeviceReplay::Run() {
  std::vector<std::uint8_t> pending(4096);
  ByteRead chunk;  // the UART bytes read and not yet fed: pending[fed .. chunk.size)
  std::size_t fed = 0;
  bool flushed = false;
  std::int64_t flush_after_us = INT64_MIN;
  for (;;) {
    const std::int64_t uart_t = fed < chunk.size ? chunk.stamp_us : uart_->next_stamp_us();
    const std::int64_t can_t = can_->next_stamp_us();
    if (!flushed && uart_t == INT64_MAX) {
      // The capture's last revolution (no wrap follows to close it), when the firmware's poll loop
      // notices the end of its UART: after the frames of the next CAN instant, or at once.
      // A firmware recording says when its revolution was taken: after every frame received before.
      if (flush_after_us == INT64_MIN) flush_after_us = uart_end_us_ != INT64_MIN ? uart_end_us_ : can_t;
      if (can_t > flush_after_us || can_t == INT64_MAX) {
        pipeline_->FlushLidar();
        flushed = true;
      }
    }
    if (can_t == INT64_MAX && uart_t == INT64_MAX) return;
    if (can_t <= uart_t) {  // frames first on a tie: the scan then sees the odometry of its instant
      const CanRead r = can_->Read();
      pipeline_->FeedCan(r.frame, r.stamp_us);
      continue;
    }
    if (fed >= chunk.size) {
      chunk = uart_->Read(pending.data(), pending.size());
      fed = 0;
    }
    fed += pipeline_->FeedLidar(pending.data() + fed, chunk.size - fed, chunk.stamp_us);
  }
}

}  // namespace dpcr
