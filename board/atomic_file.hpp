// Crash-safe file replacement: write a temp file in the same directory, fsync it, rename it
// over the target, fsync the directory. A reader sees the old file or the new one, never a mix.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "hal/ports.hpp"

namespace dpcr::board {

// False with "path: step: strerror" in `error`; the previous file is untouched on failure.
bool WriteFileAtomic(const std::string& path, const void* data, std::size_t size, std::string* error);

// The board's BlobStore port: blob `name` is the file DIR/name, each write atomic as above.
class AtomicFileStore : public BlobStore {
 public:
  explicit AtomicFileStore(std::string dir) : dir_(std::move(dir)) {}
  // kIoError with errno kept; last_error() then says which file and which step failed.
  IoStatus Write(const char* name, const std::uint8_t* data, std::size_t size) override;
  const std::string& last_error() const { return last_error_; }

 private:
  std::string dir_;
  std::string last_error_;
};

}  // namespace dpcr::board
