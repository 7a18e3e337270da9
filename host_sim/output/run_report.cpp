#include "host_sim/output/run_report.hpp"

#include <cstdlib>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "core/front_end/wheel_check.hpp"
#include "host_sim/eval/anchor_errors.hpp"
#include "host_sim/output/region_files.hpp"

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

const char* EdgeKindName(int kind) {
  static const char* const kKinds[] = {"sequence", "map_match", "loop"};
  return kind >= 0 && kind < 3 ? kKinds[kind] : "?";
}

namespace {

// metrics.json "accuracy.edges": each graph edge's measurement against the truth (the relative pose
// of its maps' best anchors) and against the graph's final anchors, and per kind the means.
nlohmann::json EdgeErrorsJson(const std::vector<dpcr::eval::EdgeError>& edges) {
  nlohmann::json list = nlohmann::json::array(), by_kind = nlohmann::json::object();
  for (int k = 0; k < 3; ++k) {
    double truth_m = 0.0, truth_deg = 0.0, final_m = 0.0, final_deg = 0.0;
    int n = 0;
    for (const auto& e : edges) {
      if (e.edge.kind != k) continue;
      ++n;
      truth_m += e.truth_m, truth_deg += e.truth_deg, final_m += e.final_m, final_deg += e.final_deg;
    }
    if (n == 0) continue;
    by_kind[EdgeKindName(k)] = {{"count", n}, {"truth_mean_m", truth_m / n}, {"truth_mean_deg", truth_deg / n},
                          {"final_mean_m", final_m / n}, {"final_mean_deg", final_deg / n}};
  }
  for (const auto& e : edges) {
    const int k = e.edge.kind;
    list.push_back({{"from", e.edge.from}, {"to", e.edge.to}, {"kind", EdgeKindName(k)},
                    {"truth_m", e.truth_m}, {"truth_deg", e.truth_deg}, {"final_m", e.final_m}, {"final_deg", e.final_deg}});
  }
  return {{"by_kind", by_kind}, {"list", list}};
}

// metrics.json "accuracy": the error a perfect back end would leave (every map at the anchor that
// fits the truth best) and, per map, how far its anchor is from that one (docs/back-end.md).
void AddAnchorDecomposition(const RunRecord& run, nlohmann::json* accuracy) {
  if (run.scan_region.size() != run.estimate.size() || run.scan_in_region.size() != run.estimate.size()) return;
  std::vector<dpcr::eval::MappedScan> scans;
  for (std::size_t i = 0; i < run.estimate.size(); ++i) {
    if (run.estimate[i].stamp_us >= run.accuracy_from_us) scans.push_back({run.estimate[i], run.scan_region[i], run.scan_in_region[i]});
  }
  const auto d = dpcr::eval::DecomposeByAnchors(scans, run.final_anchors, run.ground_truth, 1.0, 10000, run.final_edges);
  (*accuracy)["best_anchors_loc_err_ave_m"] = d.best_anchors_loc_err_ave_m;
  nlohmann::json regions = nlohmann::json::array();
  for (const auto& r : d.regions) {
    regions.push_back({{"region", r.region}, {"scans", r.scans}, {"anchor_offset_m", r.anchor_offset_m},
                       {"anchor_offset_deg", r.anchor_offset_deg}, {"in_map_mean_m", r.in_map_mean_m}});
  }
  (*accuracy)["regions"] = regions;
  (*accuracy)["edges"] = EdgeErrorsJson(d.edges);
}

}  // namespace

nlohmann::json TrackingMetrics(const dpcr::MapperCounters& c, std::uint32_t first_registrations) {
  const double scans = c.scans > 0 ? static_cast<double>(c.scans) : 1.0;
  const double rejected = static_cast<double>(c.scans_rejected - c.scans_empty - c.scans_too_sparse);
  return {{"tracking_fraction", 1.0 - static_cast<double>(c.lost_scans) / scans},
          {"lost_scans", c.lost_scans},
          {"lost_seconds", static_cast<double>(c.lost_us) * 1e-6},
          {"streak_scans", c.streak_scans},
          {"streak_seconds", static_cast<double>(c.streak_us) * 1e-6},
          {"longest_streak_scans", c.longest_streak_scans},
          {"longest_streak_seconds", static_cast<double>(c.longest_streak_us) * 1e-6},
          {"first_rejected_fraction", first_registrations > 0 ? rejected / first_registrations : 0.0},
          {"scans_fused_at_prediction", c.scans_fused_at_prediction},
          {"scans_kept_out_rejected", c.scans_kept_out_rejected},
          {"submap_restarts", c.submap_restarts}};
}

