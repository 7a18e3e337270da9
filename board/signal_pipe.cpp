#include "board/signal_pipe.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace dpcr::board {
namespace {

// The one piece of process-global state: the write end the handler uses to wake poll() (a
// handler can only touch async-signal-safe things).
int g_signal_write_fd = -1;

void OnSignal(int /*signo*/) {
  const int saved = errno;
  const char byte = 1;
  if (g_signal_write_fd >= 0) static_cast<void>(::write(g_signal_write_fd, &byte, 1));
  errno = saved;
}

}  // namespace

bool SignalPipe::Open(std::string* error) {
  int fds[2];
  if (::pipe2(fds, O_NONBLOCK | O_CLOEXEC) != 0) {
    *error = std::string("pipe: ") + std::strerror(errno);
    return false;
  }
  read_.Reset(fds[0]);
  write_.Reset(fds[1]);
  g_signal_write_fd = write_.get();
  struct sigaction sa {};
  sa.sa_handler = &OnSignal;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGINT, &sa, &old_int_);
  ::sigaction(SIGTERM, &sa, &old_term_);
  installed_ = true;
  return true;
}

SignalPipe::~SignalPipe() {
  if (!installed_) return;
  ::sigaction(SIGINT, &old_int_, nullptr);
  ::sigaction(SIGTERM, &old_term_, nullptr);
  g_signal_write_fd = -1;
}

}  // namespace dpcr::board
