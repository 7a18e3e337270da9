// SIGINT/SIGTERM as a readable fd (the self-pipe trick), so that poll() wakes on a stop request.
// Installs the handlers on Open and restores the previous ones, and closes the pipe, when it goes.
#pragma once

#include <csignal>
#include <string>

#include "board/unique_fd.hpp"

namespace dpcr::board {

class SignalPipe {
 public:
  SignalPipe() = default;
  ~SignalPipe();
  SignalPipe(const SignalPipe&) = delete;
  SignalPipe& operator=(const SignalPipe&) = delete;

  // False with "pipe: strerror" in `error`. One SignalPipe at a time per process.
  bool Open(std::string* error);
  int read_fd() const { return read_.get(); }  // readable once a signal arrived

 private:
  UniqueFd read_;
  UniqueFd write_;
  bool installed_ = false;
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

}  // namespace dpcr::board
