// dpcr-bench: measurements that are not unit tests (docs/*.md hold their tables).
#include <CLI/CLI.hpp>

#include "tools/bench/registration_bench.hpp"

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
  CLI11_PARSE(app, argc, argv);
  if (r->parsed()) return dpcr_bench::RunRegistrationBench(reg);
  return 0;
}
