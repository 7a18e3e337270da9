// SocketCAN raw socket for the wheel encoders, and struct can_frame reads from any fd (the
// firmware test passes one end of a socketpair carrying struct can_frame: same code path).
#pragma once

#include <cstdint>
#include <string>

#include "board/unique_fd.hpp"
#include "hal/can_frame.hpp"
#include "hal/ports.hpp"

namespace dpcr::board {

// Opens a CAN_RAW socket on `interface`, non-blocking, with receive filters for the wheel
// protocol IDs (0x120, 0x121, 0x122) and error frames. -1 with "interface: step: strerror" on failure.
int OpenSocketCan(const std::string& interface, std::string* error);
// Whether a data frame with Linux `can_id` passes those ID filters, by the kernel's CAN_RAW rule
// (error frames pass through CAN_RAW_ERR_FILTER instead).
bool WheelFiltersPass(std::uint32_t can_id);

// Reads one struct can_frame from `fd` (non-blocking). kWouldBlock when none is queued,
// kEndOfStream when the peer closed, kIoError (errno kept) otherwise.
IoStatus ReadCanFrame(int fd, CanFrame* frame);
// Writes one struct can_frame (tests, vcan smoke).
IoStatus WriteCanFrame(int fd, const CanFrame& frame);

// The wheel-encoder CAN bus as the firmware's CanSource: each frame stamped with `clock` when
// it is read.
class SocketCanPort : public CanSource {
 public:
  explicit SocketCanPort(const Clock* clock) : clock_(clock) {}
  // Opens (and owns) a CAN_RAW socket on `interface`; false with the reason in `error`.
  bool Open(const std::string& interface, std::string* error);
  // Reads from an fd opened elsewhere (tests: a socketpair end), made non-blocking, never closed here.
  void Borrow(int fd);
  int fd() const { return fd_; }  // to wait on with poll(); -1 once failed (or never opened)
  // A failed read closes the socket (the interface went down): kEndOfStream / kIoError.
  CanRead Read() override;
  // Opens the interface given to Open again (the firmware's retry while it maps without wheels).
  IoStatus Reopen() override;

 private:
  const Clock* clock_;
  std::string interface_;
  std::string reopen_error_;  // why the last reopen failed (the firmware only counts retries)
  UniqueFd owned_;
  int fd_ = -1;
};

}  // namespace dpcr::board
