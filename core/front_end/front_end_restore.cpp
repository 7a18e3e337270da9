// FrontEnd's part of loading a saved map (front_end.hpp: RestoreRegion, RestoreStart).
#include <cmath>

#include "core/front_end/front_end.hpp"

namespace dpcr {

RegionalMap* FrontEnd::RestoreRegion(RegionKey key, const Pose2& anchor, std::uint32_t scans_inserted) {
  return regions_.Restore(key, anchor, scans_inserted);
}

void FrontEnd::RestoreStart(Point2 region_origin, const Pose2& start) {
  pose_ = Pose2::Identity();
  submap_pose_ = start;
  grid_turn_pending_ = false;  // a saved map's frame is kept
  start_pending_ = false;      // and its start, wherever this session began
  last_world_ = start;
  if (regions_.size() == 0) return;  // nothing saved: the first scan starts a lattice as usual
  const FrontEndConfig& f = config_.front_end;
  tracker_.Restore(region_origin, f.region_width_m, f.region_hysteresis_m, Point2{start.x, start.y});
  have_scan_ = true;
  if (config_.localisation.unknown_start && config_.localisation.relocalise && config_.front_end.enable_registration) {
    // Where the robot is will be searched for (front_end_relocalise.cpp): no region yet.
    StartRelocalisation(false);  // no pose to fall back on: searched until found
    return;
  }
  // The map the robot's pose is known in until it enters one: the nearest saved one.
  float best = INFINITY;
  for (int i = 0; i < regions_.size(); ++i) {
    const float d = std::hypot(regions_[i].anchor.x - start.x, regions_[i].anchor.y - start.y);
    if (d < best) {
      best = d;
      anchor_region_ = i;
    }
  }
  const RegionKey key = tracker_.current();
  if (config_.localisation.localise_only) {
    // Maps frozen: no new map; the nearest saved one is the reference until a region has one.
    EnterFrozenRegion();
    if (regions_.current() < 0) (void)regions_.Enter(regions_[anchor_region_].key, tracker_.Centre(regions_[anchor_region_].key));
    return;
  }
  EnterRegionChainedTo(key, anchor_region_);
}

void FrontEnd::EnterRegionChainedTo(RegionKey key, int from) {
  switch (regions_.Enter(key, tracker_.Centre(key))) {
    case RegionSet::Entry::kKnown:
      anchor_region_ = regions_.current();
      break;
    case RegionSet::Entry::kCreated:
      ++counters_.regions_created;
      back_end_.AddRegion(regions_.maps(), regions_.current(), from);
      anchor_region_ = regions_.current();
      break;
    case RegionSet::Entry::kPoolFull:
      ++counters_.region_pool_full;
      break;
  }
}

}  // namespace dpcr
