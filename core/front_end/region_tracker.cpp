#include "core/front_end/region_tracker.hpp"

#include <cmath>

namespace dpcr {

void RegionTracker::Start(Point2 origin, float width_m, float hysteresis_m) {
  // Region (0, 0) is centred on the start, so a robot that starts in a room starts mid-region.
  origin_ = Point2{origin.x - width_m / 2, origin.y - width_m / 2};
  width_m_ = width_m;
  hysteresis_m_ = hysteresis_m;
  current_ = RegionKey{};
}

void RegionTracker::Restore(Point2 region_origin, float width_m, float hysteresis_m, Point2 position) {
  origin_ = Point2{region_origin.x - width_m / 2, region_origin.y - width_m / 2};
  width_m_ = width_m;
  hysteresis_m_ = hysteresis_m;
  current_ = KeyOf(position);
}

RegionKey RegionTracker::KeyOf(Point2 p) const {
  return RegionKey{static_cast<std::int32_t>(std::floor((p.x - origin_.x) / width_m_)),
                   static_cast<std::int32_t>(std::floor((p.y - origin_.y) / width_m_))};
}

Point2 RegionTracker::Centre(RegionKey key) const {
  return Point2{origin_.x + (static_cast<float>(key.i) + 0.5f) * width_m_,
                origin_.y + (static_cast<float>(key.j) + 0.5f) * width_m_};
}

bool RegionTracker::Update(Point2 p) {
  // Stay while inside the current square grown by the hysteresis margin.
  const Point2 c = Centre(current_);
  const float half = width_m_ / 2 + hysteresis_m_;
  if (std::fabs(p.x - c.x) <= half && std::fabs(p.y - c.y) <= half) return false;
  current_ = KeyOf(p);
  return true;
}

}  // namespace dpcr
