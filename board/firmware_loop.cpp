#include "board/firmware_loop.hpp"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <memory>
#include <poll.h>
#include <unistd.h>
#include <vector>

#include "board/atomic_file.hpp"
#include "board/socketcan_port.hpp"
#include "board/termios_uart.hpp"
#include "core/capacity.hpp"
#include "core/mapper.hpp"
#include "hal/device_pipeline.hpp"
#include "hal/map_export.hpp"

namespace dpcr::board {
namespace {

using BoardMapper = Mapper<VacuumProfile>;

// The one piece of process-global state: the write end of the self-pipe the signal handler
// uses to wake poll() (a handler can only touch async-signal-safe things).
int g_signal_write_fd = -1;

void OnSignal(int /*signo*/) {
  const int saved = errno;
  const char byte = 1;
  if (g_signal_write_fd >= 0) static_cast<void>(::write(g_signal_write_fd, &byte, 1));
  errno = saved;
}

std::int64_t MonotonicUs() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

MapSaveResult SaveMap(const BoardMapper& mapper, const std::string& dir) {
  MapSaveResult r;
  const CellBox box = mapper.MapBounds();
  r.width = box.width();
  r.height = box.height();
  if (r.width <= 0 || r.height <= 0) {
    r.error = "map is empty, nothing saved";
    return r;
  }
  std::vector<std::int16_t> cells(static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height));
  if (mapper.RenderMap(box, Span<std::int16_t>(cells.data(), cells.size())) != Status::kOk) {
    r.error = "map rendering failed";
    return r;
  }
  std::vector<std::uint8_t> pgm(PgmSize(r.width, r.height));
  const std::size_t pgm_size = EncodePgm(Span<const std::int16_t>(cells.data(), cells.size()), r.width, r.height,
                                         Span<std::uint8_t>(pgm.data(), pgm.size()));
  char yaml[512];
  const std::size_t yaml_size =
      EncodeMapYaml("map.pgm", mapper.config().grid.resolution_m, box, Span<char>(yaml, sizeof(yaml)));
  if (pgm_size == 0 || yaml_size == 0) {
    r.error = "map encoding failed";
    return r;
  }
  // Image first: a YAML never names an image that is not complete.
  r.ok = WriteFileAtomic(dir + "/map.pgm", pgm.data(), pgm_size, &r.error) &&
         WriteFileAtomic(dir + "/map.yaml", yaml, yaml_size, &r.error);
  return r;
}

// The device pipeline's outputs into the mapper, scans counted for the status line.
class MapperSink : public DeviceSink {
 public:
  explicit MapperSink(BoardMapper* mapper) : mapper_(mapper) {}
  void AddOdometry(const OdometrySample& sample) override { mapper_->AddOdometry(sample); }
  void AddScan(const DeviceScan& scan) override {
    static_cast<void>(mapper_->AddScan(scan));  // rejections are counted by the mapper
    ++scans;
  }
  std::uint32_t scans = 0;

 private:
  BoardMapper* mapper_;
};

}  // namespace

