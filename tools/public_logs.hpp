// Where the public CARMEN logs live (README "Public logs"): $DPCR_DATA_DIR, else ../shared/data
// beside the repository (DPCR_DEFAULT_DATA_DIR, set by CMake from the source tree). The one
// setting every bench and test reads; the logs are not in the repository (CC BY, 20 MB).
#pragma once

#include <cstdlib>
#include <string>

#ifndef DPCR_DEFAULT_DATA_DIR
#error "link dpcr_public_logs: it defines DPCR_DEFAULT_DATA_DIR"
#endif

namespace dpcr {

inline std::string PublicDataDir() {
  const char* dir = std::getenv("DPCR_DATA_DIR");
  return dir != nullptr && dir[0] != '\0' ? std::string(dir) : std::string(DPCR_DEFAULT_DATA_DIR);
}

// e.g. PublicLogPath("intel.clf"); the file may be missing: callers say so and skip.
inline std::string PublicLogPath(const std::string& name) { return PublicDataDir() + "/" + name; }

// Exit code of a bench or test run that skips for want of a log (ctest SKIP_RETURN_CODE).
constexpr int kSkippedExitCode = 77;

}  // namespace dpcr
