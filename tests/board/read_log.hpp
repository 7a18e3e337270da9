// The firmware tests' log: everything written so far to a temporary FILE (tmpfile()), as one string.
#pragma once

#include <cstdio>
#include <string>

namespace dpcr::test {

inline std::string ReadLog(std::FILE* log) {
  std::fflush(log);
  std::rewind(log);
  std::string s;
  char buf[512];
  while (std::fgets(buf, sizeof(buf), log) != nullptr) s += buf;
  return s;
}

}  // namespace dpcr::test
