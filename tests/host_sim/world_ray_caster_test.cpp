#include "host_sim/sim/world_ray_caster.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace dpcr::sim;

TEST_CASE("Analytic ray-segment and ray-circle distances", "[raycast]") {
  CHECK(RaySegment({0, 0}, {1, 0}, {2, -1}, {2, 1}) == Approx(2.0));
  const double s = std::sqrt(0.5);
  CHECK(RaySegment({0, 0}, {s, s}, {2, -1}, {2, 5}) == Approx(2.0 * std::sqrt(2.0)));
  CHECK(RaySegment({0, 0}, {-1, 0}, {2, -1}, {2, 1}) < 0.0);  // behind
  CHECK(RaySegment({0, 0}, {1, 0}, {2, 0.5}, {2, 1}) < 0.0);  // passes beside the end
  CHECK(RaySegment({0, 0}, {1, 0}, {1, 0}, {3, 0}) < 0.0);    // parallel
  CHECK(RayCircle({0, 0}, {1, 0}, {3, 0}, 0.5) == Approx(2.5));
  // Tangent-ish offset: distance = cx - sqrt(r^2 - dy^2).
  CHECK(RayCircle({0, 0}, {1, 0}, {3, 0.3}, 0.5) == Approx(3.0 - 0.4));
  CHECK(RayCircle({0, 0}, {1, 0}, {3, 0.6}, 0.5) < 0.0);
  CHECK(RayCircle({0, 0}, {1, 0}, {-3, 0}, 0.5) < 0.0);
}

TEST_CASE("Grid ray casting matches brute force and analytic cases", "[raycast]") {
  World w;
  AddBox(&w, 0, 0, 10, 8);
  w.circles.push_back(Circle{{5, 4}, 0.5, 0});
  AddWall(&w, 2, 1, 3, 7);
  const WorldRayCaster caster(w, 0.5);
  RayHit h = caster.Cast({1, 4}, 0.0, 12.0);  // hits the slanted wall first
  REQUIRE(h.hit);
  CHECK(h.range_m == Approx(2.0 + 0.5 - 1.0));
  h = caster.Cast({7, 4}, dpcr::sim::kPiD, 12.0);
  CHECK(h.range_m == Approx(1.5));
  h = caster.Cast({7, 4}, 0.0, 12.0);
  CHECK(h.range_m == Approx(3.0));
  h = caster.Cast({7, 4}, 0.0, 2.0);  // beyond max range: no hit
  CHECK_FALSE(h.hit);
  CHECK(caster.Clearance({7, 4}, 5.0) == Approx(1.5));
  CHECK(caster.Clearance({0.1, 4}, 5.0) == Approx(0.1));

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0.05, 9.95), uy(0.05, 7.95), ua(-4.0, 4.0);
  int hits = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec2 p{ux(rng), uy(rng)};
    const double a = ua(rng);
    const RayHit g = caster.Cast(p, a, 12.0);
    const RayHit b = caster.CastBruteForce(p, a, 12.0);
    REQUIRE(g.hit == b.hit);
    REQUIRE(g.range_m == Approx(b.range_m).margin(1e-9));
    hits += g.hit ? 1 : 0;
  }
  CHECK(hits > 1900);
}
