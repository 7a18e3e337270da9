// The DPCR back end (Cao et al. 2025, §3.5): a graph whose vertices are the regional maps'
// anchors, with three kinds of edges (pose_graph.hpp): the front end's chain when a new region is
// created, map-to-map registrations between neighbouring regions (within alpha S, MatchRate of
// Eq. 11) when the robot leaves a region, and loop closures when the robot re-enters a region it
// left long ago (a correlative search past the PLICP basin, refined by PLICP, kept only if the
// graph agrees). Gauss–Newton moves the anchors; the caller moves the robot with its region.
//
// Bounded work per scan: leaving a region queues jobs (one registration per neighbour, then one
// optimisation); Step() runs at most one per scan. A loop-closure search runs in slices, one per
// Step from the scan after the one that built its grid (a wide window costs up to ~10^8
// instructions), before any queued job; its refinement and the graph's verdict run in the scan
// after the last slice. Meanwhile the robot maps into the map
// its pose is known in, not the re-entered one.
// Size-erased over BackEndStorage; Mapper<Profile> owns the arrays.
#pragma once

#include <cstdint>

#include "core/back_end/back_end_config.hpp"
#include "core/back_end/closure_confirmation.hpp"
#include "core/back_end/correlative_search.hpp"
#include "core/back_end/pose_graph.hpp"
#include "core/base/span.hpp"
#include "core/base/status.hpp"
#include "core/front_end/regional_map.hpp"
#include "core/registration/plicp.hpp"
#include "core/registration/registration_reference.hpp"

namespace dpcr {

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
  std::uint32_t loop_closures_unconfirmed = 0;   // of those: waiting for a search to agree (closure_confirmation.hpp)
  std::uint32_t loop_closures_ridge_from_guess = 0;  // searches refined from the guess along a ridge (closure_refinement.hpp)
  std::uint32_t edges_dropped_full = 0;
  std::uint32_t jobs_dropped_full = 0;
  std::uint32_t downweighted_edges = 0;  // after the last optimisation
};

struct BackEndStorage {
  PoseGraph* graph = nullptr;
  // Its cells are borrowed from `reference` (RegistrationReference::LendTable) for each search.
  MatchGrid* match_grid = nullptr;
  // Shared with the front end's second registration: after a back-end step that used it, the
  // caller rebuilds its reference (StepResult::used_reference).
  RegistrationReference* reference = nullptr;
  Span<Point2> cloud;       // a region's obstacle cloud, max_cloud_points
  Span<MatchCell> rotated;  // search scratch, search_points
  Span<Correspondence> correspondences;
  Span<std::int32_t> jobs;  // queued jobs, at least regions + 1
};

// The last loop-closure attempt, for diagnostics (search, refinement, graph).
struct ClosureTrace {
  int region = -1;
  int from = -1;
  float path_m = 0.0f;
  float window_m = 0.0f;
  CorrelativeSearchResult search;
  Pose2 guess;
  Status refinement = Status::kNotEnoughData;
  float inlier_ratio = 0.0f;
  float mean_residual_m = 0.0f;
  Status graph = Status::kNotEnoughData;
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
  // Its storage, which the front end's global localiser borrows while the back end is idle.
  const BackEndStorage& storage() const { return s_; }

  // `reference`: how the regional maps become registration references (the front end's, for the
  // lidar's noise: ReferenceForNoise); its obstacle threshold also picks the maps' obstacle cells.
  // `config` is kept by reference, not copied (the vacuum's RAM): it must outlive the back end,
  // as the front end's own MapperConfig does.
  void Init(const BackEndConfig& config, float region_width_m, const ReferenceConfig& reference);

  // A region was created (index == its vertex); `from` is the region the robot came from (-1 for
  // the first). Adds the vertex and the chain edge.
  void AddRegion(Span<RegionalMap> regions, int index, int from);
  // The robot left region `index`: queue its map-to-map registrations and an optimisation.
  void OnRegionLeft(Span<RegionalMap> regions, int index);

  struct StepResult {
    bool anchors_moved = false;  // regions[i].anchor were rewritten
    bool used_reference = false;
    bool loop_search_done = false;  // FinishLoopClosure is due
  };
  // Runs one slice of a loop-closure search under way, or else at most one queued job.
  StepResult Step(Span<RegionalMap> regions);

  // Re-entering region `region` from `from` with the submap at `submap_world` (the front end's
  // estimate) after `path_m` metres since the robot last registered against that map. `cloud`:
  // the submap's obstacle cells in the submap frame. Starts the search (false: none started);
  // until Step reports it done, the region reference's table is the search's (searching()).
  bool BeginLoopClosure(Span<RegionalMap> regions, int region, int from, Span<const Point2> cloud,
                        const Pose2& submap_world, float path_m);
  // After Step reported the search done: refines its answer with the submap as it is now (`cloud`,
  // at `submap_world`; the drift since the search began is the front end's, and small) and offers
  // the closure to the graph. On kOk the anchors have moved (written into regions) and the submap
  // belongs at regions[region].anchor * submap_in_region.
  LoopClosureResult FinishLoopClosure(Span<RegionalMap> regions, Span<const Point2> cloud, const Pose2& submap_world);
  // Drops a search under way (the robot left the region it searched for).
  void CancelLoopClosure() { search_region_ = -1; }
  bool searching() const { return search_region_ >= 0; }
  int search_region() const { return search_region_; }

  // A registration of the submap (at `submap_world` before it) to region `region`'s map alone,
  // made while the robot's pose was known in region `from`: the same closure edge, without the
  // search. True when the graph took it (anchors moved and written into regions).
  bool AddClosure(Span<RegionalMap> regions, int region, int from, const RegistrationResult& r, const Pose2& submap_world,
                  float search_score = 1.0f);

  const BackEndCounters& counters() const { return counters_; }
  const ClosureTrace& last_closure() const { return trace_; }
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
  // A registration Hessian (over the measurement's parameters) as an edge's information.
  Eigen::Matrix3f RegistrationInformation(const Eigen::Matrix3f& hessian, const Pose2& measurement) const;
  void BuildReference(const RegionalMap& map);

  BackEndStorage s_;
  const BackEndConfig* config_ = nullptr;  // set by Init
  float region_width_m_ = 4.0f;
  ReferenceConfig reference_;  // set by Init
  BackEndCounters counters_;
  ClosureTrace trace_;
  // The loop-closure search under way: its region, the anchor map, the submap's world pose when it
  // began, the number of thinned cloud points in s_.cloud.
  CorrelativeSearchRun search_;
  int search_region_ = -1;
  int search_from_ = -1;
  bool search_begun_this_scan_ = false;
  Pose2 search_submap_world_;
  ClosureConfirmation confirmation_;  // a doubtful closure waiting for a second search
  std::size_t search_points_ = 0;
  int job_head_ = 0;
  int job_count_ = 0;
};

}  // namespace dpcr
