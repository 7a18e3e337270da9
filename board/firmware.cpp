#include "board/firmware.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <sys/resource.h>
#include <vector>

#include "board/map_store.hpp"
#include "hal/map_export.hpp"

namespace dpcr::board {

namespace {
constexpr const char* kMapFileName = "map.dpcr";
}  // namespace

// The device pipeline's outputs into the mapper, scans counted for the status line.
// With a trajectory capacity, each scan's stamp, map and pose in that map are kept (storage
// reserved at start-up; scans past the capacity are counted, not kept).
class Firmware::MapperSink : public DeviceSink {
 public:
  struct ScanRecord {
    std::int64_t stamp_us;
    int region;
    Pose2 in_region;
    Pose2 online;  // kept for a scan in no map
  };
  MapperSink(BoardMapper* mapper, std::size_t trajectory_capacity) : mapper_(mapper) {
    trajectory.reserve(trajectory_capacity);
  }
  void AddOdometry(const OdometrySample& sample) override { mapper_->AddOdometry(sample); }
  void AddScan(const DeviceScan& scan) override {
    static_cast<void>(mapper_->AddScan(scan));  // rejections are counted by the mapper
    ++scans;
    if (trajectory.size() < trajectory.capacity()) {
      trajectory.push_back(
          {scan.stamp_us, mapper_->last_scan_region(), mapper_->last_scan_in_region(), mapper_->pose()});
    } else {
      ++trajectory_overflow;
    }
  }
  std::uint32_t scans = 0;
  std::vector<ScanRecord> trajectory;
  std::uint32_t trajectory_overflow = 0;

