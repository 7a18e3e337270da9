// The run of the worst-scan instruction budget (tests/budget/back_end_cost.sh runs it under
// callgrind): the simulated apartment, vacuum profile, long enough for loop closures and graph
// optimisations. Under callgrind, the counters are zeroed before every AddScan and dumped after
// each one in which the back end worked (a queued job or a loop-closure search) or the robot was
// lost (a kidnap at the end of the run, wheels lifted: each scan then takes one step of the global
// search, core/back_end/global_localiser.hpp), so each dump holds one such call; the script takes
// the largest. Prints the scans, the back end's and the relocalisation's work and the budget for
// the script to check.
#include <valgrind/callgrind.h>

#include <cstdio>

#include "core/capacity.hpp"
#include "core/mapper.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"

int main() {
  using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;
  static MapperType mapper;
  const dpcr::sim::World world = dpcr::sim::LoadBuiltinWorld("apartment");
  dpcr::sim::SimConfig config;
  config.duration_min = 12.0;
  config.seed = 1;
  // Kidnaps in the last minutes, once most of the apartment is mapped.
  config.kidnaps.count = 3;
  config.kidnaps.from_min = 9.0;
  // The lidar as dpcr-sim declares it to the mapper (its range noise: the returns' smoothing runs).
  dpcr::MapperConfig mapper_config;
  mapper_config.lidar = dpcr::sim::MapperLidarConfig(config);
  if (mapper.Init(mapper_config) != dpcr::Status::kOk) return 2;
  dpcr::sim::Simulation sim(world, config);
  dpcr::sim::SimEvent e;
  int scans = 0, dumped = 0;
  while (sim.Step(&e)) {
    if (e.type == dpcr::sim::SimEventType::kOdometry) {
      mapper.AddOdometry(e.odometry);
      continue;
    }
    const auto& b = mapper.back_end().counters();
    const auto work = [&] { return b.optimizations + b.map_match_attempts + b.loop_searches; };
    const unsigned before = work();
    const bool lost_before = mapper.status() == dpcr::MapperStatus::kLost;
    CALLGRIND_ZERO_STATS;
    (void)mapper.AddScan(e.scan);
    if (work() != before || lost_before || mapper.status() == dpcr::MapperStatus::kLost) {
      CALLGRIND_DUMP_STATS_AT("back-end scan");
      ++dumped;
    }
    ++scans;
  }
  const auto& b = mapper.back_end().counters();
  std::printf("scans %d\n", scans);
  std::printf("back_end_scans %d\n", dumped);
  std::printf("optimizations %u\n", b.optimizations);
  std::printf("loop_searches %u\n", b.loop_searches);
  std::printf("loop_closures_accepted %u\n", b.loop_closures_accepted);
  std::printf("relocalisations %u\n", mapper.counters().relocalisations);
  std::printf("budget worst_scan %llu\n", static_cast<unsigned long long>(dpcr::VacuumProfile::kBudgetWorstScanInstr));
  return 0;
}