int RunFirmware(const FirmwareConfig& config, std::FILE* log) {
  std::string error;
  if (config.wheels.Validate() != Status::kOk) {
    std::fprintf(log, "dpcr-firmware: error: invalid wheel configuration\n");
    return 1;
  }
  const int uart = OpenLidarUart(config.uart_device, config.baud, &error);
  if (uart < 0) {
    std::fprintf(log, "dpcr-firmware: error: lidar UART %s\n", error.c_str());
    return 1;
  }
  int can = config.can_fd;
  if (can < 0) {
    can = OpenSocketCan(config.can_interface, &error);
    if (can < 0) {
      std::fprintf(log, "dpcr-firmware: error: CAN %s\n", error.c_str());
      ::close(uart);
      return 1;
    }
  } else {
    ::fcntl(can, F_SETFL, ::fcntl(can, F_GETFL) | O_NONBLOCK);
  }
  int sig_pipe[2];
  if (::pipe2(sig_pipe, O_NONBLOCK | O_CLOEXEC) != 0) {
    std::fprintf(log, "dpcr-firmware: error: pipe: %s\n", std::strerror(errno));
    return 1;
  }
  g_signal_write_fd = sig_pipe[1];
  struct sigaction sa {};
  sa.sa_handler = &OnSignal;
  sigemptyset(&sa.sa_mask);
  struct sigaction old_int {};
  struct sigaction old_term {};
  ::sigaction(SIGINT, &sa, &old_int);
  ::sigaction(SIGTERM, &sa, &old_term);

  // The mapper and the scan buffers are allocated once here, never during the run.
  auto mapper = std::make_unique<BoardMapper>();
  MapperConfig mapper_config;
  if (mapper->Init(mapper_config) != Status::kOk) {
    std::fprintf(log, "dpcr-firmware: error: mapper configuration rejected\n");
    return 1;
  }
  MapperSink sink(mapper.get());
  DevicePipelineConfig pipeline_config;
  pipeline_config.lidar.kind = config.lidar;
  pipeline_config.lidar.assembler.angle_map = config.angle_map;
  pipeline_config.wheels = config.wheels;
  auto pipeline = std::make_unique<DevicePipeline>(pipeline_config, &sink);

  const std::int64_t start_us = MonotonicUs();
  std::int64_t next_status_us = start_us + config.status_period_ms * 1000LL;
  std::int64_t next_save_us = config.autosave_s > 0 ? start_us + config.autosave_s * 1000000LL : INT64_MAX;
  std::int64_t last_lidar_us = start_us;
  std::uint32_t scans_at_last_status = 0;
  bool uart_open = true;
  bool can_open = true;
  int exit_code = 0;
  std::uint8_t buffer[4096];

  for (;;) {
    pollfd fds[3] = {{sig_pipe[0], POLLIN, 0}, {uart_open ? uart : -1, POLLIN, 0}, {can_open ? can : -1, POLLIN, 0}};
    const int ready = ::poll(fds, 3, 100);
    if (ready < 0 && errno != EINTR) {
      std::fprintf(log, "dpcr-firmware: error: poll: %s\n", std::strerror(errno));
      exit_code = 1;
      break;
    }
    const std::int64_t now = MonotonicUs();
    if (ready > 0 && (fds[0].revents & POLLIN) != 0) {
      std::fprintf(log, "dpcr-firmware: signal received, saving map and exiting\n");
      break;
    }
    if (ready > 0 && (fds[1].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
      const ssize_t n = ::read(uart, buffer, sizeof(buffer));
      if (n > 0) {
        pipeline->FeedAllLidar(buffer, static_cast<std::size_t>(n), now);
        if (pipeline->last_lidar_packet_us() != 0) last_lidar_us = now;
      } else if (n == 0 || (errno != EAGAIN && errno != EINTR)) {
        std::fprintf(log, "dpcr-firmware: error: lidar UART %s: %s\n", config.uart_device.c_str(),
                     n == 0 ? "end of file" : std::strerror(errno));
        uart_open = false;
      }
    }
    if (ready > 0 && (fds[2].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
      for (;;) {
        CanFrame frame;
        const IoStatus s = ReadCanFrame(can, &frame);
        if (s == IoStatus::kWouldBlock) break;
        if (s != IoStatus::kOk) {
          std::fprintf(log, "dpcr-firmware: error: CAN %s: %s\n", config.can_interface.c_str(),
                       s == IoStatus::kEndOfStream ? "closed" : std::strerror(errno));
          can_open = false;
          break;
        }
        pipeline->FeedCan(frame, now);
      }
    }
    if (now - last_lidar_us > config.lidar_timeout_ms * 1000LL) {
      std::fprintf(log, "dpcr-firmware: error: lidar timeout: no packet from %s for %d ms\n",
                   config.uart_device.c_str(), config.lidar_timeout_ms);
      exit_code = 2;
      break;
    }
    if (now >= next_status_us) {
      const double period_s = static_cast<double>(config.status_period_ms) / 1000.0;
      const DevicePipelineCounters counters = pipeline->counters();
      const LidarStreamCounters& lc = counters.lidar;
      const WheelCanCounters& cc = counters.can;
      const Pose2 pose = mapper->pose();
      std::fprintf(log,
                   "dpcr-firmware: t=%.1fs scan_rate=%.1f/s packets=%u bad=%u resyncs=%u gaps=%u "
                   "can_lost=%u dup=%u reord=%u err=%u pose=(%.3f,%.3f,%.3f) mapper=%s\n",
                   static_cast<double>(now - start_us) / 1e6,
                   static_cast<double>(sink.scans - scans_at_last_status) / period_s, lc.packets, lc.bad_packets,
                   lc.resyncs, lc.gaps, cc.lost, cc.duplicated, cc.reordered, cc.error_frames,
                   static_cast<double>(pose.x), static_cast<double>(pose.y), static_cast<double>(pose.theta),
                   ToString(mapper->status()));
      std::fflush(log);
      scans_at_last_status = sink.scans;
      next_status_us = now + config.status_period_ms * 1000LL;
    }
    if (now >= next_save_us) {
      const MapSaveResult r = SaveMap(*mapper, config.map_dir);
      if (!r.ok) std::fprintf(log, "dpcr-firmware: autosave: %s\n", r.error.c_str());
      next_save_us = now + config.autosave_s * 1000000LL;
    }
  }

  const MapSaveResult saved = SaveMap(*mapper, config.map_dir);
  if (saved.ok) {
    std::fprintf(log, "dpcr-firmware: map saved to %s/map.pgm (%dx%d), %u scans\n", config.map_dir.c_str(),
                 saved.width, saved.height, sink.scans);
  } else {
    std::fprintf(log, "dpcr-firmware: error: map not saved: %s\n", saved.error.c_str());
    if (exit_code == 0) exit_code = 1;
  }
  std::fflush(log);
  ::sigaction(SIGINT, &old_int, nullptr);
  ::sigaction(SIGTERM, &old_term, nullptr);
  g_signal_write_fd = -1;
  ::close(sig_pipe[0]);
  ::close(sig_pipe[1]);
  ::close(uart);
  if (config.can_fd < 0) ::close(can);
  return exit_code;
}

}  // namespace dpcr::board
