#include "board/firmware.hpp"

#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstring>
#include <sys/resource.h>
#include <vector>

#include "board/errno_name.hpp"
#include "board/map_store.hpp"
#include "core/persistence/map_stream.hpp"

namespace dpcr::board {

namespace {
constexpr const char* kMapFileName = "map.dpcr";
}  // namespace

// The device pipeline's outputs into the mapper, scans counted. With a trajectory capacity, each
// scan's stamp, map and pose in that map are kept (storage reserved at start-up; scans past the
// capacity are counted, not kept).
class Firmware::MapperSink : public DeviceSink {
 public:
  struct ScanRecord {
    std::int64_t stamp_us;
    int region;
    Pose2 in_region;
    Pose2 online;  // kept for a scan in no map
  };
  MapperSink(BoardMapper* mapper, std::uint32_t* scans, std::size_t trajectory_capacity)
      : mapper_(mapper), scans_(scans) {
    trajectory.reserve(trajectory_capacity);
  }
  void AddOdometry(const OdometrySample& sample) override { mapper_->AddOdometry(sample); }
  void AddScan(const DeviceScan& scan) override {
    static_cast<void>(mapper_->AddScan(scan));  // rejections are counted by the mapper
    ++*scans_;
    if (trajectory.size() < trajectory.capacity()) {
      trajectory.push_back(
          {scan.stamp_us, mapper_->last_scan_region(), mapper_->last_scan_in_region(), mapper_->pose()});
    } else {
      ++trajectory_overflow;
    }
  }
  std::vector<ScanRecord> trajectory;
  std::uint32_t trajectory_overflow = 0;

