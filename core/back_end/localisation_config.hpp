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
};

}  // namespace dpcr
