// Turns a scan's beams into points: robot-frame at the scan stamp, with each beam moved by the
// robot motion between the scan stamp and the beam's own time (de-skew: core/front_end/scan_motion.hpp).
#pragma once

#include <cstdint>

#include "core/config.hpp"
#include "core/front_end/scan_motion.hpp"
#include "core/geometry/pose2.hpp"
#include "core/geometry/scan.hpp"
#include "core/base/span.hpp"

namespace dpcr {

struct ProjectedScan {
  std::size_t hits = 0;       // points with a return, written to hits_out
  std::size_t free_ends = 0;  // no-return beams cleared up to no_return_free_m
  std::size_t invalid = 0;    // beams with neither
  std::size_t isolated = 0;   // returns dropped as junk (LidarConfig::drop_isolated_returns)
  // Beams in the revolution's sectors of kReturnSectorBeams neighbours that hold a return: the
  // beams that point at something within range. A sector looking down a corridor past the range
  // holds none, so hits / these is the share of readings the lidar returns from walls it does see
  // (core/front_end/return_share.hpp).
  std::size_t beams_in_returning_sectors = 0;
};

constexpr std::size_t kReturnSectorBeams = 8;

// Points are expressed in the robot frame at the scan stamp (the one `motion` was made for).
ProjectedScan ProjectScan(Span<const Beam> beams, const LidarConfig& lidar, const ScanMotion& motion,
                          Span<Point2> hits_out, Span<Point2> free_ends_out);
// The same for a scan kept packed (FrontEnd's fixed-lag de-skew).
ProjectedScan ProjectScan(Span<const PackedBeam> beams, const LidarConfig& lidar, const ScanMotion& motion,
                          Span<Point2> hits_out, Span<Point2> free_ends_out);

}  // namespace dpcr
