#include "board/socketcan_port.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include "board/errno_name.hpp"
#include "hal/wheel_can_protocol.hpp"

namespace dpcr::board {

static_assert(kCanEffFlag == CAN_EFF_FLAG && kCanRtrFlag == CAN_RTR_FLAG && kCanErrFlag == CAN_ERR_FLAG,
              "hal CAN flags must match Linux can_id flags");

namespace {

// Each protocol ID as a standard data frame (the EFF and RTR flags in the mask must be clear).
constexpr std::uint32_t kExactStandardFrame = CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG;
const can_filter kFilters[] = {
    {kWheelTicksCanId, kExactStandardFrame},
    {kGyroCanId, kExactStandardFrame},
    {kStatusCanId, kExactStandardFrame},
};

}  // namespace

bool WheelFiltersPass(std::uint32_t can_id) {
  for (const can_filter& f : kFilters) {
    if ((can_id & f.can_mask) == (f.can_id & f.can_mask)) return true;  // CAN_RAW's rule
  }
  return false;
}

int OpenSocketCan(const std::string& interface, std::string* error) {
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    *error = interface + ": socket(PF_CAN): " + DescribeErrno(errno);
    return -1;
  }
  ifreq ifr{};
  if (interface.size() >= sizeof(ifr.ifr_name)) {
    *error = interface + ": interface name too long";
    ::close(fd);
    return -1;
  }
  std::strncpy(ifr.ifr_name, interface.c_str(), sizeof(ifr.ifr_name) - 1);
  if (::ioctl(fd, SIOCGIFINDEX, &ifr) != 0) {
    *error = interface + ": no such CAN interface: " + DescribeErrno(errno);
    ::close(fd);
    return -1;
  }
  const can_err_mask_t err_mask = CAN_ERR_MASK;
  if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, kFilters, sizeof(kFilters)) != 0 ||
      ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof(err_mask)) != 0) {
    *error = interface + ": setsockopt(CAN_RAW_FILTER): " + DescribeErrno(errno);
    ::close(fd);
    return -1;
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
    *error = interface + ": bind: " + DescribeErrno(errno);
    ::close(fd);
    return -1;
  }
  return fd;
}

IoStatus ReadCanFrame(int fd, CanFrame* frame) {
  can_frame raw{};
  const ssize_t n = ::read(fd, &raw, sizeof(raw));
  if (n == 0) return IoStatus::kEndOfStream;
  if (n < 0) return (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) ? IoStatus::kWouldBlock : IoStatus::kIoError;
  if (static_cast<std::size_t>(n) != sizeof(raw)) {
    errno = EMSGSIZE;
    return IoStatus::kIoError;
  }
  frame->id = raw.can_id;
  frame->dlc = raw.can_dlc > 8 ? 8 : raw.can_dlc;
  std::memcpy(frame->data, raw.data, 8);
  return IoStatus::kOk;
}

IoStatus WriteCanFrame(int fd, const CanFrame& frame) {
  can_frame raw{};
  raw.can_id = frame.id;
  raw.can_dlc = frame.dlc;
  std::memcpy(raw.data, frame.data, 8);
  const ssize_t n = ::write(fd, &raw, sizeof(raw));
  if (n == static_cast<ssize_t>(sizeof(raw))) return IoStatus::kOk;
  return (n < 0 && errno == EAGAIN) ? IoStatus::kWouldBlock : IoStatus::kIoError;
}

bool SocketCanPort::Open(const std::string& interface, std::string* error) {
  interface_ = interface;
  owned_.Reset(OpenSocketCan(interface, error));
  fd_ = owned_.get();
  return fd_ >= 0;
}

IoStatus SocketCanPort::Reopen() {
  if (interface_.empty()) return IoStatus::kIoError;  // a borrowed fd cannot be reopened
  owned_.Reset(OpenSocketCan(interface_, &reopen_error_));
  fd_ = owned_.get();
  return fd_ >= 0 ? IoStatus::kOk : IoStatus::kIoError;
}

void SocketCanPort::Borrow(int fd) {
  owned_.Reset();
  interface_.clear();
  fd_ = fd;
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
}

CanRead SocketCanPort::Read() {
  CanRead r;
  r.status = ReadCanFrame(fd_, &r.frame);
  const int saved = errno;  // kIoError keeps the read's errno
  r.stamp_us = clock_->NowUs();
  if (r.status == IoStatus::kEndOfStream || r.status == IoStatus::kIoError) {
    // Failed (the interface went down, bus-off): closed, so that poll() no longer wakes for it;
    // Reopen() tries again.
    owned_.Reset();
    fd_ = -1;
  }
  errno = saved;
  return r;
}

}  // namespace dpcr::board
