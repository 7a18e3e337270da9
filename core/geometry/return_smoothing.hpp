// Range-noise smoothing of a scan's returns along straight walls. A low-cost lidar's range noise
// (an LD06: 1 cm + 0.5 % of the range, independent from beam to beam) makes a wall mapped from
// its returns a band of cells two to three thick, and maps built from such bands bend (measured:
// docs/back-end.md, "Returns moved onto their wall"). A return that lies with its neighbours
// (three on each side) on one straight line, within the lidar's noise, is moved along its own ray
// onto that line: its range error shrinks by about the square root of the window. At a corner the
// window on the return's own side of it is taken; an edge, clutter or a gap between beams keeps
// the return as measured.
#pragma once

#include <cstddef>

#include "core/base/span.hpp"
#include "core/geometry/pose2.hpp"

namespace dpcr {

struct ReturnSmoothingConfig {
  int half_window = 3;         // neighbours on each side (a window of 2 * half_window + 1 returns)
  float noise_m = 0.0f;        // the lidar's range sigma at 3 m (LidarConfig::range_noise_m); 0 = off
  float max_rms_sigmas = 2.0f;  // the window's fit residual (rms) allowed, in the noise at its range
  float max_move_sigmas = 3.0f;  // a return moves at most this many sigmas along its ray
  float max_gap_beams = 1.5f;    // neighbours are returns of adjacent beams (no gap)
};

// `hits`: a scan's returns in beam order, in the robot frame; `origin`: the lidar's position in
// that frame; `beam_step_rad`: the angle between adjacent beams. Returns how many returns moved.
std::size_t SmoothReturns(Span<Point2> hits, Point2 origin, float beam_step_rad, const ReturnSmoothingConfig& config);

}  // namespace dpcr
