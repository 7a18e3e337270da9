#include "core/registration/pivot_frame.hpp"

#include <cmath>

namespace dpcr {

Point2 RecentreOnCentroid(Span<Point2> points) {
  if (points.empty()) return Point2{};
  // Any point among the cloud would do as the pivot; summed in double, the centroid of a few
  // hundred cells tens of metres out is that, to well under a millimetre.
  double sx = 0.0, sy = 0.0;
  for (const Point2& p : points) {
    sx += static_cast<double>(p.x);
    sy += static_cast<double>(p.y);
  }
  const double n = static_cast<double>(points.size());
  const Point2 c{static_cast<float>(sx / n), static_cast<float>(sy / n)};
  for (Point2& p : points) {
    p.x -= c.x;
    p.y -= c.y;
  }
  return c;
}

Eigen::Matrix3f FrameInformation(const Eigen::Matrix3f& pivot_information, const Pose2& frame_pose, Point2 pivot) {
  // pivot.xy = frame.xy + R(frame.θ) c, pivot.θ = frame.θ: d pivot.xy / d θ = (-(R c).y, (R c).x).
  const float c = std::cos(frame_pose.theta), s = std::sin(frame_pose.theta);
  const float rx = c * pivot.x - s * pivot.y, ry = s * pivot.x + c * pivot.y;
  Eigen::Matrix3f j = Eigen::Matrix3f::Identity();
  j(0, 2) = -ry;
  j(1, 2) = rx;
  return j.transpose() * pivot_information * j;
}

}  // namespace dpcr
