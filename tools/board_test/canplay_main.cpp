// dpcr-canplay: replays a candump log onto a SocketCAN interface with the log's own timing
// (frame i at start + (stamp_i - stamp_0)), like canplayer, with optional faults: every Nth
// wheel-ticks frame dropped, every Mth sent twice. Runs inside the emulated board
// (tools/emulated-board-test). Prints one summary line; exits 0 when every frame was sent.
//   dpcr-canplay --log wheels.log --iface vcan0 [--drop-every N] [--dup-every M] [--ready PATH]
// --ready: once the log is loaded and the socket open, "DPCR-READY" is written to PATH (the
// guest's console, where the host starts the lidar bytes on it) and the first frame goes at once:
// both streams start from the same instant. (Said before the log was loaded, the wheels started
// 0.5 s after the lidar in a 3-minute run, and the firmware rightly saw the turns that late.)
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <poll.h>
#include <string>
#include <time.h>
#include <vector>

#include "board/socketcan_port.hpp"
#include "board/unique_fd.hpp"
#include "hal/wheel_can_protocol.hpp"
#include "host_sim/drivers/candump_log.hpp"

namespace {

std::int64_t NowUs() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

void SleepUntilUs(std::int64_t t_us) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t_us / 1000000);
  ts.tv_nsec = static_cast<long>((t_us % 1000000) * 1000);
  while (::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

// Sends one frame, waiting (up to 1 s) while the interface's queue is full.
bool Send(int fd, const dpcr::CanFrame& frame) {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const dpcr::IoStatus s = dpcr::board::WriteCanFrame(fd, frame);
    if (s == dpcr::IoStatus::kOk) return true;
    if (s != dpcr::IoStatus::kWouldBlock && errno != ENOBUFS) return false;
    pollfd p{fd, POLLOUT, 0};
    ::poll(&p, 1, 1);
  }
  return false;
}

// "DPCR-READY" and the uptime, one line to `path`.
bool SayReady(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) {
    std::fprintf(stderr, "dpcr-canplay: %s: %s\n", path.c_str(), std::strerror(errno));
    return false;
  }
  std::fprintf(f, "DPCR-READY %.2f\n", static_cast<double>(NowUs()) / 1e6);
  return std::fclose(f) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string log_path;
  std::string iface = "vcan0";
  long drop_every = 0;
  long dup_every = 0;
  std::string ready_path;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const char* v = argv[i + 1];
    if (a == "--log") {
      log_path = v;
    } else if (a == "--iface") {
      iface = v;
    } else if (a == "--drop-every") {
      drop_every = std::atol(v);
    } else if (a == "--dup-every") {
      dup_every = std::atol(v);
    } else if (a == "--ready") {
      ready_path = v;
    } else {
      std::fprintf(stderr, "dpcr-canplay: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (log_path.empty()) {
    std::fprintf(stderr, "usage: dpcr-canplay --log FILE [--iface IF] [--drop-every N] [--dup-every M] [--ready PATH]\n");
    return 2;
  }
  std::vector<dpcr::CandumpRecord> records;
  std::string error;
  if (!dpcr::ReadCandumpLog(log_path, &records, &error)) {
    std::fprintf(stderr, "dpcr-canplay: %s\n", error.c_str());
    return 1;
  }
  const dpcr::board::UniqueFd fd(dpcr::board::OpenSocketCan(iface, &error));
  if (fd.get() < 0) {
    std::fprintf(stderr, "dpcr-canplay: %s\n", error.c_str());
    return 1;
  }
  if (!ready_path.empty() && !SayReady(ready_path)) return 1;
  long sent = 0, dropped = 0, duplicated = 0, failed = 0, ticks = 0;
  std::int64_t late_max_us = 0;
  const std::int64_t start_us = NowUs();
  const std::int64_t first_stamp = records.empty() ? 0 : records.front().stamp_us;
  for (const dpcr::CandumpRecord& r : records) {
    const std::int64_t due = start_us + (r.stamp_us - first_stamp);
    SleepUntilUs(due);
    const std::int64_t late = NowUs() - due;
    if (late > late_max_us) late_max_us = late;
    const bool is_ticks = (r.frame.id & dpcr::kCanSffMask) == dpcr::kWheelTicksCanId;
    if (is_ticks) {
      ++ticks;
      if (drop_every > 0 && ticks % drop_every == 0) {
        ++dropped;
        continue;
      }
    }
    if (!Send(fd.get(), r.frame)) {
      ++failed;
      continue;
    }
    ++sent;
    if (is_ticks && dup_every > 0 && ticks % dup_every == 0) {
      if (Send(fd.get(), r.frame)) ++duplicated;
    }
  }
  std::printf("dpcr-canplay: frames=%zu sent=%ld dropped=%ld duplicated=%ld failed=%ld late_max_ms=%.1f span_s=%.1f\n",
              records.size(), sent, dropped, duplicated, failed, static_cast<double>(late_max_us) / 1000.0,
              static_cast<double>(NowUs() - start_us) / 1e6);
  return failed == 0 ? 0 : 1;
}
