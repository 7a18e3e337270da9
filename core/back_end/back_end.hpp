// The DPCR back end (Cao et al. 2025, §3.5): a graph whose vertices are the regional maps'
// anchors, with three kinds of edges (pose_graph.hpp): the front end's chain when a new region is
// created, map-to-map registrations between neighbouring regions (within alpha S, MatchRate of
// Eq. 11) when the robot leaves a region, and loop closures when the robot re-enters a region it
// left long ago (a correlative search past the PLICP basin, refined by PLICP, kept only if the
// graph agrees). Gauss–Newton moves the anchors; the caller moves the robot with its region.
//
// Bounded work per scan: leaving a region queues jobs (one registration per neighbour, then one
// optimisation); Step() runs at most one per scan. A loop closure runs at once (the robot must
// not insert scans into the re-entered map at a drifted pose), and costs one search.
// Size-erased over BackEndStorage; Mapper<Profile> owns the arrays.
#pragma once

#include <cstdint>

#include "core/back_end/correlative_search.hpp"
#include "core/back_end/pose_graph.hpp"
#include "core/base/span.hpp"
#include "core/base/status.hpp"
#include "core/front_end/regional_map.hpp"
#include "core/registration/plicp.hpp"
#include "core/registration/registration_reference.hpp"

namespace dpcr {

struct BackEndConfig {
  bool enable = true;
  // Map-to-map edges (paper Eqs. 10-11): regions whose anchors are within alpha S, both holding
  // at least `min_scans` scans, registered with a MatchRate of at least `min_match_rate`.
  float neighbour_factor = 1.5f;
  int min_scans = 20;
  float min_match_rate = 0.3f;
  int max_cloud_points = 600;
  // Information of a registration edge: the PLICP Hessian of unit-weight residuals, divided by
  // the residual variance and by how many neighbouring points a wall's residuals share (cells of
  // one wall are not independent measurements), plus a floor so that every direction is weakly
  // held (a corridor edge stays weak along the corridor).
  float residual_sigma_m = 0.03f;
  float correlated_points = 20.0f;
  float floor_sigma_m = 1.0f;
  float floor_sigma_rad = 0.3f;
  // The front end's chain between a region and the one it was created from.
  float sequence_sigma_m = 0.05f;
  float sequence_sigma_rad = 0.01f;
  // Loop closures: the search window grows with the path since the robot last registered
  // against the re-entered map (front-end drift), up to a limit.
  float search_base_m = 0.3f;
  float search_per_metre_m = 0.03f;
  float search_max_m = 2.5f;
  float search_base_rad = 0.05f;
  float search_per_metre_rad = 0.002f;
  float search_max_rad = 0.35f;
  int search_points = 200;
  int match_grid_coarsen = 2;  // match cells of 2 x 2 grid cells (10 cm)
  CorrelativeSearchConfig search;
  // Map-to-map registrations and the refinement of a found closure.
  PlicpConfig registration;
  // A closure is kept only if, optimised with it, no edge's chi2 exceeds this (pose_graph.hpp).
  float max_edge_chi2 = 25.0f;
  PoseGraphConfig optimizer;
};

struct BackEndCounters {
  std::uint32_t optimizations = 0;
  std::uint32_t optimizer_iterations = 0;
  std::uint32_t sequence_edges = 0;
  std::uint32_t map_match_attempts = 0;
  std::uint32_t map_match_edges = 0;  // accepted (added or refreshed)
  std::uint32_t loop_searches = 0;
  std::uint32_t loop_closures_accepted = 0;
  std::uint32_t loop_closures_rejected = 0;  // search weak or ambiguous, PLICP refused, or the graph disagreed
  std::uint32_t loop_closures_inconsistent = 0;  // of those: refused by the graph
  std::uint32_t edges_dropped_full = 0;
  std::uint32_t jobs_dropped_full = 0;
  std::uint32_t downweighted_edges = 0;  // after the last optimisation
};

struct BackEndStorage {
  PoseGraph* graph = nullptr;
  MatchGrid* match_grid = nullptr;
  // Shared with the front end's second registration: after a back-end step that used it, the
  // caller rebuilds its reference (StepResult::used_reference).
  RegistrationReference* reference = nullptr;
  Span<Point2> cloud;       // a region's obstacle cloud, max_cloud_points
  Span<Point2> rotated;     // search scratch, search_points
  Span<Correspondence> correspondences;
  Span<std::int32_t> jobs;  // queued jobs, at least regions + 1
};

// What a loop-closure attempt decided.
struct LoopClosureResult {
  Status verdict = Status::kNotEnoughData;  // kOk: accepted and the graph optimised
  Pose2 submap_in_region;  // the submap frame in the re-entered region's frame, when accepted
  float search_score = 0.0f;
  bool used_reference = false;  // the caller rebuilds its region reference
};

class BackEnd {
 public:
  explicit BackEnd(const BackEndStorage& storage) : s_(storage) {}
  BackEnd(const BackEnd&) = delete;
  BackEnd& operator=(const BackEnd&) = delete;

  void Init(const BackEndConfig& config, float region_width_m, std::int16_t obstacle_threshold);

  // A region was created (index == its vertex); `from` is the region the robot came from (-1 for
  // the first). Adds the vertex and the chain edge.
  void AddRegion(Span<RegionalMap> regions, int index, int from);
  // The robot left region `index`: queue its map-to-map registrations and an optimisation.
  void OnRegionLeft(Span<RegionalMap> regions, int index);

  struct StepResult {
    bool anchors_moved = false;  // regions[i].anchor were rewritten
    bool used_reference = false;
  };
  // Runs at most one queued job.
  StepResult Step(Span<RegionalMap> regions);

  // Re-entering region `region` from `from` with the submap at `submap_world` (the front end's
  // estimate) after `path_m` metres since the robot last registered against that map. `cloud`:
  // the submap's obstacle cells in the submap frame. On kOk the anchors have moved (written into
  // regions) and the submap belongs at regions[region].anchor * submap_in_region.
  LoopClosureResult TryLoopClosure(Span<RegionalMap> regions, int region, int from, Span<const Point2> cloud,
                                   const Pose2& submap_world, float path_m);

  const BackEndCounters& counters() const { return counters_; }
  const PoseGraph& graph() const { return *s_.graph; }
  bool busy() const { return job_count_ > 0; }

 private:
  // Jobs: a region pair to register (encoded from * kPairBase + to), or an optimisation (-1).
  static constexpr std::int32_t kOptimize = -1;
  static constexpr std::int32_t kPairBase = 1 << 15;

  void Push(std::int32_t job);
  bool MatchMaps(Span<RegionalMap> regions, int older, int newer);
  void Optimize(Span<RegionalMap> regions);
  void WriteAnchors(Span<RegionalMap> regions) const;
  Eigen::Matrix3f RegistrationInformation(const RegistrationResult& r, const Pose2& measurement) const;
  void BuildReference(const RegionalMap& map);

  BackEndStorage s_;
  BackEndConfig config_;
  float region_width_m_ = 4.0f;
  std::int16_t obstacle_threshold_ = 3000;
  BackEndCounters counters_;
  int job_head_ = 0;
  int job_count_ = 0;
};

}  // namespace dpcr
