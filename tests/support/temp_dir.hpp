// A fresh directory under the system temp dir, removed with its contents when the test ends:
// test runs leave nothing in the working tree, and parallel runs never share files.
#pragma once

#include <stdlib.h>  // mkdtemp

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace dpcr::test {

class ScopedTempDir {
 public:
  // `tag` names the test in the directory name (dpcr_<tag>_XXXXXX), for whoever finds a leftover.
  explicit ScopedTempDir(const std::string& tag) {
    std::string pattern = (std::filesystem::temp_directory_path() / ("dpcr_" + tag + "_XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed: " + pattern);
    path_ = pattern;
  }
  ~ScopedTempDir() {
    std::error_code ignored;  // nothing useful to do about a failed cleanup at the end of a test
    std::filesystem::remove_all(path_, ignored);
  }
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string str() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace dpcr::test
