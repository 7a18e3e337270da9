// People walking through the home (a home that changes): each walks along the robot's tour (its
// waypoints are joined by free straight lines) from a random waypoint, at walking speed, standing
// a while at some waypoints. At a vacuum's lidar height a person is legs: one circle of
// `radius_m`. Deterministic for a seed; positions are a function of time.
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
};

class People {
 public:
  People() = default;
  // `tour`: the robot's closed waypoint tour; `end_s`: how long the walks are planned for.
  People(const PeopleConfig& config, const std::vector<Vec2>& tour, std::uint64_t seed, double end_s);

  // Distance from `origin` along the ray at `angle_rad` to the nearest person at time t_s
  // (a negative number: none within max_range_m). People the origin is inside of are not seen.
  double Cast(Vec2 origin, double angle_rad, double t_s, double max_range_m) const;
  Vec2 PositionAt(std::size_t person, double t_s) const;
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
};

}  // namespace dpcr::sim
