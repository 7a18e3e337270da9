#include "host_sim/output/run_report.hpp"

#include <cstdlib>

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace dpcr::output {
namespace {

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t i = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

void WriteTumFile(const std::string& path, const dpcr::eval::Trajectory& t) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  dpcr::eval::WriteTum(out, t);
  if (!out) throw std::runtime_error(path + ": write failed");
}

nlohmann::json RelationsJson(const dpcr::eval::RelationsResult& r) {
  return {{"trans_mean_m", r.trans_mean_m}, {"trans_std_m", r.trans_std_m}, {"rot_mean_deg", r.rot_mean_deg},
          {"rot_std_deg", r.rot_std_deg},   {"matched", r.matched},         {"unmatched", r.unmatched}};
}

}  // namespace

nlohmann::json WriteRunOutputs(const std::string& dir, const FusedMap& map, const RunRecord& run,
                               nlohmann::json metrics) {
  WriteRosMap(dir, map);
  WriteMapPng(dir, map, run.estimate, run.ground_truth);
  WriteTumFile(dir + "/trajectory.tum", run.estimate);
  if (!run.ground_truth.empty()) WriteTumFile(dir + "/ground_truth.tum", run.ground_truth);

  metrics["per_scan_ms"] = {{"median", Percentile(run.per_scan_ms, 0.5)},
                            {"p95", Percentile(run.per_scan_ms, 0.95)},
                            {"max", Percentile(run.per_scan_ms, 1.0)}};
  metrics["wall_seconds"] = run.wall_seconds;
  metrics["map_size_cells"] = {map.width(), map.height()};
  if (!run.ground_truth.empty()) {
    const auto a = dpcr::eval::EvaluateAgainstGroundTruth(run.estimate, run.ground_truth);
    metrics["accuracy"] = {{"loc_err_ave_m", a.loc_err_ave_m}, {"ate_rmse_m", a.ate_rmse_m},
                           {"max_err_m", a.max_err_m}, {"samples", a.samples}, {"unmatched", a.unmatched}};
  }
  if (run.relations != nullptr) {
    const auto r = dpcr::eval::EvaluateRelations(run.estimate, *run.relations);
    metrics["relations"] = RelationsJson(r);
    // Split at 10 s apart: local accuracy (front end) and global consistency (back end).
    std::vector<dpcr::eval::Relation> near, far;
    for (const auto& rel : *run.relations) (std::llabs(rel.t2_us - rel.t1_us) < 10'000'000 ? near : far).push_back(rel);
    metrics["relations"]["under_10s"] = RelationsJson(dpcr::eval::EvaluateRelations(run.estimate, near));
    metrics["relations"]["over_10s"] = RelationsJson(dpcr::eval::EvaluateRelations(run.estimate, far));
  }
  metrics["backend"]["calls"] = run.backend_calls;
  metrics["backend"]["total_ms"] = run.backend_total_ms;
  metrics["backend"]["max_ms"] = run.backend_max_ms;
  std::ofstream out(dir + "/metrics.json");
  out << metrics.dump(2) << "\n";
  if (!out) throw std::runtime_error(dir + "/metrics.json: write failed");
  return metrics;
}

}  // namespace dpcr::output
