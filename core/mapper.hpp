// The whole SLAM core in one fixed-size object: sizeof(Mapper<Profile>) is the RAM bill.
// Feed it odometry and scans in time order; read the pose, status, counters and maps.
//
// Pipeline "odometry" (walking skeleton): the pose is dead-reckoned from wheel odometry,
// each scan is de-skewed and inserted once into the current region's map. The registration
// issues replace the pose step behind this same interface.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/capacity.hpp"
#include "core/config.hpp"
#include "core/map_fusion.hpp"
#include "core/mapper_types.hpp"
#include "core/odometry_buffer.hpp"
#include "core/ray_caster.hpp"
#include "core/region_tracker.hpp"
#include "core/scan.hpp"
#include "core/scan_projection.hpp"
#include "core/tile_pool.hpp"
#include "core/tiled_grid.hpp"

namespace dpcr {

template <class Profile>
class Mapper {
 public:
  using ProfileType = Profile;
  using ScanType = Scan<Profile::kMaxBeams>;
  static constexpr int kBoxTiles = Profile::kRegionBoxTiles;

  Mapper() {
    for (RegionSlot& r : regions_) r.grid.Attach(&tiles_);
  }
  Mapper(const Mapper&) = delete;
  Mapper& operator=(const Mapper&) = delete;

  // Validates the configuration and clears all state. Call once at start-up (and to restart).
  Status Init(const MapperConfig& config) {
    const Status s = Validate(config);
    if (s != Status::kOk) return s;
    if (config.front_end.submap_scans > Profile::kSubmapMaxScans) return Status::kInvalidArgument;
    config_ = config;
    for (int i = 0; i < region_count_; ++i) regions_[i].grid.Reset();
    region_count_ = 0;
    current_region_ = -1;
    odometry_.Clear();
    counters_ = MapperCounters{};
    status_ = MapperStatus::kWaitingForData;
    pose_ = Pose2::Identity();
    have_scan_ = false;
    stamp_ = 0;
    return Status::kOk;
  }

  void AddOdometry(const OdometrySample& sample) {
    const std::uint32_t before = odometry_.steps_back();
    odometry_.Add(sample);
    // A stamp stepping back breaks interpolation, not the odometry frame: increments go on.
    if (odometry_.steps_back() != before) ++counters_.odometry_steps_back;
    ++counters_.odometry_samples;
  }

  // For sources that give increments (robot frame) instead of an absolute wheel pose.
  void AddOdometryIncrement(std::int64_t stamp_us, const Pose2& delta) {
    OdometrySample s;
    s.stamp_us = stamp_us;
    s.pose = (odometry_.empty() ? Pose2::Identity() : odometry_.newest().pose) * delta;
    AddOdometry(s);
  }

  // kOk when the scan was fused; kNotEnoughData when it had no usable beam (counted, pose kept).
  Status AddScan(const ScanType& scan) {
    ++counters_.scans;
    if (++stamp_ == 0) stamp_ = 1;  // 0 means "no once-per-scan rule" to the grid
    PredictPose(scan.stamp_us);
    const ProjectedScan projected =
        ProjectScan(scan.beams.span(), scan.stamp_us, config_.lidar, odometry_, Span<Point2>(hits_, Profile::kMaxBeams),
                    Span<Point2>(free_ends_, Profile::kMaxBeams));
    counters_.beams_invalid += static_cast<std::uint32_t>(projected.invalid);
    if (projected.hits == 0 && projected.free_ends == 0) {
      ++counters_.scans_rejected;
      return Status::kNotEnoughData;
    }
    if (!have_scan_) {
      tracker_.Start(Point2{pose_.x, pose_.y}, config_.front_end.region_width_m, config_.front_end.region_hysteresis_m);
      have_scan_ = true;
      status_ = MapperStatus::kTracking;
      EnterRegion();
    } else if (tracker_.Update(Point2{pose_.x, pose_.y})) {
      EnterRegion();
    }
    if (current_region_ >= 0) Insert(projected);
    return Status::kOk;
  }

  Pose2 pose() const { return pose_; }
  MapperStatus status() const { return status_; }
  const MapperCounters& counters() const { return counters_; }
  const MapperConfig& config() const { return config_; }
  const char* pipeline() const { return "odometry"; }
  int region_count() const { return region_count_; }

