// Everything a run writes to its output directory: map.pgm, map.yaml, map.png,
// trajectory.tum, ground_truth.tum (when known) and metrics.json.
#pragma once

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <cstdint>
#include <utility>
#include <vector>

#include "host_sim/output/map_files.hpp"
#include "host_sim/output/trajectory_refinement.hpp"
#include "host_sim/eval/accuracy.hpp"
#include "host_sim/eval/anchor_errors.hpp"
#include "host_sim/eval/trajectory.hpp"
#include "core/front_end/start_heading.hpp"
#include "core/front_end/start_scans.hpp"
#include "core/mapper_types.hpp"

namespace dpcr::output {

struct RunRecord {
  dpcr::eval::Trajectory estimate;
  dpcr::eval::Trajectory ground_truth;      // empty when unknown
  std::vector<double> per_scan_ms;          // time inside Mapper::AddScan, one per scan
  const std::vector<dpcr::eval::Relation>* relations = nullptr;  // with --relations
  double wall_seconds = 0.0;                // the whole run, parsing included
  // Per scan: the regional map it went into (-1: none) and the robot's pose in that map's frame,
  // so that the trajectory follows the back end's later corrections (FinalizeTrajectory).
  std::vector<int> scan_region;
  std::vector<dpcr::Pose2> scan_in_region;
  std::vector<dpcr::Pose2> final_anchors;  // each map's anchor at the end (FinalizeTrajectory)
  std::vector<dpcr::eval::AnchorEdge> final_edges;  // the region graph's edges at the end
  // AddScan calls in which the back end worked (a queued job or a loop-closure search), and the
  // time they took (front end included: the core has no clock of its own).
  int backend_calls = 0;
  double backend_total_ms = 0.0;
  double backend_max_ms = 0.0;
  // metrics.json "accuracy" from this stamp on (start-aligned there): a session started at an
  // unknown pose in a loaded map has no pose worth measuring before its first fix.
  std::int64_t accuracy_from_us = INT64_MIN;
  bool write_regions = false;  // also regions.tsv and graph.tsv (region_files.hpp)
  dpcr::StartRefinement start_refinement;  // the start placed in the finished first map (FinalizeTrajectory)
  // The trajectory registered again in the finished maps (trajectory_refinement.hpp): on unless
  // refine_trajectory is false; the scans' returns are recorded while the run goes.
  bool refine_trajectory = true;
  ScanPointRecord scan_points;
  RefinementStats refinement;
  // With relations: their error on the trajectory before that refinement (metrics.json
  // "relations_unrefined"), each scan at its map's final anchor times its pose in the map then.
  dpcr::eval::Trajectory unrefined;
};

// An edge's kind as metrics.json and graph.tsv name it (AnchorEdge::kind, dpcr::EdgeKind order).
const char* EdgeKindName(int kind);

// The back end's work counted so far (jobs and searches): a change across a call means it worked.
template <class MapperType>
std::uint64_t BackEndWork(const MapperType& mapper) {
  const auto& b = mapper.back_end().counters();
  return std::uint64_t{b.optimizations} + b.map_match_attempts + b.loop_searches;
}

// Feeds one scan to the mapper, timing only the core's work, and records the pose it gives.
template <class MapperType>
void AddTimedScan(MapperType& mapper, const typename MapperType::ScanType& scan, RunRecord* run) {
  const std::uint64_t work = BackEndWork(mapper);
  const bool searching = mapper.back_end().searching();
  if (run->refine_trajectory && run->scan_points.scans() == 0) run->scan_points.Attach(mapper);
  const auto t0 = std::chrono::steady_clock::now();
  (void)mapper.AddScan(scan);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  run->per_scan_ms.push_back(ms);
  run->estimate.push_back({scan.stamp_us, mapper.pose()});
  run->scan_region.push_back(mapper.last_scan_region());
  run->scan_in_region.push_back(mapper.last_scan_in_region());
  if (run->refine_trajectory) run->scan_points.AfterScan(mapper);
  if (std::getenv("DPCR_TRACE_CLOSURES") != nullptr && searching && !mapper.back_end().searching()) {
    const auto& t = mapper.back_end().last_closure();
    std::fprintf(stderr, "closure t=%.1f r%d<-r%d path %.1f win %.2f score %.2f/%.2f d(%.2f %.2f %.3f) plicp %s inl %.2f res %.3f graph %s\n",
                 static_cast<double>(scan.stamp_us) * 1e-6, t.region, t.from, static_cast<double>(t.path_m),
                 static_cast<double>(t.window_m), static_cast<double>(t.search.score), static_cast<double>(t.search.second_score),
                 static_cast<double>(t.search.pose.x - t.guess.x), static_cast<double>(t.search.pose.y - t.guess.y),
                 static_cast<double>(t.search.pose.theta - t.guess.theta), dpcr::ToString(t.refinement),
                 static_cast<double>(t.inlier_ratio), static_cast<double>(t.mean_residual_m), dpcr::ToString(t.graph));
  }
  if (BackEndWork(mapper) != work) {
    ++run->backend_calls;
    run->backend_total_ms += ms;
    run->backend_max_ms = ms > run->backend_max_ms ? ms : run->backend_max_ms;
  }
}

// Each scan's final pose (see FinalizeTrajectory) from its recorded map and pose in it.
template <class MapperType>
dpcr::eval::Trajectory FinalPoses(const MapperType& mapper, const RunRecord& run, dpcr::eval::Trajectory online) {
  for (std::size_t i = 0; i < online.size() && i < run.scan_region.size(); ++i) {
    auto& e = online[i];
    e.pose = mapper.ScanWorldPose(e.stamp_us, run.scan_region[i], run.scan_in_region[i], e.pose);
  }
  return online;
}

// At the end of a run: each scan's pose becomes its map's final anchor times its pose in the map
// (the globally consistent trajectory, as the maps are), that pose registered again in the finished
// map unless run->refine_trajectory is off (trajectory_refinement.hpp); scans in no map keep their online pose;
// the start and the scans before it follow the start placed in the finished first map
// (Mapper::RefineStart, done here first) or else the refined start heading (Mapper::ScanWorldPose).
template <class MapperType>
void FinalizeTrajectory(MapperType& mapper, RunRecord* run) {
  run->start_refinement = mapper.RefineStart();
  run->final_anchors.clear();
  for (int r = 0; r < mapper.region_count(); ++r) run->final_anchors.push_back(mapper.region_anchor(r));
  run->final_edges.clear();
  const auto& graph = mapper.back_end().graph();
  for (int i = 0; i < graph.edge_count(); ++i) {
    const auto& e = graph.edge(i);
    run->final_edges.push_back({e.from, e.to, static_cast<int>(e.kind), e.measurement});
  }
  if (run->refine_trajectory) {
    if (run->relations != nullptr) run->unrefined = FinalPoses(mapper, *run, run->estimate);
    run->refinement = RefineTrajectory(mapper, run->scan_points, run->scan_region, &run->scan_in_region);
    run->scan_points.Clear();
    mapper.RecordScanPoints(dpcr::Span<dpcr::Point2>());  // the buffer goes with the run record
  }
  run->estimate = FinalPoses(mapper, *run, std::move(run->estimate));
}

// Writes the files (regions.tsv and graph.tsv too when run.write_regions); returns metrics.json's
// content. Throws std::runtime_error on I/O errors.
nlohmann::json WriteRunOutputs(const std::string& dir, const FusedMap& map, const RunRecord& run,
                               nlohmann::json mapper_metrics);

// The start heading's fit (metrics.json "start_heading"): its outcome (none, applied, small,
// refused, aborted, wheels), the offset and the heading sensor's bias fitted, the scans it took.
nlohmann::json StartHeadingMetrics(const dpcr::StartHeadingFit& fit);

// The start placed in the finished first map at the end of the run (metrics.json "start_scans"):
// whether it was, the start scans kept and registered again, the offset and the gyro's bias fitted.
nlohmann::json StartRefinementMetrics(const dpcr::StartRefinement& refinement);

// How much of the run the mapper knew where it was (metrics.json "tracking"): scans and seconds
// lost (status kLost after the scan) and in rejection streaks, the longest streak, the share of
// first registrations rejected; tracking_fraction = 1 - lost scans / scans.
nlohmann::json TrackingMetrics(const dpcr::MapperCounters& c, std::uint32_t first_registrations);

// One clause for a summary line: the final status, the tracking fraction, rejection figures; and
// a warning sentence when the run was lost most of the time (empty otherwise).
std::string TrackingSummary(const nlohmann::json& metrics);
std::string TrackingWarning(const nlohmann::json& metrics);

// The metrics a Mapper reports about itself.
template <class MapperType>
nlohmann::json MapperMetrics(const MapperType& mapper) {
  const auto& c = mapper.counters();
  nlohmann::json j;
  j["mapper"] = mapper.pipeline();
  j["profile"] = MapperType::ProfileType::kName;
  j["status"] = dpcr::ToString(mapper.status());
  j["scans"] = c.scans;
  j["scans_rejected"] = c.scans_rejected;
  j["regions"] = mapper.region_count();
  j["static_ram_bytes"] = sizeof(MapperType);
  j["map_storage_bytes"] = mapper.map_storage_bytes();
  j["map_file_bytes"] = mapper.map_file_bytes();  // the saved map (core/persistence)
  j["tiles_used"] = mapper.tiles_used();
  const auto& b = mapper.back_end().counters();
  j["backend"] = {{"runs", b.optimizations},
                  {"optimizer_iterations", b.optimizer_iterations},
                  {"vertices", mapper.back_end().graph().vertex_count()},
                  {"edges", mapper.back_end().graph().edge_count()},
                  {"sequence_edges", b.sequence_edges},
                  {"map_match_attempts", b.map_match_attempts},
                  {"map_match_edges", b.map_match_edges},
                  {"loop_searches", b.loop_searches},
                  {"loop_closures_accepted", b.loop_closures_accepted},
                  {"loop_closures_rejected", b.loop_closures_rejected},
                  {"loop_closures_inconsistent", b.loop_closures_inconsistent},
                  {"loop_closures_unconfirmed", b.loop_closures_unconfirmed},
                  {"loop_closures_ridge_from_guess", b.loop_closures_ridge_from_guess},
                  {"downweighted_edges", b.downweighted_edges},
                  {"edges_dropped_full", b.edges_dropped_full},
                  {"jobs_dropped_full", b.jobs_dropped_full}};
  j["counters"] = {{"scans_without_odometry", c.scans_without_odometry},
                   {"odometry_samples", c.odometry_samples},
                   {"odometry_steps_back", c.odometry_steps_back},
                   {"odometry_rejected", c.odometry_rejected},
                   {"odometry_without_wheel_translation", c.odometry_without_wheel_translation},
                   {"beams_invalid", c.beams_invalid},
                   {"regions_created", c.regions_created},
                   {"region_pool_full", c.region_pool_full},
                   {"updates_out_of_box", c.updates_out_of_box},
                   {"updates_dropped_pool_full", c.updates_dropped_pool_full},
                   {"scans_not_inserted", c.scans_not_inserted},
                   {"scans_into_anchor_map", c.scans_into_anchor_map},
                   {"scans_turning_not_mapped", c.scans_turning_not_mapped},
                   {"scans_empty", c.scans_empty},
                   {"scans_too_sparse", c.scans_too_sparse},
                   {"scans_bad_stamp", c.scans_bad_stamp},
                   {"scan_stamp_jumps", c.scan_stamp_jumps},
                   {"beams_isolated", c.beams_isolated},
                   {"scans_fused_at_prediction", c.scans_fused_at_prediction},
                   {"scans_kept_out_rejected", c.scans_kept_out_rejected},
                   {"scans_kept_out_bent", c.scans_kept_out_bent},
                   {"submap_restarts", c.submap_restarts}};
  j["relocalisation"] = {{"lost_events", c.lost_events}, {"relocalisations", c.relocalisations},
                         {"failed_rounds", c.relocalisation_failures}, {"lifted_scans", c.lifted_scans},
                         {"localise_only", mapper.config().localisation.localise_only},
                         {"unknown_start", mapper.config().localisation.unknown_start}};
  const auto& w = mapper.wheel_check();
  j["wheels"] = {{"translation_ignored_at_end", w.translation_ignored()},
                 {"heading_agrees", w.heading_used()},
                 {"translation_windows_missed", w.translation_misses()},
                 {"translation_switched_off", w.translation_switched_off()},
                 {"heading_scale", w.heading_scale()},
                 // OdometryCalibration: the factors fitted by the end (1 until enough was seen); the
                 // prediction applies them when `calibrated`.
                 {"calibrated", mapper.config().front_end.calibrate_odometry},
                 {"translation_scale", mapper.odometry_calibration().translation_scale()},
                 {"turn_scale", mapper.odometry_calibration().turn_scale()}};
  j["tracking"] = TrackingMetrics(c, mapper.front_end_counters().first_registrations);
  j["tracking_fraction"] = j["tracking"]["tracking_fraction"];
  const auto& f = mapper.front_end_counters();
  j["front_end"] = {{"first_registrations", f.first_registrations}, {"first_rejected", f.first_rejected},
                    {"second_registrations", f.second_registrations}, {"second_rejected", f.second_rejected},
                    {"submap_line_builds", f.submap_line_builds}, {"region_line_builds", f.region_line_builds},
                    {"reference_cells_dropped", f.reference_cells_dropped}, {"submap_early_builds", f.submap_early_builds},
                    {"submap_sparse_builds", f.submap_sparse_builds}, {"return_share", f.return_share},
                    {"weak_direction_holds", f.weak_direction_holds},
                    {"redeskews", f.redeskews}, {"odometry_doubted", f.odometry_doubted}, {"odometry_overruled", f.odometry_overruled}, {"odometry_stalls", f.odometry_stalls}, {"bent_tracked", f.bent_tracked}, {"lag_reregistered", f.lag_reregistered}, {"lag_bent_taken", f.lag_bent_taken}, {"searches", f.search.searches},
                    {"first_wall_direction_deg", std::isfinite(f.first_wall_direction_rad) ? nlohmann::json(f.first_wall_direction_rad * 180.0 / M_PI) : nlohmann::json()},
                    {"grid_turn_deg", f.grid_turn_rad * 180.0 / M_PI},
                    {"search_recoveries", f.search.search_recoveries}, {"search_grid_builds", f.search.search_grid_builds}};
  j["start_heading"] = StartHeadingMetrics(mapper.start_heading());
  return j;
}

}  // namespace dpcr::output
