// dpcr-eval: accuracy of a TUM trajectory against ground truth or relations; or how well a
// relations file agrees with itself.
//   dpcr-eval TRAJ.tum --ground-truth GT.tum | --relations FILE [--out metrics.json]
//   dpcr-eval --relations FILE --consistency [--out metrics.json]
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "host_sim/eval/accuracy.hpp"
#include "host_sim/eval/relations_consistency.hpp"

namespace {

// The relations' own error (dpcr-eval --relations FILE --consistency).
nlohmann::json ConsistencyFigures(const std::string& relations) {
  const auto c = dpcr::eval::CheckRelationsConsistency(dpcr::eval::ReadRelationsFile(relations));
  std::printf("relations consistency: %zu loops of three, left %.4f m / %.3f deg on average; "
              "per relation %.4f m / %.3f deg rms\n",
              c.loops, c.loop_trans_mean_m, c.loop_rot_mean_deg, c.relation_trans_rms_m, c.relation_rot_rms_deg);
  return {{"loops", c.loops}, {"loop_trans_mean_m", c.loop_trans_mean_m}, {"loop_rot_mean_deg", c.loop_rot_mean_deg},
          {"relation_trans_rms_m", c.relation_trans_rms_m}, {"relation_rot_rms_deg", c.relation_rot_rms_deg}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dpcr-eval: LocErr_ave / ATE / max error against ground truth, or the relations metric"};
  std::string trajectory, ground_truth, relations, out;
  double sample_period_s = 1.0;
  bool consistency = false;
  auto* traj = app.add_option("trajectory", trajectory, "estimated trajectory (TUM)")->check(CLI::ExistingFile);
  auto* gt = app.add_option("--ground-truth", ground_truth, "ground-truth trajectory (TUM)")->check(CLI::ExistingFile);
  auto* rel = app.add_option("--relations", relations, "relations file (t1 t2 x y z roll pitch yaw)")->check(CLI::ExistingFile);
  app.add_option("--sample-period", sample_period_s, "LocErr_ave sampling period (s)")->capture_default_str();
  app.add_flag("--consistency", consistency,
               "with --relations and no trajectory: the relations' own error, from loops of three relations");
  app.add_option("--out", out, "also write the figures as JSON to this file");
  CLI11_PARSE(app, argc, argv);
  if (consistency && (rel->count() == 0 || traj->count() > 0 || gt->count() > 0)) {
    std::fprintf(stderr, "dpcr-eval: --consistency takes --relations FILE alone\n");
    return 2;
  }
  if (!consistency && (traj->count() == 0 || (gt->count() == 0 && rel->count() == 0))) {
    std::fprintf(stderr, "dpcr-eval: give a trajectory and --ground-truth or --relations (or --relations FILE --consistency)\n");
    return 2;
  }
  try {
    nlohmann::json j;
    if (consistency) j["relations_consistency"] = ConsistencyFigures(relations);
    const auto estimate = consistency ? dpcr::eval::Trajectory() : dpcr::eval::ReadTumFile(trajectory);
    if (gt->count() > 0) {
      const auto a = dpcr::eval::EvaluateAgainstGroundTruth(estimate, dpcr::eval::ReadTumFile(ground_truth), sample_period_s);
      j["accuracy"] = {{"loc_err_ave_m", a.loc_err_ave_m}, {"ate_rmse_m", a.ate_rmse_m},
                       {"rigid_loc_err_ave_m", a.rigid_loc_err_ave_m}, {"max_err_m", a.max_err_m},
                       {"samples", a.samples}, {"unmatched", a.unmatched}};
      std::printf("LocErr_ave %.4f m  ATE RMSE %.4f m  max %.4f m  (%zu samples, %zu unmatched)\n", a.loc_err_ave_m,
                  a.ate_rmse_m, a.max_err_m, a.samples, a.unmatched);
    }
    if (rel->count() > 0 && !consistency) {
      const auto r = dpcr::eval::EvaluateRelations(estimate, dpcr::eval::ReadRelationsFile(relations));
      j["relations"] = {{"trans_mean_m", r.trans_mean_m}, {"trans_std_m", r.trans_std_m}, {"rot_mean_deg", r.rot_mean_deg},
                        {"rot_std_deg", r.rot_std_deg}, {"matched", r.matched}, {"unmatched", r.unmatched}};
      std::printf("relations: trans %.4f +- %.4f m  rot %.3f +- %.3f deg  (%zu matched, %zu unmatched)\n", r.trans_mean_m,
                  r.trans_std_m, r.rot_mean_deg, r.rot_std_deg, r.matched, r.unmatched);
    }
    if (!out.empty()) {
      std::ofstream f(out);
      f << j.dump(2) << "\n";
      if (!f) throw std::runtime_error(out + ": write failed");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dpcr-eval: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
