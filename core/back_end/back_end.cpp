#include "core/back_end/back_end.hpp"

#include <cmath>

#include "core/back_end/closure_refinement.hpp"
#include "core/back_end/region_cloud.hpp"
#include "core/base/assert.hpp"
#include "core/registration/pivot_frame.hpp"

namespace dpcr {
namespace {

// Rotates an information matrix over a pose's (x, y, theta) perturbation in the `from` frame into
// the frame of the edge error e = Z^-1 (Xi^-1 Xj) (its translation is in the measured `to` frame).
Eigen::Matrix3f IntoErrorFrame(const Eigen::Matrix3f& information, const Pose2& measurement) {
  Eigen::Matrix3f m = Eigen::Matrix3f::Identity();
  const float c = std::cos(measurement.theta), s = std::sin(measurement.theta);
  m(0, 0) = c;
  m(0, 1) = -s;
  m(1, 0) = s;
  m(1, 1) = c;
  return m.transpose() * information * m;
}

}  // namespace

void BackEnd::Init(const BackEndConfig& config, float region_width_m, const ReferenceConfig& reference) {
  config_ = &config;
  region_width_m_ = region_width_m;
  reference_ = reference;
  counters_ = BackEndCounters{};
  s_.graph->Clear();
  job_head_ = job_count_ = 0;
  search_region_ = -1;
  confirmation_.Clear();
}

void BackEnd::Push(std::int32_t job) {
  const int capacity = static_cast<int>(s_.jobs.size());
  if (job_count_ == capacity) {
    ++counters_.jobs_dropped_full;
    return;
  }
  s_.jobs[static_cast<std::size_t>((job_head_ + job_count_) % capacity)] = job;
  ++job_count_;
}

void BackEnd::AddRegion(Span<RegionalMap> regions, int index, int from) {
  PoseGraph& g = *s_.graph;
  if (!config_->enable || index != g.vertex_count()) return;
  if (g.AddVertex(regions[static_cast<std::size_t>(index)].anchor) != Status::kOk) return;
  if (from < 0) return;
  GraphEdge e;
  e.from = from;
  e.to = index;
  e.measurement = Between(regions[static_cast<std::size_t>(from)].anchor, regions[static_cast<std::size_t>(index)].anchor);
  const float it = 1.0f / (config_->sequence_sigma_m * config_->sequence_sigma_m);
  const float ir = 1.0f / (config_->sequence_sigma_rad * config_->sequence_sigma_rad);
  e.information = Eigen::Vector3f(it, it, ir).asDiagonal();
  e.kind = EdgeKind::kSequence;
  if (g.AddOrReplaceEdge(e) == Status::kOk) {
    ++counters_.sequence_edges;
  } else {
    ++counters_.edges_dropped_full;
  }
}

void BackEnd::OnRegionLeft(Span<RegionalMap> regions, int index) {
  if (!config_->enable || index < 0 || index >= s_.graph->vertex_count()) return;
  const RegionalMap& left = regions[static_cast<std::size_t>(index)];
  if (left.scans_inserted < static_cast<std::uint32_t>(config_->min_scans)) return;
  const float reach = config_->neighbour_factor * region_width_m_;
  for (int i = 0; i < s_.graph->vertex_count(); ++i) {
    const RegionalMap& other = regions[static_cast<std::size_t>(i)];
    if (i == index || other.scans_inserted < static_cast<std::uint32_t>(config_->min_scans)) continue;
    if (std::hypot(other.anchor.x - left.anchor.x, other.anchor.y - left.anchor.y) > reach) continue;
    const int older = i < index ? i : index, newer = i < index ? index : i;
    Push(older * kPairBase + newer);
  }
  Push(kOptimize);
}

BackEnd::StepResult BackEnd::Step(Span<RegionalMap> regions) {
  StepResult out;
  if (searching()) {
    // The map-to-map jobs would rebuild the reference whose table the search holds: they wait.
    // The last slice and the refinement never share a scan.
    out.used_reference = true;
    if (search_begun_this_scan_) {
      search_begun_this_scan_ = false;  // building its grid was this scan's share
    } else if (search_.done()) {
      out.loop_search_done = true;
    } else {
      (void)search_.Continue(*s_.match_grid, Span<const Point2>(s_.cloud.data(), search_points_), config_->search,
                             s_.rotated, static_cast<std::uint32_t>(config_->search_evaluations_per_step));
    }
    return out;
  }
  if (job_count_ == 0) return out;
  const std::int32_t job = s_.jobs[static_cast<std::size_t>(job_head_)];
  job_head_ = (job_head_ + 1) % static_cast<int>(s_.jobs.size());
  --job_count_;
  if (job == kOptimize) {
    Optimize(regions);
    out.anchors_moved = true;
  } else {
    (void)MatchMaps(regions, job / kPairBase, job % kPairBase);
    out.used_reference = true;
  }
  return out;
}

void BackEnd::BuildReference(const RegionalMap& map) {
  ReferenceBuildStats stats;
  (void)s_.reference->Build(*map.grid, map.grid->box(), reference_, &stats);
}

Eigen::Matrix3f BackEnd::RegistrationInformation(const Eigen::Matrix3f& hessian, const Pose2& measurement) const {
  const float scale = 1.0f / (config_->residual_sigma_m * config_->residual_sigma_m * config_->correlated_points);
  Eigen::Matrix3f info = IntoErrorFrame(hessian * scale, measurement);
  info(0, 0) += 1.0f / (config_->floor_sigma_m * config_->floor_sigma_m);
  info(1, 1) += 1.0f / (config_->floor_sigma_m * config_->floor_sigma_m);
  info(2, 2) += 1.0f / (config_->floor_sigma_rad * config_->floor_sigma_rad);
  return info;
}

bool BackEnd::MatchMaps(Span<RegionalMap> regions, int older, int newer) {
  const RegionalMap& ref = regions[static_cast<std::size_t>(older)];
  const RegionalMap& target = regions[static_cast<std::size_t>(newer)];
  ++counters_.map_match_attempts;
  const std::size_t ref_cells = CountObstacleCells(*ref.grid, reference_.obstacle_threshold);
  const std::size_t target_cells = CountObstacleCells(*target.grid, reference_.obstacle_threshold);
  const std::size_t n = CollectObstacleCloud(*target.grid, reference_.obstacle_threshold, target_cells,
                                             Span<Point2>(s_.cloud.data(), static_cast<std::size_t>(config_->max_cloud_points)));
  if (n < 20 || ref_cells < 20) return false;
  BuildReference(ref);
  // A pair measured before is registered again from its last measurement, not from the graph's
  // estimate: where the maps leave the registration free (along a corridor, between look-alike
  // doorways) it ends near where it starts, and started from a graph bent by a wrong closure it
  // would measure the bend and hold it in place.
  const int previous = s_.graph->FindEdge(EdgeKind::kMapMatch, older, newer);
  const Pose2 measured = previous >= 0 ? s_.graph->edge(previous).measurement : Between(ref.anchor, target.anchor);
  // Posed about the cloud's centroid: a map's cells reach the lidar's range from its anchor
  // (pivot_frame.hpp).
  const Point2 pivot = RecentreOnCentroid(Span<Point2>(s_.cloud.data(), n));
  const RegistrationResult r =
      FrameResult(RegisterImproved(*s_.reference, Span<const Point2>(s_.cloud.data(), n), PivotPose(measured, pivot), nullptr,
                                   config_->registration, s_.correspondences),
                  pivot);
  if (r.verdict != Status::kOk) return false;
  // Eq. 11 on the thinned cloud: matched points over the mean cloud size, both counted at the
  // thinning of the target (the reference's cells thinned alike).
  const float thinning = static_cast<float>(n) / static_cast<float>(target_cells);
  const float match_rate = 2.0f * static_cast<float>(r.inliers) /
                           (static_cast<float>(n) + thinning * static_cast<float>(ref_cells));
  if (match_rate < config_->min_match_rate) return false;
  GraphEdge e;
  e.from = older;
  e.to = newer;
  e.measurement = r.pose;
  e.information = RegistrationInformation(r.hessian, r.pose);
  e.kind = EdgeKind::kMapMatch;
  if (s_.graph->AddOrReplaceEdge(e) != Status::kOk) {
    ++counters_.edges_dropped_full;
    return false;
  }
  ++counters_.map_match_edges;
  return true;
}

void BackEnd::Optimize(Span<RegionalMap> regions) {
  const OptimizationResult r = s_.graph->Optimize(config_->optimizer);
  if (r.status != Status::kOk) return;
  ++counters_.optimizations;
  counters_.optimizer_iterations += static_cast<std::uint32_t>(r.iterations);
  counters_.downweighted_edges = static_cast<std::uint32_t>(r.downweighted_edges);
  WriteAnchors(regions);
}

void BackEnd::WriteAnchors(Span<RegionalMap> regions) const {
  for (int i = 0; i < s_.graph->vertex_count(); ++i) regions[static_cast<std::size_t>(i)].anchor = s_.graph->vertex(i);
}

bool BackEnd::BeginLoopClosure(Span<RegionalMap> regions, int region, int from, Span<const Point2> cloud,
                               const Pose2& submap_world, float path_m) {
  PoseGraph& g = *s_.graph;
  if (!config_->enable || region < 0 || from < 0 || region == from || region >= g.vertex_count() ||
      from >= g.vertex_count() || cloud.size() < 20) {
    return false;
  }
  ++counters_.loop_searches;
  const RegionalMap& map = regions[static_cast<std::size_t>(region)];
  // Where is the submap in the map? A search over the window the drift allows, on a grid in
  // memory lent by the region reference until the search is done.
  s_.match_grid->Attach(s_.reference->LendTable());
  s_.match_grid->Build(*map.grid, map.grid->box(), config_->match_grid_coarsen, reference_.obstacle_threshold);
  const std::size_t stride = (cloud.size() + static_cast<std::size_t>(config_->search_points) - 1) /
                             static_cast<std::size_t>(config_->search_points);
  std::size_t n = 0;
  for (std::size_t i = 0; i < cloud.size() && n < s_.cloud.size(); i += stride) s_.cloud[n++] = cloud[i];
  const Pose2 guess = Between(map.anchor, submap_world);
  const float window_m = std::fmin(config_->search_base_m + config_->search_per_metre_m * path_m, config_->search_max_m);
  const float window_rad = std::fmin(config_->search_base_rad + config_->search_per_metre_rad * path_m, config_->search_max_rad);
  search_.Begin(*s_.match_grid, Span<const Point2>(s_.cloud.data(), n), guess, window_m, window_rad, config_->search);
  search_region_ = region;
  search_begun_this_scan_ = true;
  search_from_ = from;
  search_submap_world_ = submap_world;
  search_points_ = n;
  trace_ = ClosureTrace{};
  trace_.region = region;
  trace_.from = from;
  trace_.path_m = path_m;
  trace_.window_m = window_m;
  trace_.guess = guess;
  return true;
}

LoopClosureResult BackEnd::FinishLoopClosure(Span<RegionalMap> regions, Span<const Point2> cloud,
                                             const Pose2& submap_world) {
  LoopClosureResult out;
  const int region = search_region_, from = search_from_;
  search_region_ = -1;
  if (region < 0 || !search_.done()) return out;
  out.used_reference = true;
  const CorrelativeSearchResult& found = search_.result();
  out.search_score = found.score;
  trace_.search = found;
  const RegionalMap& map = regions[static_cast<std::size_t>(region)];
  // The search placed the submap as it was when the search began; the submap has moved since by
  // what the front end measured: carry the answer (or, when the search is weak or ambiguous, the
  // guess, which may still be within PLICP's basin) along.
  const Pose2 moved = search_submap_world_.Inverse() * submap_world;
  const Pose2 start = (found.verdict == Status::kOk ? found.pose : trace_.guess) * moved;
  // Refined by PLICP against the map's lines; along a ridge, from the guess (closure_refinement.hpp).
  BuildReference(map);
  const ClosureRefinement refined = RefineClosure(*s_.reference, cloud, start, trace_.guess * moved,
                                                  found.verdict == Status::kOk, *config_, s_.correspondences);
  const RegistrationResult& r = refined.result;
  if (refined.guess_on_ridge) ++counters_.loop_closures_ridge_from_guess;
  trace_.refinement = r.verdict;
  trace_.inlier_ratio = r.inlier_ratio;
  trace_.mean_residual_m = r.mean_residual_m;
  // Refined from the guess (no clear peak): only a small correction is trusted, as on loop entry;
  // PLICP from a guess metres or degrees off finds the nearest look-alike as readily as the map.
  const bool verified = found.verdict == Status::kOk || WithinSearchBaseWindow(*config_, Between(start, r.pose));
  if (r.verdict != Status::kOk || !verified) {
    ++counters_.loop_closures_rejected;
    out.verdict = Status::kRejected;
    return out;
  }
  const bool near_peak = found.verdict == Status::kOk && config_->confirm_second_ratio > 0.0f &&
                         found.second_score >= config_->confirm_second_ratio * found.score;
  const bool from_far_guess = found.verdict != Status::kOk && config_->confirm_guess_window_m > 0.0f &&
                              trace_.window_m > config_->confirm_guess_window_m;
  const bool doubtful = near_peak || from_far_guess;
  if (!confirmation_.Take(region, doubtful, map.anchor * r.pose, submap_world, *config_)) {
    ++counters_.loop_closures_rejected;
    ++counters_.loop_closures_unconfirmed;
    out.verdict = Status::kRejected;
    return out;
  }
  if (!AddClosure(regions, region, from, r, submap_world, found.verdict == Status::kOk ? found.score : 0.0f)) {
    out.verdict = Status::kRejected;
    return out;
  }
  out.submap_in_region = r.pose;
  out.verdict = Status::kOk;
  return out;
}

bool BackEnd::AddClosure(Span<RegionalMap> regions, int region, int from, const RegistrationResult& r,
                         const Pose2& submap_world, float search_score) {
  PoseGraph& g = *s_.graph;
  if (!config_->enable || region < 0 || from < 0 || region == from || region >= g.vertex_count() ||
      from >= g.vertex_count()) {
    return false;
  }
  // The edge region -> from: Z = S_region * S_from^-1, with S the submap in each frame. Its
  // information is the registration's, carried from the submap's pose to Z (a rotation of the
  // submap swings the lever arm to the other anchor).
  const Pose2 in_region = r.pose;
  const Pose2 in_from = Between(regions[static_cast<std::size_t>(from)].anchor, submap_world);
  const Pose2 z = in_region * in_from.Inverse();
  const Point2 lever{z.x - in_region.x, z.y - in_region.y};
  Eigen::Matrix3f j_inv = Eigen::Matrix3f::Identity();  // d S / d Z
  j_inv(0, 2) = lever.y;
  j_inv(1, 2) = -lever.x;
  // A closure that moves the graph by more than PLICP's basin reshapes the map: it must fit as
  // closely as a first registration does (a look-alike one doorway over fitted at 6 cm).
  const Pose2 change = Between(Between(regions[static_cast<std::size_t>(region)].anchor,
                                       regions[static_cast<std::size_t>(from)].anchor), z);
  if (!WithinSearchBaseWindow(*config_, change) && r.mean_residual_m > config_->large_closure_max_residual_m) {
    ++counters_.loop_closures_rejected;
    return false;
  }
  GraphEdge e;
  e.from = region;
  e.to = from;
  e.measurement = z;
  e.information = RegistrationInformation(j_inv.transpose() * r.hessian * j_inv, z);
  e.kind = EdgeKind::kLoop;
  // ...and, unless the search found it unmistakably, the graph must follow it to within what
  // PLICP alone is trusted with (BackEndConfig::unfollowed_closure_min_score).
  const bool unmistakable = search_score >= config_->unfollowed_closure_min_score;
  const Status added = g.AddEdgeIfConsistent(e, config_->optimizer, config_->max_edge_chi2,
                                             unmistakable ? PoseGraph::kUnbounded : config_->search_base_m,
                                             unmistakable ? PoseGraph::kUnbounded : config_->search_base_rad);
  trace_.graph = added;
  if (added != Status::kOk) {
    ++counters_.loop_closures_rejected;
    if (added == Status::kRejected) ++counters_.loop_closures_inconsistent;
    if (added == Status::kPoolFull) ++counters_.edges_dropped_full;
    return false;
  }
  ++counters_.loop_closures_accepted;
  confirmation_.Clear();
  WriteAnchors(regions);
  return true;
}

}  // namespace dpcr
