// A loop closure's refinement by PLICP, and the guess kept along a ridge.
//
// A correlative search places the submap where its points score best; along a direction the map
// barely fixes (a corridor's length) the scores form a ridge and the best of it is the noise's
// pick. PLICP from there stays there: the registration has next to nothing to say along the ridge
// either, and its prior holds it at its start. On intel.clf the second lap back into the start
// corridor was placed 0.19 m along it from the front end's guess, with 1.2 of the xy block's 170
// information along it. The guess was right: the relations from that lap to the first one were
// off by those 0.19 m until the walls across the corridor corrected the robot 20 s later.
// So where the fit leaves a direction with less information per inlier than
// BackEndConfig::ridge_information, the closure is refined once more from the search's answer
// moved to the guess along that direction (across it the search's answer stays), and that fit is
// taken if it is as good: a mean residual and an inlier count within ridge_fit_tolerance of the
// search's. A search that found a real offset along a corridor, where something in the corridor
// fixes it, sees the guess fit worse and keeps its answer. The guess is tried only within the
// search's base window (search_base_m) of the search's answer: a correction PLICP alone may make.
// Past it the guess has drifted beyond what it can say: intel with its odometry uncalibrated
// (range 21-23 m) had guesses 1.1-1.2 m along the corridor that fitted as well, and taking them
// bent the map (0.06-0.075 m over all pairs instead of 0.018-0.019).
#pragma once

#include "core/back_end/back_end_config.hpp"
#include "core/base/span.hpp"
#include "core/geometry/pose2.hpp"
#include "core/registration/plicp.hpp"
#include "core/registration/registration_reference.hpp"

namespace dpcr {

struct ClosureRefinement {
  RegistrationResult result;
  bool guess_on_ridge = false;  // the fit from the guess along the ridge was taken
};

// PLICP of `cloud` into `reference` from `start`, with BackEndConfig::closure_prior_info at `start`.
// When `start` came from a search (`from_search`), a ridge is kept at `guess` as above.
ClosureRefinement RefineClosure(const RegistrationReference& reference, Span<const Point2> cloud, const Pose2& start,
                                const Pose2& guess, bool from_search, const BackEndConfig& config,
                                Span<Correspondence> correspondences);

}  // namespace dpcr
