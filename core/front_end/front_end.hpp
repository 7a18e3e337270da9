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

#include <cmath>
#include <cstdint>

#include "core/back_end/back_end.hpp"
#include "core/back_end/global_localiser.hpp"
#include "core/base/stage.hpp"
#include "core/config.hpp"
#include "core/front_end/first_registration.hpp"
#include "core/front_end/odometry_buffer.hpp"
#include "core/front_end/odometry_calibration.hpp"
#include "core/front_end/odometry_stall.hpp"
#include "core/front_end/region_set.hpp"
#include "core/front_end/region_tracker.hpp"
#include "core/front_end/scan_motion.hpp"
#include "core/front_end/start_heading.hpp"
#include "core/front_end/start_scans.hpp"
#include "core/front_end/submap.hpp"
#include "core/front_end/wheel_check.hpp"
#include "core/geometry/scan.hpp"
#include "core/geometry/scan_projection.hpp"
#include "core/grid/scan_marker.hpp"
#include "core/mapper_types.hpp"
#include "core/registration/plicp.hpp"
#include "core/registration/registration_reference.hpp"

namespace dpcr {

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
  // Submap references built with the threshold lowered for a lidar that returns few of its
  // readings (FrontEndConfig::sparse_reference_full_share), and that share as it stands
  // (UpdateReturnShare: the running share of returns where the lidar sees anything).
  std::uint32_t submap_sparse_builds = 0;
  float return_share = 1.0f;
  std::uint32_t redeskews = 0;     // scans projected and registered again with the motion found (no wheels)
  std::uint32_t bent_tracked = 0;  // bent scans tracked past the residual bound (FrontEnd::TrackBent)
  // Accepted first registrations moved back toward the constant velocity's guess along a direction
  // the walls barely fix (FrontEndConfig::weak_direction_information; no wheels).
  std::uint32_t weak_direction_holds = 0;
  // First registrations rejected from the wheels' prediction that were tried again from the
  // constant velocity's (FrontEndConfig::odometry_doubt_*), and how many of those were accepted.
  std::uint32_t odometry_doubted = 0;
  std::uint32_t odometry_overruled = 0;
  std::uint32_t odometry_stalls = 0;  // catch-ups taken from where the wheels stalled (OdometryStall)
  // Fixed-lag de-skew (FrontEndConfig::lidar_only_fixed_lag): scans registered again once projected
  // with the motion over their own revolution (accepted), and scans kept out as bent
  // (scans_kept_out_bent) that went into the maps after all.
  std::uint32_t lag_reregistered = 0;
  std::uint32_t lag_bent_taken = 0;
  // The new map's grid against the robot's first pose (FrontEndConfig::grid_turn_rad): the first
  // scan's wall direction modulo 90 degrees in the robot frame (NaN: not looked for or none found)
  // and the turn applied.
  float first_wall_direction_rad = NAN;
  float grid_turn_rad = 0.0f;
  FirstRegistrationStats search;               // the coarse pose search of the first registration
};

// The arrays the front end works in (Mapper<Profile> owns them). The front end keeps this part;
// the back end keeps its own (FrontEndStorage::back_end), and the front end reaches it there.
struct FrontEndBuffers {
  Submap* submap = nullptr;
  RegistrationReference* submap_reference = nullptr;
  RegistrationReference* region_reference = nullptr;
  Span<RegionalMap> regions;  // the RegionSet's pool
  Span<Point2> hits;       // kMaxBeams each
  Span<Point2> free_ends;
  Span<Point2> target;     // second-registration target points (submap obstacle cells)
  Span<CellIndex> scratch;  // the RegionSet's InsertRays scratch, kMaxBeams
  Span<Correspondence> correspondences;  // registration scratch, kMaxBeams
  Span<PackedBeam> pending_beams;  // the fixed-lag de-skew's waiting scan, kMaxBeams
  Span<Point2> recorded;  // RecordScanPoints' buffer (host tools; empty on the robot)
  CoarseScoreGrid* search_grid = nullptr;  // the first registration's coarse search (null: none)
};

struct FrontEndStorage : FrontEndBuffers {
  BackEndStorage back_end;
};

