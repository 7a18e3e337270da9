// Run-time parameters of the mapper, with the paper's defaults (Cao et al. 2025, §3-4), in one struct.
// Validate() runs once at start-up; nothing below re-checks them.
#pragma once

#include <cstdint>

#include "core/back_end/back_end_config.hpp"
#include "core/back_end/localisation_config.hpp"
#include "core/registration/plicp.hpp"
#include "core/geometry/pose2.hpp"
#include "core/registration/registration_reference.hpp"
#include "core/registration/rotation_search.hpp"
#include "core/base/status.hpp"

namespace dpcr {

struct GridConfig {
  float resolution_m = 0.05f;  // w_g: the paper's grid width
  // Log-odds in Q10 (1024 = 1 nat). Hit 0.7 -> +0.847 nat, miss 0.4 -> -0.405 nat.
  std::int16_t hit_delta = 867;
  std::int16_t miss_delta = -415;
  // Clamp at +-3.5 nat (p = 0.97 / 0.03) so that moved furniture can be unlearnt.
  std::int16_t clamp_max = 3584;
  std::int16_t clamp_min = -3584;
  // Regional-map cells that reach a clamp are settled and keep their value (TiledGrid::
  // set_settle_at_bounds): a settled map cannot follow the robot's drift (measured:
  // docs/front-end-accuracy.md). The price: a wall or free space that has settled is not unlearnt
  // when furniture moves.
  bool settle_at_clamp = true;
  // ...unless the scans keep contradicting it: a settled cell counts the scans that observed the
  // opposite since one last agreed with it, and after this many learns again (0: never). A
  // person who stood still, a door that opened, leave occupied cells that only such a count can
  // clear; a drifted scan does not clear a wall this way, since the wall's own returns keep
  // resetting the count. Off by default: at 50 it unlearns the ghosts of people who stood (12
  // cells -> 1 over ten runs) and of open doors, at an unchanged mean LocErr_ave without people,
  // but it also unlearns cells a wall only partly covers, and ten save/load sessions drift a
  // little more (measured: docs/relocalisation.md, "A home that changes").
  std::uint8_t unsettle_occupied_after = 0;
  // The same for settled free cells that keep being hit (a door that closed, furniture moved in).
  std::uint8_t unsettle_free_after = 0;
  // Settled occupied cells of the regional maps learn where in them the returns fall (their hit
  // means, core/grid/hit_mean.hpp), and the maps' lines are fitted to those positions rather than
  // to cell centres. Needs settle_at_clamp and clamp_max below kHitMeanCodeBase (4096).
  bool hit_means = true;
  // A return 2 m or more away that lies behind a settled wall along its own ray, 2 to this many
  // cells behind a settled occupied cell, is range noise carried through the wall (1 cm + 0.5 %
  // of the range on an LD06-class lidar: 5 cm at 8 m) and is dropped (its ray too). Nothing else
  // reaches a cell behind a wall, so without this such cells collect those hits session after
  // session and thicken the walls the lines are fitted to. 0 or 1: none dropped. At 5 (on since
  // 2026-11-30): apartment mean LocErr_ave 0.049 -> 0.037 m, office 0.083 -> 0.039 m, intel all
  // pairs 0.034 -> 0.032 m, ten sessions' off-wall growth gone (docs/relocalisation.md).
  std::uint8_t drop_hits_behind_settled_cells = 5;
  // Only a ray's cells farther than this before its return count against a settled occupied
  // cell: a scan inserted a few centimetres off puts its misses just before the returns, on the
  // wall it should have hit; a ray that crosses a cell and returns far behind it says the cell is
  // empty.
  float unsettle_miss_margin_m = 0.3f;
  // A ray to a return clears cells only up to this distance before the return. Range noise
  // (1-3.5 cm on an LD06-class lidar) puts some returns of a wall in front of it and some
  // behind: without the margin, the rays of the longer returns clear the cells the shorter ones
  // marked, scan after scan (measured: docs/front-end-accuracy.md).
  float hit_margin_m = 0.05f;
};

// The deltas of a grid that learns at `rate` of `g`'s (rounded towards 0); the rest as is.
inline GridConfig ScaledLearning(const GridConfig& g, float rate) {
  GridConfig s = g;
  s.hit_delta = static_cast<std::int16_t>(static_cast<float>(g.hit_delta) * rate);
  s.miss_delta = static_cast<std::int16_t>(static_cast<float>(g.miss_delta) * rate);
  return s;
}

struct LidarConfig {
  float min_range_m = 0.02f;
  float max_range_m = 12.0f;  // R: LD06/LD19 range
  // Beams with no return clear free space up to this distance (0 = they clear nothing).
  float no_return_free_m = 0.0f;
  Pose2 mount;  // the lidar's pose in the robot frame
  // Junk filter (a low-cost lidar's stray readings, e.g. an XV-11's): a return that no valid
  // return within two beams on either side confirms (|range difference| <= k beams x (5 cm + 5 %
  // of its range)) is dropped and counted (MapperCounters::beams_isolated). A junk range reaches
  // through walls, up to 6 m: each would put an obstacle, and a tile, outside the home. Off by
  // default: a clean lidar's single-beam returns (a chair leg) are real.
  bool drop_isolated_returns = false;
  // The lidar's range noise: its sigma at a room's typical range (3 m); 0 = not known. The first
  // registration never trims residuals below twice this (PlicpConfig::trim_floor_m, when larger):
  // returns that miss their wall by the lidar's own noise are not outliers. Trimmed as such, an
  // LD06's (1 cm + 0.5 % of the range) bend the maps (measured: docs/back-end.md, "The lidar's
  // range noise is what bends the maps"). A SICK LMS (the public logs): ~0.01 m, under the floor.
  float range_noise_m = 0.0f;
  // The widest angle, in beams, between two returns that the range-noise smoothing still takes as
  // neighbours on one wall (ReturnSmoothingConfig::max_gap_beams; a lidar that declares its noise).
  // 1.5: adjacent beams only. An XV-11 loses 30-40 % of its readings, so few of its windows of
  // seven adjacent returns are whole (0.7^7, one in twelve) and its returns went unsmoothed; it
  // sets 3.5 (hal/device_options.hpp): XV-11 + gyro heading, apartment seeds 1-30, LocErr_ave
  // 0.0386 -> 0.0348 m, through the device files 0.0406 -> 0.0341 m (docs/back-end.md, "The
  // XV-11's missing readings").
  float smoothing_max_gap_beams = 1.5f;
  // A vacuum's lidar sits at ankle height: feet, table and chair legs, a pet stand right beside
  // it, and near the lidar a surface is sampled ever more densely (the LD06's beams 7 mm apart
  // at 0.5 m, seven to a 5 cm cell), so a person beside the robot gets as many points as the
  // room. Returns within this distance of the robot weigh distance / this in the first
  // registration (PlicpConfig::near_weight_range_m; 0 = all alike, the default). The vacuum's
  // lidars (hal/device_options.hpp, the simulator) set 0.5 m: apartment with 3 people walking
  // LocErr_ave 0.0269 -> 0.0225 m; intel.clf, whose narrow doorways are near walls, keeps 0
  // (docs/back-end.md "People step aside").
  float near_weight_range_m = 0.0f;
  // A scan taken while the robot turns faster than this (its registered scan-to-scan turn over
  // the time between the scans) is tracked and goes into the submap, but not into the regional
  // maps (MapperCounters::scans_turning_not_mapped); 0 = every scan is mapped. A vacuum turning
  // at a lane's end sweeps 9 degrees during one LD06 revolution; with those scans kept out of the
  // long-lived maps (60 deg/s) their anchors come out closer to the truth: apartment seeds 1-30
  // LocErr_ave 0.0210 -> 0.0194 m, doors 0.0263 -> 0.0218, device path 0.0276 -> 0.0250
  // (docs/back-end.md, "Scans taken in a turn"). The XV-11 (5 Hz, ~250 returns a revolution)
  // keeps 0: its maps lost more than they gained (XV-11 + gyro 0.0330 -> 0.0364, wheels alone
  // 0.060 -> 0.104); the public logs keep 0.
  float map_max_turn_rate_rad_s = 0.0f;
};

// LidarConfig::near_weight_range_m of a vacuum's lidar (0.3 / 0.5 / 1 m measured: 0.5 best).
constexpr float kVacuumNearWeightRangeM = 0.5f;
// LidarConfig::map_max_turn_rate_rad_s of an LD06 on a vacuum: 60 deg/s (45 and 30 measured alike
// on the apartment, 90 keeps every scan of the simulator's 86 deg/s turns).
constexpr float kLd06MapMaxTurnRateRadS = 60.0f * kPi / 180.0f;
// LidarConfig::smoothing_max_gap_beams of an XV-11 (1 degree a beam, 30-40 % of readings invalid):
// two missing beams between neighbours (2.5 / 3.5 / 4.5 / 6 measured on apartment seeds 1-30:
// 0.0380 / 0.0348 / 0.0349 / 0.0366 m, adjacent only 0.0386).
constexpr float kXv11SmoothingMaxGapBeams = 3.5f;

constexpr ReferenceConfig ReferenceWithThreshold(std::int16_t obstacle_threshold) {
  ReferenceConfig c;
  c.obstacle_threshold = obstacle_threshold;
  return c;
}

// The start heading refined with the gyro (core/front_end/start_heading.hpp): applied when a gyro
// gave the turns (FrontEndConfig::gyro_heading, or a gyro without wheels) or wheel ticks that the
// wheel check found to carry only a heading (an IMU's); not for a loaded map.
struct StartHeadingConfig {
  float window_s = 30.0f;  // the fit's window from the start scan; 0 = never refined
  float skip_s = 1.0f;     // the start's first turn, registered to the first scan's walls alone
  int min_samples = 20;    // accepted scans in the window
  // The fit's own error is ~0.15 degrees (gyro noise, registration noise): a smaller offset is left
  // alone (XV-11 with a gyro heading, apartment seeds 1-80; LD06 with a gyro heading unchanged).
  float min_offset_rad = 0.0035f;  // 0.2 degrees
  float max_offset_rad = 0.035f;   // 2 degrees: more is not the first scan's noise
  float max_bias_rad_s = 0.02f;    // 1.1 degrees/s: a gyro further off is not fitted
};

// The start placed in the finished first map (core/front_end/start_scans.hpp): scans of the
// run's first window_s seconds, one every every_s, kept with the gyro's turn since the start and
// registered again against the first map at the end of the run (Mapper::RefineStart).
struct StartScansConfig {
  bool enabled = true;
  // Without wheels measuring the translation (a gyro alone, heading-only ticks) a young submap can
  // hold the pose while the robot drives off along a room it cannot see the end of: the whole run
  // is then mapped metres from its start. At the end the start scan is registered where it was
  // recorded and searched for within 3 m of it in the finished first map, and the start moves to
  // the pose found when that is 0.1 m or more away (FrontEnd::LocateStart). A switch only, beside
  // `enabled`: the vacuum profile has no byte left for a setting of another size.
  bool locate = true;
  float window_s = 10.0f;
  float every_s = 0.3f;
  int min_scans = 8;              // registered again and accepted
  float max_offset_rad = 0.035f;  // 2 degrees: more is not a map's tilt
  float max_bias_rad_s = 0.02f;   // 1.1 degrees/s: a gyro further off is not fitted
};

struct FrontEndConfig {
  int submap_scans = 20;          // N: scans fused into the submap
  int submap_line_period = 10;    // K1: re-extract submap lines every K1 scans
  // K2: re-extract regional-map lines every K2 scans (the paper: 50). Lines re-extracted from cells
  // the robot has just written let a map turn with its heading drift; with lines that fit a noisy
  // lidar's walls (ReferenceForNoise), 100 is better on every world and log measured
  // (docs/front-end-accuracy.md, "Registration periods and prior").
  int region_line_period = 100;
  int second_registration_period = 5;  // Ks: submap -> regional map every Ks scans
  // Misses a submap scan applies: only the last this-many metres of each ray before its hit
  // (0 = the whole ray). The submap serves registration, which needs hits and the free space
  // next to them: 0.5 m is as accurate as whole rays at a fraction of the submap upkeep
  // (measured: docs/front-end-cost.md).
  float submap_miss_range_m = 0.5f;
  // The same for the scans a regional map takes (beams without a return always clear their whole
  // length; 0 = whole rays). Near the robot every ray crosses the cells its neighbours crossed,
  // so much of a whole-ray walk repeats; 4 m keeps the free space a reference needs next to the
  // walls, at the same accuracy and fewer instructions (measured: docs/front-end-cost.md).
  float region_miss_range_m = 4.0f;
  // Submap lines are refitted to the raw points of the submap's scans lying within this distance
  // (RegistrationReference::AddRefitPoint), so they sit where the walls are, not on cell centres.
  // 0 = off (lines from cell centres only).
  float submap_refit_gate_m = 0.1f;
  int submap_refit_min_points = 10;
  float region_width_m = 4.0f;    // S
  float region_hysteresis_m = 0.3f;  // distance past a border before switching region
  // The second registration aligns the submap to one reference made of the current regional map
  // (once it holds more than the submap it was seeded from) and of the map of the region the robot
  // came from, once that one holds `region_mature_scans` scans and while the robot is at least
  // `reference_inner_margin_m` inside its box. A new region is so built in the frame of the
  // previous one, and neighbouring maps keep pulling each other to one heading.
  int region_mature_scans = 100;
  float reference_inner_margin_m = 2.0f;
  // A regional map that holds `region_slow_learning_scans` scans learns from each further scan at
  // `region_slow_learning_rate` of the grid's deltas (rounded towards 0; the submap always learns
  // at full rate). Log-odds count every scan alike, so a map keeps following its latest scans, and
  // those carry the drift since the map was built: scans' headings against one map moved by 0.2°
  // within a run, and the maps bent with them. A slow learner keeps what its first scans agreed on
  // and still maps what it has not seen. Rate 1 = off. Measured: docs/back-end.md, "Maps that
  // learn slowly once they hold 300 scans".
  int region_slow_learning_scans = 300;
  float region_slow_learning_rate = 0.25f;
  // false: the odometry pipeline (dead reckoning + insertion), for comparison.
  bool enable_registration = true;
  // Consecutive rejected first registrations before the status says "lost".
  int lost_after_rejections = 10;
  // Without wheels measuring the translation (the lidar alone, a gyro alone, or wheel ticks the
  // wheel check set aside), also lost after this many consecutive second registrations rejected in
  // a mature regional map (0: never). There a turn the first registration under-followed, or a
  // translation it let slide, leaves the submap off while each scan still matches it: the first
  // registrations pass and only the regional map disagrees (apartment seed 5, XV-11 without
  // odometry: 135 s at up to 7.5 m off; XV-11 with heading-only ticks, seed 7: 1.3 m off for the
  // last 1100 s of the run). With wheels such a streak is drift the back end reconciles, not a
  // slip: applied there, intel's relations error doubled.
  int lidar_only_lost_after_second_rejections = 3;
  // Never smear: a scan whose first registration was rejected while the prediction was uncertain
  // goes into neither the submap nor the regional map (counted scans_not_inserted). Uncertain: no
  // odometry sample yet, the previous scan's registration rejected too (a streak), odometry
  // without wheels (a gyro alone: no translation), or a predicted turn since the last scan above
  // uncertain_turn_rad. Rejected under a certain prediction (one
  // miss with good odometry), the scan is fused at the predicted pose (scans_fused_at_prediction).
  float uncertain_turn_rad = 0.15f;
  // Kept out of everything, the submap could never track again: at every this-many consecutive
  // rejections it restarts from the current scan at the predicted pose (the regional maps are
  // untouched; the second registration then pulls the fresh submap onto them). Half the lost
  // threshold: a robot entering what its submap has not seen (mit-csail.clf, weaving 12° a scan
  // into a new corridor) tracks again from a fresh submap before it is declared lost (lost 23 s ->
  // 0 of the log's 420 s); XV-11 with a gyro alone, 40 % of readings, seeds 1-80: runs over 0.2 m
  // 23 at 10, 12 / 16 / 16 at 4 / 5 / 6 (docs/back-end.md, "A fresh submap sooner").
  int submap_restart_after_rejections = 5;
  // A scan with fewer returns than this neither starts the submap (the first scan, a restart) nor
  // joins it while the submap is empty: a lidar's spin-up revolution (an XV-11: 7-17 returns of
  // 360) would otherwise be the only thing the next scans can be registered against.
  int min_start_hits = 40;
  // A sparse scan (returns from fewer than sparse_scan_share of its revolution's beams: an XV-11
  // that loses half its readings or more) has few neighbours for the range-noise smoothing, so its
  // returns keep their noise; against a young submap (a reference of a scan or two as noisy) their
  // mean residual exceeds the first registration's bound (PlicpConfig::max_mean_residual_m, 4 cm)
  // while the match is right. Its first registrations accept a mean residual up to
  // sparse_residual_noise_factor x the lidar's range noise (LidarConfig::range_noise_m; a lidar
  // that declares none is unaffected). XV-11 with 40 % of its readings, heading-only ticks,
  // apartment seeds 1-10, with LocalisationConfig::heading_window_rad: LocErr_ave 3.0 -> 0.53 m,
  // lost 1092 -> 248 s; with 70 % (the model's)
  // unchanged (docs/back-end.md, "Sparse scans"). 0: off.
  float sparse_scan_share = 0.45f;
  float sparse_residual_noise_factor = 2.0f;
  // Heading increment of the prediction: false = the wheels'; true = the integrated gyro yaw when
  // the odometry samples carry a rate (OdometrySample::has_gyro), the wheels keeping the
  // translation (and the de-skew within a revolution). Samples without wheels (has_wheels false)
  // always take the gyro's heading.
  bool gyro_heading = false;
  // The wheels' step scale and turn scale calibrated online from the accepted registrations
  // (core/front_end/odometry_calibration.hpp) and applied to the prediction. intel.clf, 64 draws:
  // median 0.021 -> 0.019 m, worst 0.041 -> 0.024 m (docs/back-end.md, "Wheels calibrated
  // online"). false: the wheels as they are.
  bool calibrate_odometry = true;
  // The first registration accepts a clean fit of part of the scan below its inlier ratio
  // (PlicpConfig::accept_partial_overlap; why in core/registration/plicp.cpp, PartialOverlapFits).
  // mit-csail.clf, 15 draws (--max-range 15-25, --region-width 3.6-4.2) on its own odometry and
  // with its steps scaled by 0.995 and 1.005, maps with a rotated or doubled hall: 24 -> 16 of 45
  // with the calibration, 15 -> 11 without it.
  bool accept_partial_overlap = true;
  // Odometry prior of the first registration (PosePrior units: unit-weight point residuals).
  float prior_info_xy = 20.0f;
  float prior_info_theta = 20.0f;
  // The robot's largest acceleration (m/s^2): where no wheels measure the translation, the
  // constant-velocity guess changes by no more than this from scan to scan (acceleration_limit.hpp).
  // A vacuum's drive accelerates at about 0.5 m/s^2 (the simulator's robot too); a faster robot
  // sets its own. 0: no limit.
  float max_acceleration_mps2 = 0.5f;
  // After a degenerate first registration, the same guess keeps only the step's part along the
  // robot's heading (core/front_end/forward_step.hpp): a differential drive cannot move sideways.
  // XV-11, 15 min in the office (7 m rooms, 6 m reach), seeds 1-40, runs over 0.2 m: gyro alone
  // 21 -> 15, heading-only ticks 22 -> 13; half the readings at 3.5-5 Hz, 10 min, gyro alone
  // seeds 1-240 8 -> 8, heading-only ticks seeds 1-80 9 -> 9; the apartment alike
  // (docs/back-end.md, "What is left of the XV-11's gap"). After every registration, not only a
  // degenerate one: the office alike, the sparse gyro-alone set 8 -> 13 of 240. false: the step as
  // registered.
  bool degenerate_guess_forward = true;
  // Without wheels, an accepted first registration keeps within max_acceleration_mps2 x interval^2
  // of the constant velocity's guess along each direction whose information per inlier (the xy
  // block of its Hessian) is below this (core/registration/weak_direction_hold.hpp): there the answer
  // is the pull of a few far returns, and taken whole it slowed the guess until the estimate
  // stood in a lane while the robot drove on. Well-fixed registrations carry 0.12-0.22 on the
  // apartment's XV-11 scans; weak ones 0-0.07. XV-11, runs over 0.2 m: gyro alone, half the
  // readings at 3.5-5 Hz, apartment 35 min, seeds 1-120 10 -> 7; office 15 min, seeds 1-40 6 -> 1;
  // lidar alone, apartment seeds 1-20, mean 0.389 -> 0.064 m (docs/front-end-accuracy.md, "A lane
  // with little hold along it"). 0 (or no acceleration limit, max_acceleration_mps2 0): never.
  float weak_direction_information = 0.1f;
  // Without wheels, while the heading sensor (a gyro, heading-only ticks) measures a turn faster
  // than FrontEnd::kTurnInPlaceRadS, the first registration's translation prior is as firm as the
  // wheels' (FrontEnd::PriorXyScale): a vacuum turns in place, or on a tight arc at the speed it
  // had, so the constant velocity's guess is as good a measure then. With the weak prior, scans
  // taken while the robot turned in place in a doorway (walls seen edge-on, nothing within reach
  // across the way) registered degenerate and walked the pose 0.3-0.5 m while it stood. XV-11,
  // 15 min in the office, runs over 0.2 m: gyro alone seeds 1-200 82 -> 46; heading-only ticks
  // seeds 1-40 15 -> 8 (docs/back-end.md, "A robot that turns in place").
  bool turn_holds_translation = true;
  // A first registration rejected from the wheels' prediction is tried again from the constant
  // velocity's when the two differ by more than these (0: never; wheels without a gyro heading).
  // Logged odometry stalls and then catches up in one step (mit-csail.clf: 0.85 m and 50 deg in
  // 0.2 s): from that step no registration converges, and the pose it leaves sends the robot lost.
  float odometry_doubt_m = 0.1f;
  float odometry_doubt_rad = 0.1f;
  // Second registration: at most this many submap obstacle cells as target points.
  int second_registration_max_points = 600;
  PlicpConfig first_registration;  // its near_weight_range_m is the lidar's (LidarConfig)
  // A rejected first registration is tried again from the best pose of a coarse search
  // (PoseSearchConfig: ±20°, ±0.3 m) on the submap reference; and when the predicted turn since the
  // last scan exceeds search_turn_rad (0 = never), the search runs first.
  // Without wheels: a scan is de-skewed again with the motion its registration found, and
  // registered once more, when that motion moves the revolution's last beam by more than these
  // against the velocity the de-skew assumed (FrontEnd::RegisterRedeskewed).
  float redeskew_min_m = 0.01f;
  float redeskew_min_rad = 0.01f;
  // At twice these, the scan is registered but kept out of the maps (FrontEnd::KeepOutBent).
  // Without wheels or a gyro, each scan goes into the maps one revolution late, de-skewed again
  // with the motion over its own revolution once the next scan's registration has measured it,
  // and registered again (FrontEnd::FlushPendingScan). The de-skew otherwise assumes the motion of
  // the revolution before, one revolution late at every start and stop of a turn.
  bool lidar_only_fixed_lag = true;
  bool search_on_rejection = true;
  float search_turn_rad = 0.0f;
  PoseSearchConfig search;
  // A weak match (inlier ratio below this, or rejected) rebuilds the submap reference before the
  // next scan, not K1 scans later, with the obstacle threshold lowered to weak_match_obstacle_
  // threshold (one hit not yet missed): walls seen for the first time (a fast turn with a 180° lidar,
  // 0.2 m between scans) enter the reference now. 0 = off.
  float weak_match_inlier_ratio = 0.6f;
  std::int16_t weak_match_obstacle_threshold = 800;
  PlicpConfig second_registration;
  // Obstacle thresholds (Q10 log-odds) of the two references. The submap holds unclamped sums
  // of its N scans: 2000 = hit in about three scans more than missed (a young submap asks for
  // hits in every scan so far). A regional map is clamped at +-3584: 3000 = settled or nearly.
  // Cells that range noise touches only now and then stay out, so lines do not tilt with them.
  ReferenceConfig submap_reference = ReferenceWithThreshold(2000);
  ReferenceConfig region_reference = ReferenceWithThreshold(3000);
  // A lidar returning fewer than this share of the readings that point at something in range
  // (core/front_end/return_share.hpp) has the submap's obstacle threshold scaled by its share over
  // this one: its walls collect that much fewer hits. The lidars the threshold was set on return
  // more (the LD06 about 95 %, the XV-11 model 65 %, the public logs' SICKs 96-99 %) and are left
  // as they were; 0.6 also touched the XV-11 model when its share dipped (0.5 and 0.6 measured).
  // XV-11 with a gyro alone and 40 % of its readings at 3.5-5 Hz, apartment seeds 1-40: runs over
  // 0.2 m 15 -> 5 (docs/front-end-accuracy.md, "Sparse returns, sparse walls"). 0 = off.
  float sparse_reference_full_share = 0.5f;
  // A new map's grid (the world frame) is turned by grid_turn_rad against the robot's first pose
  // when the first scan not skipped (after an XV-11's spin-up revolution) has its walls within
  // grid_turn_band_rad of the grid's axes, as they do when
  // the robot starts square to a wall (from its dock): noisy walls along cell rows cost the
  // apartment 2.7x its LocErr_ave (core/geometry/wall_direction.hpp). 0 = never turned. Not for
  // a loaded map: its frame is kept.
  float grid_turn_rad = 0.2618f;       // 15 degrees
  float grid_turn_band_rad = 0.1222f;  // 7 degrees
  StartHeadingConfig start_heading;
  StartScansConfig start_scans;
};

struct MapperConfig {
  GridConfig grid;
  LidarConfig lidar;
  FrontEndConfig front_end;
  BackEndConfig back_end;
  LocalisationConfig localisation;
};

// What a profile's storage holds (Mapper<Profile>::Init passes its own; the defaults bound nothing).
struct ConfigLimits {
  int submap_max_scans = 1 << 30;
  int second_target_points = 1 << 30;  // second-registration target points
  int back_end_cloud_points = 1 << 30;
  int search_points = 1 << 30;
  int region_box_cells = 0;  // a regional map's box side in cells (0: unbounded)
};

// Every field of every nested configuration (grid, lidar, front end, back end, the four PLICP
// configurations, both references and their line extraction, the search, the optimiser) within
// its meaningful range, every relation between them (clamps beyond the deltas, the submap's
// exact removal: N x hit_delta and N x |miss_delta| below 32767, regions on the cell lattice,
// thresholds the grids can reach, ...), and the capacities of `limits`. kInvalidArgument
// otherwise: 0, negative, NaN and huge values where they make no sense included.
Status Validate(const MapperConfig& config, const ConfigLimits& limits);
Status Validate(const MapperConfig& config);  // without storage limits

}  // namespace dpcr
