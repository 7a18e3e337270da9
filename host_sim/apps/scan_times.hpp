// --scan-times FILE: the time of every Mapper::AddScan call in ms, one per line in scan order
// (for tools/bench/run: percentiles and the mean beyond metrics.json's median/p95/max).
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

#include "host_sim/output/run_report.hpp"

namespace dpcr::apps {

inline void WriteScanTimes(const std::string& path, const dpcr::output::RunRecord& run) {
  if (path.empty()) return;
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw std::runtime_error(path + ": cannot write");
  for (const double ms : run.per_scan_ms) std::fprintf(f, "%.4f\n", ms);
  if (std::fclose(f) != 0) throw std::runtime_error(path + ": write failed");
}

}  // namespace dpcr::apps
