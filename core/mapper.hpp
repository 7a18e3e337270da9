// The whole SLAM core in one fixed-size object: sizeof(Mapper<Profile>) is the RAM bill.
// Feed it odometry and scans in time order; read the pose, status, counters and maps.
// The work is done by FrontEnd (core/front_end/front_end.hpp); this class owns its storage, sized by the
// profile, and exports the maps.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/back_end/back_end.hpp"
#include "core/capacity.hpp"
#include "core/config.hpp"
#include "core/front_end/front_end.hpp"
#include "core/grid/map_fusion.hpp"
#include "core/mapper_types.hpp"
#include "core/persistence/map_reader.hpp"
#include "core/persistence/map_writer.hpp"
#include "core/registration/registration_reference.hpp"
#include "core/geometry/scan.hpp"
#include "core/front_end/submap.hpp"
#include "core/grid/tile_pool.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr {

template <class Profile>
class Mapper {
 public:
  using ProfileType = Profile;
  using ScanType = Scan<Profile::kMaxBeams>;
  static constexpr int kBoxTiles = Profile::kRegionBoxTiles;
  static constexpr int kRegionCells = kBoxTiles * kTileSide;
  static constexpr int kSecondTargetPoints = 600;
  static constexpr int kBackEndCloudPoints = 400;
  static constexpr int kSearchPoints = 200;
  static constexpr int kMatchGridSide = kRegionCells / 2;

  static_assert(MatchGrid::BytesFor(kMatchGridSide, kMatchGridSide) <= 2u * kRegionCells * kRegionCells,
                "the loop-closure search grid fits in the regional reference's table");
  Mapper() : front_end_(Storage()) {
    for (int i = 0; i < Profile::kMaxRegions; ++i) {
      region_grids_[i].Attach(&tiles_);
      regions_[i].grid = &region_grids_[i];
    }
  }
  Mapper(const Mapper&) = delete;
  Mapper& operator=(const Mapper&) = delete;

  // Validates the configuration (Validate: every field, every relation, this profile's
  // capacities) and clears all state. Call once at start-up (and to restart).
  Status Init(const MapperConfig& config) {
    const Status v = Validate(config, Limits());
    return v != Status::kOk ? v : front_end_.Init(config);
  }
  // What this profile's storage holds, for Validate.
  static ConfigLimits Limits() {
    ConfigLimits l;
    l.submap_max_scans = Profile::kSubmapMaxScans;
    l.second_target_points = kSecondTargetPoints;
    l.back_end_cloud_points = kBackEndCloudPoints;
    l.search_points = kSearchPoints;
    l.region_box_cells = kRegionCells;
    return l;
  }
  void AddOdometry(const OdometrySample& sample) { (void)front_end_.AddOdometry(sample); }
  // For sources that give increments (robot frame) instead of an absolute wheel pose. An
  // increment the front end drops (not finite, a kilometre, a bad stamp) is not accumulated: the
  // next one goes on from the last good pose.
  void AddOdometryIncrement(std::int64_t stamp_us, const Pose2& delta) {
    OdometrySample s;
    s.stamp_us = stamp_us;
    s.pose = last_increment_pose_ * delta;
    if (front_end_.AddOdometry(s)) last_increment_pose_ = s.pose;
  }
  // kOk when the scan was used; kNotEnoughData when it had no usable beam (counted, pose predicted);
  // kInvalidArgument for a stamp before 1970 or past 2^56 us (counted, nothing changed).
  Status AddScan(const ScanType& scan) { return front_end_.AddScan(scan.beams.span(), scan.stamp_us); }