 private:
  BoardMapper* mapper_;
  std::uint32_t* scans_;
};

Firmware::Firmware(const FirmwareConfig& config, const FirmwarePorts& ports, std::FILE* log)
    : config_(config), ports_(ports), log_(log) {}

Firmware::~Firmware() = default;

bool Firmware::Start() {
  if (!(config_.wheels.ticks_per_rev > 0.0f)) {
    std::fprintf(log_,
                 "dpcr-firmware: error: the wheel encoders' ticks per revolution are not stated "
                 "(--ticks-per-rev N or \"ticks_per_rev\" in --config; dpcr-sim's device files: 4096)\n");
    return false;
  }
  if (config_.wheels.Validate() != Status::kOk) {
    std::fprintf(log_, "dpcr-firmware: error: invalid wheel configuration (radius %g m, track %g m, %g ticks)\n",
                 static_cast<double>(config_.wheels.wheel_radius_m), static_cast<double>(config_.wheels.track_width_m),
                 static_cast<double>(config_.wheels.ticks_per_rev));
    return false;
  }
  mapper_ = std::make_unique<BoardMapper>();
  MapperConfig mapper_config;
  DeviceOptions device;
  device.max_range_m = config_.max_range_m;
  device.laser_offset_m = config_.laser_offset_m;
  device.ApplyTo(&mapper_config.lidar);
  ApplyLidarModel(config_.lidar, &mapper_config.lidar);  // as dpcr-replay
  mapper_config.front_end.gyro_heading = GyroHeadingFor(config_.heading, config_.lidar);
  mapper_config.front_end.max_acceleration_mps2 = config_.max_accel_mps2;
  if (mapper_->Init(mapper_config) != Status::kOk) {
    std::fprintf(log_, "dpcr-firmware: error: mapper configuration rejected\n");
    return false;
  }
  LoadSavedMap();
  if (!CheckMapDirectory()) return false;
  std::string error;
  if (!saver_.Start(ports_.storage, static_cast<std::size_t>(MaxMapFileBytes(mapper_->map_file_limits())), &error)) {
    std::fprintf(log_, "dpcr-firmware: error: %s\n", error.c_str());
    return false;
  }
  sink_ = std::make_unique<MapperSink>(mapper_.get(), &counters_.scans,
                                       config_.trajectory_path.empty() ? 0 : config_.trajectory_capacity);
  DevicePipelineConfig pipeline;
  pipeline.lidar.kind = config_.lidar;
  pipeline.lidar.timing = config_.lidar_timing;
  pipeline.lidar.assembler.angle_map = config_.angle_map;
  pipeline.wheels = config_.wheels;
  pipeline.wheel_timeout_us = config_.wheel_timeout_ms * 1000LL;
  pipeline_ = std::make_unique<DevicePipeline>(pipeline, sink_.get());
  start_us_ = ports_.clock->NowUs();
  next_status_us_ = start_us_ + config_.status_period_ms * 1000LL;
  next_save_us_ = config_.autosave_s > 0 ? start_us_ + config_.autosave_s * 1000000LL : INT64_MAX;
  last_lidar_us_ = start_us_;
  wheels_lost_us_ = start_us_;
  if (ports_.notifier != nullptr) watchdog_period_us_ = ports_.notifier->watchdog_period_us();
  // systemd asks for a kick within WatchdogSec: kick at half of it.
  next_kick_us_ = watchdog_period_us_ > 0 ? start_us_ : INT64_MAX;
  return true;
}

bool Firmware::CheckMapDirectory() {
  // The store's own write path, without replacing anything: begin a map.dpcr and abandon it.
  if (ports_.storage->Begin(kMapFileName) == IoStatus::kOk) {
    ports_.storage->Abort();
    return true;
  }
  const int error = errno;
  std::fprintf(log_, "dpcr-firmware: error: map directory %s is not writable: %s\n", config_.map_dir.c_str(),
               DescribeErrno(error));
  return false;
}

void Firmware::Running() {
  std::fprintf(log_, "dpcr-firmware: running: lidar on %s, wheels on CAN %s%s, map in %s\n", config_.uart_device.c_str(),
               config_.can_interface.c_str(), can_up_ ? "" : " (not yet there)", config_.map_dir.c_str());
  std::fflush(log_);
  if (ports_.notifier != nullptr) ports_.notifier->Ready();
}

void Firmware::StopRequested() {
  std::fprintf(log_, "dpcr-firmware: signal received, saving map and exiting\n");
  std::fflush(log_);
}

void Firmware::WaitFailed(int error) {
  std::fprintf(log_, "dpcr-firmware: error: poll: %s\n", DescribeErrno(error));
  std::fflush(log_);
}

void Firmware::CanUnavailable(const char* reason) {
  can_up_ = false;
  ++counters_.can_failures;
  next_can_retry_us_ = ports_.clock->NowUs() + config_.can_retry_ms * 1000LL;
  std::fprintf(log_, "dpcr-firmware: warning: CAN %s unavailable (%s): mapping from the lidar alone, retrying every %d ms\n",
               config_.can_interface.c_str(), reason, config_.can_retry_ms);
  std::fflush(log_);
}

bool Firmware::ServiceLidar() {
  const ByteRead r = ports_.lidar->Read(buffer_, sizeof(buffer_));
  if (r.status == IoStatus::kWouldBlock) return true;
  if (r.status != IoStatus::kOk) {
    if (r.status == IoStatus::kEndOfStream) {
      std::fprintf(log_, "dpcr-firmware: error: lidar UART %s: end of file\n", config_.uart_device.c_str());
    } else {
      std::fprintf(log_, "dpcr-firmware: error: lidar UART %s: %s\n", config_.uart_device.c_str(), DescribeErrno(errno));
    }
    FlushLidar();
    return false;
  }
  pipeline_->FeedAllLidar(buffer_, r.size, r.stamp_us);
  if (pipeline_->last_lidar_packet_us() != 0) last_lidar_us_ = r.stamp_us;
  return true;
}

void Firmware::CanDown(const char* what, int error) {
  can_up_ = false;
  ++counters_.can_failures;
  next_can_retry_us_ = ports_.clock->NowUs() + config_.can_retry_ms * 1000LL;
  std::fprintf(log_, "dpcr-firmware: error: CAN %s: %s%s%s: mapping from the lidar alone, retrying every %d ms\n",
               config_.can_interface.c_str(), what, error != 0 ? ": " : "", error != 0 ? DescribeErrno(error) : "",
               config_.can_retry_ms);
  std::fflush(log_);
}

void Firmware::ServiceCan() {
  if (!can_up_) return;
  for (;;) {
    const CanRead r = ports_.can->Read();
    if (r.status == IoStatus::kWouldBlock) return;
    if (r.status == IoStatus::kEndOfStream) {
      CanDown("closed", 0);
      return;
    }
    if (r.status != IoStatus::kOk) {
      CanDown("read", errno);
      return;
    }
    pipeline_->FeedCan(r.frame, r.stamp_us);
  }
}

void Firmware::TryReopenCan(std::int64_t now_us) {
  if (can_up_ || now_us < next_can_retry_us_) return;
  if (ports_.can->Reopen() == IoStatus::kOk) {
    can_up_ = true;
    next_can_retry_us_ = INT64_MAX;
    std::fprintf(log_, "dpcr-firmware: CAN %s open again\n", config_.can_interface.c_str());
    std::fflush(log_);
    return;
  }
  next_can_retry_us_ = now_us + config_.can_retry_ms * 1000LL;
}

// The wheels' state from the ticks frames: silent past the timeout -> the lidar alone (the
// pipeline resumes the odometry from where it stopped when they return: the gap's motion is the
// lidar's, not a jump in the prior).
void Firmware::WatchWheels(std::int64_t now_us) {
  // Ticks that come but miss the motion the lidar sees (an IMU's yaw made into ticks, a dead
  // encoder): said once per switch, as the mapper sets their translation aside or takes it back.
  const bool ignored = mapper_->wheel_check().translation_ignored();
  if (ignored != wheel_translation_ignored_) {
    wheel_translation_ignored_ = ignored;
    std::fprintf(log_, ignored ? "dpcr-firmware: warning: wheel ticks on CAN %s miss the motion the lidar sees: their translation is ignored%s\n"
                               : "dpcr-firmware: wheel ticks on CAN %s agree with the lidar again: their translation is used%s\n",
                 config_.can_interface.c_str(),
                 ignored && mapper_->wheel_check().heading_used() ? " (their heading is kept)" : "");
    std::fflush(log_);
  }
  const std::int64_t last = pipeline_->last_ticks_us();
  const bool fresh = last != INT64_MIN && now_us - last <= config_.wheel_timeout_ms * 1000LL;
  if (fresh && !wheels_up_) {
    if (wheels_ever_) {
      std::fprintf(log_, "dpcr-firmware: wheels back on CAN %s after %.1f s: odometry resumed\n",
                   config_.can_interface.c_str(), static_cast<double>(now_us - wheels_lost_us_) / 1e6);
    } else {
      std::fprintf(log_, "dpcr-firmware: wheels on CAN %s\n", config_.can_interface.c_str());
    }
    std::fflush(log_);
    wheels_up_ = true;
    wheels_ever_ = true;
  } else if (!fresh && wheels_up_) {
    ++counters_.wheel_silences;
    wheels_up_ = false;
    wheels_lost_us_ = now_us;
    std::fprintf(log_, "dpcr-firmware: warning: no wheel ticks on CAN %s for %d ms: mapping from the lidar alone\n",
                 config_.can_interface.c_str(), config_.wheel_timeout_ms);
    std::fflush(log_);
  } else if (!fresh && !wheels_ever_ && now_us - start_us_ > config_.wheel_timeout_ms * 1000LL &&
             counters_.wheel_silences == 0) {
    ++counters_.wheel_silences;  // never heard: said once
    std::fprintf(log_, "dpcr-firmware: warning: no wheel ticks on CAN %s since start: mapping from the lidar alone\n",
                 config_.can_interface.c_str());
    std::fflush(log_);
  }
}

bool Firmware::LidarSilent() {
  if (ports_.clock->NowUs() - last_lidar_us_ <= config_.lidar_timeout_ms * 1000LL) return false;
  std::fprintf(log_, "dpcr-firmware: error: lidar timeout: no packet from %s for %d ms\n",
               config_.uart_device.c_str(), config_.lidar_timeout_ms);
  return true;
}

bool Firmware::SubmitSave() {
  ++counters_.saves_requested;
  const CellBox box = mapper_->MapBounds();
  if (box.width() <= 0 || box.height() <= 0) {
    std::fprintf(log_, "dpcr-firmware: map is empty, nothing saved\n");
    return false;
  }
  MemoryMapSink sink(Span<std::uint8_t>(saver_.buffer(), saver_.capacity()));
  const MapFileResult r = mapper_->SaveMap(sink);
  if (!r.ok()) {
    ++counters_.saves_failed;
    std::fprintf(log_, "dpcr-firmware: error: map not saved: %s\n", Describe(r.error));
    return false;
  }
  saver_.Submit(kMapFileName, sink.size());
  return true;
}

void Firmware::CollectSave() {
  SaveOutcome outcome;
  if (!saver_.TakeResult(&outcome)) return;
  if (outcome.ok) {
    ++counters_.saves_ok;
  } else {
    ++counters_.saves_failed;
    std::fprintf(log_, "dpcr-firmware: error: autosave: %s\n", outcome.error);
    std::fflush(log_);
  }
}

void Firmware::ServiceTimers() {
  const std::int64_t now = ports_.clock->NowUs();
  // Frames that queued while a long scan was mapped are read before the wheels are judged silent.
  ServiceCan();
  WatchWheels(now);
  TryReopenCan(now);
  CollectSave();
  if (now >= next_save_us_) {
    if (saver_.idle()) {
      SubmitSave();
      next_save_us_ = now + config_.autosave_s * 1000000LL;
    } else {
      ++counters_.saves_deferred;  // the previous save is still being written: again in a second
      next_save_us_ = now + 1000000LL;
    }
  }
  if (now >= next_status_us_) {
    PrintCounters(now);
    next_status_us_ = now + config_.status_period_ms * 1000LL;
  }
  if (now >= next_kick_us_) {
    ports_.notifier->Alive();
    ++counters_.watchdog_kicks;
    next_kick_us_ = now + watchdog_period_us_ / 2;
  }
}

std::int64_t Firmware::next_timer_us() const {
  std::int64_t t = next_status_us_;
  if (next_save_us_ < t) t = next_save_us_;
  if (next_kick_us_ < t) t = next_kick_us_;
  if (next_can_retry_us_ < t) t = next_can_retry_us_;
  return t;
}

void Firmware::LoadSavedMap() {
  const MapLoad load = LoadMapBlob(*mapper_, *ports_.storage, kMapFileName);
  const std::string path = config_.map_dir + "/" + kMapFileName;
  if (load.io == IoStatus::kNotFound) {
    std::fprintf(log_, "dpcr-firmware: no saved map at %s, starting a new one\n", path.c_str());
  } else if (load.loaded()) {
    std::fprintf(log_, "dpcr-firmware: map loaded from %s (%d regions, %zu bytes)\n", path.c_str(),
                 mapper_->region_count(), load.bytes);
  } else {
    std::fprintf(log_, "dpcr-firmware: error: %s, mapping from scratch\n", DescribeMapLoad(path.c_str(), load).c_str());
  }
}

// One line of counters per status period (a minute by default): what a robot's log needs to tell
// a healthy run from a degraded one.
void Firmware::PrintCounters(std::int64_t now_us) {
  const double period_s = static_cast<double>(config_.status_period_ms) / 1000.0;
  const DevicePipelineCounters counters = pipeline_->counters();
  const LidarStreamCounters& lc = counters.lidar;
  const WheelCanCounters& cc = counters.can;
  const Pose2 pose = mapper_->pose();
  std::fprintf(log_,
               "dpcr-firmware: t=%.1fs scan_rate=%.1f/s scans=%u packets=%u bad=%u resyncs=%u gaps=%u dropouts=%u "
               "ticks=%u can_lost=%u dup=%u reord=%u err=%u wheels=%s can=%s saves=%u/%u pose=(%.3f,%.3f,%.3f) mapper=%s\n",
               static_cast<double>(now_us - start_us_) / 1e6,
               static_cast<double>(counters_.scans - scans_at_last_status_) / period_s, counters_.scans, lc.packets,
               lc.bad_packets, lc.resyncs, lc.gaps, lc.dropouts, cc.ticks_frames, cc.lost, cc.duplicated, cc.reordered,
               cc.error_frames, wheels_up_ ? "up" : "silent", can_up_ ? "up" : "down", counters_.saves_ok,
               counters_.saves_requested, static_cast<double>(pose.x), static_cast<double>(pose.y),
               static_cast<double>(pose.theta), ToString(mapper_->status()));
  std::fflush(log_);
  scans_at_last_status_ = counters_.scans;
}

void Firmware::PrintSummary() {
  const DevicePipelineCounters c = pipeline_->counters();
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  std::fprintf(log_,
               "dpcr-firmware: summary scans=%u rejected=%u odometry=%u packets=%u bad=%u resyncs=%u "
               "discarded=%u out_of_range=%u revolutions=%u gaps=%u dropouts=%u partial_dropped=%u ticks=%u gyro=%u "
               "status=%u reserved_flags=%u lifts=%u lifted_samples=%u can_lost=%u dup=%u reord=%u err=%u bad_dlc=%u "
               "foreign=%u wheel_gaps=%u can_failures=%u "
               "wheel_silences=%u saves=%u/%u deferred=%u regions=%d peak_rss_kb=%ld\n",
               counters_.scans, mapper_->counters().scans_rejected, c.odometry, c.lidar.packets, c.lidar.bad_packets,
               c.lidar.resyncs, c.lidar.discarded_bytes, c.lidar.out_of_range, c.lidar.revolutions, c.lidar.gaps,
               c.lidar.dropouts, c.lidar.partial_dropped, c.can.ticks_frames, c.can.gyro_frames,
               c.can.status_frames, c.can.reserved_flags, c.lifts, c.lifted_samples, c.can.lost,
               c.can.duplicated, c.can.reordered, c.can.error_frames, c.can.bad_dlc, c.can.foreign, c.wheel_gaps,
               counters_.can_failures, counters_.wheel_silences, counters_.saves_ok, counters_.saves_requested,
               counters_.saves_deferred, mapper_->region_count(), static_cast<long>(usage.ru_maxrss));
  std::fflush(log_);
}

// TUM lines (t x y 0 0 0 qz qw), each scan placed by its map's final anchor, as dpcr-replay does.
bool Firmware::WriteTrajectory(std::string* error) const {
  std::FILE* f = std::fopen(config_.trajectory_path.c_str(), "w");
  if (f == nullptr) {
    *error = config_.trajectory_path + ": " + DescribeErrno(errno);
    return false;
  }
  for (const MapperSink::ScanRecord& r : sink_->trajectory) {
    const Pose2 pose = mapper_->ScanWorldPose(r.stamp_us, r.region, r.in_region, r.online);
    const double half = 0.5 * static_cast<double>(pose.theta);
    const std::int64_t s = r.stamp_us / 1000000;
    const std::int64_t us = r.stamp_us % 1000000;
    std::fprintf(f, "%lld.%06lld %.6f %.6f 0 0 0 %.9f %.9f\n", static_cast<long long>(s),
                 static_cast<long long>(us < 0 ? -us : us), static_cast<double>(pose.x), static_cast<double>(pose.y),
                 std::sin(half), std::cos(half));
  }
  if (std::fclose(f) != 0) {
    *error = config_.trajectory_path + ": " + DescribeErrno(errno);
    return false;
  }
  return true;
}

void Firmware::FlushLidar() {
  if (lidar_flushed_ || !pipeline_) return;
  lidar_flushed_ = true;
  pipeline_->FlushLidar();  // the stream's last revolution: no wrap follows to close it
}

int Firmware::Finish(int exit_code) {
  if (ports_.notifier != nullptr) ports_.notifier->Stopping();
  FlushLidar();
  PrintSummary();
  if (!config_.trajectory_path.empty()) {
    // The start placed in the finished first map before the trajectory is written (the saved map
    // does not change: only where the trajectory starts in it).
    const StartRefinement start = mapper_->RefineStart();
    if (start.refined) {
      std::fprintf(log_, "dpcr-firmware: start placed in the finished map: %+.3f deg (%d of %d start scans)\n",
                   static_cast<double>(start.offset_rad) * 57.29577951308232, start.registered, start.kept);
    }
    std::string error;
    if (WriteTrajectory(&error)) {
      std::fprintf(log_, "dpcr-firmware: trajectory of %zu scans written to %s (%u not kept)\n",
                   sink_->trajectory.size(), config_.trajectory_path.c_str(), sink_->trajectory_overflow);
    } else {
      std::fprintf(log_, "dpcr-firmware: error: trajectory not written: %s\n", error.c_str());
      if (exit_code == 0) exit_code = 1;
    }
  }
  // The final save: after any autosave still being written, the map as it is now.
  saver_.WaitIdle();
  CollectSave();
  bool saved = false;
  if (SubmitSave()) {
    saver_.WaitIdle();
    SaveOutcome outcome;
    saved = saver_.TakeResult(&outcome) && outcome.ok;
    if (saved) {
      ++counters_.saves_ok;
      std::fprintf(log_, "dpcr-firmware: map saved to %s/%s (%zu bytes), %u scans\n", config_.map_dir.c_str(),
                   kMapFileName, outcome.bytes, counters_.scans);
    } else {
      ++counters_.saves_failed;
      std::fprintf(log_, "dpcr-firmware: error: map not saved: %s\n", outcome.error);
    }
  }
  if (!saved && exit_code == 0) exit_code = 1;
  std::fflush(log_);
  return exit_code;
}

}  // namespace dpcr::board
