#include "board/errno_name.hpp"

#include <cstdio>
#include <cstring>

namespace dpcr::board {

const char* DescribeErrno(int error) {
  thread_local char text[160];
  const char* name = nullptr;
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 32))
  name = ::strerrorname_np(error);
#endif
  char description[96];
  const char* d = description;
#if defined(__GLIBC__) && defined(_GNU_SOURCE)
  d = ::strerror_r(error, description, sizeof(description));  // GNU: may return a static string
#else
  if (::strerror_r(error, description, sizeof(description)) != 0) std::snprintf(description, sizeof(description), "error %d", error);
#endif
  if (name != nullptr) {
    std::snprintf(text, sizeof(text), "%s (%s)", name, d);
  } else {
    std::snprintf(text, sizeof(text), "errno %d (%s)", error, d);
  }
  return text;
}

}  // namespace dpcr::board
