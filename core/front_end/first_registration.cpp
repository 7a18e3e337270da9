#include "core/front_end/first_registration.hpp"

#include <algorithm>
#include <cmath>

namespace dpcr {

bool SparseScan(const FrontEndConfig& config, std::size_t hits, std::size_t beams) {
  return static_cast<float>(hits) < config.sparse_scan_share * static_cast<float>(beams);
}

PlicpConfig FirstRegistrationBase(const MapperConfig& config, bool sparse) {
  PlicpConfig c = config.front_end.first_registration;
  c.near_weight_range_m = config.lidar.near_weight_range_m;
  c.accept_partial_overlap = config.front_end.accept_partial_overlap;
  if (sparse) {
    c.max_mean_residual_m =
        std::max(c.max_mean_residual_m, config.front_end.sparse_residual_noise_factor * config.lidar.range_noise_m);
  }
  return c;
}

PlicpConfig FirstRegistrationPlicp(const MapperConfig& config, bool wheels, bool sparse) {
  PlicpConfig c = FirstRegistrationBase(config, sparse);
  if (wheels) c.trim_floor_m = std::min(std::max(c.trim_floor_m, 2.0f * config.lidar.range_noise_m), c.gate_m);
  return c;
}

RegistrationResult RegisterFirst(const RegistrationReference& ref, CoarseScoreGrid* grid, std::uint32_t* grid_version,
                                 std::uint32_t reference_version, Span<const Point2> points, const Pose2& previous,
                                 const Pose2& predicted, const FrontEndConfig& f, Span<Correspondence> scratch,
                                 FirstRegistrationStats* stats, float prior_xy_scale,
                                 float prior_theta_scale, const PlicpConfig* plicp) {
  const PlicpConfig& registration = plicp != nullptr ? *plicp : f.first_registration;
  const float turn = std::fabs(NormalizeAngle(predicted.theta - previous.theta));
  const bool fast_turn = grid != nullptr && f.search_turn_rad > 0.0f && turn > f.search_turn_rad;
  RegistrationResult r;
  if (!fast_turn) {
    const PosePrior prior{predicted, f.prior_info_xy * prior_xy_scale, f.prior_info_theta * prior_theta_scale};
    r = RegisterImproved(ref, points, predicted, &prior, registration, scratch);
    if (r.verdict == Status::kOk || !f.search_on_rejection || grid == nullptr) return r;
  }
  if (*grid_version != reference_version || grid->empty()) {
    grid->Build(ref, f.search);
    *grid_version = reference_version;
    ++stats->search_grid_builds;
  }
  ++stats->searches;
  const PoseSearchResult s = SearchPose(*grid, points, predicted, f.search);
  if (!s.moved && !fast_turn) return r;  // the search agrees with the prediction: nothing new to try
  // PLICP from the search's pose; the prior moves with it (the prediction was the doubtful part).
  const PosePrior prior{s.pose, f.prior_info_xy * prior_xy_scale, f.prior_info_theta * prior_theta_scale};
  const RegistrationResult again = RegisterImproved(ref, points, s.pose, &prior, registration, scratch);
  if (again.verdict == Status::kOk) {
    if (!fast_turn || s.moved) ++stats->search_recoveries;
    return again;
  }
  return fast_turn ? again : r;
}

}  // namespace dpcr
