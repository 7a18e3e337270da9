// `dpcr-bench mapper`: the cost of Mapper::AddScan on a CARMEN log (building profile) or on a
// simulated vacuum run (--world, vacuum profile, host_sim/sim) (docs/front-end-cost.md).
// The input is parsed or simulated into memory first; only AddScan is timed or counted.
#pragma once

#include <string>

#include "tools/public_logs.hpp"

namespace dpcr_bench {

struct MapperBenchOptions {
  std::string clf_path = dpcr::PublicLogPath("intel.clf");
  // A simulated world instead of the log (builtin name or world file), as dpcr-sim maps it.
  std::string world;
  double minutes = 5.0;
  unsigned long long seed = 1;
  bool fixed_plan = false;  // the world's start pose and canonical plan for every seed
  int scans = 0;  // the first N laser scans (0: all)
  float max_range_m = 20.0f;  // as dpcr-replay
  // Callgrind mode (> 0): every k-th scan's AddScan is bracketed by collection toggles and
  // followed by a stats dump (run under valgrind --tool=callgrind --collect-atstart=no).
  int callgrind_stride = 0;
  // Schedule / submap overrides (negative: the MapperConfig default).
  float submap_miss_range_m = -1.0f;
  float region_miss_range_m = -1.0f;
  float reference_max_distance_m = -1.0f;
  int k1 = -1, k2 = -1, ks = -1, n = -1;
  int submap_threshold = -1, region_threshold = -1;  // ReferenceConfig::obstacle_threshold (Q10)
  int settle = -1;                                    // GridConfig::settle_at_clamp (0/1)
  float hit_margin_m = -1.0f;                         // GridConfig::hit_margin_m
  float inner_margin_m = -1.0f;                       // FrontEndConfig::reference_inner_margin_m
  int mature_scans = -1;                              // FrontEndConfig::region_mature_scans
  std::string trajectory_path;  // TUM output of the run (empty: none)
};

int RunMapperBench(const MapperBenchOptions& options);

}  // namespace dpcr_bench
