#include "host_sim/sim/doors.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace dpcr::sim {

Doors::Doors(const DoorsConfig& config, const World& world, std::uint64_t seed, double end_s)
    : robot_clearance_m_(config.robot_clearance_m) {
  if (!config.enabled) return;
  if (!(config.open_min_s > 0.0 && config.open_max_s >= config.open_min_s && config.closed_min_s > 0.0 &&
        config.closed_max_s >= config.closed_min_s)) {
    throw WorldError("doors: spells must be positive with min <= max");
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const Door& door : world.doors) {
    if (!door.leaf) continue;
    leaves_.push_back(Segment{door.a, door.b, 0});
    bool closed = unit(rng) < config.closed_at_start_probability;
    closed_at_start_.push_back(closed);
    std::vector<double> changes;
    double t = 0.0;
    for (;;) {
      const double lo = closed ? config.closed_min_s : config.open_min_s;
      const double hi = closed ? config.closed_max_s : config.open_max_s;
      t += lo + unit(rng) * (hi - lo);
      if (t >= end_s) break;
      changes.push_back(t);
      closed = !closed;
    }
    changes_.push_back(std::move(changes));
  }
}

bool Doors::ScheduledClosed(std::size_t door, double t_s) const {
  const std::vector<double>& c = changes_[door];
  const std::size_t flips = static_cast<std::size_t>(std::upper_bound(c.begin(), c.end(), t_s) - c.begin());
  return closed_at_start_[door] != ((flips & 1u) != 0);
}

bool Doors::Closed(std::size_t door, double t_s, Vec2 robot) const {
  if (!ScheduledClosed(door, t_s)) return false;
  const Segment& s = leaves_[door];
  return PointSegmentDistance(robot, s.a, s.b) > robot_clearance_m_;
}

double Doors::Cast(Vec2 origin, double angle_rad, double t_s, Vec2 robot, double max_range_m) const {
  const Vec2 dir{std::cos(angle_rad), std::sin(angle_rad)};
  double best = -1.0;
  for (std::size_t i = 0; i < leaves_.size(); ++i) {
    if (!Closed(i, t_s, robot)) continue;
    const double d = RaySegment(origin, dir, leaves_[i].a, leaves_[i].b);
    if (d >= 0.0 && d <= max_range_m && (best < 0.0 || d < best)) best = d;
  }
  return best;
}

std::size_t Doors::scheduled_changes() const {
  std::size_t n = 0;
  for (const std::vector<double>& c : changes_) n += c.size();
  return n;
}

}  // namespace dpcr::sim
