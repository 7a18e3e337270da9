// Crash-safe file replacement: write a temp file in the same directory, fsync it, rename it
// over the target, fsync the directory. A reader sees the old file or the new one, never a mix,
// and after a power cut at any point the old file or the new one is there (the new one once the
// directory fsync returned). The POSIX calls go through FileOps so that tests can fail or cut
// them at any step (tests/board/atomic_file_fault_test.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <sys/types.h>
#include <utility>

#include "hal/ports.hpp"

namespace dpcr::board {

// The calls an atomic write makes, errno set on failure as POSIX does.
class FileOps {
 public:
  virtual ~FileOps() = default;
  virtual int Open(const char* path, int flags, mode_t mode) = 0;
  virtual ssize_t Write(int fd, const void* data, std::size_t size) = 0;
  virtual ssize_t PRead(int fd, void* data, std::size_t size, off_t offset) = 0;
  virtual int Fsync(int fd) = 0;
  virtual int Close(int fd) = 0;
  virtual int Rename(const char* from, const char* to) = 0;
  virtual int Unlink(const char* path) = 0;
};

// The real calls.
FileOps& PosixFileOps();

// One atomic replacement of `path`, written in pieces: Begin (opens path.tmp), Append..., Commit
// (fsync, close, rename, fsync the directory). A failed step, Abort or the destructor before
// Commit removes the temp file and leaves `path` as it was. Errors read "file: step: strerror".
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(FileOps& ops = PosixFileOps());
  ~AtomicFileWriter() { Abort(); }
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  bool Begin(const std::string& path, std::string* error);
  bool Append(const void* data, std::size_t size, std::string* error);
  // True once the new file is in place and its directory entry durable. False after the rename
  // only when the directory fsync failed: the new file is in place, not yet durable.
  bool Commit(std::string* error);
  void Abort();
  bool open() const { return fd_ >= 0; }

 private:
  bool Fail(const std::string& file, const char* step, std::string* error);

  FileOps& ops_;
  std::string path_;
  std::string tmp_;
  std::string dir_;
  int fd_ = -1;
};

// Begin + Append + Commit. False with "path: step: strerror" in `error`.
bool WriteFileAtomic(const std::string& path, const void* data, std::size_t size, std::string* error,
                     FileOps& ops = PosixFileOps());

// The board's BlobStore port: blob `name` is the file DIR/name, each write atomic as above.
class AtomicFileStore : public BlobStore {
 public:
  explicit AtomicFileStore(std::string dir, FileOps& ops = PosixFileOps());
  // kIoError with errno kept; last_error() then says which file and which step failed.
  IoStatus Write(const char* name, const std::uint8_t* data, std::size_t size) override;
  IoStatus Begin(const char* name) override;
  IoStatus Append(const std::uint8_t* data, std::size_t size) override;
  IoStatus Commit() override;
  void Abort() override { writer_.Abort(); }
  ByteRead ReadAt(const char* name, std::uint64_t offset, std::uint8_t* buffer, std::size_t capacity) override;
  const std::string& last_error() const { return last_error_; }
  const std::string& dir() const { return dir_; }

 private:
  const std::string& PathOf(const char* name);  // DIR/name, in storage kept between calls

  std::string dir_;
  FileOps& ops_;
  AtomicFileWriter writer_;
  std::string path_;
  std::string last_error_;
};

}  // namespace dpcr::board
