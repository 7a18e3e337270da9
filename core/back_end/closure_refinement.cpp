#include "core/back_end/closure_refinement.hpp"

#include <cmath>

#include "core/registration/weak_direction_hold.hpp"

namespace dpcr {

namespace {

RegistrationResult RefineFrom(const RegistrationReference& reference, Span<const Point2> cloud, const Pose2& start,
                              const BackEndConfig& config, Span<Correspondence> correspondences) {
  const PosePrior prior{start, config.closure_prior_info, config.closure_prior_info};
  return RegisterImproved(reference, cloud, start, config.closure_prior_info > 0.0f ? &prior : nullptr,
                          config.closure_registration, correspondences);
}

// `b` fits as well as `a`, to within `tolerance` of its mean residual and of its inliers.
bool FitsAsWell(const RegistrationResult& b, const RegistrationResult& a, float tolerance) {
  return b.verdict == Status::kOk && b.mean_residual_m <= a.mean_residual_m * (1.0f + tolerance) &&
         static_cast<float>(b.inliers) >= static_cast<float>(a.inliers) * (1.0f - tolerance);
}

}  // namespace

ClosureRefinement RefineClosure(const RegistrationReference& reference, Span<const Point2> cloud, const Pose2& start,
                                const Pose2& guess, bool from_search, const BackEndConfig& config,
                                Span<Correspondence> correspondences) {
  ClosureRefinement out;
  out.result = RefineFrom(reference, cloud, start, config, correspondences);
  if (!from_search || out.result.verdict != Status::kOk) return out;
  // The search's answer with its component along each weak direction of the fit set to the guess's.
  Pose2 on_ridge = start;
  if (!HoldWeakDirections(out.result.hessian, out.result.inliers, guess, config.ridge_information, 0.0f, &on_ridge)) {
    return out;
  }
  // The guess is trusted along the ridge as far as a correction PLICP alone may make (the search's
  // base window): beyond that it has drifted past what it can say.
  if (std::hypot(on_ridge.x - start.x, on_ridge.y - start.y) > config.search_base_m) return out;
  const RegistrationResult from_guess = RefineFrom(reference, cloud, on_ridge, config, correspondences);
  if (FitsAsWell(from_guess, out.result, config.ridge_fit_tolerance)) {
    out.result = from_guess;
    out.guess_on_ridge = true;
  }
  return out;
}

}  // namespace dpcr
