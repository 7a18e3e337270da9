// The DPCR front end (Cao et al. 2025, §3.1, §3.3-3.4, Algorithm 1), size-erased over the
// storage that Mapper<Profile> owns:
//   1 predict the pose from wheel odometry and de-skew the scan;
//   2 first registration: scan -> submap (improved PLICP), lines re-extracted every K1 scans;
//   3 every Ks scans and on entering a region: second registration, submap -> regional map
//     (here: the current one and the one the robot came from, in one reference; the paper uses
//     the current one), lines re-extracted every K2 scans; the correction moves the submap (and
//     the robot with it);
//   4 insert the scan into the submap (ring of N) and once into the current regional map.
// Frames: the robot pose lives in the submap frame; submap_pose_ places that frame in the world;
// each regional map's cells are in its anchor frame.
#pragma once

#include <cstdint>

#include "core/config.hpp"
#include "core/mapper_types.hpp"
#include "core/front_end/first_registration.hpp"
#include "core/front_end/odometry_buffer.hpp"
#include "core/registration/plicp.hpp"
#include "core/front_end/region_tracker.hpp"
#include "core/registration/registration_reference.hpp"
#include "core/geometry/scan.hpp"
#include "core/geometry/scan_projection.hpp"
#include "core/front_end/submap.hpp"
#include "core/grid/tiled_grid.hpp"

// The per-stage cost budgets (tests/budget/stage_cost.sh, label "budget") count instructions by
// function: stage functions stay out of line so that callgrind sees each as one call.
#define DPCR_STAGE __attribute__((noinline))

namespace dpcr {

struct RegionalMap {
  RegionKey key;
  Pose2 anchor;              // the map's frame in the world; the back end moves it
  TiledGrid* grid = nullptr;  // points into the Mapper's storage
  std::uint32_t scans_inserted = 0;
};

// Counts of what the registrations did (metrics.json "front_end").
struct FrontEndCounters {
  std::uint32_t first_registrations = 0;
  std::uint32_t first_rejected = 0;
  std::uint32_t second_registrations = 0;
  std::uint32_t second_rejected = 0;
  std::uint32_t submap_line_builds = 0;
  std::uint32_t region_line_builds = 0;
  std::uint32_t reference_cells_dropped = 0;  // obstacle cells past a reference's capacity
  std::uint32_t submap_early_builds = 0;      // submap references rebuilt after a weak match
  FirstRegistrationStats search;               // the coarse pose search of the first registration
};

struct FrontEndStorage {
  Submap* submap = nullptr;
  RegistrationReference* submap_reference = nullptr;
  RegistrationReference* region_reference = nullptr;
  Span<RegionalMap> regions;
  Span<Point2> hits;       // kMaxBeams each
  Span<Point2> free_ends;
  Span<Point2> target;     // second-registration target points (submap obstacle cells)
  Span<CellIndex> scratch;
  Span<Correspondence> correspondences;  // registration scratch, kMaxBeams
  CoarseScoreGrid* search_grid = nullptr;  // the first registration's coarse search (null: none)
};

class FrontEnd {
 public:
  explicit FrontEnd(const FrontEndStorage& storage) : s_(storage) {}
  FrontEnd(const FrontEnd&) = delete;
  FrontEnd& operator=(const FrontEnd&) = delete;

  Status Init(const MapperConfig& config);
  void AddOdometry(const OdometrySample& sample);
  Status AddScan(Span<const Beam> beams, std::int64_t stamp_us);

  Pose2 pose() const { return submap_pose_ * pose_; }
  MapperStatus status() const { return status_; }
  const MapperCounters& counters() const { return counters_; }
  const FrontEndCounters& front_end_counters() const { return fe_counters_; }
  const MapperConfig& config() const { return config_; }
  int region_count() const { return region_count_; }
  const RegionalMap& region(int i) const { return s_.regions[static_cast<std::size_t>(i)]; }
  bool registration_enabled() const { return config_.front_end.enable_registration; }

 private:
  // Stages (budgeted): prediction = Predict + ProjectScan; first registration = RegisterScan;
  // second registration = RegisterSubmap; insertion = Submap::Add + InsertIntoRegion +
  // SeedRegionFromSubmap; line extraction = RegistrationReference::Build (submap) +
  // BuildRegionReference + RefitSubmapLines.
  DPCR_STAGE Pose2 Predict(std::int64_t stamp_us);
  DPCR_STAGE void RegisterScan(std::size_t hits, const Pose2& predicted);
  DPCR_STAGE void BuildRegionReference(const int (&maps)[2], int n);
  DPCR_STAGE void RegisterSubmap(RegionalMap& r);
  DPCR_STAGE void InsertIntoRegion(const ProjectedScan& projected);
  DPCR_STAGE void SeedRegionFromSubmap(RegionalMap& r);
  void RebuildSubmapReferenceIfDue();
  DPCR_STAGE void RefitSubmapLines();
  void EnterRegion(bool first);
  void SecondRegistration();
  // The regional maps the second registration aligns to (1 or 2; 0: none yet); the first one's
  // frame is the registration's frame.
  int ReferenceMaps(int (&maps)[2]) const;
  bool WellInside(const RegionalMap& r) const;
  void UpdateStatus();

  FrontEndStorage s_;
  MapperConfig config_;
  MapperStatus status_ = MapperStatus::kWaitingForData;
  MapperCounters counters_;
  FrontEndCounters fe_counters_;
  OdometryBuffer odometry_;
  RegionTracker tracker_;
  Pose2 pose_;         // robot in the submap frame
  Pose2 submap_pose_;  // submap frame in the world
  Pose2 last_odom_;
  static constexpr std::uint32_t kMinScansBetweenEarlyBuilds = 2;
  bool weak_match_ = false;  // the last first registration matched weakly (see FrontEndConfig)
  std::uint32_t search_grid_version_ = 0;  // submap_line_builds when the search grid was built
  bool have_odom_ = false;
  bool have_scan_ = false;
  bool pool_full_ = false;
  int consecutive_rejections_ = 0;
  int region_count_ = 0;
  int current_region_ = -1;
  int previous_region_ = -1;  // the region the robot was in before current_region_
  int reference_maps_[2] = {-1, -1};  // whose lines region_reference holds (-1: none)
  std::uint32_t scans_since_submap_lines_ = 0;
  std::uint32_t scans_since_region_lines_ = 0;
  std::uint32_t scans_since_second_ = 0;
  std::uint32_t stamp_ = 0;
};

}  // namespace dpcr