std::string TrackingSummary(const nlohmann::json& m) {
  const auto& t = m["tracking"];
  char buf[320];
  std::snprintf(buf, sizeof buf,
                ", status %s, tracking %.0f %% (lost %.1f s), first registrations rejected %.0f %% "
                "(%u fused at prediction, %u kept out; longest streak %u scans, %.1f s)",
                m["status"].get<std::string>().c_str(), 100.0 * t["tracking_fraction"].get<double>(),
                t["lost_seconds"].get<double>(), 100.0 * t["first_rejected_fraction"].get<double>(),
                t["scans_fused_at_prediction"].get<unsigned>(), t["scans_kept_out_rejected"].get<unsigned>(),
                t["longest_streak_scans"].get<unsigned>(), t["longest_streak_seconds"].get<double>());
  std::string line = buf;
  const auto& c = m["counters"];
  const unsigned ignored = c.value("odometry_without_wheel_translation", 0u);
  if (ignored > 0) {
    std::snprintf(buf, sizeof buf, "; wheels' translation ignored in %u of %u odometry samples (they missed the motion the lidar saw)",
                  ignored, c["odometry_samples"].get<unsigned>());
    line += buf;
  }
  // A turn scale far from 1 (as far as the wheel check corrects it): the wheel geometry given
  // (track width) is not the robot's.
  const double scale = m.contains("wheels") ? m["wheels"].value("heading_scale", 1.0) : 1.0;
  if (std::fabs(scale - 1.0) > static_cast<double>(dpcr::WheelCheck::kScaleDeadBand)) {
    std::snprintf(buf, sizeof buf, "; the lidar turns %.2f x what the wheels say (check the track width)", scale);
    line += buf;
  }
  return line;
}

std::string TrackingWarning(const nlohmann::json& m) {
  if (m["tracking"]["tracking_fraction"].get<double>() >= 0.5) return "";
  return "warning: lost for most of the run (tracking " +
         std::to_string(static_cast<int>(100.0 * m["tracking"]["tracking_fraction"].get<double>())) +
         " %): the map and trajectory are not to be trusted";
}

namespace {

// metrics.json "relations": all pairs, and split at 10 s apart: local accuracy (front end) and
// global consistency (back end).
nlohmann::json RelationsSplitJson(const dpcr::eval::Trajectory& trajectory, const std::vector<dpcr::eval::Relation>& relations) {
  nlohmann::json j = RelationsJson(dpcr::eval::EvaluateRelations(trajectory, relations));
  std::vector<dpcr::eval::Relation> near, far;
  for (const auto& rel : relations) (std::llabs(rel.t2_us - rel.t1_us) < 10'000'000 ? near : far).push_back(rel);
  j["under_10s"] = RelationsJson(dpcr::eval::EvaluateRelations(trajectory, near));
  j["over_10s"] = RelationsJson(dpcr::eval::EvaluateRelations(trajectory, far));
  return j;
}

nlohmann::json RefinementJson(const RefinementStats& r) {
  return {{"enabled", r.enabled}, {"scans_recorded", r.recorded}, {"registered", r.registered},
          {"refused", r.refused}, {"moved_too_far", r.too_far}, {"stored_bytes", r.stored_bytes},
          {"points_not_stored", r.points_not_stored}, {"seconds", r.seconds}};
}

}  // namespace

