// dpcr-board-feed: the emulated board's lidar, on the host (tools/emulated-board-test). Reads
// the guest's console from stdin (qemu's serial output) into a log file; when a line holds the
// ready word (the guest's firmware has its UART open), connects to qemu's unix-socket chardev
// of the guest's pci-serial port and writes the UART capture's bytes with the capture's timing
// (chunk i at start + (stamp_i - stamp_0)). Faults for the robustness run: a burst of random
// bytes every N chunks, and a pause (the chunks of a time window not sent: the lidar stopped).
// Prints one summary line on stderr; exits 0 when every chunk due was written.
//   dpcr-board-feed --capture lidar.uart --socket PATH --console-log FILE [--ready WORD]
//                   [--garbage-every N] [--garbage-bytes L] [--pause-at S] [--pause-s S]
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <random>
#include <string>
#include <sys/socket.h>
#include <sys/un.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "host_sim/drivers/uart_capture.hpp"

namespace {

using SteadyClock = std::chrono::steady_clock;

struct Options {
  std::string capture;
  std::string socket_path;
  std::string console_log;
  std::string ready = "DPCR-READY";
  long garbage_every = 0;
  long garbage_bytes = 16;
  double pause_at_s = -1.0;
  double pause_s = 0.0;
};

struct FeedResult {
  bool ok = false;
  long chunks = 0;
  long bytes = 0;
  long garbage_bursts = 0;
  long garbage_bytes = 0;
  long paused_chunks = 0;
  double late_max_ms = 0.0;
  std::string error;
};

bool WriteAll(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

int Connect(const std::string& path, std::string* error) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, path.c_str(), sizeof(addr.sun_path) - 1);
  if (fd < 0 || ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
    *error = path + ": connect: " + std::strerror(errno);
    if (fd >= 0) ::close(fd);
    return -1;
  }
  return fd;
}

void Feed(const Options& opt, const std::vector<dpcr::UartChunk>& chunks, const std::atomic<bool>* stop,
          FeedResult* out) {
  const int fd = Connect(opt.socket_path, &out->error);
  if (fd < 0) return;
  std::mt19937 rng(16);
  const auto start = SteadyClock::now();
  const std::int64_t first = chunks.empty() ? 0 : chunks.front().stamp_us;
  const std::int64_t pause_from = first + static_cast<std::int64_t>(opt.pause_at_s * 1e6);
  const std::int64_t pause_to = pause_from + static_cast<std::int64_t>(opt.pause_s * 1e6);
  std::vector<std::uint8_t> garbage;
  for (std::size_t i = 0; i < chunks.size() && !stop->load(); ++i) {
    const dpcr::UartChunk& c = chunks[i];
    if (opt.pause_at_s >= 0.0 && c.stamp_us >= pause_from && c.stamp_us < pause_to) {
      ++out->paused_chunks;
      continue;
    }
    const auto due = start + std::chrono::microseconds(c.stamp_us - first);
    std::this_thread::sleep_until(due);
    const double late = std::chrono::duration<double, std::milli>(SteadyClock::now() - due).count();
    if (late > out->late_max_ms) out->late_max_ms = late;
    if (opt.garbage_every > 0 && i > 0 && static_cast<long>(i) % opt.garbage_every == 0) {
      garbage.resize(static_cast<std::size_t>(opt.garbage_bytes));
      for (std::uint8_t& b : garbage) b = static_cast<std::uint8_t>(rng());
      if (!WriteAll(fd, garbage.data(), garbage.size())) break;
      ++out->garbage_bursts;
      out->garbage_bytes += opt.garbage_bytes;
    }
    if (!WriteAll(fd, c.bytes.data(), c.bytes.size())) {
      out->error = std::string("write: ") + std::strerror(errno);
      break;
    }
    ++out->chunks;
    out->bytes += static_cast<long>(c.bytes.size());
  }
  out->ok = out->error.empty() && !stop->load() && out->chunks + out->paused_chunks == static_cast<long>(chunks.size());
  if (!out->ok && out->error.empty()) out->error = "stopped before the end of the capture";
  // Keep the connection open until the guest is done: closing it is not a lidar event.
  while (!stop->load()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::close(fd);
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const char* v = argv[i + 1];
    if (a == "--capture") opt.capture = v;
    else if (a == "--socket") opt.socket_path = v;
    else if (a == "--console-log") opt.console_log = v;
    else if (a == "--ready") opt.ready = v;
    else if (a == "--garbage-every") opt.garbage_every = std::atol(v);
    else if (a == "--garbage-bytes") opt.garbage_bytes = std::atol(v);
    else if (a == "--pause-at") opt.pause_at_s = std::atof(v);
    else if (a == "--pause-s") opt.pause_s = std::atof(v);
    else {
      std::fprintf(stderr, "dpcr-board-feed: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (opt.capture.empty() || opt.socket_path.empty() || opt.console_log.empty()) {
    std::fprintf(stderr, "usage: dpcr-board-feed --capture FILE --socket PATH --console-log FILE [...]\n");
    return 2;
  }
  std::signal(SIGPIPE, SIG_IGN);
  std::vector<dpcr::UartChunk> chunks;
  std::string error;
  if (!dpcr::ReadUartCapture(opt.capture, &chunks, &error)) {
    std::fprintf(stderr, "dpcr-board-feed: %s\n", error.c_str());
    return 1;
  }
  std::FILE* log = std::fopen(opt.console_log.c_str(), "w");
  if (log == nullptr) {
    std::fprintf(stderr, "dpcr-board-feed: %s: %s\n", opt.console_log.c_str(), std::strerror(errno));
    return 1;
  }
  std::atomic<bool> stop{false};
  FeedResult result;
  std::thread feeder;
  bool started = false;
  std::string line;
  while (std::getline(std::cin, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::fprintf(log, "%s\n", line.c_str());
    std::fflush(log);
    if (!started && line.find(opt.ready) != std::string::npos) {
      started = true;
      feeder = std::thread(Feed, std::cref(opt), std::cref(chunks), &stop, &result);
    }
  }
  stop = true;  // the guest is gone (qemu exited)
  if (feeder.joinable()) feeder.join();
  std::fclose(log);
  if (!started) result.error = "the guest never said " + opt.ready;
  std::fprintf(stderr,
               "dpcr-board-feed: chunks=%ld/%zu bytes=%ld garbage_bursts=%ld garbage_bytes=%ld paused_chunks=%ld "
               "late_max_ms=%.1f%s%s\n",
               result.chunks, chunks.size(), result.bytes, result.garbage_bursts, result.garbage_bytes,
               result.paused_chunks, result.late_max_ms, result.error.empty() ? "" : " error: ", result.error.c_str());
  return result.ok ? 0 : 1;
}
