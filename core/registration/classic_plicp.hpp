// Classic PLICP (Censi 2008) on the same reference data, the baseline of the paper's Fig. 2a:
// the error of a target point is its distance to the line through its nearest and second-nearest
// reference points (here: obstacle cell centres; the second searched in the 5x5 cells around the
// first). Same solver, gate, trimming, kernel and verdict as the improved method (core/registration/plicp.hpp).
#pragma once

#include "core/registration/plicp.hpp"

namespace dpcr {

RegistrationResult RegisterClassic(const RegistrationReference& ref, Span<const Point2> target, Pose2 initial,
                                   const PosePrior* prior, const PlicpConfig& config);

}  // namespace dpcr
