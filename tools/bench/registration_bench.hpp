// `dpcr-bench registration`: improved vs classic PLICP from perturbed initial poses, on simulated
// scan -> submap registrations and on intel.clf scan pairs (docs/registration.md).
#pragma once

#include <string>

#include "tools/public_logs.hpp"

namespace dpcr_bench {

struct RegistrationBenchOptions {
  std::string clf_path = dpcr::PublicLogPath("intel.clf");
  int sim_poses_per_world = 12;
  int perturbations = 12;
  int intel_pairs = 120;
  unsigned seed = 1;
  // Callgrind mode: only simulated scan -> submap registrations of `method`, `callgrind_count`
  // of them, each bracketed by collection toggles and followed by a stats dump.
  int callgrind_count = 0;
  std::string method = "improved";
  std::string figure_path;  // PNG of one hall registration (empty: none)
};

int RunRegistrationBench(const RegistrationBenchOptions& options);

}  // namespace dpcr_bench
