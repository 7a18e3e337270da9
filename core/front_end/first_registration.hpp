// The first registration (scan -> submap) with its recovery: improved PLICP from the prediction,
// and when that is rejected or the prediction is doubtful (a fast turn), a coarse pose search
// (core/registration/rotation_search.hpp) on the submap reference, then PLICP again from the
// search's best pose. The search runs only then: on intel 1-2 % of scans.
#pragma once

#include <cstdint>

#include "core/base/span.hpp"
#include "core/config.hpp"
#include "core/geometry/pose2.hpp"
#include "core/registration/plicp.hpp"
#include "core/registration/registration_reference.hpp"
#include "core/registration/rotation_search.hpp"

namespace dpcr {

struct FirstRegistrationStats {
  std::uint32_t searches = 0;         // coarse searches run
  std::uint32_t search_recoveries = 0;  // registrations accepted thanks to a search
  std::uint32_t search_grid_builds = 0;
};

// Whether a scan with `hits` returns of `beams` readings is sparse (FrontEndConfig::sparse_scan_share).
bool SparseScan(const FrontEndConfig& config, std::size_t hits, std::size_t beams);

// config.front_end.first_registration with the lidar's weighting of near returns
// (LidarConfig::near_weight_range_m), and for a sparse scan (SparseScan) the mean residual bound
// raised to FrontEndConfig::sparse_residual_noise_factor x LidarConfig::range_noise_m: what every
// first registration of a scan starts from.
PlicpConfig FirstRegistrationBase(const MapperConfig& config, bool sparse);

// The first registration's PLICP settings (FirstRegistrationBase) for a scan whose
// motion the wheels measured or not: with them the scan is de-skewed by measurement, and
// residuals of the lidar's own noise are not outliers: the trim floor is raised to twice
// LidarConfig::range_noise_m (up to the gate). Without them a residual also holds the de-skew's
// guess, which the adaptive trim must cut (the lidar alone, XV-11: 0.073 -> 0.088 m with the floor).
PlicpConfig FirstRegistrationPlicp(const MapperConfig& config, bool wheels, bool sparse);

// `grid_version` / `reference_version`: the score grid is rebuilt from `ref` only when a search
// needs it and the reference changed since (versions differ). `prior_xy_scale` and
// `prior_theta_scale` scale the prediction's priors (FrontEndConfig::prior_info_xy, _theta):
// weaker for a guessed motion. `plicp`: PLICP's settings when not config.first_registration.
RegistrationResult RegisterFirst(const RegistrationReference& ref, CoarseScoreGrid* grid, std::uint32_t* grid_version,
                                 std::uint32_t reference_version, Span<const Point2> points, const Pose2& previous,
                                 const Pose2& predicted, const FrontEndConfig& config, Span<Correspondence> scratch,
                                 FirstRegistrationStats* stats, float prior_xy_scale = 1.0f,
                                 float prior_theta_scale = 1.0f, const PlicpConfig* plicp = nullptr);

}  // namespace dpcr
