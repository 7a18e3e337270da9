// Ray casting and clearance queries against a World, accelerated by a uniform grid of buckets
// (each bucket lists the segments and circles whose bounding box overlaps it). A ray walks the
// buckets in order (Amanatides-Woo) and stops once the best hit is nearer than the bucket exit.
#pragma once

#include <vector>

#include "host_sim/sim/world.hpp"

namespace dpcr::sim {

struct RayHit {
  bool hit = false;
  double range_m = 0.0;
  int material = 0;
};

class WorldRayCaster {
 public:
  // Keeps a pointer to `world`, which must outlive the caster.
  explicit WorldRayCaster(const World& world, double bucket_m = 0.5);

  // First obstacle along the ray from `origin` at `angle_rad` within max_range_m.
  RayHit Cast(Vec2 origin, double angle_rad, double max_range_m) const;
  // Same answer by testing every primitive: the oracle for tests.
  RayHit CastBruteForce(Vec2 origin, double angle_rad, double max_range_m) const;
  // Distance from p to the nearest obstacle surface, capped at max_dist_m.
  double Clearance(Vec2 p, double max_dist_m) const;

  const World& world() const { return *world_; }

 private:
  void TestBucket(int bucket, Vec2 origin, Vec2 dir, RayHit* best) const;

  const World* world_;
  double bucket_m_;
  double x0_ = 0.0;
  double y0_ = 0.0;
  int nx_ = 1;
  int ny_ = 1;
  std::vector<int> bucket_begin_;  // CSR: items of bucket b are items_[begin[b] .. begin[b+1])
  std::vector<int> items_;         // >= 0: segment index; < 0: circle index ~item
};

}  // namespace dpcr::sim
