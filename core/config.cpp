#include "core/config.hpp"

#include <climits>
#include <cstdint>
#include <cmath>

#include "core/grid/cell.hpp"
#include "core/grid/hit_mean.hpp"

namespace dpcr {
namespace {

// Ranges, closed unless named otherwise; false for NaN.
bool In(float v, float lo, float hi) { return v >= lo && v <= hi; }
bool AboveUpTo(float v, float lo, float hi) { return v > lo && v <= hi; }  // (lo, hi]
bool In(int v, int lo, int hi) { return v >= lo && v <= hi; }

// Plausibility bounds: far past any sensible setting, well short of overflow.
constexpr float kMaxRangeM = 200.0f;       // no 2D lidar sees farther
constexpr float kMaxMountOffsetM = 10.0f;  // the lidar sits on the robot
constexpr float kMaxDistanceM = 100.0f;
constexpr float kMaxSigma = 1000.0f;
constexpr float kMinSigma = 1e-4f;  // 1 / sigma^2 stays finite
constexpr float kMaxInformation = 1e6f;
constexpr int kMaxCount = 1000000;  // periods, scan counts, points
constexpr int kMaxIterations = 1000;

bool GridOk(const GridConfig& g) {
  return AboveUpTo(g.resolution_m, 0.005f, 1.0f) && g.resolution_m < 1.0f && g.hit_delta > 0 && g.miss_delta < 0 &&
         g.clamp_max > g.hit_delta && g.clamp_min < g.miss_delta && g.clamp_min > kUnknownCell &&
         In(g.hit_margin_m, 0.0f, 1.0f) &&
         // The count lives in the values next to a bound (TiledGrid::set_settle_rule): the bands
         // must not meet 0.
         g.unsettle_occupied_after < g.clamp_max && g.unsettle_free_after < -static_cast<int>(g.clamp_min) &&
         In(g.unsettle_miss_margin_m, 0.0f, 100.0f) &&
         // Hit-mean codes are the values above kHitMeanCodeBase: no clamp may reach them.
         (!g.hit_means || g.clamp_max < kHitMeanCodeBase);
}

bool LidarOk(const LidarConfig& l) {
  return In(l.min_range_m, 0.0f, kMaxRangeM) && AboveUpTo(l.max_range_m, l.min_range_m, kMaxRangeM) &&
         In(l.no_return_free_m, 0.0f, l.max_range_m) && In(l.mount.x, -kMaxMountOffsetM, kMaxMountOffsetM) &&
         In(l.mount.y, -kMaxMountOffsetM, kMaxMountOffsetM) && In(l.mount.theta, -2.0f * kPi, 2.0f * kPi) &&
         In(l.range_noise_m, 0.0f, 0.5f) && In(l.smoothing_max_gap_beams, 1.0f, 10.0f) && In(l.near_weight_range_m, 0.0f, 10.0f) &&
         In(l.map_max_turn_rate_rad_s, 0.0f, 100.0f);
}

bool LinesOk(const LineExtractorConfig& c) {
  return In(c.link_radius_cells, 1, 8) && AboveUpTo(c.split_tolerance_cells, 0.0f, 100.0f) &&
         In(c.min_support, 2, kMaxCount) && AboveUpTo(c.max_rms_cells, 0.0f, 100.0f) &&
         In(c.merge_angle_rad, 0.0f, kPi / 2) && In(c.merge_offset_cells, 0.0f, 100.0f) &&
         In(c.merge_gap_cells, 0.0f, 1000.0f);
}

// An obstacle threshold the grid can exceed (below `reachable`), and lines to find.
bool ReferenceOk(const ReferenceConfig& r, std::int64_t reachable) {
  return r.obstacle_threshold >= 0 && r.obstacle_threshold < reachable && AboveUpTo(r.max_distance_m, 0.0f, 10.0f) && LinesOk(r.lines);
}

bool PlicpOk(const PlicpConfig& c) {
  const bool loop = In(c.max_iterations, 1, kMaxIterations) && AboveUpTo(c.gate_m, 0.0f, 10.0f) &&
                    In(c.trim_floor_m, 0.0f, c.gate_m) && In(c.fine_phase_step_m, 0.0f, 10.0f) &&
                    In(c.fine_phase_step_rad, 0.0f, kPi) && AboveUpTo(c.huber_m, 0.0f, 10.0f) &&
                    In(c.local_line_weight, 0.0f, 1.0f) && In(c.point_weight, 0.0f, 1.0f) &&
                    In(c.min_step_m, 0.0f, 1.0f) && In(c.min_step_rad, 0.0f, 1.0f) &&
                    In(c.near_weight_range_m, 0.0f, 10.0f);
  const bool accept = In(c.min_correspondences, 3, kMaxCount) && In(c.min_inlier_ratio, 0.0f, 1.0f) &&
                      AboveUpTo(c.max_mean_residual_m, 0.0f, 10.0f) &&
                      In(c.min_translation_information, 0.0f, kMaxInformation) &&
                      AboveUpTo(c.max_correction_m, 0.0f, kMaxDistanceM) && AboveUpTo(c.max_correction_rad, 0.0f, kPi);
  return loop && accept;
}

// The first registration's coarse pose search (rotation_search.hpp). The grid's cells and the
// window's steps are counted in ints from these: a cell under the grid's 5 mm, a kernel outside
// 1..6 cells (the search caps it at 6), an angle step under 1 mrad (0 = translations only), a
// sigma under 1 mm (2 sigma^2 is 0 in float for sigma = 1e-30: the score table turns NaN) or a
// non-finite value would overflow them or loop for ever (found by fuzz/fuzz_mapper_config.cpp).
bool PoseSearchOk(const PoseSearchConfig& c) {
  return In(c.resolution_m, 0.005f, 1.0f) && In(c.sigma_m, 1e-3f, 10.0f) && In(c.kernel_radius_cells, 1, 6) &&
         In(c.angle_window_rad, 0.0f, kPi) && (c.angle_step_rad == 0.0f || In(c.angle_step_rad, 1e-3f, kPi)) &&
         In(c.xy_window_m, 0.0f, 10.0f) && In(c.max_points, 1, kMaxCount) && In(c.step_penalty, 0.0f, 1.0f) &&
         In(c.min_gain, 0.0f, 1.0f);
}

// A miss range of 0 (whole rays), or one that reaches past the hit margin.
bool MissRangeOk(float range_m, const GridConfig& g) {
  return range_m == 0.0f || AboveUpTo(range_m, g.hit_margin_m, kMaxRangeM);
}

bool FrontEndOk(const FrontEndConfig& f, const GridConfig& g) {
  // The submap holds unclamped sums of its N scans, at most one update per cell each: removal is
  // exact only while N updates of either sign stay inside int16 (submap.hpp). 64-bit products:
  // the check must not overflow on the values it refuses.
  const std::int64_t most_hits = std::int64_t{f.submap_scans} * g.hit_delta;
  const std::int64_t most_misses = -std::int64_t{f.submap_scans} * g.miss_delta;
  const bool submap = In(f.submap_scans, 1, kMaxCount) && most_hits < INT16_MAX && most_misses < INT16_MAX &&
                      MissRangeOk(f.submap_miss_range_m, g) &&
                      MissRangeOk(f.region_miss_range_m, g) && In(f.submap_refit_gate_m, 0.0f, 1.0f) &&
                      In(f.submap_refit_min_points, 1, kMaxCount);
  const bool periods = In(f.submap_line_period, 1, kMaxCount) && In(f.region_line_period, 1, kMaxCount) &&
                       In(f.second_registration_period, 1, kMaxCount) && In(f.region_mature_scans, 1, kMaxCount) &&
                       In(f.region_slow_learning_scans, 1, kMaxCount) &&
                       // Both deltas must still move a cell at the slow rate.
                       AboveUpTo(f.region_slow_learning_rate, 0.0f, 1.0f) &&
                       ScaledLearning(g, f.region_slow_learning_rate).hit_delta > 0 &&
                       ScaledLearning(g, f.region_slow_learning_rate).miss_delta < 0 &&
                       In(f.lost_after_rejections, 1, kMaxCount) && In(f.lidar_only_lost_after_second_rejections, 0, kMaxCount) &&
                       In(f.submap_restart_after_rejections, 1, kMaxCount) &&
                       In(f.min_start_hits, 0, kMaxCount) && In(f.redeskew_min_m, 0.0f, 1.0f) &&
                       In(f.sparse_scan_share, 0.0f, 1.0f) && In(f.sparse_reference_full_share, 0.0f, 1.0f) && In(f.sparse_residual_noise_factor, 0.0f, 10.0f) &&
                       In(f.redeskew_min_rad, 0.0f, kPi) && In(f.odometry_doubt_m, 0.0f, 10.0f) &&
                       In(f.odometry_doubt_rad, 0.0f, kPi) &&
                       In(f.uncertain_turn_rad, 0.0f, kPi);
  // Regions tile one cell lattice, so neighbouring regional maps are a whole number of cells apart
  // (FrontEnd::BuildRegionReference merges two of them by shifting cells).
  const float cells_per_region = f.region_width_m / g.resolution_m;
  const bool regions = AboveUpTo(f.region_width_m, 0.5f, kMaxDistanceM) &&
                       std::fabs(cells_per_region - std::round(cells_per_region)) < 1e-3f &&
                       In(f.region_hysteresis_m, 0.0f, f.region_width_m / 2) && f.region_hysteresis_m < f.region_width_m / 2 &&
                       In(f.reference_inner_margin_m, 0.0f, kMaxDistanceM);
  // The search (a turn threshold of 0 = never before PLICP) and the weak-match rebuild (a ratio of
  // 0 = off; its threshold, like the references', one the grid can reach from 0).
  const bool search = PoseSearchOk(f.search) && In(f.search_turn_rad, 0.0f, kPi) &&
                      In(f.weak_match_inlier_ratio, 0.0f, 1.0f) && f.weak_match_obstacle_threshold >= 0;
  const bool registration = search && In(f.prior_info_xy, 0.0f, kMaxInformation) && In(f.prior_info_theta, 0.0f, kMaxInformation) &&
                            In(f.max_acceleration_mps2, 0.0f, 100.0f) && In(f.weak_direction_information, 0.0f, kMaxInformation) &&
                            In(f.second_registration_max_points, 1, kMaxCount) && PlicpOk(f.first_registration) &&
                            PlicpOk(f.second_registration) &&
                            ReferenceOk(f.submap_reference, most_hits) &&
                            ReferenceOk(f.region_reference, g.clamp_max);
  // A turn that takes walls within the band out of it, short of the 45 degrees where they would
  // lie on the grid's diagonals.
  const bool turn = In(f.grid_turn_rad, 0.0f, 0.7f) && In(f.grid_turn_band_rad, 0.0f, 0.35f) &&
                    (f.grid_turn_rad == 0.0f || f.grid_turn_band_rad <= 0.5f * f.grid_turn_rad);
  const StartHeadingConfig& h = f.start_heading;
  // The skip within the window, unless the fit is off (window 0).
  const bool start = In(h.window_s, 0.0f, 600.0f) && In(h.skip_s, 0.0f, 600.0f) &&
                     (h.window_s == 0.0f || h.skip_s <= h.window_s) && In(h.min_samples, 2, 10000) &&
                     In(h.min_offset_rad, 0.0f, h.max_offset_rad) && In(h.max_offset_rad, 0.0f, 0.35f) &&
                     In(h.max_bias_rad_s, 0.0f, 1.0f);
  // The kept scans' times are int16 milliseconds (start_scans.hpp): a window of 30 s at most.
  const StartScansConfig& k = f.start_scans;
  const bool kept = AboveUpTo(k.window_s, 0.0f, 30.0f) && AboveUpTo(k.every_s, 0.0f, k.window_s) &&
                    In(k.min_scans, 3, 1000) && AboveUpTo(k.max_offset_rad, 0.0f, 0.35f) && AboveUpTo(k.max_bias_rad_s, 0.0f, 1.0f);
  return submap && periods && regions && registration && turn && start && kept;
}

bool SearchOk(const CorrelativeSearchConfig& c) {
  return AboveUpTo(c.min_angle_step_rad, 0.0f, 1.0f) && In(c.max_angle_step_rad, c.min_angle_step_rad, 1.0f) &&
         AboveUpTo(c.min_score, 0.0f, 1.0f) && AboveUpTo(c.max_second_ratio, 0.0f, 1.0f) &&
         In(c.peak_separation_m, 0.0f, kMaxDistanceM) && In(c.peak_separation_rad, 0.0f, kPi);
}

bool OptimizerOk(const PoseGraphConfig& c) {
  return In(c.max_iterations, 1, kMaxIterations) && In(c.min_step_m, 0.0f, 1.0f) && In(c.min_step_rad, 0.0f, 1.0f) &&
         AboveUpTo(c.kernel_phi, 0.0f, kMaxInformation) && In(c.damping, 0.0f, 1.0f);
}

bool BackEndOk(const BackEndConfig& b) {
  const bool matching = AboveUpTo(b.neighbour_factor, 0.0f, 10.0f) && In(b.min_scans, 1, kMaxCount) &&
                        In(b.min_match_rate, 0.0f, 1.0f) && In(b.max_cloud_points, 1, kMaxCount) &&
                        PlicpOk(b.registration) && PlicpOk(b.closure_registration);
  const bool information = In(b.residual_sigma_m, kMinSigma, kMaxSigma) && In(b.correlated_points, 1.0f, kMaxInformation) &&
                           In(b.floor_sigma_m, kMinSigma, kMaxSigma) && In(b.floor_sigma_rad, kMinSigma, kMaxSigma) &&
                           In(b.sequence_sigma_m, kMinSigma, kMaxSigma) && In(b.sequence_sigma_rad, kMinSigma, kMaxSigma) &&
                           AboveUpTo(b.max_edge_chi2, 0.0f, kMaxInformation) && OptimizerOk(b.optimizer);
  const bool loops = In(b.loop_min_path_m, 0.0f, 1e6f) && In(b.loop_retry_scans, 1, kMaxCount) &&
                     In(b.loop_retry_path_m, 0.0f, 1e6f) && In(b.search_base_m, 0.0f, kMaxDistanceM) &&
                     In(b.search_per_metre_m, 0.0f, 1.0f) && AboveUpTo(b.search_max_m, 0.0f, kMaxDistanceM) &&
                     In(b.search_base_rad, 0.0f, kPi) && In(b.search_per_metre_rad, 0.0f, 1.0f) &&
                     AboveUpTo(b.search_max_rad, 0.0f, kPi) && In(b.search_points, 1, b.max_cloud_points) &&
                     In(b.search_evaluations_per_step, 1, kMaxCount) &&
                     In(b.match_grid_coarsen, 2, 16) && SearchOk(b.search) &&
                     AboveUpTo(b.large_closure_max_residual_m, 0.0f, 1.0f) &&
                     In(b.unfollowed_closure_min_score, 0.0f, 1.0f) && In(b.closure_prior_info, 0.0f, kMaxInformation) &&
                     In(b.ridge_information, 0.0f, 1.0f) && In(b.ridge_fit_tolerance, 0.0f, 1.0f) &&
                     In(b.confirm_second_ratio, 0.0f, 1.0f) && In(b.confirm_guess_window_m, 0.0f, kMaxDistanceM);
  return matching && information && loops;
}

bool LocalisationOk(const LocalisationConfig& c, const BackEndConfig& b) {
  return In(c.angles_per_step, 1, 2000) && In(c.coarsen, 2, 16) && AboveUpTo(c.coarse_angle_step_rad, 0.0f, kPi / 4) &&
         In(c.window_margin_m, 0.0f, kMaxDistanceM) && In(c.cloud_points, 10, b.search_points) &&
         AboveUpTo(c.max_second_ratio, 0.0f, 1.0f) && In(c.min_inlier_ratio, 0.0f, 1.0f) &&
         In(c.near_window_m, 0.0f, kMaxDistanceM) && In(c.near_window_mps, 0.0f, 10.0f) &&
         In(c.clear_min_score, 0.0f, 1.0f) && In(c.clear_max_ratio, 0.0f, 1.0f) &&
         In(c.heading_window_rad, 0.0f, kPi) && In(c.heading_window_rad_s, 0.0f, 1.0f);
}

// What the profile's storage holds.
bool FitsStorage(const MapperConfig& c, const ConfigLimits& l) {
  const FrontEndConfig& f = c.front_end;
  // A region and its hysteresis inside its map's box, the anchor at the box centre.
  const float box_half_m = 0.5f * static_cast<float>(l.region_box_cells) * c.grid.resolution_m;
  const bool box = l.region_box_cells <= 0 || f.region_width_m / 2 + f.region_hysteresis_m <= box_half_m;
  return box && f.submap_scans <= l.submap_max_scans && f.second_registration_max_points <= l.second_target_points &&
         c.back_end.max_cloud_points <= l.back_end_cloud_points && c.back_end.search_points <= l.search_points;
}

}  // namespace

Status Validate(const MapperConfig& c, const ConfigLimits& limits) {
  // The grid first: the others' checks divide by its resolution and compare with its deltas.
  const bool ok = GridOk(c.grid) && LidarOk(c.lidar) && FrontEndOk(c.front_end, c.grid) && BackEndOk(c.back_end) &&
                  LocalisationOk(c.localisation, c.back_end) &&
                  MissRangeOk(c.front_end.region_miss_range_m, c.grid) && FitsStorage(c, limits);
  return ok ? Status::kOk : Status::kInvalidArgument;
}

Status Validate(const MapperConfig& c) { return Validate(c, ConfigLimits{}); }

}  // namespace dpcr
