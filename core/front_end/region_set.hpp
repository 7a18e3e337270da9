// The regional maps (paper §3.4): one per region the robot has entered, taken from a fixed pool
// on first entry and never evicted (a full pool stops the map from growing), with the map of the
// region the robot is in and of the one it came from. Scans go into the current map only.
// Each map's cells are in its anchor frame; the anchor places that frame in the world.
#pragma once

#include <cstdint>

#include "core/base/span.hpp"
#include "core/base/stage.hpp"
#include "core/config.hpp"
#include "core/front_end/region_tracker.hpp"
#include "core/front_end/regional_map.hpp"
#include "core/front_end/submap.hpp"
#include "core/geometry/pose2.hpp"
#include "core/grid/ray_caster.hpp"
#include "core/grid/scan_marker.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr {

class RegionSet {
 public:
  // `maps`: the pool, each with its grid attached; `scratch`: InsertRays scratch, kMaxBeams.
  RegionSet(Span<RegionalMap> maps, Span<CellIndex> scratch) : maps_(maps), scratch_(scratch) {}
  RegionSet(const RegionSet&) = delete;
  RegionSet& operator=(const RegionSet&) = delete;

  // Forgets every map. Maps made from now on use `grid`; a scan's rays to its hits clear only
  // their last `miss_range_m` metres (0: whole rays; see InsertRays).
  void Reset(const GridConfig& grid, float miss_range_m);

  enum class Entry {
    kKnown,     // the region has a map: it is current again
    kCreated,   // a new, empty map is current
    kPoolFull,  // no map left for the region: none is current
  };
  // The robot enters region `key` (centred at `centre` in the world). The map that was current
  // becomes the previous one; with a full pool it stays the previous one (still a reference).
  Entry Enter(RegionKey key, Point2 centre);

  // Seeds the current map with the submap's scans but the newest (the caller inserts that one
  // with InsertScan); `submap_pose` places the submap frame in the world. Each seeded scan takes
  // its own marker, and the scan after them one more. `points`: scratch, kMaxBeams.
  // Returns the updates dropped for want of tiles.
  DPCR_STAGE int SeedFromSubmap(const Submap& submap, const Pose2& submap_pose, Span<Point2> points,
                                ScanMarker& marker);
  // Inserts a scan into map `index` (the current one: -1), if any: `hits` and `free_ends` are
  // robot-frame (the robot at `robot` in the world) and are moved into the map's frame in place.
  // `learning_rate` (0, 1]: the share of the grid's deltas it learns with (ScaledLearning).
  DPCR_STAGE InsertionStats InsertScan(const Pose2& robot, Span<Point2> hits, Span<Point2> free_ends,
                                       std::uint32_t marker, int index = -1, float learning_rate = 1.0f);

  // Loading a saved map (core/persistence), after Reset: appends a map in creation order, empty,
  // with its key, anchor and scan count (none current); nullptr when the pool is full.
  RegionalMap* Restore(RegionKey key, const Pose2& anchor, std::uint32_t scans_inserted);

  int size() const { return size_; }
  // The maps made so far (the back end's vertices, in creation order).
  Span<RegionalMap> maps() const { return Span<RegionalMap>(maps_.data(), static_cast<std::size_t>(size_)); }
  RegionalMap& operator[](int i) { return maps_[static_cast<std::size_t>(i)]; }
  const RegionalMap& operator[](int i) const { return maps_[static_cast<std::size_t>(i)]; }
  // Index of the map of region `key`, -1 if it has none.
  int Find(RegionKey key) const;
  // The map the robot is in and the one it was in before (-1: none).
  int current() const { return current_; }
  int previous() const { return previous_; }
  // Set once a region found the pool empty or a map dropped updates for want of tiles.
  bool pool_full() const { return pool_full_; }
  // The tile pool every map draws from (the kept start scans borrow from it too).
  TilePool& pool() { return maps_[0].grid->pool(); }

 private:
  Span<RegionalMap> maps_;
  Span<CellIndex> scratch_;
  GridConfig grid_;
  float miss_range_m_ = 0.0f;
  int size_ = 0;
  int current_ = -1;
  int previous_ = -1;
  bool pool_full_ = false;
};

}  // namespace dpcr
