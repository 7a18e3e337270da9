// The submap (paper §3.3): the last N scans fused in a grid of their own, with the scans kept
// in a ring so that the oldest leaves exactly (its rays are replayed with negated deltas).
// Cells hold unclamped sums: N scans of at most one update per cell each stay far inside int16
// (20 x 867 < 32767), so removal restores the previous value bit for bit.
//
// The submap has its own frame; scan poses are in it. Moving the whole submap (second
// registration) changes its pose in the world, not its cells. The grid's box follows the robot:
// when the robot strays from the box centre, the box is re-placed and the ring re-inserted.
#pragma once

#include <cstdint>

#include "core/config.hpp"
#include "core/geometry/pose2.hpp"
#include "core/grid/ray_caster.hpp"
#include "core/grid/scan_marker.hpp"
#include "core/base/span.hpp"
#include "core/base/static_vector.hpp"
#include "core/grid/tile_pool.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr {

// One scan as the submap keeps it: robot-frame points and the robot pose in the submap frame.
struct SubmapScanView {
  Pose2 pose;
  Span<Point2> points;
};

class Submap {
 public:
  Submap(TiledGrid* grid, Span<Point2> point_store, Span<Pose2> poses, Span<std::uint16_t> counts,
         Span<Point2> transformed, Span<CellIndex> scratch, int max_beams);
  Submap(const Submap&) = delete;
  Submap& operator=(const Submap&) = delete;

  // Empties the submap; `scans` (N) scans at most are kept from now on. `miss_range_m` > 0: each
  // ray clears only its last miss_range_m metres before the hit (see InsertRays).
  void Reset(const GridConfig& grid_config, int scans, float miss_range_m = 0.0f);

  // Adds a scan (robot-frame points, robot pose in the submap frame); when N scans are held the
  // oldest is removed first. Returns the insertion stats of the new scan.
  InsertionStats Add(const Pose2& pose, Span<const Point2> points);

  const TiledGrid& grid() const { return *grid_; }
  int size() const { return size_; }
  // Index 0 is the oldest scan.
  SubmapScanView scan(int i) const;
  std::uint32_t recentres() const { return recentres_; }
  // The ray-casting scratch (kMaxBeams cells), only used inside Add: the regional maps' insertion
  // shares it (Mapper), which frees room for the fixed-lag de-skew's packed scan.
  Span<CellIndex> ray_scratch() const { return scratch_; }

  // Keep the box centred within this distance of the robot (m).
  static constexpr float kRecentreDistanceM = 2.0f;

 private:
  InsertionStats Insert(const Pose2& pose, Span<const Point2> points, const GridConfig& config);
  void RecentreOn(Point2 p);
  int Slot(int i) const { return (head_ + i) % capacity_; }

  TiledGrid* grid_;
  Span<Point2> point_store_;  // capacity_ x max_beams_
  Span<Pose2> poses_;
  Span<std::uint16_t> counts_;
  Span<Point2> transformed_;  // one scan in the submap frame, for InsertRays
  Span<CellIndex> scratch_;
  int max_beams_;
  // The ring of scans. Not a RingBuffer: N is a run-time setting (<= the storage's), the class is
  // size-erased over its storage, and a slot is a run of max_beams_ points in point_store_.
  int capacity_ = 0;  // N in use (<= poses_.size())
  int head_ = 0;
  int size_ = 0;
  GridConfig add_config_;
  GridConfig remove_config_;
  float miss_range_m_ = 0.0f;
  ScanMarker scan_marker_;  // one per insertion or removal: each is a scan to the grid
  std::uint32_t recentres_ = 0;
};

template <int kMaxScans, int kMaxBeams, int kSideCells>
class SubmapStorage : public Submap {
  static constexpr int kSideTiles = kSideCells / kTileSide;
  static_assert(kSideCells % kTileSide == 0, "submap side must be whole tiles");

 public:
  SubmapStorage()
      : Submap(&grid_, Span<Point2>(points_, kMaxScans * kMaxBeams), Span<Pose2>(poses_, kMaxScans),
               Span<std::uint16_t>(counts_, kMaxScans), Span<Point2>(transformed_, kMaxBeams),
               Span<CellIndex>(scratch_, kMaxBeams), kMaxBeams) {}

 private:
  TilePoolStorage<kSideTiles * kSideTiles> tiles_;
  TiledGridStorage<kSideTiles, kSideTiles> grid_{&tiles_};
  Point2 points_[kMaxScans * kMaxBeams];
  Pose2 poses_[kMaxScans];
  std::uint16_t counts_[kMaxScans];
  Point2 transformed_[kMaxBeams];
  CellIndex scratch_[kMaxBeams];
};

}  // namespace dpcr
