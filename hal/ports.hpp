// Port interfaces between the firmware (board/firmware.hpp) and its devices. board/ implements
// them on Linux: TermiosUart, SocketCanPort, MonotonicClock, AtomicFileStore; host_sim/drivers
// with recordings: UartCaptureSource, CandumpSource, ReplayClock. Decoders depend on none of
// them. Small abstract classes (one virtual call per read, not per byte).
#pragma once

#include <cstddef>
#include <cstdint>

#include "hal/can_frame.hpp"

namespace dpcr {

enum class IoStatus : std::uint8_t {
  kOk = 0,
  kWouldBlock,   // nothing available now
  kEndOfStream,  // file ended / peer closed
  kIoError,      // errno-level failure (the port keeps the errno)
  kNotFound,     // no such blob (BlobStore::ReadAt)
};

struct ByteRead {
  IoStatus status = IoStatus::kOk;
  std::size_t size = 0;          // bytes written to the buffer when kOk
  std::int64_t stamp_us = 0;     // host time the bytes arrived (or were recorded)
};

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual ByteRead Read(std::uint8_t* buffer, std::size_t capacity) = 0;
};

struct CanRead {
  IoStatus status = IoStatus::kOk;
  CanFrame frame;
  std::int64_t stamp_us = 0;
};

class CanSource {
 public:
  virtual ~CanSource() = default;
  virtual CanRead Read() = 0;
  // After a failure (or a start without the bus): tries once to open the bus again, without
  // waiting; kOk once it reads again. A source that cannot reopen says kIoError.
  virtual IoStatus Reopen() { return IoStatus::kIoError; }
};

class Clock {
 public:
  virtual ~Clock() = default;
  virtual std::int64_t NowUs() const = 0;  // monotonic
};

// What the firmware's loop waits for: the board waits with poll() on the devices and a stop
// signal; a test moves a replay clock to the next recorded byte or frame (no sleeps).
struct PortEvents {
  bool stop = false;   // a stop request (SIGTERM / SIGINT): save and exit
  bool lidar = false;  // the lidar port has bytes, or hung up
  bool can = false;    // the CAN port has frames, or failed
  int error = 0;       // the wait itself failed (errno): the loop cannot go on
};

class PortWaiter {
 public:
  virtual ~PortWaiter() = default;
  // Returns when an event is there or `timeout_us` has passed (no event then).
  virtual PortEvents Wait(std::int64_t timeout_us) = 0;
};

// The service manager's view of the firmware (the board: systemd's notify socket). All calls
// are cheap and never wait.
class ServiceNotifier {
 public:
  virtual ~ServiceNotifier() = default;
  virtual void Ready() = 0;     // start-up done: the service is running
  virtual void Alive() = 0;     // the watchdog kick: the loop is turning
  virtual void Stopping() = 0;  // the final save has begun
  // How often Alive() must come (0: no watchdog).
  virtual std::int64_t watchdog_period_us() const = 0;
};

// Persistent storage of named blobs; Write is atomic (the old blob survives a failed write).
class BlobStore {
 public:
  virtual ~BlobStore() = default;
  virtual IoStatus Write(const char* name, const std::uint8_t* data, std::size_t size) = 0;
  // Write in pieces (a map streamed chunk by chunk, no copy of it in RAM): Begin, Append...,
  // Commit, atomic as Write. A failed step or Abort leaves the old blob; one write at a time.
  virtual IoStatus Begin(const char* name) = 0;
  virtual IoStatus Append(const std::uint8_t* data, std::size_t size) = 0;
  virtual IoStatus Commit() = 0;
  virtual void Abort() = 0;
  // Up to `capacity` bytes of blob `name` from `offset` (size 0 at its end); kNotFound when there
  // is no such blob.
  virtual ByteRead ReadAt(const char* name, std::uint64_t offset, std::uint8_t* buffer, std::size_t capacity) = 0;
};

}  // namespace dpcr
