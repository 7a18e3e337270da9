// Improved PLICP (Cao et al. 2025, §3.2, Fig. 2b): the error of a target point is its distance to
// the *line feature* owning its nearest reference cell, not to a line through two neighbouring
// reference points (classic PLICP, Censi 2008, core/registration/classic_plicp.hpp). Both share the
// solver here: Gauss–Newton on (x, y, θ), distance gate, Censi's adaptive trimming, Huber kernel,
// optional odometry prior, and an acceptance verdict. O(points) per iteration, no heap, no throw.
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "core/geometry/pose2.hpp"
#include "core/registration/registration_reference.hpp"
#include "core/base/span.hpp"
#include "core/base/status.hpp"

namespace dpcr {

struct PlicpConfig {
  int max_iterations = 30;
  float gate_m = 0.5f;    // no correspondence beyond this residual (and the reference's table bound)
  bool trim = true;       // Censi's adaptive trimming: keep residuals below min(p95, 2 p70)
  // Accept a clean fit of part of the points (PartialOverlapFits in plicp.cpp) below
  // min_inlier_ratio (FrontEndConfig::accept_partial_overlap sets it for the first registration).
  bool accept_partial_overlap = false;
  float trim_floor_m = 0.03f;  // never trim below this: sensor noise is not an outlier
  // Trimming starts once a step is below these (before, gate and kernel only).
  float fine_phase_step_m = 0.01f;
  float fine_phase_step_rad = 0.005f;
  float huber_m = 0.03f;  // robust kernel: quadratic below, linear above
  // Target points nearer than this to the target frame's origin (the robot, for a scan) weigh
  // their distance / near_weight_range_m (0: all alike). The first registration takes
  // LidarConfig::near_weight_range_m (why there).
  float near_weight_range_m = 0.0f;
  // Fallbacks for points whose nearest reference cell owns no line: a local line from
  // the cell's 5x5 normal, else point-to-point; down-weighted, they keep corridors constrained.
  float local_line_weight = 0.5f;
  float point_weight = 0.25f;
  // Stop: step below these, or the correspondence set of one or two iterations ago again with a
  // step below 10x these.
  float min_step_m = 1e-4f;
  float min_step_rad = 1e-4f;
  // Acceptance.
  int min_correspondences = 20;
  float min_inlier_ratio = 0.5f;
  float max_mean_residual_m = 0.04f;
  // Smallest eigenvalue of the translational block of the Hessian per inlier: ~0.5 in a room,
  // ~0 in a featureless corridor (sliding direction unobservable).
  float min_translation_information = 0.03f;
  float max_correction_m = 0.6f;    // |result - (prior or initial)|: what odometry makes plausible
  float max_correction_rad = 0.4f;
};

// The odometry prediction as a soft constraint; information in units of one unit-weight point
// residual (info_xy = 20: as strong as 20 wall points with the same σ as the odometry in metres).
struct PosePrior {
  Pose2 pose;
  float info_xy = 0.0f;
  float info_theta = 0.0f;
};

struct RegistrationResult {
  Pose2 pose;                    // target frame in the reference's world frame
  // Σ w JᵀJ of the points (no prior) over (x, y, θ). Like the ratios below, taken at the last
  // linearisation point, i.e. one (stop-sized) step before `pose`.
  Eigen::Matrix3f hessian = Eigen::Matrix3f::Zero();
  float inlier_ratio = 0.0f;     // inliers / target points
  float mean_residual_m = 0.0f;  // mean |residual| of the inliers
  int iterations = 0;
  int inliers = 0;
  float translation_information = 0.0f;  // smallest eigenvalue of the xy block / inliers
  bool degenerate = false;       // translation_information below the threshold
  Status verdict = Status::kNotEnoughData;  // kOk, kRejected or kNotEnoughData
};

// A fit as close as the walls' noise allows: the mean residual within half the bound. Trusted
// beyond the usual acceptance (PartialOverlapFits in plicp.cpp; the wheel check's word that
// wheels spin on, FrontEnd::RegisterScan).
inline bool FitsCleanly(const RegistrationResult& r, const PlicpConfig& config) {
  return r.mean_residual_m <= 0.5f * config.max_mean_residual_m;
}

// One correspondence: residual = normal · w - offset (a line), or w - q (point-to-point).
struct Correspondence {
  Point2 normal;
  float offset = 0.0f;
  Point2 q;
  float weight = 1.0f;
  bool point_to_point = false;
  std::uint16_t ref = kNoCell;
};
using CorrespondenceFn = bool (*)(const RegistrationReference& ref, Point2 w, const PlicpConfig& config,
                                  Correspondence* out);

// The shared solver. `target`: points in the target frame; `initial`: target frame in the world
// frame; `prior` may be null. `scratch` (optional, at least target.size() entries): the trimmed
// iterations keep the correspondences their residual pass found for the solve pass (same pose,
// same answers) instead of looking them up twice; the result is the same with or without.
// A found correspondence has ref != kNoCell.
RegistrationResult RunPlicp(const RegistrationReference& ref, Span<const Point2> target, Pose2 initial,
                            const PosePrior* prior, const PlicpConfig& config, CorrespondenceFn find,
                            Span<Correspondence> scratch = Span<Correspondence>());

// Improved PLICP: point to the line feature of the nearest reference cell (paper §3.2.1 step 3).
RegistrationResult RegisterImproved(const RegistrationReference& ref, Span<const Point2> target, Pose2 initial,
                                    const PosePrior* prior, const PlicpConfig& config,
                                    Span<Correspondence> scratch = Span<Correspondence>());

}  // namespace dpcr