class FrontEnd {
 public:
  explicit FrontEnd(const FrontEndStorage& storage)
      : s_(storage), regions_(storage.regions, storage.scratch), back_end_(storage.back_end) {}
  FrontEnd(const FrontEnd&) = delete;
  FrontEnd& operator=(const FrontEnd&) = delete;

  Status Init(const MapperConfig& config);
  // false: the sample was implausible (counted in odometry_rejected) and dropped.
  bool AddOdometry(const OdometrySample& sample);
  Status AddScan(Span<const Beam> beams, std::int64_t stamp_us);

  Pose2 pose() const { return submap_pose_ * pose_; }
  MapperStatus status() const { return status_; }
  const MapperCounters& counters() const { return counters_; }
  const FrontEndCounters& front_end_counters() const { return fe_counters_; }
  const WheelCheck& wheel_check() const { return wheel_check_; }
  const OdometryCalibration& odometry_calibration() const { return calibration_; }
  const MapperConfig& config() const { return config_; }
  int region_count() const { return regions_.size(); }
  const RegionalMap& region(int i) const { return regions_[i]; }
  bool registration_enabled() const { return config_.front_end.enable_registration; }
  const BackEnd& back_end() const { return back_end_; }
  // Where the last scan went: its regional map (-1: none, e.g. a full pool) and the robot's pose
  // in that map's frame. Its world pose after later optimisations is the map's anchor times it.
  int last_scan_region() const { return last_scan_region_; }
  const Pose2& last_scan_in_region() const { return last_scan_in_region_; }
  // The final world pose of a scan recorded after AddScan as (its stamp, last_scan_region(),
  // last_scan_in_region(), pose()): its map's anchor now times its pose in the map; a scan in no
  // map keeps its online pose, turned with the grid if it came before the grid's turn (a skipped
  // spin-up). The start scan, and the scans before it, follow the start heading once the gyro
  // has refined it (start_heading.hpp): the map's frame stays, the start moves.
  Pose2 ScanWorldPose(std::int64_t stamp_us, int region, const Pose2& in_region, const Pose2& online) const;
  const StartHeadingFit& start_heading() const { return start_heading_; }
  // At the end of a run, before the trajectory is written: the kept start scans registered again
  // against the finished first map place the start in it (start_scans.hpp); ScanWorldPose then
  // turns the start by that offset instead of the start heading fit's. Without wheels measuring
  // the translation the start scan is also searched for in that map, and the start moves to where
  // it is found when that is far from where it was recorded (StartScansConfig::locate).
  // Builds the regional reference (a loop-closure search in progress is cancelled, and so is a
  // lost robot's search: the start's uses the localiser) and gives the kept scans' tiles back.
  // Once refined, later calls return the same offset and move.
  StartRefinement RefineStart();

  // For a trajectory refined after the run (host tools: host_sim/output/trajectory_refinement.hpp).
  // Given a buffer (kMaxBeams points; none on the robot), AddScan copies into it the returns of
  // each scan it places while tracking, in the robot frame and de-skewed as registered, before the
  // maps take them; recorded_points() says how many (0: this scan was not recorded: a lost robot's,
  // one held back by the fixed-lag de-skew, one without returns, or a bad stamp).
  void RecordScanPoints(Span<Point2> buffer) { s_.recorded = buffer; }
  std::size_t recorded_points() const { return recorded_points_; }
  // At the end of a run: BeginMapRegistration builds one reference of map `region` as it is now and,
  // unless `other` is -1, map `other` placed by the two anchors (false: no such map), cancelling a
  // loop-closure search in progress; then each RegisterInMap registers recorded points from their
  // pose in `region`'s frame, `in_region`, with the first registration's prior and acceptance and at
  // most `max_iterations` steps.
  bool BeginMapRegistration(int region, int other = -1);
  RegistrationResult RegisterInMap(Span<const Point2> robot_points, const Pose2& in_region, int max_iterations);

  // Loading a saved map (core/persistence/map_reader.hpp; front_end_restore.cpp), after Init:
  // RestoreRegion appends the regional maps in their saved order (nullptr: pool full); after the
  // graph, RestoreStart puts the robot at `start` in the saved world frame, on the saved region
  // lattice, in its region (a new one is chained to the nearest saved map), so that mapping goes
  // on in the same frame and new regions join the same graph.
  RegionalMap* RestoreRegion(RegionKey key, const Pose2& anchor, std::uint32_t scans_inserted);
  void RestoreStart(Point2 region_origin, const Pose2& start);
  // The world centre of region (0, 0): the region lattice a saved map keeps.
  Point2 region_origin() const { return tracker_.Centre(RegionKey{}); }

