// Where no wheel measures the translation (a gyro alone, heading-only ticks, the lidar alone), the
// first registration's answer along a direction the walls barely fix is not a measurement. A lane
// down a hallway longer than the lidar's reach, or a room's length seen through a sparse
// revolution, holds the pose across it and hardly along it; along it the answer follows whatever
// few far returns or smeared wall ends pull it, and registrations that pulled 4-10 cm back twice
// in a row halved the constant velocity's guess. The next scans then registered near that slower
// guess (nothing along the lane to say otherwise) and the estimate stood while the robot drove
// on, or drove backwards (XV-11, half its readings, 3.5-5 Hz, gyro alone, apartment seed 53:
// 4 m off for the rest of the run). A vacuum's speed changes by at most its acceleration times
// the scan interval, so along a direction whose information per inlier is below the bound, the
// registered pose keeps within acceleration x interval^2 of the constant velocity's guess (twice
// the position change a full acceleration makes from the guess, which carries the last step's
// own error). Across it, and along any direction the walls do fix, the registration's answer is
// kept as it is.
// The back end uses the same split to start a loop closure's second refinement at the guess along
// a ridge the search could not resolve (core/back_end/closure_refinement.hpp).
#pragma once

#include <Eigen/Core>

#include "core/geometry/pose2.hpp"
#include "core/geometry/symmetric_eigen2.hpp"

namespace dpcr {

// The xy block of `hessian` (the points' normal equations, no prior) over `inliers` gives each
// eigen-direction's information per inlier; along each one below `min_information`, the
// translation from `predicted` to `registered` is clamped to +-`max_deviation_m`. The heading is
// left as registered. Returns whether anything moved.
inline bool HoldWeakDirections(const Eigen::Matrix3f& hessian, int inliers, const Pose2& predicted, float min_information,
                               float max_deviation_m, Pose2* registered) {
  if (inliers <= 0 || !(min_information > 0.0f) || !(max_deviation_m >= 0.0f)) return false;
  const SymmetricEigen2 eigen = EigenOfSymmetric2(hessian(0, 0), hessian(0, 1), hessian(1, 1));
  const float ex = eigen.minor.x, ey = eigen.minor.y, n = static_cast<float>(inliers);
  const float dx = registered->x - predicted.x, dy = registered->y - predicted.y;
  // Components along the weak direction (e) and the one across it (-ey, ex).
  const float along[2] = {dx * ex + dy * ey, -dx * ey + dy * ex};
  const float information[2] = {eigen.lambda_min / n, eigen.lambda_max / n};
  float kept[2] = {along[0], along[1]};
  bool moved = false;
  for (int i = 0; i < 2; ++i) {
    if (!(information[i] < min_information)) continue;
    if (kept[i] > max_deviation_m) kept[i] = max_deviation_m;
    if (kept[i] < -max_deviation_m) kept[i] = -max_deviation_m;
    moved = moved || kept[i] != along[i];
  }
  if (!moved) return false;
  registered->x = predicted.x + kept[0] * ex - kept[1] * ey;
  registered->y = predicted.y + kept[0] * ey + kept[1] * ex;
  return true;
}

}  // namespace dpcr