  Pose2 pose() const { return front_end_.pose(); }
  MapperStatus status() const { return front_end_.status(); }
  const MapperCounters& counters() const { return front_end_.counters(); }
  const FrontEndCounters& front_end_counters() const { return front_end_.front_end_counters(); }
  // Whether the wheels measure the motion the lidar sees (core/front_end/wheel_check.hpp).
  const WheelCheck& wheel_check() const { return front_end_.wheel_check(); }
  const OdometryCalibration& odometry_calibration() const { return front_end_.odometry_calibration(); }
  const MapperConfig& config() const { return front_end_.config(); }
  const char* pipeline() const {
    if (!front_end_.registration_enabled()) return "odometry";
    return config().back_end.enable ? "dpcr" : "dpcr-front-end";
  }
  int region_count() const { return front_end_.region_count(); }
  const BackEnd& back_end() const { return front_end_.back_end(); }
  // The anchor of regional map i (the back end moves it).
  Pose2 region_anchor(int i) const { return front_end_.region(i).anchor; }
  // The centre of regional map i's box, in the world (its anchor now times the centre in its frame).
  Point2 region_centre(int i) const {
    const CellBox b = region_grids_[i].box();
    const float res = region_grids_[i].resolution_m();
    return region_anchor(i).Apply(Point2{0.5f * res * static_cast<float>(b.min.x + b.max.x), 0.5f * res * static_cast<float>(b.min.y + b.max.y)});
  }
  // Where the last scan went (FrontEnd::last_scan_region): a trajectory kept as (map, pose in
  // the map) follows every later optimisation.
  int last_scan_region() const { return front_end_.last_scan_region(); }
  Pose2 last_scan_in_region() const { return front_end_.last_scan_in_region(); }
  // A recorded scan's final world pose (FrontEnd::ScanWorldPose): record (stamp, last_scan_region(),
  // last_scan_in_region(), pose()) after each AddScan, and ask at the end of the run.
  Pose2 ScanWorldPose(std::int64_t stamp_us, int region, const Pose2& in_region, const Pose2& online) const {
    return front_end_.ScanWorldPose(stamp_us, region, in_region, online);
  }
  // The start heading refined with the gyro (core/front_end/start_heading.hpp).
  const StartHeadingFit& start_heading() const { return front_end_.start_heading(); }
  // At the end of a run, before the trajectory is written: the start placed in the finished first
  // map (FrontEnd::RefineStart, core/front_end/start_scans.hpp).
  StartRefinement RefineStart() { return front_end_.RefineStart(); }
  // A trajectory refined after the run (FrontEnd::RecordScanPoints, host_sim/output/trajectory_refinement.hpp):
  // each scan's returns recorded as it is mapped, registered again at the end in its finished map.
  void RecordScanPoints(Span<Point2> buffer) { front_end_.RecordScanPoints(buffer); }
  std::size_t recorded_points() const { return front_end_.recorded_points(); }
  bool BeginMapRegistration(int region, int other = -1) { return front_end_.BeginMapRegistration(region, other); }
  RegistrationResult RegisterInMap(Span<const Point2> robot_points, const Pose2& in_region, int max_iterations) {
    return front_end_.RegisterInMap(robot_points, in_region, max_iterations);
  }

  // World-frame bounds of everything mapped so far.
  CellBox MapBounds() const {
    PlacedGrid placed[Profile::kMaxRegions];
    return FusedBounds(PlaceRegions(placed), config().grid.resolution_m);
  }
  // The global map: regional maps fused into `out` (see FuseInto).
  Status RenderMap(CellBox box, Span<std::int16_t> out) const {
    PlacedGrid placed[Profile::kMaxRegions];
    return FuseInto(PlaceRegions(placed), box, config().grid.resolution_m, config().grid.clamp_min,
                    config().grid.clamp_max, out);
  }
  // Bytes that storing the maps takes: allocated tiles' cells plus each region's tile index.
  std::size_t map_storage_bytes() const {
    return tiles_.used() * sizeof(std::int16_t) * kTileCells +
           static_cast<std::size_t>(region_count()) * sizeof(TileId) * kBoxTiles * kBoxTiles;
  }
  std::size_t tiles_used() const { return tiles_.used(); }

  // Persistence (core/persistence/, docs/map-file-format.md): the regional maps, their anchors,
  // the region lattice and the back end's graph as one versioned file, streamed in small chunks.
  MapFileResult SaveMap(MapByteSink& sink) const { return WriteMapFile(map_file_content(), sink); }
  // Bytes SaveMap writes now.
  std::size_t map_file_bytes() const { return static_cast<std::size_t>(MapFileHeaderOf(map_file_content()).file_bytes()); }
  MapFileLimits map_file_limits() const {
    const GridConfig& g = config().grid;
    return ProfileMapLimits<Profile>(g.resolution_m, config().front_end.region_width_m, g.clamp_min, g.clamp_max);
  }
  MapFileContent map_file_content() const {
    MapFileContent c;
    c.limits = map_file_limits();
    c.region_origin = front_end_.region_origin();
    c.regions = Span<const RegionalMap>(regions_, static_cast<std::size_t>(region_count()));
    c.graph = &graph_;
    return c;
  }
  // Replaces the maps and the graph with a saved map and puts the robot at `start` in its world
  // frame (mapping goes on there: new regions join the same graph). The file is checked whole
  // first (map_reader.hpp) against this profile and the configuration Init took: a file refused
  // then leaves the mapper as it was. Counters restart; the configuration stays.
  MapFileResult LoadMap(MapByteSource& source, const Pose2& start = Pose2::Identity()) {
    static_assert(kSecondTargetPoints >= Profile::kMaxRegions, "LoadMap borrows the target scratch for region keys");
    if (!PlausiblePose(start)) return MapFileResult{Status::kInvalidArgument, MapFileError::kBadStartPose, 0};
    // The configuration the maps are restored under (a mapper never Init'ed has the defaults).
    if (Validate(config(), Limits()) != Status::kOk) {
      return MapFileResult{Status::kInvalidArgument, MapFileError::kConfigMismatch, 0};
    }
    const MapFileLimits limits = map_file_limits();
    MapFileHeader header;
    // The second-registration target is per-scan scratch, not state: it holds the keys.
    MapFileResult r = CheckMapFile(source, &limits, Span<Point2>(target_, kSecondTargetPoints), &header, nullptr);
    if (!r.ok()) return r;
    if (!source.Rewind()) return MapFileResult{Status::kInvalidArgument, MapFileError::kUnreadable, 0};
    // From here on the mapper changes.
    const MapperConfig config = this->config();
    (void)front_end_.Init(config);
    last_increment_pose_ = Pose2::Identity();
    r = ApplyMapFile(source, header, front_end_, graph_);
    if (!r.ok()) {
      (void)front_end_.Init(config);
      return r;
    }
    front_end_.RestoreStart(header.region_origin, start);
    return r;
  }

