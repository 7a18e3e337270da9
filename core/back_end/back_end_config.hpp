// The back end's parameters (core/back_end/back_end.hpp), part of MapperConfig.
#pragma once

#include <cmath>

#include "core/back_end/correlative_search.hpp"
#include "core/back_end/pose_graph.hpp"
#include "core/registration/plicp.hpp"

namespace dpcr {

// PLICP for maps and closures: two maps overlap only in part, so the inlier ratio may be low;
// MatchRate (Eq. 11) and the residual decide.
constexpr PlicpConfig MapRegistrationConfig() {
  PlicpConfig c;
  c.min_inlier_ratio = 0.25f;
  return c;
}

// PLICP refining a closure: the submap reaches past the re-entered map's box and sees what that
// map never saw, so some of its points find no wall in it; but at least half must: a refinement
// that fits a third of the submap (a weak or ambiguous search, refined from the guess) fitted
// whatever wall was near, and the graph took such closures because they agreed with the drift.
constexpr PlicpConfig ClosureRegistrationConfig() {
  PlicpConfig c;
  c.min_inlier_ratio = 0.5f;
  c.max_mean_residual_m = 0.06f;
  return c;
}

struct BackEndConfig {
  bool enable = true;
  // Map-to-map edges (paper Eqs. 10-11): regions whose anchors are within alpha S, both holding
  // at least `min_scans` scans, registered with a MatchRate of at least `min_match_rate`.
  float neighbour_factor = 1.5f;
  int min_scans = 20;
  float min_match_rate = 0.3f;
  int max_cloud_points = 400;
  // Information of a registration edge: the PLICP Hessian of unit-weight residuals, divided by
  // the residual variance and by how many neighbouring points a wall's residuals share (cells of
  // one wall are not independent measurements), plus a floor so that every direction is weakly
  // held (a corridor edge stays weak along the corridor).
  float residual_sigma_m = 0.03f;
  float correlated_points = 400.0f;
  float floor_sigma_m = 1.0f;
  float floor_sigma_rad = 0.3f;
  // The front end's chain between a region and the one it was created from.
  float sequence_sigma_m = 0.05f;
  float sequence_sigma_rad = 0.01f;
  // Loop closures: tried on entering a map the robot left at least this path ago (shorter
  // detours: the second registration as usual), and every `loop_retry_scans` scans after a
  // failure while the robot stays in that map, once it has moved `loop_retry_path_m` since the last try.
  float loop_min_path_m = 8.0f;
  int loop_retry_scans = 10;
  float loop_retry_path_m = 1.0f;
  // The search window grows with the path since the robot last registered
  // against the re-entered map (front-end drift), up to a limit.
  float search_base_m = 0.3f;
  float search_per_metre_m = 0.04f;
  float search_max_m = 4.0f;
  float search_base_rad = 0.05f;
  float search_per_metre_rad = 0.002f;
  float search_max_rad = 0.35f;
  int search_points = 200;
  // Poses and bounds a search slice evaluates (each ~200 likelihood look-ups, ~2-3 k instructions);
  // a slice sweeps blocks of offsets, one at least, and starts another only if its worst case fits.
  int search_evaluations_per_step = 3000;
  int match_grid_coarsen = 2;  // match cells of 2 x 2 grid cells (10 cm)
  CorrelativeSearchConfig search;
  // Map-to-map registrations; the refinement of a closure (the submap lies inside the map it
  // re-enters, so the usual inlier ratio holds).
  PlicpConfig registration = MapRegistrationConfig();
  PlicpConfig closure_registration = ClosureRegistrationConfig();
  // The closure's refinement keeps a prior at the search's pose of this strength (PosePrior units,
  // xy and θ; 0 = none). In a corridor the map cannot fix the pose along it: without the prior the
  // refinement was rejected as degenerate, or slid a door's spacing along it past its correction
  // bound, and the corridor's block of the map stayed off (intel.clf at a 19.3 m range limit:
  // 0.46 m). The edge's information is the points' Hessian alone, so that direction stays weak in
  // the graph. Intel over ten range limits: mean 0.146 -> 0.071 m (docs/back-end.md).
  float closure_prior_info = 10.0f;
  // A search's answer along a ridge (closure_refinement.hpp): a direction where the refined fit
  // has less information per inlier than this (the xy block of the points' Hessian, whose
  // eigenvalues per inlier run from 0, nothing fixes it, to 1, every normal along it) is refined
  // again from the front end's guess along it, and that fit is taken if it is as good as the
  // search's, to within ridge_fit_tolerance of its mean residual and of its inliers. Intel's
  // closure that had slid 0.19 m along a corridor: 0.007 per inlier. 0: never.
  float ridge_information = 0.1f;
  float ridge_fit_tolerance = 0.05f;
  // The mean residual a closure may have when it moves the graph by more than the search's base
  // window (search_base_m, search_base_rad): a first registration's bound. (Apartment seed 16 with
  // calibrated odometry: a look-alike one doorway over, 0.98 m from the graph, fitted at 5.9 cm
  // and split the graph in two; the closures the logs need fit at 1.6-3.4 cm when they move it.)
  float large_closure_max_residual_m = 0.04f;
  // A closure the graph does not follow (optimised with it, its own error stays beyond the search's
  // base window: an edge weak along one direction moves nothing) is kept only when its search
  // found it unmistakably, at least this mean likelihood. The robot is placed by the closure's
  // measurement and the map by the graph: with a look-alike, the robot would jump where the map
  // does not. (Apartment seed 4 with doors: a bathroom look-alike 1.2 m along the cleaning lane
  // scored 0.58 against the true pose's 0.45, and the robot ran a metre off for 76 s; the closures
  // intel needs that the graph does not follow at once score 0.89-0.97.)
  float unfollowed_closure_min_score = 0.75f;
  // A search whose best pose passes but whose separate second peak scores at least this share of
  // it (below search.max_second_ratio, which refuses outright) is not taken at once: the closure
  // waits for the next search of that map to agree with it (closure_confirmation.hpp), as does a
  // search of that map that contradicts the one waiting. On intel.clf the closure that decides a
  // replay, the first lap back into the start corridor, has a second peak 0.9-2.5 m along the
  // corridor scoring 0.94-0.95 of the best; the draws that took the wrong peak ended 4-11 cm off
  // over all pairs. 0: off.
  float confirm_second_ratio = 0.85f;
  // A closure refined by PLICP from the front end's guess (the search found no clear peak) waits
  // alike when that search's window was wider than this: the guess may then be metres off, and
  // PLICP from it settles on whatever wall is near. (Intel with its odometry calibrated, range
  // 18.5-23 m: such a closure of the start corridor 1.2-1.5 m off held the graph, and the clear
  // closures of the next maps were refused; 7 of 64 draws over 5 cm, 2 with this.) The window grows
  // with the path since the map was last seen (search_base_m + search_per_metre_m x path): 2 m is
  // 42 m of path. 0: never.
  float confirm_guess_window_m = 2.0f;
  // A closure is kept only if, optimised with it, no edge's chi2 exceeds this (pose_graph.hpp).
  float max_edge_chi2 = 100.0f;
  PoseGraphConfig optimizer;
};

// A correction no larger than the loop-closure search's base window (search_base_m,
// search_base_rad): what PLICP alone may be trusted with; a larger one a search must verify.
inline bool WithinSearchBaseWindow(const BackEndConfig& b, const Pose2& correction) {
  return std::hypot(correction.x, correction.y) <= b.search_base_m && std::fabs(correction.theta) <= b.search_base_rad;
}

}  // namespace dpcr
