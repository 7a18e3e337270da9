// The dominant wall direction of a scan, modulo 90 degrees (a home's walls meet mostly at right
// angles). The front end turns a new map's grid away from its walls when they would lie along the
// grid's axes (FrontEnd::TurnFrameFromWalls): a noisy wall along a cell row is a band whose cells all
// quantise the same way, so the map cannot hold its heading to better than half a cell over the
// wall's length; a wall that crosses rows and columns averages that out. Measured (apartment,
// seeds 1-10, the robot started square to the walls as from a dock): LocErr_ave 0.058 m, 0.023 m
// with the grid turned; 0.021 m from the seeds' own headings (docs/back-end.md, "Walls along the
// grid").
#pragma once

#include "core/base/span.hpp"
#include "core/geometry/pose2.hpp"

namespace dpcr {

struct WallDirectionConfig {
  int window = 7;                // returns per straight piece (consecutive in beam order)
  float max_step_m = 0.15f;      // neighbours in a piece at most this far apart
  float max_rms_m = 0.02f;       // a piece's straight-line fit residual (rms) at most this
  float min_length_m = 0.15f;    // and at least this long end to end
  int min_pieces = 20;           // fewer straight pieces: no direction
  float min_agreement = 0.5f;    // |mean of (cos 4a, sin 4a)| over the pieces: a home, not clutter
};

struct WallDirection {
  bool found = false;
  float angle_rad = 0.0f;  // in [-pi/4, pi/4): the walls' direction modulo 90 degrees
  int pieces = 0;          // straight pieces that voted
  float agreement = 0.0f;  // 1: every piece along the same or a perpendicular direction
};

// `points`: a scan's returns in beam order (any frame: the angle is in that frame).
WallDirection DominantWallDirection(Span<const Point2> points, const WallDirectionConfig& config);

}  // namespace dpcr
