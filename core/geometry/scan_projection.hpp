// Turns a scan's beams into points: robot-frame at the scan stamp, with each beam moved by the
// robot motion between the scan stamp and the beam's own time (de-skew from odometry).
#pragma once

#include <cstdint>

#include "core/config.hpp"
#include "core/front_end/odometry_buffer.hpp"
#include "core/geometry/pose2.hpp"
#include "core/geometry/scan.hpp"
#include "core/base/span.hpp"

namespace dpcr {

struct ProjectedScan {
  std::size_t hits = 0;       // points with a return, written to hits_out
  std::size_t free_ends = 0;  // no-return beams cleared up to no_return_free_m
  std::size_t invalid = 0;    // beams with neither
};

// Points are expressed in the robot frame at `stamp_us`. `odometry` may be empty (no de-skew).
ProjectedScan ProjectScan(Span<const Beam> beams, std::int64_t stamp_us, const LidarConfig& lidar,
                          const OdometryBuffer& odometry, Span<Point2> hits_out, Span<Point2> free_ends_out);

}  // namespace dpcr
