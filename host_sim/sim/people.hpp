// People walking through the home (a home that changes): each walks along the robot's tour (its
// waypoints are joined by free straight lines) from a random waypoint, at walking speed, standing
// a while at some waypoints. At a vacuum's lidar height a person is legs: one circle of
// `radius_m`. Nobody walks through the robot: a person who would come closer than
// `robot_clearance_m` to its centre steps aside, straight away from it, until it has passed.
// Deterministic for a seed; positions are a function of time (and of where the robot is).
#pragma once

#include <cstdint>
#include <vector>

#include "host_sim/sim/geometry.hpp"

namespace dpcr::sim {

struct PeopleConfig {
  int count = 0;
  double speed_mps = 0.8;
  double radius_m = 0.12;
  double stand_probability = 0.3;  // at each waypoint
  double stand_min_s = 2.0;
  double stand_max_s = 20.0;
  // Centre to centre: the robot's radius (0.17 m) plus the legs' plus a step's margin. Without
  // it a person's legs stood inside the robot and the lidar saw them 1 cm away.
  double robot_clearance_m = 0.32;
};

class People {
 public:
  People() = default;
  // `tour`: the robot's closed waypoint tour; `end_s`: how long the walks are planned for.
  People(const PeopleConfig& config, const std::vector<Vec2>& tour, std::uint64_t seed, double end_s);

  // Distance from `origin` along the ray at `angle_rad` to the nearest person at time t_s, the
  // robot's centre at `robot` (a negative number: none within max_range_m). People the origin
  // is inside of are not seen.
  double Cast(Vec2 origin, double angle_rad, double t_s, double max_range_m, Vec2 robot) const;
  // Where the person's walk puts them at t_s.
  Vec2 PositionAt(std::size_t person, double t_s) const;
  // Where they are with the robot at `robot`: stepped aside if the walk comes too close to it.
  Vec2 PositionBeside(std::size_t person, double t_s, Vec2 robot) const;
  std::size_t size() const { return walks_.size(); }
  // Where someone stood still at some time (each place once).
  std::vector<Vec2> StandingSpots() const;
  double radius_m() const { return radius_m_; }

 private:
  // One straight stretch: from `a` at t0 to `b` at t1 (a == b: standing).
  struct Stretch {
    double t0 = 0.0, t1 = 0.0;
    Vec2 a, b;
  };
  std::vector<std::vector<Stretch>> walks_;
  double radius_m_ = 0.12;
  double robot_clearance_m_ = 0.32;
};

}  // namespace dpcr::sim
