// A vacuum-like coverage plan over a World: per room, boustrophedon lanes along the room's
// longer axis (spacing ~ robot width), then one wall-following loop inset from the room's
// walls; rooms are joined by shortest paths (A* on a 5 cm grid) that pass through the doors.
// Every point is checked against the obstacles inflated by the robot radius plus a margin, and
// every straight leg of the returned polyline keeps at least the robot radius from all obstacles,
// so a robot that turns in place at waypoints and drives straight between them never collides.
// Lane pieces that are blocked or unreachable from the start are skipped.
// A plan variation (PlannerConfig::variation != 0) changes what a real vacuum's plan changes from
// one cleaning to the next: the room order (the start room first), each room's lane axis and
// the side its lanes start from, and the direction of its wall-following loop.
#pragma once

#include <cstdint>
#include <vector>

#include "host_sim/sim/world_ray_caster.hpp"

namespace dpcr::sim {

struct PlannerConfig {
  double robot_radius_m = 0.17;
  double margin_m = 0.04;        // extra clearance for lanes and grid cells (covers the 5 cm grid's diagonal)
  double lane_spacing_m = 0.30;  // ~ robot width: lanes overlap a little, as a vacuum's do
  double grid_m = 0.05;
  double min_piece_m = 0.10;     // shorter free lane pieces are not worth the detour
  bool wall_following = true;
  // 0: the canonical plan (rooms in declared order, lanes along each room's longer axis from its
  // low side, walls followed counter-clockwise); otherwise the seed of a plan variation.
  std::uint64_t variation = 0;
};

struct CoveragePlan {
  // A closed tour: the last waypoint connects back to the first through a collision-free path
  // included in the list, so the plan can be repeated.
  std::vector<Vec2> waypoints;
  int lane_pieces = 0;
  int skipped_pieces = 0;  // blocked or unreachable lane pieces
};

// The free point (robot fits with margin) nearest to `near` on a 5 cm lattice; false if none.
bool FindFreePoint(const WorldRayCaster& caster, const PlannerConfig& config, Vec2 near, Vec2* out);

// Plans from `start` (moved to the nearest free point if it is too close to an obstacle).
CoveragePlan PlanCoverage(const WorldRayCaster& caster, const PlannerConfig& config, Vec2 start);

}  // namespace dpcr::sim
