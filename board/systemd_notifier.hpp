// systemd's notify protocol without libsystemd: one AF_UNIX datagram per message to the socket
// named by $NOTIFY_SOCKET ("READY=1", "WATCHDOG=1", "STOPPING=1"); the watchdog period from
// $WATCHDOG_USEC (for this process when $WATCHDOG_PID names it). Without $NOTIFY_SOCKET (not
// started by systemd) it is disabled. Sends never wait (MSG_DONTWAIT): a full socket loses a
// message, never stalls the scan loop.
#pragma once

#include <cstdint>

#include "board/unique_fd.hpp"
#include "hal/ports.hpp"

namespace dpcr::board {

class SystemdNotifier : public ServiceNotifier {
 public:
  // Reads the environment.
  SystemdNotifier();
  bool enabled() const { return fd_.get() >= 0; }
  void Ready() override { Send("READY=1\nSTATUS=mapping"); }
  void Alive() override { Send("WATCHDOG=1"); }
  void Stopping() override { Send("STOPPING=1\nSTATUS=saving the map"); }
  std::int64_t watchdog_period_us() const override { return watchdog_us_; }
  // Messages the socket refused (full, or the manager gone).
  std::uint32_t send_failures() const { return send_failures_; }

 private:
  void Send(const char* message);

  UniqueFd fd_;
  char address_[108] = {};  // sockaddr_un::sun_path; a leading '@' is the abstract namespace
  unsigned address_length_ = 0;
  std::int64_t watchdog_us_ = 0;
  std::uint32_t send_failures_ = 0;
};

}  // namespace dpcr::board
