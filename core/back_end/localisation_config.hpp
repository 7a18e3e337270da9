// Localisation in known maps (core/back_end/global_localiser.hpp, the front end's lost handling),
// part of MapperConfig.
#pragma once

namespace dpcr {

struct LocalisationConfig {
  // Lost (a rejection streak of FrontEndConfig::lost_after_rejections, or the wheels lifted)
  // starts a global search; false: the robot stays lost (scans kept out) until local tracking
  // and the second registration bring it back, as before.
  bool relocalise = true;
  // Loading a saved map: the start pose is unknown, the first scans search for it.
  bool unknown_start = false;
  // Maps frozen: nothing is inserted into the regional maps, no region is created, the graph is
  // unchanged; the robot localises against the maps (and relocalises when lost).
  bool localise_only = false;
  // The coarse search (GlobalLocaliser::kCoarsePoints of the cloud): a match grid of `coarsen`
  // map cells per match cell (20 cm: a point on a wall still scores with the robot a few
  // centimetres off), headings every coarse_angle_step_rad (0.08 rad moves a point 3 m away by
  // 24 cm), whole slices of headings per scan until angles_per_step are done (the bound on a
  // scan's work: 45 = one slice, half a map, per scan; 90 = a map per scan, about twice the
  // instructions and half the time to recover: docs/relocalisation.md). The best poses are then
  // refined on the loop-closure search's 10 cm grid.
  int coarsen = 4;
  float coarse_angle_step_rad = 0.08f;
  int angles_per_step = 45;
  // Translations searched in each map: its region square (S wide, centred on the anchor) plus
  // this margin on every side (hysteresis and drift put the robot a little outside it).
  float window_margin_m = 0.5f;
  // The scan's hits thinned to this many points (at most BackEndConfig::search_points).
  int cloud_points = 150;
  // The best pose must reach BackEndConfig::search.min_score (mean likelihood on the 10 cm grid,
  // 0..1); a pose separated from it by search.peak_separation_m / _rad (in the world frame)
  // scoring above max_second_ratio of it makes the answer ambiguous.
  float max_second_ratio = 0.9f;
  // PLICP verification (BackEndConfig::closure_registration, with a stricter inlier ratio: the
  // scan is all inside the map it is found in).
  float min_inlier_ratio = 0.6f;
  // Without a heading sensor (no wheels, no gyro: the dead-reckoned pose is the constant velocity,
  // which fades during the rejection streak), a robot lost without a lift may be metres from where
  // it believes, and the second registration from there converged to whatever minimum was near
  // (apartment, XV-11 without odometry: fixes 0.5-0.7 m off). Such a robot is first searched for in
  // the map it was in, within near_window_m + near_window_mps x the time since the streak began of
  // its believed pose (every heading; the same ambiguity test and verification as the global
  // search), and globally once that round fails or the window would pass the map's square and
  // margin. near_window_m 0: off (the second registration's near fix, as with a heading sensor).
  // With a heading sensor the window bounds the fixes taken at once: one farther from the belief
  // of a robot that was not carried must be clear or agree with a held one (clear_min_score below;
  // FrontEnd::PastNearWindow). 0: every verified fix at once.
  float near_window_m = 0.3f;
  float near_window_mps = 0.3f;
  // Without a heading sensor, a fix scoring below clear_min_score or whose separate second best
  // scores above clear_max_ratio of it is held until a later round (another scan, carried by the
  // local tracking) agrees with it within half the search's peak separation; a disagreeing one is
  // held instead. clear_min_score 0 and clear_max_ratio 1: every verified fix is taken.
  float clear_min_score = 0.85f;
  float clear_max_ratio = 0.75f;
  // A robot lost on the floor (not carried) whose heading a sensor measures (wheels, a gyro, an
  // IMU's heading-only ticks) still knows which way it faces: only headings within
  // heading_window_rad + heading_window_rad_s x the time since the streak began of its believed
  // heading are searched (a gyro's bias, a streak's mis-turns). A room's 180-degree twin is then no
  // candidate: XV-11 with 40 % of its readings, heading-only ticks, apartment seed 2: a fix 180
  // degrees off, 6.4 m from the truth (docs/relocalisation.md). 0: every heading.
  float heading_window_rad = 0.35f;
  float heading_window_rad_s = 0.005f;
};

}  // namespace dpcr