 private:
  // Stages (budgeted): prediction = Predict + ProjectScan; first registration = RegisterScan;
  // second registration = RegisterSubmap; insertion = Submap::Add + RegionSet::InsertScan +
  // RegionSet::SeedFromSubmap; line extraction = RegistrationReference::Build (submap) +
  // BuildRegionReference + RefitSubmapLines.
  // The time since the previous scan, 0 across a clock jump (counted); remembers this stamp.
  std::int64_t ScanInterval(std::int64_t stamp_us);
  DPCR_STAGE Pose2 Predict(std::int64_t stamp_us, std::int64_t dt_us);
  // The last scan-to-scan motion scaled to `dt_us` (the constant-velocity part of the prediction),
  // and per second (the de-skew's, core/front_end/scan_motion.hpp).
  Pose2 ConstantVelocity(std::int64_t dt_us) const;
  Pose2 VelocityPerSecond() const;
  // The wheels' step since the last scan (their pose now: `odom`), calibrated, a stall's catch-up
  // taken from where it stalled (OdometryCalibration, OdometryStall; the constant velocity's step
  // tells a catch-up from wheels that resume where they stopped); and, after the scan's
  // registration, what those learn from it.
  Pose2 WheelStep(const Pose2& odom, bool wheels, const Pose2& constant_velocity);
  void AfterWheelStep(const Pose2& registered_step, std::int64_t stamp_us, bool registered, bool keep_out, bool clean_fit);
  void WheelsUnmeasured(std::int64_t stamp_us);
  // The scan's registered step as the next constant-velocity guess (acceleration_limit.hpp).
  Pose2 GuessedVelocityStep(const Pose2& step, std::int64_t dt_us) const;
  // After a rejected scan: the last motion fades (see the definition for what is held).
  void FadeConstantVelocity();
  bool HoldsVelocity() const {
    return HeadingMeasured() && !WheelsMeasured() && streak_us_ <= kHoldTranslationInStreakUs;
  }
  // Returns whether the scan was accepted and FitsCleanly (WheelCheck::AddScan takes only such
  // fits' word that the wheels spin on).
  DPCR_STAGE bool RegisterScan(Span<const Beam> beams, const ScanMotion& motion, std::int64_t dt_us, ProjectedScan* projected,
                               const Pose2& predicted);
  // Without wheels the de-skew assumed the last motion's velocity; a turn or a drive that started
  // or stopped since leaves the scan bent (a spin-up to 120°/s bends a 5 Hz revolution by ~7°).
  // When the registration's motion differs enough (FrontEndConfig::redeskew_min_*), the beams are
  // projected again with it and registered once more from the first answer.
  // Without wheels the predicted translation is the constant velocity's guess, not a measurement:
  // its prior is this much weaker (at full strength a robot that starts to drive where the walls
  // give little hold along the way stayed where the guess said, for metres: gyro alone, apartment
  // seeds 4 and 6, 2.2 and 2.4 m LocErr_ave; at 0.1 0.10 and 0.05 m; at 0.02 0.27 and 0.08 m).
  static constexpr float kPriorXyWithoutWheels = 0.1f;
  // Wheels whose translation the WheelCheck doubts count as none.
  bool WheelsTranslate(const ScanMotion& motion) const { return motion.wheels() && !wheel_check_.translation_doubted(); }
  // A measured turn this fast (29 deg/s) is a turn in place or on a tight arc: a vacuum's lanes
  // are straight, and it turns between them standing (FrontEndConfig::turn_holds_translation).
  static constexpr float kTurnInPlaceRadS = 0.5f;
  bool TurningInPlace(std::int64_t dt_us) const {
    return config_.front_end.turn_holds_translation && step_turn_measured_ && dt_us > 0 &&
           std::fabs(step_turn_) * 1e6f > kTurnInPlaceRadS * static_cast<float>(dt_us);
  }
  float PriorXyScale(const ScanMotion& motion, std::int64_t dt_us) const {
    return WheelsTranslate(motion) || TurningInPlace(dt_us) ? 1.0f : kPriorXyWithoutWheels;
  }
  // Without wheels the constant velocity guesses the step; one scan after a tracked one the robot
  // cannot be this far from it (a vacuum's acceleration changes a 5 Hz step by centimetres), but
  // the weak prior lets a look-alike (a doorway, a row of chair legs) pull the pose half a metre
  // along: such a registration is rejected. (Gyro alone, apartment seed 10: 1.7 m in one second.)
  static constexpr float kMaxLeapWithoutWheelsM = 0.2f;
  // With a heading sensor but no wheels a run of registrations, each close to the constant
  // velocity, can still race away along such a place (heading ticks, spins, a 3.5-5 Hz lidar,
  // seed 2: 0.66 m/s estimated for 3 s, 3.6 m LocErr_ave; 0.05 m with this cap): faster than twice
  // a vacuum's top speed is not taken.
  static constexpr float kMaxSpeedWithoutWheelsMps = 0.6f;
  bool ImplausibleWithoutWheels(const Pose2& registered, const Pose2& predicted, const ScanMotion& motion,
                                std::int64_t dt_us) const;
  // Whether an accepted first registration keeps near the constant velocity's guess along the
  // directions the walls barely fix (FrontEndConfig::weak_direction_information).
  bool GuessHoldsWeakDirections(const ScanMotion& motion, std::int64_t dt_us) const;
  // Without wheels or a gyro the predicted turn is the constant velocity's guess too: a turn that
  // speeds up or slows down is not in it, and at full strength its prior held each step short of
  // the turn (XV-11 at 5 Hz, no odometry: 1-3 deg of heading lost per start or stop of a turn;
  // apartment seeds 1-10 LocErr_ave 0.55 m at 0.3 against several metres at 1).
  static constexpr float kPriorThetaWithoutHeading = 0.3f;
  static float PriorThetaScale(const ScanMotion& motion) { return motion.wheels() || motion.gyro() ? 1.0f : kPriorThetaWithoutHeading; }
  // Wheels measure the translation (the newest odometry sample says; the wheel check may have set
  // them aside), wheels or a gyro the turns.
  bool WheelsMeasured() const { return !odometry_.empty() && odometry_.newest().has_wheels; }
  bool HeadingMeasured() const { return WheelsMeasured() || (!odometry_.empty() && odometry_.newest().has_gyro); }
  // A first registration rejected from the wheels' prediction, tried again from the constant
  // velocity's when they differ by more than FrontEndConfig::odometry_doubt_*: the answer if
  // accepted, else `rejected`. (The scan was projected with the wheels' motion: logged odometry
  // carries no beam times, and a device's wheels that glitch between two revolutions bend neither.)
  RegistrationResult RegisterFromConstantVelocity(std::size_t hits, bool sparse, std::int64_t dt_us, const Pose2& predicted,
                                                  const RegistrationResult& rejected);
  // A rejected registration of a bent scan accepted for its pose when only the residual bound
  // failed, up to twice it (counted bent_tracked); `from`: where the registration started.
  RegistrationResult TrackBent(RegistrationResult r, const Pose2& from);
  // `sparse`: the scan is (SparseScan), as in the registrations after it.
  RegistrationResult RegisterRedeskewed(Span<const Beam> beams, const ScanMotion& motion, std::int64_t dt_us, bool sparse,
                                        ProjectedScan* projected, const RegistrationResult& first);
  DPCR_STAGE void BuildRegionReference(const int (&maps)[2], int n);
  DPCR_STAGE RegistrationResult RegisterSubmap(RegionalMap& r);
  // Into map `index`: the current one, or the anchor map while the robot cannot place itself in
  // the current one (its pose is known in the anchor's frame, so that map takes the scan unsmeared).
  // `world`: the scan's pose (the robot's, or the fixed-lag de-skew's waiting scan's).
  void InsertIntoRegion(const ProjectedScan& projected, int index, const Pose2& world);
  // Once into the current regional map, or the anchor map while the robot cannot place itself in
  // the current one; not a scan kept out, nor one taken turning fast, nor in localise-only mode
  // (false, counted).
  bool InsertIntoMaps(const ProjectedScan& projected, const Pose2& world, bool keep_out, bool turning);
  // The last scan-to-scan motion turned faster than LidarConfig::map_max_turn_rate_rad_s.
  bool TurningFast() const;
  // Whether the regional maps keep hit means (GridConfig::hit_means): only behind a lidar that
  // declares its range noise (FrontEnd::Init).
  bool HitMeans() const { return config_.grid.hit_means && config_.lidar.range_noise_m > 0.0f; }
  // An empty scan, or a sparse one while the submap is empty (FrontEndConfig::min_start_hits):
  // the pose is the prediction and the scan goes nowhere (counted). True when skipped.
  bool SkipScan(const ProjectedScan& projected, const Pose2& predicted);
  // After a scan has gone into the maps: the run's start scan (its first not skipped) begins the
  // start heading's fit when it went into a map; every later scan feeds it (FeedStartHeading), a
  // skipped one too (SkipScan).
  void FitStartHeading(std::int64_t stamp_us, bool start_scan, bool accepted);
  void FeedStartHeading(bool accepted);
  // A lost robot: the start heading's fit aborts, the start scans keep no more.
  void StopStartFits();
  // Before the regional map takes the scan: the start scan begins the kept start scans (with a
  // gyro's yaw, or the wheels' heading), later ones are kept when due; a pool that ran out takes
  // their tiles back (front_end_start_scans.cpp).
  void KeepStartScan(std::int64_t stamp_us, bool start_scan, std::size_t hits, bool accepted);
  // What every scan starts from: its marker for the grids, nothing recorded, not bent yet.
  void BeginScan();
  // The scan's returns (s_.hits, robot frame) to the start scans (KeepStartScan) and the
  // RecordScanPoints buffer, before the maps take them into their frames.
  void KeepScanPoints(std::int64_t stamp_us, bool start_scan, std::size_t hits, bool accepted);
  // The gyro's yaw at the start scan (false: no gyro).
  bool StartGyroYaw(std::int64_t stamp_us, float* yaw) const;
  // RefineStart's parts: the kept scans' headings in the finished first map (the offset), and the
  // start scan searched for in it (the move; the global localiser's local round, run to its end).
  void FitStartInMap(StartRefinement* out);
  void LocateStart(StartRefinement* out);
  // LocateStart's move (start_shift_mm_) in metres, and whether there is one.
  Pose2 StartShift() const {
    return Pose2{static_cast<float>(start_shift_mm_[0]) * 1e-3f, static_cast<float>(start_shift_mm_[1]) * 1e-3f, 0.0f};
  }
  bool StartMoved() const { return start_shift_mm_[0] != 0 || start_shift_mm_[1] != 0; }
  // The run's first scan not skipped, into a new map: turns the world frame about its origin, and
  // the robot's poses in it (pose_, `previous`, `predicted`), so that the scan's walls lie off the
  // grid's axes when they lie along them (FrontEndConfig::grid_turn_rad; recorded in fe_counters_).
  // Scans skipped before it (a spin-up) keep their reported poses; ScanWorldPose turns them.
  void TurnFrameFromWalls(std::int64_t stamp_us, Span<const Point2> hits, Pose2* previous, Pose2* predicted);
  // Without wheels, a scan whose velocity changed much since the last one (a turn starting or
  // stopping: twice FrontEndConfig::redeskew_min_*) is registered but kept out of the maps, which so
  // keep only well de-skewed scans; registration against them is absolute, so the bent scan's
  // error does not stay. At most kMaxBentKeptOut in a row; a submap of one scan takes the bent
  // scan in its place. True when kept out (counted).
  bool KeepOutBent(std::size_t hits);
  // Never smear (FrontEndConfig::uncertain_turn_rad): whether a rejection now would leave the
  // scan placed by an uncertain prediction; after RegisterScan, the streak counters, and true when
  // the scan stays out of the maps (restarting the submap from it after a long streak).
  bool UncertainPrediction(const Pose2& predicted) const;
  bool AfterFirstRegistration(bool uncertain, std::int64_t since_last_us, std::size_t hits);
  void RebuildSubmapReferenceIfDue();
  DPCR_STAGE void RefitSubmapLines();
  // Step 3 of AddScan: the region the robot is in (entering one may close a loop), and the
  // second registration when due.
  void TrackRegions();
  void EnterRegion(bool first);
  // The second registration; `result` (optional) gets the registration's answer when one ran,
  // and `region` the map whose frame it is in. True when accepted. `loop_entry`: against the
  // current map alone (a loop closure must not be pulled by the map the robot drifted in).
  bool SecondRegistration(RegistrationResult* result = nullptr, int* region = nullptr, bool loop_entry = false);
  // The regional maps the second registration aligns to (1 or 2; 0: none yet); the first one's
  // frame is the registration's frame. While the robot cannot place itself in the current map,
  // the anchor map alone.
  int ReferenceMaps(int (&maps)[2], bool loop_entry) const;
  bool WellInside(const RegionalMap& r) const;
  void UpdateStatus();
  // After each scan: last_world_, the status, the lost time.
  void FinishScan(std::int64_t since_last_us);
  // A fresh submap from the current scan at pose_ (the regional maps untouched).
  void RestartSubmap(std::size_t hits);
  // Fixed-lag de-skew (FrontEndConfig::lidar_only_fixed_lag), for a robot with neither wheels nor
  // a gyro: the de-skew of a scan assumes the motion of the revolution before it, which is one
  // revolution late whenever a turn starts or stops, and everything registered to a bent scan
  // inherits the bend (the run's first scan, projected with no motion known, rotated the whole
  // first map by 0.2-2.75 deg). So each scan is registered as it comes, but goes into the maps
  // only once the next one is registered: then the motion over its own revolution is known from
  // both sides, and it is projected again with it and registered again before it goes in.
  bool FixedLag() const;
  // The waiting scan's motion per second over its revolution: the mean of the registered motions
  // before and after it (the scan before to it, it to the current scan), both in its frame. The
  // run's first scan follows a standstill (the robot does not drive before its lidar reports
  // full revolutions); after a gap, the motion after it alone.
  Pose2 PendingVelocity(std::int64_t stamp_us) const;
  // Steps 3-4 with the lag: the waiting scan projected and registered again and inserted (or kept
  // out), the regions and the second registration, then the current scan waits in its place.
  // `current`: the current scan's projection; `first`: it is the run's first (it goes into the
  // submap at once, for the next scan to match); `restarted`: its registration restarted the submap.
  void FlushPendingScan(Span<const Beam> beams, std::int64_t stamp_us, const Pose2& previous, std::int64_t since_last_us,
                        const ProjectedScan& current, bool keep_out, bool bent, bool first, bool restarted);
  // A scan kept out as bent goes in after its second de-skew when it registers again within these
  // of where it was first placed (measured: lidar alone, apartment seeds 1-40; without the bound
  // a turn that stopped short left scans bent both ways, and one seed lost its heading for good).
  static constexpr float kLagBentMaxMoveRad = 0.0349f;  // 2 deg
  static constexpr float kLagBentMaxMoveM = 0.2f;
  // Lost and relocalisation (front_end_relocalise.cpp): whether this scan belongs to the lost
  // path (the wheels lifted, a long rejection streak, an unknown start); the lost path itself
  // (local tracking against a fresh submap, one bounded step of the global search, nothing
  // inserted anywhere); resuming at the pose found.
  bool LostNow();
  // `may_be_near`: lost without a lift, the robot may be where it believes (front_end_relocalise.cpp).
  void StartRelocalisation(bool may_be_near);
  void RelocaliseScan(Span<const Beam> beams, const ScanMotion& motion, std::int64_t dt_us, ProjectedScan* projected,
                      const Pose2& predicted);
  void StepRelocalisation(std::size_t hits);
  // Without a heading sensor (LocalisationConfig::near_window_m): the half-width of the local
  // round's window around the believed pose, 0 when the round is global.
  float NearWindow() const;
  // How far from its belief a robot that lost track without being carried may be: near_window_m +
  // near_window_mps x the time since the streak began (LocalisationConfig).
  float NearDistance() const;
  // Seconds since the streak that lost the robot began (0 or more).
  float LostSeconds() const;
  // The half window of headings a lost robot's search covers about its believed heading
  // (LocalisationConfig::heading_window_rad; 0: every heading).
  float HeadingWindow() const;
  // Whether a verified fix is taken now, clear or agreeing with the held one
  // (LocalisationConfig::clear_min_score); else it is held. Without a heading sensor always; with
  // one only when the fix is past the near window of a robot that was not carried.
  bool TakeFix(const GlobalFix& fix);
  // A robot that lost track where it was (not carried) is near its belief: a fix farther than the
  // near window (LocalisationConfig::near_window_m) from it is a look-alike as often as a slip
  // (XV-11, half its readings, gyro alone, seed 4: a fix 3.4 m back along the robot's lane).
  bool PastNearWindow(const GlobalFix& fix) const;
  // The submap frame in the world by a fix of the frozen scan.
  Pose2 SubmapFrameOf(const GlobalFix& fix) const;
  void ResumeAt(const GlobalFix& fix);
  // Back on the region lattice at the current pose, found in map `found`.
  void Rejoin(int found);
  // Localise-only (maps frozen): entering a region makes its map current if it has one (no new
  // map, no back-end job, no closure) and aligns the submap to it at once.
  void EnterFrozenRegion();
  // Makes region `key` current (a new one chained to map `from`) and the anchor; counts a full pool.
  void EnterRegionChainedTo(RegionKey key, int from);
  // Back end: the region just left, a loop closure on re-entry, one queued job per scan.
  void OnRegionLeft(int left);
  // The regional reference no longer holds what reference_maps_ says (the back end used its
  // storage or moved anchors): the next second registration rebuilds it.
  void InvalidateRegionReference();
  void EnterKnownRegion();
  // A loop-closure search for the current map (the robot's pose known in map `from`), run by
  // the back end in slices; its end refines and offers the closure, and on success places the
  // robot in the map.
  void BeginLoopClosure(int from);
  void FinishLoopClosure();
  void StepBackEnd();
  // The submap's obstacle cells (from its reference), thinned to the target capacity, moved so
  // that their centroid, target_pivot_ in the submap's frame, is their origin.
  std::size_t SubmapTarget();

