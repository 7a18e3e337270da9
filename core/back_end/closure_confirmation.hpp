// A loop closure whose search was not clear-cut waits for a second search of the same map to
// agree with it before the graph takes it.
//
// The correlative search refuses a closure outright when a separate peak scores within
// CorrelativeSearchConfig::max_second_ratio (95 %) of the best. Below that a look-alike still
// wins now and then: on intel.clf the closure that decides a replay, the robot's first lap back
// into the start corridor, has a second peak 0.9-2.5 m along the corridor scoring 0.94-0.95 of the
// best, and which of the two wins depends on a range limit or a region width. Taken, the wrong one
// held the rest of the log 4-11 cm off over all pairs. A doubtful closure
// (BackEndConfig::confirm_second_ratio) therefore waits; the next search of that map (the front
// end retries after 10 scans and 1 m) takes it if it lands on the same correction. A search that
// contradicts the one waiting, doubtful or not, waits in its place: two searches of one map that
// disagree cannot both be right. Searches of other maps are judged alone: until the graph has
// closed the loop between two maps, their anchors disagree by that loop's drift, and closures into
// both may be right.
// A closure refined from the front end's guess after a search without a clear peak is doubtful
// too when that search's window was wide (BackEndConfig::confirm_guess_window_m): PLICP from a
// guess metres off finds the nearest look-alike as readily as the map.
#pragma once

#include "core/back_end/back_end_config.hpp"
#include "core/geometry/pose2.hpp"

namespace dpcr {

class ClosureConfirmation {
 public:
  // Whether a closure into map `region` is taken now: its submap was found at `found_world` and
  // tracked at `submap_world` (both world poses), `doubtful` when its search's second peak came
  // near the best or it was refined from a far guess. When not taken, it is the closure waiting
  // from now on.
  bool Take(int region, bool doubtful, const Pose2& found_world, const Pose2& submap_world, const BackEndConfig& config) {
    const bool same_map = waiting_ && region == region_;
    if (!doubtful && !same_map) return true;
    // The correction a closure implies (found x tracked^-1) is compared where the robot is now, in
    // its frame, not in the world's: there a hundredth of a radian between two corrections is 20 cm
    // for a robot 20 m from the origin, here a centimetre per metre driven between the searches.
    const bool agrees = same_map && WithinSearchBaseWindow(config, Between(correction_ * submap_world, found_world));
    waiting_ = !agrees;
    if (agrees) return true;
    region_ = region;
    correction_ = found_world * submap_world.Inverse();
    return false;
  }
  // A closure was taken (the robot is placed): the one waiting is moot.
  void Clear() { waiting_ = false; }
  bool waiting() const { return waiting_; }

 private:
  Pose2 correction_;
  int region_ = -1;
  bool waiting_ = false;
};

}  // namespace dpcr
