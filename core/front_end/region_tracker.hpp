// Which region the robot is in: square cells of width S keyed from the start position
// (key = floor((x - x0) / S)), with hysteresis so that jitter on a border does not
// switch regions back and forth.
#pragma once

#include <cstdint>

#include "core/geometry/pose2.hpp"

namespace dpcr {

struct RegionKey {
  std::int32_t i = 0;
  std::int32_t j = 0;
  friend bool operator==(RegionKey a, RegionKey b) { return a.i == b.i && a.j == b.j; }
  friend bool operator!=(RegionKey a, RegionKey b) { return !(a == b); }
};

class RegionTracker {
 public:
  // The first position becomes the centre of region (0, 0).
  void Start(Point2 origin, float width_m, float hysteresis_m);
  // Loading a saved map: the saved lattice (`region_origin`: the world centre of region (0, 0)),
  // the robot at `position`; its region becomes the current one.
  void Restore(Point2 region_origin, float width_m, float hysteresis_m, Point2 position);
  // Updates the current region; true when it changed.
  bool Update(Point2 position);

  RegionKey current() const { return current_; }
  // World position of a region's centre.
  Point2 Centre(RegionKey key) const;
  // The key of the square containing p, without hysteresis.
  RegionKey KeyOf(Point2 p) const;

 private:
  Point2 origin_;
  float width_m_ = 4.0f;
  float hysteresis_m_ = 0.3f;
  RegionKey current_;
};

}  // namespace dpcr
