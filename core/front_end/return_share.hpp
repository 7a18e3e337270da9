// How many of its readings a lidar loses on the walls it sees, and the submap reference's obstacle
// threshold for it. The threshold (FrontEndConfig::submap_reference) asks a wall cell for about
// three hits more than misses among the submap's 20 scans; a lidar that returns 40 % of its
// readings (the sparsest real XV-11 recordings) gives a wall cell proportionally fewer hits, and
// with range noise spreading them over two or three cells many of its walls never reach the
// threshold: the reference is left with holes, registrations lean on what is left, and without
// wheels the robot loses its way. Scaled with the share of returns below half
// (FrontEndConfig::sparse_reference_full_share), the threshold asks of a sparser lidar's walls
// what it asks of those of a lidar returning half its readings.
#pragma once

#include "core/geometry/scan_projection.hpp"
#include "core/registration/registration_reference.hpp"

namespace dpcr {

// The running share of returns among the beams pointing at something within range
// (ProjectedScan::beams_in_returning_sectors), over the last scans (an exponential mean with a
// weight of kReturnShareWeight a scan, about 20 scans). Starts at 1; a scan with no returning
// sector (a lidar facing nothing) leaves it as it is.
constexpr float kReturnShareWeight = 0.05f;
float UpdateReturnShare(float share, const ProjectedScan& scan);

// `base` with its obstacle threshold scaled by share / full_share when the share is below
// full_share (0: unchanged).
ReferenceConfig ReferenceForReturnShare(const ReferenceConfig& base, float share, float full_share);

}  // namespace dpcr
