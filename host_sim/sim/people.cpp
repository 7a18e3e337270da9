#include "host_sim/sim/people.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace dpcr::sim {

People::People(const PeopleConfig& config, const std::vector<Vec2>& tour, std::uint64_t seed, double end_s)
    : radius_m_(config.radius_m), robot_clearance_m_(config.robot_clearance_m) {
  if (config.count <= 0 || tour.size() < 2) return;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int p = 0; p < config.count; ++p) {
    std::vector<Stretch> walk;
    std::size_t i = std::uniform_int_distribution<std::size_t>(0, tour.size() - 1)(rng);
    const int direction = unit(rng) < 0.5 ? 1 : -1;
    double t = 0.0;
    while (t < end_s) {
      const std::size_t j = (i + tour.size() + static_cast<std::size_t>(direction)) % tour.size();
      const double d = Norm(tour[j] - tour[i]);
      walk.push_back(Stretch{t, t + d / config.speed_mps, tour[i], tour[j]});
      t += d / config.speed_mps;
      if (unit(rng) < config.stand_probability) {
        const double stand = config.stand_min_s + unit(rng) * (config.stand_max_s - config.stand_min_s);
        walk.push_back(Stretch{t, t + stand, tour[j], tour[j]});
        t += stand;
      }
      i = j;
    }
    walks_.push_back(std::move(walk));
  }
}

Vec2 People::PositionAt(std::size_t person, double t_s) const {
  const std::vector<Stretch>& w = walks_[person];
  const auto it = std::upper_bound(w.begin(), w.end(), t_s, [](double t, const Stretch& s) { return t < s.t0; });
  const Stretch& s = it == w.begin() ? w.front() : *(it - 1);
  if (s.t1 <= s.t0 || t_s >= s.t1) return s.b;
  const double u = std::max(0.0, (t_s - s.t0) / (s.t1 - s.t0));
  return s.a + u * (s.b - s.a);
}

Vec2 People::PositionBeside(std::size_t person, double t_s, Vec2 robot) const {
  const Vec2 p = PositionAt(person, t_s);
  const Vec2 away = p - robot;
  const double d = Norm(away);
  if (d >= robot_clearance_m_) return p;
  // Exactly at the robot's centre (a walk through it): aside along +y, any side will do.
  const Vec2 unit = d > 1e-9 ? (1.0 / d) * away : Vec2{0.0, 1.0};
  return robot + robot_clearance_m_ * unit;
}

std::vector<Vec2> People::StandingSpots() const {
  std::vector<Vec2> spots;
  for (const std::vector<Stretch>& walk : walks_) {
    for (const Stretch& s : walk) {
      if (s.t1 <= s.t0 || Norm(s.b - s.a) > 0.0) continue;
      const bool known = std::any_of(spots.begin(), spots.end(), [&](Vec2 p) { return Norm(p - s.a) < 1e-9; });
      if (!known) spots.push_back(s.a);
    }
  }
  return spots;
}

double People::Cast(Vec2 origin, double angle_rad, double t_s, double max_range_m, Vec2 robot) const {
  const Vec2 dir{std::cos(angle_rad), std::sin(angle_rad)};
  double best = -1.0;
  for (std::size_t p = 0; p < walks_.size(); ++p) {
    const Vec2 c = PositionBeside(p, t_s, robot) - origin;
    const double along = Dot(c, dir);
    const double r2 = radius_m_ * radius_m_;
    const double off2 = Dot(c, c) - along * along;
    if (Dot(c, c) <= r2 || along <= 0.0 || off2 > r2) continue;  // inside, behind, or missed
    const double d = along - std::sqrt(r2 - off2);
    if (d <= max_range_m && (best < 0.0 || d < best)) best = d;
  }
  return best;
}

}  // namespace dpcr::sim
