#include "board/firmware_loop.hpp"

#include <cerrno>
#include <poll.h>
#include <string>

#include "board/atomic_file.hpp"
#include "board/monotonic_clock.hpp"
#include "board/signal_pipe.hpp"
#include "board/socketcan_port.hpp"
#include "board/stream_recorder.hpp"
#include "board/systemd_notifier.hpp"
#include "board/termios_uart.hpp"

namespace dpcr::board {
namespace {

// The longest wait: the lidar-silence check's resolution when nothing speaks and no timer is due.
constexpr std::int64_t kMaxWaitUs = 100000;

// poll() over the stop-signal pipe, the UART and the CAN socket (a port that failed has closed
// its descriptor and is left out).
class PollWaiter : public PortWaiter {
 public:
  PollWaiter(const SignalPipe* signals, const TermiosUart* uart, const SocketCanPort* can)
      : signals_(signals), uart_(uart), can_(can) {}
  PortEvents Wait(std::int64_t timeout_us) override {
    pollfd fds[3] = {{signals_->read_fd(), POLLIN, 0}, {uart_->fd(), POLLIN, 0}, {can_->fd(), POLLIN, 0}};
    const int timeout_ms = static_cast<int>((timeout_us + 999) / 1000);
    PortEvents e;
    const int ready = ::poll(fds, 3, timeout_ms);
    if (ready < 0) {
      if (errno != EINTR) e.error = errno;
      return e;
    }
    constexpr short kReadable = POLLIN | POLLHUP | POLLERR;
    e.stop = (fds[0].revents & POLLIN) != 0;
    e.lidar = (fds[1].revents & kReadable) != 0;
    e.can = (fds[2].revents & kReadable) != 0;
    return e;
  }

 private:
  const SignalPipe* signals_;
  const TermiosUart* uart_;
  const SocketCanPort* can_;
};

// The board's ports and the stop signal. Each owns its descriptor: whatever the exit path, the
// devices close and the signal handlers are restored when a BoardPorts goes. With a record
// directory, the firmware reads through recording decorators.
struct BoardPorts {
  explicit BoardPorts(const FirmwareConfig& config)
      : storage(config.map_dir), recording(!config.record_dir.empty()), waiter(&signals, &uart, &can) {}
  FirmwarePorts ports() {
    ServiceNotifier* n = notifier.enabled() ? &notifier : nullptr;
    if (recording) return FirmwarePorts{&recorded_uart, &recorded_can, &clock, &storage, n};
    return FirmwarePorts{&uart, &can, &clock, &storage, n};
  }

  MonotonicClock clock;
  TermiosUart uart{&clock};
  SocketCanPort can{&clock};
  AtomicFileStore storage;
  SignalPipe signals;
  SystemdNotifier notifier;
  bool recording;
  StreamRecorder recorder;
  RecordingByteSource recorded_uart{&uart, &recorder};
  RecordingCanSource recorded_can{&can, &recorder};
  PollWaiter waiter;
};

// Start-up: the firmware's state first (configuration and map directory checked before any
// device is touched), then the lidar UART, the CAN socket (or the fd given; a missing bus is a
// warning: the lidar maps alone), the recording and the signal pipe. False when logged.
bool SetUp(const FirmwareConfig& config, Firmware* firmware, BoardPorts* board, std::FILE* log) {
  if (!firmware->Start()) return false;
  std::string error;
  if (!board->uart.Open(config.uart_device, config.baud, &error)) {
    std::fprintf(log, "dpcr-firmware: error: lidar UART %s\n", error.c_str());
    return false;
  }
  if (config.can_fd >= 0) {
    board->can.Borrow(config.can_fd);
  } else if (!board->can.Open(config.can_interface, &error)) {
    firmware->CanUnavailable(error.c_str());
  }
  if (board->recording) {
    const DeviceOptions device{config.wheels, config.angle_map.angle_sign, config.max_range_m, config.laser_offset_m};
    if (!board->recorder.Open(config.record_dir, config.can_interface, device,
                              config.lidar == LidarKind::kXv11 ? "xv11" : "ld06", &error)) {
      std::fprintf(log, "dpcr-firmware: error: %s\n", error.c_str());
      return false;
    }
  }
  if (!board->signals.Open(&error)) {
    std::fprintf(log, "dpcr-firmware: error: %s\n", error.c_str());
    return false;
  }
  firmware->Running();
  return true;
}

// The final map save; the ports close when the caller's BoardPorts goes.
int TearDown(Firmware* firmware, BoardPorts* board, int exit_code) {
  if (board->recording && !board->recorder.Close(board->clock.NowUs()) && exit_code == 0) exit_code = 1;
  return firmware->Finish(exit_code);
}

}  // namespace

int RunFirmwareLoop(Firmware* firmware, PortWaiter* waiter, const Clock& clock) {
  bool lidar_open = true;
  for (;;) {
    std::int64_t wait_us = firmware->next_timer_us() - clock.NowUs();
    if (wait_us > kMaxWaitUs) wait_us = kMaxWaitUs;
    if (wait_us < 0) wait_us = 0;
    const PortEvents events = waiter->Wait(wait_us);
    if (events.error != 0) {
      firmware->WaitFailed(events.error);
      return 1;
    }
    if (events.stop) {
      firmware->StopRequested();
      return 0;
    }
    if (events.lidar && lidar_open) lidar_open = firmware->ServiceLidar();
    if (events.can) firmware->ServiceCan();
    if (firmware->LidarSilent()) return 2;
    firmware->ServiceTimers();
  }
}

int RunFirmware(const FirmwareConfig& config, std::FILE* log) {
  BoardPorts board(config);
  Firmware firmware(config, board.ports(), log);
  if (!SetUp(config, &firmware, &board, log)) return 1;
  const int exit_code = RunFirmwareLoop(&firmware, &board.waiter, board.clock);
  return TearDown(&firmware, &board, exit_code);
}

}  // namespace dpcr::board
