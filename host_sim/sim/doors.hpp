// Doors that open and close (a home that changes): each door of the world with a leaf
// (Door::leaf) is, when closed, a wall across its opening, and open otherwise (the leaf lies flat
// against the wall, not modelled). Each alternates open and closed on a schedule drawn from the
// seed. The robot is never shut out or in: a closed door opens while the robot is within
// `robot_clearance_m` of it (someone opens it for the vacuum, which then drives through; the
// coverage plan ignores doors), and closes again on its schedule once the robot is farther away.
#pragma once

#include <cstdint>
#include <vector>

#include "host_sim/sim/world.hpp"

namespace dpcr::sim {

struct DoorsConfig {
  bool enabled = false;
  double open_min_s = 60.0;  // each open spell lasts a uniform draw in [min, max]
  double open_max_s = 600.0;
  double closed_min_s = 60.0;
  double closed_max_s = 600.0;
  double closed_at_start_probability = 0.5;
  double robot_clearance_m = 1.0;
};

class Doors {
 public:
  Doors() = default;
  // Schedules every door of `world` that has a leaf, from 0 to `end_s` (none unless enabled).
  Doors(const DoorsConfig& config, const World& world, std::uint64_t seed, double end_s);

  // Whether door `door` is closed at t_s with the robot at `robot`.
  bool Closed(std::size_t door, double t_s, Vec2 robot) const;
  // Distance from `origin` along the ray at `angle_rad` to the nearest closed door (a negative
  // number: none within max_range_m).
  double Cast(Vec2 origin, double angle_rad, double t_s, Vec2 robot, double max_range_m) const;
  // The leaves across their openings (where a closed door stands), one per scheduled door.
  const std::vector<Segment>& leaves() const { return leaves_; }
  std::size_t size() const { return leaves_.size(); }
  // How many times the doors' schedules open or close them over the run.
  std::size_t scheduled_changes() const;

 private:
  // Whether the schedule has door `door` closed at t_s (the robot aside).
  bool ScheduledClosed(std::size_t door, double t_s) const;

  std::vector<Segment> leaves_;
  std::vector<bool> closed_at_start_;
  std::vector<std::vector<double>> changes_;  // per door: the times it opens or closes, ascending
  double robot_clearance_m_ = 1.0;
};

}  // namespace dpcr::sim
