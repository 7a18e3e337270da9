#include "board/systemd_notifier.hpp"

#include <cstdlib>
#include <cstring>
#include <stddef.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

namespace dpcr::board {

SystemdNotifier::SystemdNotifier() {
  const char* socket_path = std::getenv("NOTIFY_SOCKET");
  if (socket_path == nullptr || socket_path[0] == '\0') return;
  const std::size_t length = std::strlen(socket_path);
  if ((socket_path[0] != '/' && socket_path[0] != '@') || length >= sizeof(address_)) return;
  std::memcpy(address_, socket_path, length);
  address_length_ = static_cast<unsigned>(length);
  fd_.Reset(::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
  const char* watchdog = std::getenv("WATCHDOG_USEC");
  const char* pid = std::getenv("WATCHDOG_PID");
  const bool for_us = pid == nullptr || std::strtol(pid, nullptr, 10) == static_cast<long>(::getpid());
  if (watchdog != nullptr && for_us) {
    char* end = nullptr;
    const long long us = std::strtoll(watchdog, &end, 10);
    if (end != watchdog && *end == '\0' && us > 0) watchdog_us_ = us;
  }
}

void SystemdNotifier::Send(const char* message) {
  if (fd_.get() < 0) return;
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::memcpy(addr.sun_path, address_, address_length_);
  if (addr.sun_path[0] == '@') addr.sun_path[0] = '\0';  // abstract socket
  const socklen_t size = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + address_length_);
  const ssize_t n = ::sendto(fd_.get(), message, std::strlen(message), MSG_DONTWAIT | MSG_NOSIGNAL,
                             reinterpret_cast<const sockaddr*>(&addr), size);
  if (n < 0) ++send_failures_;
}

}  // namespace dpcr::board
