// Lidar serial port: termios raw mode, 8N1, no flow control, non-blocking reads.
#pragma once

#include <string>

namespace dpcr::board {

// Returns the fd, or -1 with "device: step: strerror" in `error`.
// Supported rates: 115200 (XV-11), 230400 (LD06/LD19).
int OpenLidarUart(const std::string& device, int baud, std::string* error);

}  // namespace dpcr::board
