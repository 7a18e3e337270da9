// Where a saved map goes and where a map to load comes from: byte streams the caller provides
// (a file, flash, a buffer). The core writes and reads them in small chunks through a buffer on
// its stack, so a map of any size costs the Mapper no RAM of its own. No virtual destructor: a
// deleting destructor would pull in operator delete; the caller owns both ends.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/base/span.hpp"
#include "core/base/status.hpp"

namespace dpcr {

class MapByteSink {
 public:
  // Appends `size` bytes; anything but kOk stops the save, which returns that status.
  virtual Status Write(const std::uint8_t* data, std::size_t size) = 0;

 protected:
  ~MapByteSink() = default;
};

class MapByteSource {
 public:
  // Up to `capacity` bytes; 0 at the end of the data (or when it cannot be read).
  virtual std::size_t Read(std::uint8_t* buffer, std::size_t capacity) = 0;
  // Back to the first byte: a load reads the data more than once (check, then apply). False when
  // the source cannot start over (the load then fails without touching the mapper).
  virtual bool Rewind() = 0;

 protected:
  ~MapByteSource() = default;
};

// A map held in memory.
class MemoryMapSource final : public MapByteSource {
 public:
  explicit MemoryMapSource(Span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::size_t Read(std::uint8_t* buffer, std::size_t capacity) override {
    std::size_t n = bytes_.size() - offset_;
    if (n > capacity) n = capacity;
    for (std::size_t i = 0; i < n; ++i) buffer[i] = bytes_[offset_ + i];
    offset_ += n;
    return n;
  }
  bool Rewind() override {
    offset_ = 0;
    return true;
  }

 private:
  Span<const std::uint8_t> bytes_;
  std::size_t offset_ = 0;
};

// Saves into a fixed buffer: kCapacityExceeded when the map does not fit.
class MemoryMapSink final : public MapByteSink {
 public:
  explicit MemoryMapSink(Span<std::uint8_t> buffer) : buffer_(buffer) {}
  Status Write(const std::uint8_t* data, std::size_t size) override {
    if (size > buffer_.size() - size_) return Status::kCapacityExceeded;
    for (std::size_t i = 0; i < size; ++i) buffer_[size_ + i] = data[i];
    size_ += size;
    return Status::kOk;
  }
  std::size_t size() const { return size_; }

 private:
  Span<std::uint8_t> buffer_;
  std::size_t size_ = 0;
};

}  // namespace dpcr
