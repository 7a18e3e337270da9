#include "board/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace dpcr::board {
namespace {

class Posix final : public FileOps {
 public:
  int Open(const char* path, int flags, mode_t mode) override { return ::open(path, flags, mode); }
  ssize_t Write(int fd, const void* data, std::size_t size) override { return ::write(fd, data, size); }
  ssize_t PRead(int fd, void* data, std::size_t size, off_t offset) override { return ::pread(fd, data, size, offset); }
  int Fsync(int fd) override { return ::fsync(fd); }
  int Close(int fd) override { return ::close(fd); }
  int Rename(const char* from, const char* to) override { return ::rename(from, to); }
  int Unlink(const char* path) override { return ::unlink(path); }
};

// The directory of `path` into `dir`, reusing its storage.
void DirectoryOf(const std::string& path, std::string* dir) {
  const std::size_t slash = path.rfind('/');
  if (slash == std::string::npos) {
    dir->assign(".");
  } else if (slash == 0) {
    dir->assign("/");
  } else {
    dir->assign(path, 0, slash);
  }
}

// Paths up to this long are built without allocating (the firmware saves from a thread that
// allocates nothing after start-up); longer ones still work.
constexpr std::size_t kPathReserve = 512;

}  // namespace

FileOps& PosixFileOps() {
  static Posix posix;
  return posix;
}

bool AtomicFileWriter::Fail(const std::string& file, const char* step, std::string* error) {
  const int saved = errno;
  *error = file + ": " + step + ": " + std::strerror(saved);
  Abort();
  errno = saved;
  return false;
}

void AtomicFileWriter::Abort() {
  if (fd_ < 0) return;
  const int saved = errno;
  (void)ops_.Close(fd_);
  (void)ops_.Unlink(tmp_.c_str());
  fd_ = -1;
  errno = saved;
}

AtomicFileWriter::AtomicFileWriter(FileOps& ops) : ops_(ops) {
  path_.reserve(kPathReserve);
  tmp_.reserve(kPathReserve + 4);
  dir_.reserve(kPathReserve);
}

bool AtomicFileWriter::Begin(const std::string& path, std::string* error) {
  Abort();
  path_.assign(path);
  tmp_.assign(path).append(".tmp");
  fd_ = ops_.Open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    *error = tmp_ + ": open: " + std::strerror(errno);
    return false;
  }
  return true;
}

bool AtomicFileWriter::Append(const void* data, std::size_t size, std::string* error) {
  if (fd_ < 0) {
    errno = EBADF;
    *error = path_ + ": write: no write begun";
    return false;
  }
  const auto* p = static_cast<const unsigned char*>(data);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ops_.Write(fd_, p + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return Fail(tmp_, "write", error);
    }
    done += static_cast<std::size_t>(n);  // a short write: the rest goes in the next call
  }
  return true;
}

bool AtomicFileWriter::Commit(std::string* error) {
  if (fd_ < 0) {
    errno = EBADF;
    *error = path_ + ": commit: no write begun";
    return false;
  }
  if (ops_.Fsync(fd_) != 0) return Fail(tmp_, "fsync", error);
  const int fd = fd_;
  fd_ = -1;  // closed below whatever happens
  if (ops_.Close(fd) != 0) {
    const int saved = errno;
    (void)ops_.Unlink(tmp_.c_str());
    errno = saved;
    *error = tmp_ + ": close: " + std::strerror(saved);
    return false;
  }
  if (ops_.Rename(tmp_.c_str(), path_.c_str()) != 0) {
    const int saved = errno;
    (void)ops_.Unlink(tmp_.c_str());
    errno = saved;
    *error = path_ + ": rename: " + std::strerror(saved);
    return false;
  }
  DirectoryOf(path_, &dir_);
  const int dfd = ops_.Open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC, 0);
  if (dfd < 0) {
    *error = dir_ + ": open directory: " + std::strerror(errno);
    return false;
  }
  const bool ok = ops_.Fsync(dfd) == 0;
  const int saved = errno;
  (void)ops_.Close(dfd);
  errno = saved;
  if (!ok) *error = dir_ + ": fsync directory: " + std::strerror(saved);
  return ok;
}

bool WriteFileAtomic(const std::string& path, const void* data, std::size_t size, std::string* error, FileOps& ops) {
  AtomicFileWriter w(ops);
  return w.Begin(path, error) && w.Append(data, size, error) && w.Commit(error);
}

AtomicFileStore::AtomicFileStore(std::string dir, FileOps& ops) : dir_(std::move(dir)), ops_(ops), writer_(ops) {
  path_.reserve(dir_.size() + kPathReserve);
}

const std::string& AtomicFileStore::PathOf(const char* name) {
  path_.assign(dir_).append("/").append(name);
  return path_;
}

IoStatus AtomicFileStore::Write(const char* name, const std::uint8_t* data, std::size_t size) {
  const bool ok = writer_.Begin(PathOf(name), &last_error_) && writer_.Append(data, size, &last_error_) &&
                  writer_.Commit(&last_error_);
  return ok ? IoStatus::kOk : IoStatus::kIoError;
}

IoStatus AtomicFileStore::Begin(const char* name) {
  return writer_.Begin(PathOf(name), &last_error_) ? IoStatus::kOk : IoStatus::kIoError;
}

IoStatus AtomicFileStore::Append(const std::uint8_t* data, std::size_t size) {
  return writer_.Append(data, size, &last_error_) ? IoStatus::kOk : IoStatus::kIoError;
}

IoStatus AtomicFileStore::Commit() { return writer_.Commit(&last_error_) ? IoStatus::kOk : IoStatus::kIoError; }

ByteRead AtomicFileStore::ReadAt(const char* name, std::uint64_t offset, std::uint8_t* buffer, std::size_t capacity) {
  ByteRead r;
  const std::string& path = PathOf(name);
  const int fd = ops_.Open(path.c_str(), O_RDONLY | O_CLOEXEC, 0);
  if (fd < 0) {
    r.status = errno == ENOENT ? IoStatus::kNotFound : IoStatus::kIoError;
    last_error_ = path + ": open: " + std::strerror(errno);
    return r;
  }
  ssize_t n = 0;
  do {
    n = ops_.PRead(fd, buffer, capacity, static_cast<off_t>(offset));
  } while (n < 0 && errno == EINTR);
  const int saved = errno;
  (void)ops_.Close(fd);
  errno = saved;
  if (n < 0) {
    r.status = IoStatus::kIoError;
    last_error_ = path + ": read: " + std::strerror(saved);
    return r;
  }
  r.size = static_cast<std::size_t>(n);
  return r;
}

}  // namespace dpcr::board
