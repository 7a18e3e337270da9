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

std::string DirectoryOf(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
}

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

bool AtomicFileWriter::Begin(const std::string& path, std::string* error) {
  Abort();
  path_ = path;
  tmp_ = path + ".tmp";
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
  const std::string dir = DirectoryOf(path_);
  const int dfd = ops_.Open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC, 0);
  if (dfd < 0) {
    *error = dir + ": open directory: " + std::strerror(errno);
    return false;
  }
  const bool ok = ops_.Fsync(dfd) == 0;
  const int saved = errno;
  (void)ops_.Close(dfd);
  errno = saved;
  if (!ok) *error = dir + ": fsync directory: " + std::strerror(saved);
  return ok;
}

bool WriteFileAtomic(const std::string& path, const void* data, std::size_t size, std::string* error, FileOps& ops) {
  AtomicFileWriter w(ops);
  return w.Begin(path, error) && w.Append(data, size, error) && w.Commit(error);
}

IoStatus AtomicFileStore::Write(const char* name, const std::uint8_t* data, std::size_t size) {
  if (WriteFileAtomic(dir_ + "/" + name, data, size, &last_error_, ops_)) return IoStatus::kOk;
  return IoStatus::kIoError;
}

IoStatus AtomicFileStore::Begin(const char* name) {
  return writer_.Begin(dir_ + "/" + name, &last_error_) ? IoStatus::kOk : IoStatus::kIoError;
}

IoStatus AtomicFileStore::Append(const std::uint8_t* data, std::size_t size) {
  return writer_.Append(data, size, &last_error_) ? IoStatus::kOk : IoStatus::kIoError;
}

IoStatus AtomicFileStore::Commit() { return writer_.Commit(&last_error_) ? IoStatus::kOk : IoStatus::kIoError; }

ByteRead AtomicFileStore::ReadAt(const char* name, std::uint64_t offset, std::uint8_t* buffer, std::size_t capacity) {
  ByteRead r;
  const std::string path = dir_ + "/" + name;
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
