#include "board/firmware_loop.hpp"

#include <cerrno>
#include <cstring>
#include <poll.h>
#include <string>

#include "board/atomic_file.hpp"
#include "board/monotonic_clock.hpp"
#include "board/signal_pipe.hpp"
#include "board/socketcan_port.hpp"
#include "board/stream_recorder.hpp"
#include "board/termios_uart.hpp"

namespace dpcr::board {
namespace {

constexpr int kPollTimeoutMs = 100;  // the timers' resolution when no device speaks

// The board's ports and the stop signal. Each owns its descriptor: whatever the exit path, the
// devices close and the signal handlers are restored when a BoardPorts goes.
// With a record directory, the firmware reads through recording decorators.
struct BoardPorts {
  explicit BoardPorts(const FirmwareConfig& config) : storage(config.map_dir), recording(!config.record_dir.empty()) {}
  FirmwarePorts ports() {
    if (recording) return FirmwarePorts{&recorded_uart, &recorded_can, &clock, &storage};
    return FirmwarePorts{&uart, &can, &clock, &storage};
  }

  MonotonicClock clock;
  TermiosUart uart{&clock};
  SocketCanPort can{&clock};
  AtomicFileStore storage;
  SignalPipe signals;
  bool recording;
  StreamRecorder recorder;
  RecordingByteSource recorded_uart{&uart, &recorder};
  RecordingCanSource recorded_can{&can, &recorder};
};

// Start-up: the firmware's state first (configuration checked before any device is touched),
// then the lidar UART, the CAN socket (or the fd given) and the signal pipe. False when logged.
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
    std::fprintf(log, "dpcr-firmware: error: CAN %s\n", error.c_str());
    return false;
  }
  if (board->recording && !board->recorder.Open(config.record_dir, config.can_interface, &error)) {
    std::fprintf(log, "dpcr-firmware: error: %s\n", error.c_str());
    return false;
  }
  if (!board->signals.Open(&error)) {
    std::fprintf(log, "dpcr-firmware: error: %s\n", error.c_str());
    return false;
  }
  std::fprintf(log, "dpcr-firmware: running: lidar on %s, wheels on %s\n", config.uart_device.c_str(),
               config.can_fd >= 0 ? "the given fd" : config.can_interface.c_str());
  std::fflush(log);
  return true;
}

// Waits on the signal pipe, the UART and the CAN socket and services whatever is ready, then
// the timers. Returns the exit code: 0 on a stop signal, 1 on a poll error, 2 on lidar silence.
int Loop(Firmware* firmware, BoardPorts* board, std::FILE* log) {
  bool uart_open = true;
  bool can_open = true;
  for (;;) {
    pollfd fds[3] = {{board->signals.read_fd(), POLLIN, 0},
                     {uart_open ? board->uart.fd() : -1, POLLIN, 0},
                     {can_open ? board->can.fd() : -1, POLLIN, 0}};
    const int ready = ::poll(fds, 3, kPollTimeoutMs);
    if (ready < 0 && errno != EINTR) {
      std::fprintf(log, "dpcr-firmware: error: poll: %s\n", std::strerror(errno));
      return 1;
    }
    if (ready > 0 && (fds[0].revents & POLLIN) != 0) {
      std::fprintf(log, "dpcr-firmware: signal received, saving map and exiting\n");
      return 0;
    }
    constexpr short kReadable = POLLIN | POLLHUP | POLLERR;
    if (ready > 0 && (fds[1].revents & kReadable) != 0) uart_open = firmware->ServiceLidar();
    if (ready > 0 && (fds[2].revents & kReadable) != 0) can_open = firmware->ServiceCan();
    if (firmware->LidarSilent()) return 2;
    firmware->ServiceTimers();
  }
}

// The final map save; the ports close when the caller's BoardPorts goes.
int TearDown(Firmware* firmware, BoardPorts* board, int exit_code) {
  if (board->recording && !board->recorder.Close() && exit_code == 0) exit_code = 1;
  return firmware->Finish(exit_code);
}

}  // namespace

int RunFirmware(const FirmwareConfig& config, std::FILE* log) {
  BoardPorts board(config);
  Firmware firmware(config, board.ports(), log);
  if (!SetUp(config, &firmware, &board, log)) return 1;
  const int exit_code = Loop(&firmware, &board, log);
  return TearDown(&firmware, &board, exit_code);
}

}  // namespace dpcr::board