nlohmann::json WriteRunOutputs(const std::string& dir, const FusedMap& map, const RunRecord& run,
                               nlohmann::json metrics) {
  WriteRosMap(dir, map);
  WriteMapPng(dir, map, run.estimate, run.ground_truth);
  WriteTumFile(dir + "/trajectory.tum", run.estimate);
  if (!run.ground_truth.empty()) WriteTumFile(dir + "/ground_truth.tum", run.ground_truth);
  if (run.write_regions) WriteRegionFiles(dir, run);

  metrics["per_scan_ms"] = {{"median", Percentile(run.per_scan_ms, 0.5)},
                            {"p95", Percentile(run.per_scan_ms, 0.95)},
                            {"max", Percentile(run.per_scan_ms, 1.0)}};
  metrics["wall_seconds"] = run.wall_seconds + run.refinement.seconds;  // the refinement is part of the run
  metrics["start_scans"] = StartRefinementMetrics(run.start_refinement);
  metrics["map_size_cells"] = {map.width(), map.height()};
  if (!run.ground_truth.empty()) {
    dpcr::eval::Trajectory measured;
    for (const auto& p : run.estimate) {
      if (p.stamp_us >= run.accuracy_from_us) measured.push_back(p);
    }
    const auto a = dpcr::eval::EvaluateAgainstGroundTruth(measured, run.ground_truth);
    metrics["accuracy"] = {{"loc_err_ave_m", a.loc_err_ave_m}, {"ate_rmse_m", a.ate_rmse_m},
                           {"rigid_loc_err_ave_m", a.rigid_loc_err_ave_m}, {"max_err_m", a.max_err_m},
                           {"samples", a.samples}, {"unmatched", a.unmatched}};
    if (run.accuracy_from_us != INT64_MIN && !run.estimate.empty()) {
      metrics["accuracy"]["from_s"] = static_cast<double>(run.accuracy_from_us - run.estimate.front().stamp_us) * 1e-6;
    }
    AddAnchorDecomposition(run, &metrics["accuracy"]);
  }
  if (run.relations != nullptr) {
    metrics["relations"] = RelationsSplitJson(run.estimate, *run.relations);
    if (!run.unrefined.empty()) metrics["relations_unrefined"] = RelationsSplitJson(run.unrefined, *run.relations);
  }
  metrics["trajectory_refinement"] = RefinementJson(run.refinement);
  metrics["backend"]["calls"] = run.backend_calls;
  metrics["backend"]["total_ms"] = run.backend_total_ms;
  metrics["backend"]["max_ms"] = run.backend_max_ms;
  std::ofstream out(dir + "/metrics.json");
  out << metrics.dump(2) << "\n";
  if (!out) throw std::runtime_error(dir + "/metrics.json: write failed");
  return metrics;
}

nlohmann::json StartHeadingMetrics(const dpcr::StartHeadingFit& fit) {
  using Outcome = dpcr::StartHeadingFit::Outcome;
  static constexpr const char* kNames[] = {"none", "applied", "small", "refused", "aborted", "wheels"};
  const Outcome o = fit.outcome();
  const bool fitted = o == Outcome::kApplied || o == Outcome::kSmall || o == Outcome::kRefused || o == Outcome::kWheels;
  return {{"outcome", kNames[static_cast<int>(o)]},
          {"offset_deg", fitted ? nlohmann::json(fit.offset_rad() * 180.0 / M_PI) : nlohmann::json()},
          {"gyro_bias_deg_s", fitted ? nlohmann::json(fit.bias_rad_s() * 180.0 / M_PI) : nlohmann::json()},
          {"samples", fit.samples()}};
}

nlohmann::json StartRefinementMetrics(const dpcr::StartRefinement& r) {
  const bool fitted = r.refined || r.registered > 0;
  return {{"refined", r.refined},
          {"kept", r.kept},
          {"registered", r.registered},
          {"offset_deg", fitted ? nlohmann::json(r.offset_rad * 180.0 / M_PI) : nlohmann::json()},
          {"gyro_bias_deg_s", fitted ? nlohmann::json(r.bias_rad_s * 180.0 / M_PI) : nlohmann::json()},
          {"offset_se_deg", fitted && std::isfinite(r.offset_se_rad) ? nlohmann::json(r.offset_se_rad * 180.0 / M_PI) : nlohmann::json()},
          // The start scan found in the finished first map (without wheels measuring the translation).
          {"located", r.located},
          {"moved", r.moved},
          {"shift_m", r.located ? nlohmann::json{r.shift.x, r.shift.y} : nlohmann::json()}};
}

}  // namespace dpcr::output
