#include "host_sim/sim/world_ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dpcr::sim {

WorldRayCaster::WorldRayCaster(const World& world, double bucket_m) : world_(&world), bucket_m_(bucket_m) {
  double x1, y1;
  world.Bounds(&x0_, &y0_, &x1, &y1);
  x0_ -= bucket_m_;
  y0_ -= bucket_m_;
  nx_ = static_cast<int>(std::ceil((x1 - x0_) / bucket_m_)) + 1;
  ny_ = static_cast<int>(std::ceil((y1 - y0_) / bucket_m_)) + 1;
  std::vector<std::vector<int>> buckets(static_cast<std::size_t>(nx_ * ny_));
  auto add_box = [&](double ax, double ay, double bx, double by, int item) {
    const int i0 = std::max(0, static_cast<int>(std::floor((ax - x0_) / bucket_m_)));
    const int j0 = std::max(0, static_cast<int>(std::floor((ay - y0_) / bucket_m_)));
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((bx - x0_) / bucket_m_)));
    const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((by - y0_) / bucket_m_)));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) buckets[static_cast<std::size_t>(j * nx_ + i)].push_back(item);
    }
  };
  for (std::size_t k = 0; k < world.segments.size(); ++k) {
    const Segment& s = world.segments[k];
    add_box(std::min(s.a.x, s.b.x), std::min(s.a.y, s.b.y), std::max(s.a.x, s.b.x), std::max(s.a.y, s.b.y),
            static_cast<int>(k));
  }
  for (std::size_t k = 0; k < world.circles.size(); ++k) {
    const Circle& c = world.circles[k];
    add_box(c.centre.x - c.radius_m, c.centre.y - c.radius_m, c.centre.x + c.radius_m, c.centre.y + c.radius_m,
            ~static_cast<int>(k));
  }
  bucket_begin_.reserve(buckets.size() + 1);
  for (const auto& b : buckets) {
    bucket_begin_.push_back(static_cast<int>(items_.size()));
    items_.insert(items_.end(), b.begin(), b.end());
  }
  bucket_begin_.push_back(static_cast<int>(items_.size()));
}

void WorldRayCaster::TestBucket(int bucket, Vec2 origin, Vec2 dir, RayHit* best) const {
  const std::size_t b = static_cast<std::size_t>(bucket);
  for (int k = bucket_begin_[b]; k < bucket_begin_[b + 1]; ++k) {
    const int item = items_[static_cast<std::size_t>(k)];
    double t;
    int material;
    if (item >= 0) {
      const Segment& s = world_->segments[static_cast<std::size_t>(item)];
      t = RaySegment(origin, dir, s.a, s.b);
      material = s.material;
    } else {
      const Circle& c = world_->circles[static_cast<std::size_t>(~item)];
      t = RayCircle(origin, dir, c.centre, c.radius_m);
      material = c.material;
    }
    if (t >= 0.0 && t < best->range_m) {
      best->hit = true;
      best->range_m = t;
      best->material = material;
    }
  }
}

RayHit WorldRayCaster::Cast(Vec2 origin, double angle_rad, double max_range_m) const {
  const Vec2 dir{std::cos(angle_rad), std::sin(angle_rad)};
  int i = static_cast<int>(std::floor((origin.x - x0_) / bucket_m_));
  int j = static_cast<int>(std::floor((origin.y - y0_) / bucket_m_));
  if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return CastBruteForce(origin, angle_rad, max_range_m);
  RayHit best;
  best.range_m = max_range_m;
  const double inf = std::numeric_limits<double>::infinity();
  const int step_i = dir.x > 0.0 ? 1 : -1;
  const int step_j = dir.y > 0.0 ? 1 : -1;
  const double delta_x = dir.x != 0.0 ? bucket_m_ / std::fabs(dir.x) : inf;
  const double delta_y = dir.y != 0.0 ? bucket_m_ / std::fabs(dir.y) : inf;
  double next_x = dir.x != 0.0 ? (x0_ + (i + (dir.x > 0.0 ? 1 : 0)) * bucket_m_ - origin.x) / dir.x : inf;
  double next_y = dir.y != 0.0 ? (y0_ + (j + (dir.y > 0.0 ? 1 : 0)) * bucket_m_ - origin.y) / dir.y : inf;
  for (;;) {
    TestBucket(j * nx_ + i, origin, dir, &best);
    const double exit_t = std::min(next_x, next_y);
    if (best.hit && best.range_m <= exit_t) break;
    if (exit_t > max_range_m) break;
    if (next_x < next_y) {
      i += step_i;
      next_x += delta_x;
    } else {
      j += step_j;
      next_y += delta_y;
    }
    if (i < 0 || j < 0 || i >= nx_ || j >= ny_) break;
  }
  if (!best.hit) best.range_m = 0.0;
  return best;
}

RayHit WorldRayCaster::CastBruteForce(Vec2 origin, double angle_rad, double max_range_m) const {
  const Vec2 dir{std::cos(angle_rad), std::sin(angle_rad)};
  RayHit best;
  best.range_m = max_range_m;
  for (int b = 0; b + 1 < static_cast<int>(bucket_begin_.size()); ++b) TestBucket(b, origin, dir, &best);
  if (!best.hit) best.range_m = 0.0;
  return best;
}

double WorldRayCaster::Clearance(Vec2 p, double max_dist_m) const {
  double best = max_dist_m;
  const int i0 = std::max(0, static_cast<int>(std::floor((p.x - max_dist_m - x0_) / bucket_m_)));
  const int j0 = std::max(0, static_cast<int>(std::floor((p.y - max_dist_m - y0_) / bucket_m_)));
  const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((p.x + max_dist_m - x0_) / bucket_m_)));
  const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((p.y + max_dist_m - y0_) / bucket_m_)));
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const std::size_t b = static_cast<std::size_t>(j * nx_ + i);
      for (int k = bucket_begin_[b]; k < bucket_begin_[b + 1]; ++k) {
        const int item = items_[static_cast<std::size_t>(k)];
        double d;
        if (item >= 0) {
          const Segment& s = world_->segments[static_cast<std::size_t>(item)];
          d = PointSegmentDistance(p, s.a, s.b);
        } else {
          const Circle& c = world_->circles[static_cast<std::size_t>(~item)];
          d = std::max(0.0, Norm(p - c.centre) - c.radius_m);
        }
        best = std::min(best, d);
      }
    }
  }
  return best;
}

}  // namespace dpcr::sim
