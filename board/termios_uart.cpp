#include "board/termios_uart.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include "board/errno_name.hpp"

namespace dpcr::board {

int OpenLidarUart(const std::string& device, int baud, std::string* error) {
  speed_t speed = B230400;
  if (baud == 115200) {
    speed = B115200;
  } else if (baud != 230400) {
    *error = device + ": unsupported baud rate " + std::to_string(baud);
    return -1;
  }
  const int fd = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *error = device + ": open: " + DescribeErrno(errno);
    return -1;
  }
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    *error = device + ": tcgetattr (not a serial port?): " + DescribeErrno(errno);
    ::close(fd);
    return -1;
  }
  ::cfmakeraw(&tio);  // 8 data bits, no parity, no echo, no line discipline
  tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (::cfsetispeed(&tio, speed) != 0 || ::cfsetospeed(&tio, speed) != 0 ||
      ::tcsetattr(fd, TCSANOW, &tio) != 0) {
    *error = device + ": tcsetattr: " + DescribeErrno(errno);
    ::close(fd);
    return -1;
  }
  ::tcflush(fd, TCIFLUSH);
  return fd;
}

bool TermiosUart::Open(const std::string& device, int baud, std::string* error) {
  fd_.Reset(OpenLidarUart(device, baud, error));
  return fd_.get() >= 0;
}

ByteRead TermiosUart::Read(std::uint8_t* buffer, std::size_t capacity) {
  ByteRead r;
  const ssize_t n = ::read(fd_.get(), buffer, capacity);
  if (n > 0) {
    r.size = static_cast<std::size_t>(n);
  } else if (n == 0) {
    r.status = IoStatus::kEndOfStream;
  } else {
    r.status = (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) ? IoStatus::kWouldBlock : IoStatus::kIoError;
  }
  const int saved = errno;  // kIoError keeps the read's errno
  r.stamp_us = clock_->NowUs();
  // Ended or failed: closed, so that poll() no longer wakes for it.
  if (r.status == IoStatus::kEndOfStream || r.status == IoStatus::kIoError) fd_.Reset();
  errno = saved;
  return r;
}

}  // namespace dpcr::board