 private:
  FrontEndStorage Storage() {
    FrontEndStorage s;
    s.submap = &submap_;
    s.submap_reference = &submap_reference_;
    s.region_reference = &region_reference_;
    s.regions = Span<RegionalMap>(regions_, Profile::kMaxRegions);
    s.hits = Span<Point2>(hits_, Profile::kMaxBeams);
    s.free_ends = Span<Point2>(free_ends_, Profile::kMaxBeams);
    s.target = Span<Point2>(target_, kSecondTargetPoints);
    s.scratch = submap_.ray_scratch();  // the submap's and the regional maps' insertions never overlap
    s.pending_beams = Span<PackedBeam>(pending_beams_, Profile::kMaxBeams);
    s.correspondences = Span<Correspondence>(correspondences_, Profile::kMaxBeams);
    s.back_end.graph = &graph_;
    s.back_end.match_grid = &match_grid_;
    s.back_end.reference = &region_reference_;
    s.back_end.cloud = Span<Point2>(back_end_cloud_, kBackEndCloudPoints);
    s.back_end.rotated = Span<MatchCell>(search_rotated_, kSearchPoints);
    s.back_end.correspondences = s.correspondences;
    s.back_end.jobs = Span<std::int32_t>(back_end_jobs_, Profile::kMaxRegions + 1);
    s.search_grid = &search_grid_;
    return s;
  }
  Span<const PlacedGrid> PlaceRegions(PlacedGrid* placed) const {
    const int n = region_count();
    for (int i = 0; i < n; ++i) placed[i] = PlacedGrid{region_grids_ + i, front_end_.region(i).anchor};
    return Span<const PlacedGrid>(placed, static_cast<std::size_t>(n));
  }

  TilePoolStorage<Profile::kTilePoolTiles> tiles_;
  TiledGridStorage<kBoxTiles, kBoxTiles> region_grids_[Profile::kMaxRegions];
  RegionalMap regions_[Profile::kMaxRegions];
  SubmapStorage<Profile::kSubmapMaxScans, Profile::kMaxBeams, Profile::kSubmapSideCells> submap_;
  RegistrationReferenceStorage<Profile::kSubmapSideCells, Profile::kSubmapSideCells, Profile::kReferenceCells,
                               Profile::kMaxLines>
      submap_reference_;
  RegistrationReferenceStorage<kRegionCells, kRegionCells, Profile::kReferenceCells, Profile::kMaxLines, false>
      region_reference_;
  // Per-scan scratch, kept here so nothing of scan size lives on the stack.
  Point2 hits_[Profile::kMaxBeams];
  Point2 free_ends_[Profile::kMaxBeams];
  Point2 target_[kSecondTargetPoints];
  // The scan waiting one revolution for its de-skew (lidar alone: FrontEnd::FlushPendingScan),
  // packed; in the room of the ray-casting scratch the regional maps now share with the submap.
  PackedBeam pending_beams_[Profile::kMaxBeams];
  // Registration scratch for a scan's points (the second registration's larger target goes without).
  Correspondence correspondences_[Profile::kMaxBeams];
  // The back end: the region graph, the loop-closure search grid, a region's cloud, its job queue.
  PoseGraphStorage<Profile::kMaxRegions, Profile::kMaxGraphEdges> graph_;
  MatchGrid match_grid_{kMatchGridSide, kMatchGridSide};  // cells lent by region_reference_
  Point2 back_end_cloud_[kBackEndCloudPoints];
  MatchCell search_rotated_[kSearchPoints];
  std::int32_t back_end_jobs_[Profile::kMaxRegions + 1];
  // The first registration's coarse search grid: the submap window at 10 cm plus the kernel margin.
  static constexpr int kSearchGridSide = Profile::kSubmapSideCells / 2 + 16;
  CoarseScoreGridStorage<kSearchGridSide, kSearchGridSide> search_grid_;
  Pose2 last_increment_pose_;
  FrontEnd front_end_;  // last: constructed from the storage above
};

}  // namespace dpcr
