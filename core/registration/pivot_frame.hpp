// A cloud registered about a pivot among its points, not about its frame's origin.
//
// A submap's frame is the frame the front end started in: its cells can lie tens of metres from
// the origin. Posed about that origin, a registration's rotation swings the cloud through a lever
// arm as long as that distance, so everything that measures a pose change in (x, y, θ) stops
// meaning what it says: the prior resists a turn of the cloud as (lever × angle) of translation
// (at 20 m, five times more than the points hold it), the plausibility bound and the search's
// windows admit or refuse turns by where the run started, and the search's rotations sweep the
// cloud across its translation window. Posed about the cloud's centroid instead, rotation and
// translation are the cloud's own and every bound means the same anywhere in a building.
#pragma once

#include <Eigen/Core>

#include "core/base/span.hpp"
#include "core/geometry/pose2.hpp"
#include "core/registration/plicp.hpp"

namespace dpcr {

// Moves `points` so that their centroid is the origin; returns that centroid (in their old
// frame): the pivot. No points: (0, 0), nothing moved.
Point2 RecentreOnCentroid(Span<Point2> points);

// The pose of the pivot frame (the frame translated to `pivot`, unturned) given its frame's pose,
// and back.
inline Pose2 PivotPose(const Pose2& frame_pose, Point2 pivot) { return frame_pose * Pose2{pivot.x, pivot.y, 0.0f}; }
inline Pose2 FramePose(const Pose2& pivot_pose, Point2 pivot) {
  return pivot_pose * Pose2{-pivot.x, -pivot.y, 0.0f};
}

// The information of a frame's pose from that of its pivot's (H = Jᵀ H_pivot J, J = d pivot / d
// frame at `frame_pose`): what a caller that keeps the frame's pose needs.
Eigen::Matrix3f FrameInformation(const Eigen::Matrix3f& pivot_information, const Pose2& frame_pose, Point2 pivot);

// A registration of the pivot frame, handed back as its frame's: the pose and its information.
inline RegistrationResult FrameResult(RegistrationResult pivot_result, Point2 pivot) {
  pivot_result.pose = FramePose(pivot_result.pose, pivot);
  pivot_result.hessian = FrameInformation(pivot_result.hessian, pivot_result.pose, pivot);
  return pivot_result;
}

// A change of a frame's pose (Between(before, after)) as the pivot sees it.
inline Pose2 ChangeAboutPivot(const Pose2& frame_change, Point2 pivot) {
  const Pose2 p{pivot.x, pivot.y, 0.0f};
  return p.Inverse() * frame_change * p;
}

}  // namespace dpcr
