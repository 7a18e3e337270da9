#include "core/geometry/scan_projection.hpp"

#include <cmath>

#include "core/base/assert.hpp"

namespace dpcr {

ProjectedScan ProjectScan(Span<const Beam> beams, std::int64_t stamp_us, const LidarConfig& lidar,
                          const OdometryBuffer& odometry, Span<Point2> hits_out, Span<Point2> free_ends_out) {
  DPCR_ASSERT(hits_out.size() >= beams.size() && free_ends_out.size() >= beams.size());
  ProjectedScan out;
  const bool deskew = !odometry.empty();
  const Pose2 odom_at_stamp = deskew ? odometry.PoseAt(stamp_us) : Pose2::Identity();
  const Pose2 odom_at_stamp_inv = odom_at_stamp.Inverse();
  // Beams of one packet share a motion estimate closely; cache the last offset's correction.
  std::int32_t cached_offset = 0;
  Pose2 sensor = lidar.mount;
  for (const Beam& b : beams) {
    if (deskew && b.offset_us != cached_offset) {
      cached_offset = b.offset_us;
      sensor = odom_at_stamp_inv * odometry.PoseAt(stamp_us + b.offset_us) * lidar.mount;
    }
    const bool finite = std::isfinite(b.range_m);
    if (finite && b.range_m >= lidar.min_range_m && b.range_m <= lidar.max_range_m) {
      hits_out[out.hits++] = sensor.Apply(Point2{b.range_m * std::cos(b.angle_rad), b.range_m * std::sin(b.angle_rad)});
    } else if (lidar.no_return_free_m > 0.0f && (!finite || b.range_m <= 0.0f || b.range_m > lidar.max_range_m)) {
      const float r = lidar.no_return_free_m;
      free_ends_out[out.free_ends++] = sensor.Apply(Point2{r * std::cos(b.angle_rad), r * std::sin(b.angle_rad)});
    } else {
      ++out.invalid;
    }
  }
  return out;
}

}  // namespace dpcr
