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
};

class Clock {
 public:
  virtual ~Clock() = default;
  virtual std::int64_t NowUs() const = 0;  // monotonic
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
