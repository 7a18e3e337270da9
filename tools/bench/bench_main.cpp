// dpcr-bench: measurements that are not unit tests (docs/*.md hold their tables).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <fstream>
#include <string>

#include "tools/bench/mapper_bench.hpp"
#include "tools/bench/registration_bench.hpp"
#include "tools/public_logs.hpp"

namespace {

// A missing log is said and skipped (exit 77 for ctest), never read as an empty one.
bool LogMissing(const std::string& path) {
  if (std::ifstream(path)) return false;
  std::fprintf(stderr, "dpcr-bench: SKIP: %s not found (set DPCR_DATA_DIR or --clf; README \"Public logs\")\n",
               path.c_str());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dpcr benchmarks"};
  app.require_subcommand(1);
  dpcr_bench::RegistrationBenchOptions reg;
  CLI::App* r = app.add_subcommand("registration", "improved vs classic PLICP from perturbed initial poses");
  r->add_option("--clf", reg.clf_path, "CARMEN log for the scan-pair part");
  r->add_option("--sim-poses", reg.sim_poses_per_world, "scan->submap cases per simulated world");
  r->add_option("--perturbations", reg.perturbations, "perturbed starts per case");
  r->add_option("--intel-pairs", reg.intel_pairs, "scan pairs tried from the log");
  r->add_option("--seed", reg.seed, "random seed");
  r->add_option("--callgrind", reg.callgrind_count, "run N registrations of --method under callgrind toggles");
  r->add_option("--method", reg.method, "improved | classic | build (callgrind mode; build = reference builds)");
  r->add_option("--figure", reg.figure_path, "write a PNG of one registration (submap, lines, scans)");
  dpcr_bench::MapperBenchOptions map;
  CLI::App* m = app.add_subcommand("mapper", "cost of Mapper::AddScan on a CARMEN log or a simulated run (prepared beforehand)");
  m->add_option("--clf", map.clf_path, "CARMEN log (building profile)")->capture_default_str();
  m->add_option("--world", map.world, "simulate this world instead (apartment|office|hall|FILE; vacuum profile, as dpcr-sim)");
  m->add_option("--minutes", map.minutes, "simulated run length (with --world)")->capture_default_str();
  m->add_option("--seed", map.seed, "simulation seed (with --world)")->capture_default_str();
  m->add_flag("--fixed-plan", map.fixed_plan, "with --world: the world's own start pose and plan for every seed (only the noise varies)");
  m->add_option("--scans", map.scans, "the first N laser scans (0: all)");
  m->add_option("--max-range", map.max_range_m, "ignore returns farther than this (m)")->capture_default_str();
  m->add_option("--callgrind-stride", map.callgrind_stride,
                "count every k-th AddScan under callgrind toggles and dump after it (run under callgrind)");
  m->add_option("--submap-miss-range", map.submap_miss_range_m, "override FrontEndConfig::submap_miss_range_m");
  m->add_option("--region-miss-range", map.region_miss_range_m, "override FrontEndConfig::region_miss_range_m");
  m->add_option("--reference-max-distance", map.reference_max_distance_m, "override ReferenceConfig::max_distance_m");
  m->add_option("--k1", map.k1, "override K1 (submap line period)");
  m->add_option("--k2", map.k2, "override K2 (region line period)");
  m->add_option("--ks", map.ks, "override Ks (second registration period)");
  m->add_option("--n", map.n, "override N (submap scans)");
  m->add_option("--submap-threshold", map.submap_threshold, "override the submap reference's obstacle threshold (Q10)");
  m->add_option("--region-threshold", map.region_threshold, "override the regional reference's obstacle threshold (Q10)");
  m->add_option("--settle", map.settle, "override GridConfig::settle_at_clamp (0 or 1)");
  m->add_option("--hit-margin", map.hit_margin_m, "override GridConfig::hit_margin_m");
  m->add_option("--inner-margin", map.inner_margin_m, "override FrontEndConfig::reference_inner_margin_m");
  m->add_option("--mature-scans", map.mature_scans, "override FrontEndConfig::region_mature_scans");
  m->add_option("--trajectory", map.trajectory_path, "write the estimated trajectory (TUM)");
  CLI11_PARSE(app, argc, argv);
  if (r->parsed()) {
    const bool reads_log = reg.callgrind_count == 0 && reg.intel_pairs > 0;
    if (reads_log && LogMissing(reg.clf_path)) return dpcr::kSkippedExitCode;
    return dpcr_bench::RunRegistrationBench(reg);
  }
  if (m->parsed()) {
    if (map.world.empty() && LogMissing(map.clf_path)) return dpcr::kSkippedExitCode;
    return dpcr_bench::RunMapperBench(map);
  }
  return 0;
}