 private:
  BoardMapper* mapper_;
};

struct Firmware::SaveResult {
  bool ok = false;
  int width = 0;
  int height = 0;
  std::string error;
};

Firmware::Firmware(const FirmwareConfig& config, const FirmwarePorts& ports, std::FILE* log)
    : config_(config), ports_(ports), log_(log) {}

Firmware::~Firmware() = default;

std::uint32_t Firmware::scans() const { return sink_ ? sink_->scans : 0; }

bool Firmware::Start() {
  if (config_.wheels.Validate() != Status::kOk) {
    std::fprintf(log_, "dpcr-firmware: error: invalid wheel configuration\n");
    return false;
  }
  mapper_ = std::make_unique<BoardMapper>();
  MapperConfig mapper_config;
  DeviceOptions device;
  device.max_range_m = config_.max_range_m;
  device.laser_offset_m = config_.laser_offset_m;
  device.ApplyTo(&mapper_config.lidar);
  if (mapper_->Init(mapper_config) != Status::kOk) {
    std::fprintf(log_, "dpcr-firmware: error: mapper configuration rejected\n");
    return false;
  }
  LoadSavedMap();
  sink_ = std::make_unique<MapperSink>(mapper_.get(), config_.trajectory_path.empty() ? 0 : config_.trajectory_capacity);
  DevicePipelineConfig pipeline;
  pipeline.lidar.kind = config_.lidar;
  pipeline.lidar.timing = config_.lidar_timing;
  pipeline.lidar.assembler.angle_map = config_.angle_map;
  pipeline.wheels = config_.wheels;
  pipeline_ = std::make_unique<DevicePipeline>(pipeline, sink_.get());
  start_us_ = ports_.clock->NowUs();
  next_status_us_ = start_us_ + config_.status_period_ms * 1000LL;
  next_save_us_ = config_.autosave_s > 0 ? start_us_ + config_.autosave_s * 1000000LL : INT64_MAX;
  last_lidar_us_ = start_us_;
  return true;
}

bool Firmware::ServiceLidar() {
  const ByteRead r = ports_.lidar->Read(buffer_, sizeof(buffer_));
  if (r.status == IoStatus::kWouldBlock) return true;
  if (r.status != IoStatus::kOk) {
    std::fprintf(log_, "dpcr-firmware: error: lidar UART %s: %s\n", config_.uart_device.c_str(),
                 r.status == IoStatus::kEndOfStream ? "end of file" : std::strerror(errno));
    FlushLidar();
    return false;
  }
  pipeline_->FeedAllLidar(buffer_, r.size, r.stamp_us);
  if (pipeline_->last_lidar_packet_us() != 0) last_lidar_us_ = r.stamp_us;
  return true;
}

bool Firmware::ServiceCan() {
  for (;;) {
    const CanRead r = ports_.can->Read();
    if (r.status == IoStatus::kWouldBlock) return true;
    if (r.status != IoStatus::kOk) {
      std::fprintf(log_, "dpcr-firmware: error: CAN %s: %s\n", config_.can_interface.c_str(),
                   r.status == IoStatus::kEndOfStream ? "closed" : std::strerror(errno));
      return false;
    }
    pipeline_->FeedCan(r.frame, r.stamp_us);
  }
}

bool Firmware::LidarSilent() {
  if (ports_.clock->NowUs() - last_lidar_us_ <= config_.lidar_timeout_ms * 1000LL) return false;
  std::fprintf(log_, "dpcr-firmware: error: lidar timeout: no packet from %s for %d ms\n",
               config_.uart_device.c_str(), config_.lidar_timeout_ms);
  return true;
}

void Firmware::ServiceTimers() {
  const std::int64_t now = ports_.clock->NowUs();
  if (now >= next_status_us_) {
    PrintStatus(now);
    next_status_us_ = now + config_.status_period_ms * 1000LL;
  }
  if (now >= next_save_us_) {
    const SaveResult r = SaveMap();
    if (!r.ok) std::fprintf(log_, "dpcr-firmware: autosave: %s\n", r.error.c_str());
    next_save_us_ = now + config_.autosave_s * 1000000LL;
  }
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

void Firmware::PrintStatus(std::int64_t now_us) {
  const double period_s = static_cast<double>(config_.status_period_ms) / 1000.0;
  const DevicePipelineCounters counters = pipeline_->counters();
  const LidarStreamCounters& lc = counters.lidar;
  const WheelCanCounters& cc = counters.can;
  const Pose2 pose = mapper_->pose();
  std::fprintf(log_,
               "dpcr-firmware: t=%.1fs scan_rate=%.1f/s packets=%u bad=%u resyncs=%u gaps=%u "
               "can_lost=%u dup=%u reord=%u err=%u pose=(%.3f,%.3f,%.3f) mapper=%s\n",
               static_cast<double>(now_us - start_us_) / 1e6,
               static_cast<double>(sink_->scans - scans_at_last_status_) / period_s, lc.packets, lc.bad_packets,
               lc.resyncs, lc.gaps, cc.lost, cc.duplicated, cc.reordered, cc.error_frames,
               static_cast<double>(pose.x), static_cast<double>(pose.y), static_cast<double>(pose.theta),
               ToString(mapper_->status()));
  std::fflush(log_);
  scans_at_last_status_ = sink_->scans;
}

// Stores map.dpcr (the map itself, what a restart loads), then the exports: renders the fused map
// and stores map.pgm, then map.yaml (a YAML never names an incomplete image).
Firmware::SaveResult Firmware::SaveMap() {
  SaveResult r;
  const CellBox box = mapper_->MapBounds();
  r.width = box.width();
  r.height = box.height();
  if (r.width <= 0 || r.height <= 0) {
    r.error = "map is empty, nothing saved";
    return r;
  }
  if (!SaveMapBlob(*mapper_, *ports_.storage, kMapFileName, &r.error)) {
    r.error = config_.map_dir + "/" + r.error;
    return r;
  }
  std::vector<std::int16_t> cells(static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height));
  if (mapper_->RenderMap(box, Span<std::int16_t>(cells.data(), cells.size())) != Status::kOk) {
    r.error = "map rendering failed";
    return r;
  }
  std::vector<std::uint8_t> pgm(PgmSize(r.width, r.height));
  const std::size_t pgm_size = EncodePgm(Span<const std::int16_t>(cells.data(), cells.size()), r.width, r.height,
                                         Span<std::uint8_t>(pgm.data(), pgm.size()));
  char yaml[512];
  const std::size_t yaml_size =
      EncodeMapYaml("map.pgm", mapper_->config().grid.resolution_m, box, Span<char>(yaml, sizeof(yaml)));
  if (pgm_size == 0 || yaml_size == 0) {
    r.error = "map encoding failed";
    return r;
  }
  r.ok = Store("map.pgm", pgm.data(), pgm_size, &r.error) &&
         Store("map.yaml", reinterpret_cast<const std::uint8_t*>(yaml), yaml_size, &r.error);
  return r;
}

bool Firmware::Store(const char* name, const std::uint8_t* data, std::size_t size, std::string* error) {
  if (ports_.storage->Write(name, data, size) == IoStatus::kOk) return true;
  *error = config_.map_dir + "/" + name + ": " + std::strerror(errno);
  return false;
}

void Firmware::PrintSummary() {
  const DevicePipelineCounters c = pipeline_->counters();
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  std::fprintf(log_,
               "dpcr-firmware: summary scans=%u rejected=%u odometry=%u packets=%u bad=%u resyncs=%u "
               "discarded=%u out_of_range=%u revolutions=%u gaps=%u dropouts=%u partial_dropped=%u ticks=%u gyro=%u "
               "can_lost=%u dup=%u reord=%u err=%u bad_dlc=%u foreign=%u regions=%d peak_rss_kb=%ld\n",
               sink_->scans, mapper_->counters().scans_rejected, c.odometry, c.lidar.packets, c.lidar.bad_packets,
               c.lidar.resyncs, c.lidar.discarded_bytes, c.lidar.out_of_range, c.lidar.revolutions, c.lidar.gaps,
               c.lidar.dropouts, c.lidar.partial_dropped, c.can.ticks_frames, c.can.gyro_frames, c.can.lost, c.can.duplicated,
               c.can.reordered, c.can.error_frames, c.can.bad_dlc, c.can.foreign, mapper_->region_count(),
               static_cast<long>(usage.ru_maxrss));
  std::fflush(log_);
}

// TUM lines (t x y 0 0 0 qz qw), each scan placed by its map's final anchor, as dpcr-replay does.
bool Firmware::WriteTrajectory(std::string* error) const {
  std::FILE* f = std::fopen(config_.trajectory_path.c_str(), "w");
  if (f == nullptr) {
    *error = config_.trajectory_path + ": " + std::strerror(errno);
    return false;
  }
  for (const MapperSink::ScanRecord& r : sink_->trajectory) {
    Pose2 pose = r.online;
    if (r.region >= 0 && r.region < mapper_->region_count()) pose = mapper_->region_anchor(r.region) * r.in_region;
    const double half = 0.5 * static_cast<double>(pose.theta);
    const std::int64_t s = r.stamp_us / 1000000;
    const std::int64_t us = r.stamp_us % 1000000;
    std::fprintf(f, "%lld.%06lld %.6f %.6f 0 0 0 %.9f %.9f\n", static_cast<long long>(s),
                 static_cast<long long>(us < 0 ? -us : us), static_cast<double>(pose.x), static_cast<double>(pose.y),
                 std::sin(half), std::cos(half));
  }
  if (std::fclose(f) != 0) {
    *error = config_.trajectory_path + ": " + std::strerror(errno);
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
  FlushLidar();
  PrintSummary();
  if (!config_.trajectory_path.empty()) {
    std::string error;
    if (WriteTrajectory(&error)) {
      std::fprintf(log_, "dpcr-firmware: trajectory of %zu scans written to %s (%u not kept)\n",
                   sink_->trajectory.size(), config_.trajectory_path.c_str(), sink_->trajectory_overflow);
    } else {
      std::fprintf(log_, "dpcr-firmware: error: trajectory not written: %s\n", error.c_str());
      if (exit_code == 0) exit_code = 1;
    }
  }
  const SaveResult saved = SaveMap();
  if (saved.ok) {
    std::fprintf(log_, "dpcr-firmware: map saved to %s/%s (%zu bytes) and map.pgm (%dx%d), %u scans\n",
                 config_.map_dir.c_str(), kMapFileName, mapper_->map_file_bytes(), saved.width, saved.height,
                 sink_->scans);
  } else {
    std::fprintf(log_, "dpcr-firmware: error: map not saved: %s\n", saved.error.c_str());
    if (exit_code == 0) exit_code = 1;
  }
  std::fflush(log_);
  return exit_code;
}

}  // namespace dpcr::board