  FrontEndBuffers s_;
  MapperConfig config_;
  MapperStatus status_ = MapperStatus::kWaitingForData;
  MapperCounters counters_;
  FrontEndCounters fe_counters_;
  OdometryBuffer odometry_;
  WheelCheck wheel_check_;  // wheels that miss the motion the lidar sees become a heading source at most
  OdometryCalibration calibration_;  // the wheels' step and turn scales, from the registrations
  Pose2 wheel_step_;  // the wheels' step into the current scan, as measured (WheelStep)
  OdometryStall stall_;  // wheels whose pose repeats while the robot moves, then catches up
  RegionTracker tracker_;
  RegionSet regions_;
  Pose2 pose_;         // robot in the submap frame
  Pose2 submap_pose_;  // submap frame in the world
  Point2 target_pivot_;  // where the submap target's points were centred (SubmapTarget), in the submap frame
  Pose2 last_odom_;  // the odometry pose at the last scan's stamp (Predict)
  Pose2 last_motion_;  // the last scan-to-scan motion, in the earlier scan's frame
  std::int32_t last_motion_us_ = 0;   // the time it took
  static constexpr float kMaxVelocityScale = 2.0f;
  // How long a rejection streak keeps the constant velocity's translation (FadeConstantVelocity):
  // a vacuum that stopped meanwhile is carried at most this far at its last speed.
  static constexpr std::int64_t kHoldTranslationInStreakUs = 2'000'000;
  static constexpr std::uint32_t kMinScansBetweenEarlyBuilds = 2;
  std::uint32_t search_grid_version_ = 0;  // submap_line_builds when the search grid was built
  bool weak_match_ = false;  // the last first registration matched weakly (see FrontEndConfig)
  bool last_degenerate_ = false;  // the last first registration was accepted degenerate (FrontEndConfig::degenerate_guess_forward)
  bool have_odom_ = false;
  bool have_gyro_yaw_ = false;  // last_gyro_yaw_ holds the gyro yaw at the last prediction
  bool have_scan_ = false;
  float last_gyro_yaw_ = 0.0f;
  int consecutive_rejections_ = 0;
  int consecutive_second_rejections_ = 0;  // in a mature regional map (TrackRegions)
  bool restart_pending_ = false;  // a submap restart is due, waiting for a scan with enough returns
  bool grid_turn_pending_ = false;  // no scan has been mapped yet: the next one may turn the grid
  // The start heading's fit (FitStartHeading): pending until the run's first scan not skipped;
  // the last prediction's turn, whether a sensor measured it and whether the wheels did; whether
  // any turn since the start came from the wheels; the start scan's map and pose in it.
  // (The flags here, beside the two above and the two below, fill what was padding.)
  bool start_pending_ = false;
  bool step_turn_measured_ = false;
  bool step_turn_from_wheels_ = false;
  bool wheel_step_valid_ = false;  // wheel_step_ holds one scan's step of the wheels (not a catch-up)
  bool start_wheel_turns_ = false;
  bool bent_ = false;             // the last scan's de-skew was doubtful (RegisterRedeskewed)
  std::uint8_t bent_kept_out_ = 0;  // bent scans kept out in a row
  // RefineStart's move of the start (StartScansConfig::locate), millimetres in the
  // recorded start's frame (in what was padding).
  std::int16_t start_shift_mm_[2] = {0, 0};
  std::int64_t grid_turn_stamp_us_ = 0;  // the scan that could turn it; scans before it were in the old frame
  float step_turn_ = 0.0f;
  float start_offset_rad_ = NAN;  // RefineStart's (NaN: not refined)
  StartHeadingFit start_heading_;
  StartScans start_scans_;  // it keeps the start scan's stamp too
  int start_region_ = -1;
  Pose2 start_in_region_;
  static constexpr std::uint8_t kMaxBentKeptOut = 5;  // then one goes in: the submap must not go stale
  std::int64_t last_stamp_us_ = -1;  // the last scan's stamp, where pose_ is (-1: none yet)
  std::int64_t streak_us_ = 0;       // time covered by the current rejection streak
  int reference_maps_[2] = {-1, -1};  // whose lines region_reference holds (-1: none)
  std::uint32_t scans_since_submap_lines_ = 0;
  std::uint32_t scans_since_second_ = 0;
  // Second registrations since region_reference was built (each one Ks scans apart).
  std::uint32_t second_registrations_since_region_lines_ = 0;
  ScanMarker scan_marker_;
  BackEnd back_end_;
  float path_m_ = 0.0f;  // length of the robot's path so far (world frame)
  Pose2 last_world_;
  int last_scan_region_ = -1;
  // The regional map the robot's pose is known in: the one it is in, or, after entering a known
  // map it could not place itself in (lost_in_region_), the last one it could.
  int anchor_region_ = -1;
  bool lost_in_region_ = false;
  // Lost (front_end_relocalise.cpp; beside lost_in_region_, in what was padding).
  bool relocalising_ = false;
  bool restart_submap_ = false;  // the next scan on the floor starts a fresh submap
  bool may_be_near_ = false;     // lost without a lift: the second registration may find it
  bool near_failed_ = false;     // without a heading sensor: the local round failed, search globally
  // This scan, bent, found a submap of one scan: the waiting scan, de-skewed from both sides,
  // takes that scan's place (KeepOutBent).
  bool bent_against_single_ = false;
  std::uint32_t scans_since_closure_try_ = 0;
  float path_at_closure_try_ = 0.0f;
  Pose2 last_scan_in_region_;
  std::size_t recorded_points_ = 0;  // RecordScanPoints: points copied from the last scan
  // Lost: the global search, and the robot's pose in the submap frame at the scan it searches
  // with (the submap tracks the robot meanwhile, so the answer carries to the current scan).
  GlobalLocaliser localiser_;
  Pose2 frozen_in_submap_;
  std::int64_t lost_since_us_ = 0;  // when the trouble began: the rejection streak's first scan
  // The fixed-lag de-skew's waiting scan (its beams packed in s_.pending_beams).
  struct PendingScan {
    bool active = false;
    bool first = false;     // the run's first scan: in the submap already, projected with no motion
    bool kept_out = false;  // out of the maps (its registration was rejected, or bent)
    bool bent = false;      // kept out as bent (KeepOutBent)
    bool rejected = false;  // its first registration was rejected
    bool turning = false;   // taken turning fast (TurningFast): out of the regional maps
    std::uint16_t beams = 0;
    std::int64_t stamp_us = 0;
    std::int64_t since_before_us = 0;  // since the scan before it (0: none)
    Pose2 pose;    // in the submap frame
    Pose2 before;  // the scan before it, in the submap frame
  };
  PendingScan pending_;
};

}  // namespace dpcr