  // World-frame bounds of everything mapped so far.
  CellBox MapBounds() const {
    PlacedGrid placed[Profile::kMaxRegions];
    return FusedBounds(PlaceRegions(placed), config_.grid.resolution_m);
  }
  // The global map: regional maps fused into `out` (see FuseInto).
  Status RenderMap(CellBox box, Span<std::int16_t> out) const {
    PlacedGrid placed[Profile::kMaxRegions];
    return FuseInto(PlaceRegions(placed), box, config_.grid.resolution_m, config_.grid.clamp_min,
                    config_.grid.clamp_max, out);
  }
  // Bytes that storing the maps takes: allocated tiles' cells plus each region's tile index.
  std::size_t map_storage_bytes() const {
    return tiles_.used() * sizeof(std::int16_t) * kTileCells +
           static_cast<std::size_t>(region_count_) * sizeof(TileId) * kBoxTiles * kBoxTiles;
  }
  std::size_t tiles_used() const { return tiles_.used(); }

 private:
  struct RegionSlot {
    RegionKey key;
    Pose2 anchor;  // the regional map's frame in the world; the back end moves it
    TiledGridStorage<kBoxTiles, kBoxTiles> grid;
  };

  void PredictPose(std::int64_t stamp_us) {
    if (odometry_.empty()) {
      ++counters_.scans_without_odometry;
      return;
    }
    const Pose2 odom = odometry_.PoseAt(stamp_us);
    if (last_odom_valid_) pose_ = pose_ * Between(last_odom_, odom);
    last_odom_ = odom;
    last_odom_valid_ = true;
  }

  void EnterRegion() {
    const RegionKey key = tracker_.current();
    for (int i = 0; i < region_count_; ++i) {
      if (regions_[i].key == key) {
        current_region_ = i;
        return;
      }
    }
    if (region_count_ == Profile::kMaxRegions) {
      // Evict nothing: the map stops growing here and says so.
      ++counters_.region_pool_full;
      status_ = MapperStatus::kPoolFull;
      current_region_ = -1;
      return;
    }
    RegionSlot& r = regions_[region_count_];
    const Point2 c = tracker_.Centre(key);
    r.key = key;
    r.anchor = Pose2{c.x, c.y, 0.0f};
    r.grid.set_resolution_m(config_.grid.resolution_m);
    r.grid.Reset(CellIndex{-kBoxTiles / 2, -kBoxTiles / 2});
    current_region_ = region_count_++;
    ++counters_.regions_created;
  }

  void Insert(const ProjectedScan& projected) {
    RegionSlot& r = regions_[current_region_];
    const Pose2 to_region = r.anchor.Inverse() * pose_;
    for (std::size_t i = 0; i < projected.hits; ++i) hits_[i] = to_region.Apply(hits_[i]);
    for (std::size_t i = 0; i < projected.free_ends; ++i) free_ends_[i] = to_region.Apply(free_ends_[i]);
    const InsertionStats stats = InsertRays(
        r.grid, Point2{to_region.x, to_region.y}, Span<const Point2>(hits_, projected.hits),
        Span<const Point2>(free_ends_, projected.free_ends), config_.grid, stamp_, Span<CellIndex>(scratch_, Profile::kMaxBeams));
    counters_.updates_out_of_box += static_cast<std::uint32_t>(stats.out_of_box);
    counters_.updates_dropped_pool_full += static_cast<std::uint32_t>(stats.dropped_pool_full);
    if (stats.dropped_pool_full > 0) status_ = MapperStatus::kPoolFull;
  }

  Span<const PlacedGrid> PlaceRegions(PlacedGrid* placed) const {
    for (int i = 0; i < region_count_; ++i) placed[i] = PlacedGrid{&regions_[i].grid, regions_[i].anchor};
    return Span<const PlacedGrid>(placed, static_cast<std::size_t>(region_count_));
  }

  MapperConfig config_;
  MapperStatus status_ = MapperStatus::kWaitingForData;
  MapperCounters counters_;
  Pose2 pose_;
  Pose2 last_odom_;
  bool last_odom_valid_ = false;
  bool have_scan_ = false;
  std::uint32_t stamp_ = 0;
  OdometryBuffer odometry_;
  RegionTracker tracker_;
  int region_count_ = 0;
  int current_region_ = -1;
  TilePoolStorage<Profile::kTilePoolTiles> tiles_;
  RegionSlot regions_[Profile::kMaxRegions];
  // Per-scan scratch, kept here so nothing of scan size lives on the stack.
  Point2 hits_[Profile::kMaxBeams];
  Point2 free_ends_[Profile::kMaxBeams];
  CellIndex scratch_[Profile::kMaxBeams];
};

}  // namespace dpcr
