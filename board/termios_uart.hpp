// Lidar serial port: termios raw mode, 8N1, no flow control, non-blocking reads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "board/unique_fd.hpp"
#include "hal/ports.hpp"

namespace dpcr::board {

// Returns the fd, or -1 with "device: step: strerror" in `error`.
// Supported rates: 115200 (XV-11), 230400 (LD06/LD19).
int OpenLidarUart(const std::string& device, int baud, std::string* error);

// The lidar UART as the firmware's ByteSource: each read stamped with `clock` when it returns.
class TermiosUart : public ByteSource {
 public:
  explicit TermiosUart(const Clock* clock) : clock_(clock) {}
  // False with "device: step: strerror" in `error`.
  bool Open(const std::string& device, int baud, std::string* error);
  int fd() const { return fd_.get(); }  // to wait on with poll(); -1 once ended or failed
  // Call once poll() says readable: raw mode reads never wait (VMIN = VTIME = 0), so an empty
  // read then means the device hung up (kEndOfStream). kWouldBlock on EAGAIN/EINTR, kIoError
  // (errno kept) otherwise.
  ByteRead Read(std::uint8_t* buffer, std::size_t capacity) override;

 private:
  const Clock* clock_;
  UniqueFd fd_;
};

}  // namespace dpcr::board
