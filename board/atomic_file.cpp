#include "board/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace dpcr::board {
namespace {

bool Fail(const std::string& path, const char* step, std::string* error) {
  *error = path + ": " + step + ": " + std::strerror(errno);
  return false;
}

}  // namespace

bool WriteFileAtomic(const std::string& path, const void* data, std::size_t size, std::string* error) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return Fail(tmp, "open", error);
  const auto* p = static_cast<const unsigned char*>(data);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd, p + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int saved = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      errno = saved;
      return Fail(tmp, "write", error);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int saved = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    errno = saved;
    return Fail(tmp, "fsync", error);
  }
  if (::close(fd) != 0) return Fail(tmp, "close", error);
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    errno = saved;
    return Fail(path, "rename", error);
  }
  const std::size_t slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) return Fail(dir, "open directory", error);
  const bool ok = ::fsync(dfd) == 0;
  const int saved = errno;
  ::close(dfd);
  errno = saved;
  return ok ? true : Fail(dir, "fsync directory", error);
}

IoStatus AtomicFileStore::Write(const char* name, const std::uint8_t* data, std::size_t size) {
  if (WriteFileAtomic(dir_ + "/" + name, data, size, &last_error_)) return IoStatus::kOk;
  return IoStatus::kIoError;
}

}  // namespace dpcr::board
