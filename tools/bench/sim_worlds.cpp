#include "tools/bench/sim_worlds.hpp"

#include <cmath>
#include <random>

namespace dpcr_bench {
namespace {

using dpcr::Point2;
using dpcr::Pose2;

void Box(std::vector<Wall>* w, float x0, float y0, float x1, float y1) {
  w->push_back({{x0, y0}, {x1, y0}});
  w->push_back({{x1, y0}, {x1, y1}});
  w->push_back({{x1, y1}, {x0, y1}});
  w->push_back({{x0, y1}, {x0, y0}});
}

// Straight legs between waypoints, heading along the leg, one pose every 10 cm.
std::vector<Pose2> Path(const std::vector<Point2>& waypoints) {
  std::vector<Pose2> out;
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    const Point2 a = waypoints[i - 1], b = waypoints[i];
    const float len = std::hypot(b.x - a.x, b.y - a.y), th = std::atan2(b.y - a.y, b.x - a.x);
    for (float s = 0.0f; s < len; s += 0.1f) out.push_back(Pose2{a.x + s / len * (b.x - a.x), a.y + s / len * (b.y - a.y), th});
  }
  return out;
}

}  // namespace

std::vector<World> MakeWorlds() {
  std::vector<World> worlds;
  {  // The paper's 10 m x 10 m hall: a 1.6 m corridor along the south side, workstations north.
    World w{"hall", {}, {}};
    Box(&w.walls, 0.0f, 0.0f, 10.0f, 10.0f);
    w.walls.push_back({{0.0f, 1.6f}, {7.5f, 1.6f}});
    for (float i : {0.0f, 1.0f, 2.0f}) {
      for (float j : {0.0f, 1.0f}) Box(&w.walls, 1.5f + 2.5f * i, 4.0f + 3.0f * j, 2.7f + 2.5f * i, 4.7f + 3.0f * j);
    }
    w.path = Path({{0.8f, 0.8f}, {8.6f, 0.8f}, {8.6f, 5.5f}, {3.6f, 5.5f}, {3.6f, 8.6f}});
    worlds.push_back(w);
  }
  {  // The 21 m x 5 m three-room office: partitions at 7 m and 14 m with 0.9 m doors.
    World w{"office", {}, {}};
    Box(&w.walls, 0.0f, 0.0f, 21.0f, 5.0f);
    for (float x : {7.0f, 14.0f}) {
      w.walls.push_back({{x, 0.0f}, {x, 2.0f}});
      w.walls.push_back({{x, 2.9f}, {x, 5.0f}});
    }
    Box(&w.walls, 2.0f, 3.5f, 4.0f, 4.3f);    // desks and cupboards
    Box(&w.walls, 9.0f, 0.6f, 10.2f, 1.4f);
    Box(&w.walls, 17.0f, 3.0f, 19.5f, 3.8f);
    w.path = Path({{1.0f, 2.45f}, {20.0f, 2.45f}, {20.0f, 1.2f}, {15.0f, 1.2f}});
    worlds.push_back(w);
  }
  {  // A ~100 m² apartment: living room, kitchen, two bedrooms, hall; sofas, beds, tables.
    World w{"apartment", {}, {}};
    Box(&w.walls, 0.0f, 0.0f, 11.0f, 9.0f);
    w.walls.push_back({{6.0f, 0.0f}, {6.0f, 3.0f}});
    w.walls.push_back({{6.0f, 3.9f}, {6.0f, 9.0f}});
    w.walls.push_back({{6.0f, 4.5f}, {8.0f, 4.5f}});
    w.walls.push_back({{8.9f, 4.5f}, {11.0f, 4.5f}});
    w.walls.push_back({{0.0f, 5.5f}, {2.5f, 5.5f}});
    w.walls.push_back({{3.4f, 5.5f}, {6.0f, 5.5f}});
    Box(&w.walls, 1.0f, 0.5f, 3.2f, 1.4f);    // sofa
    Box(&w.walls, 2.5f, 2.8f, 3.7f, 3.6f);    // coffee table
    Box(&w.walls, 7.5f, 6.5f, 9.5f, 8.5f);    // bed
    Box(&w.walls, 1.0f, 7.0f, 2.4f, 8.6f);    // bed
    Box(&w.walls, 8.5f, 1.0f, 10.5f, 1.6f);   // kitchen counter
    w.path = Path({{2.9f, 6.5f}, {2.9f, 4.5f}, {4.5f, 4.5f}, {4.5f, 3.4f}, {8.4f, 3.4f}, {8.4f, 5.8f}});
    worlds.push_back(w);
  }
  return worlds;
}

std::vector<Point2> SimulateScan(const World& world, Pose2 pose, int beams, float noise_m, unsigned seed,
                                 float max_range_m) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, noise_m);
  std::vector<Point2> pts;
  pts.reserve(static_cast<std::size_t>(beams));
  for (int i = 0; i < beams; ++i) {
    const float a = -dpcr::kPi + 2.0f * dpcr::kPi * static_cast<float>(i) / static_cast<float>(beams);
    const float dx = std::cos(pose.theta + a), dy = std::sin(pose.theta + a);
    float best = -1.0f;
    for (const Wall& w : world.walls) {
      const float ex = w.b.x - w.a.x, ey = w.b.y - w.a.y;
      const float den = dx * ey - dy * ex;
      if (std::fabs(den) < 1e-9f) continue;
      const float t = ((w.a.x - pose.x) * ey - (w.a.y - pose.y) * ex) / den;
      const float u = ((w.a.x - pose.x) * dy - (w.a.y - pose.y) * dx) / den;
      if (t > 0.0f && u >= 0.0f && u <= 1.0f && t <= max_range_m && (best < 0.0f || t < best)) best = t;
    }
    if (best < 0.0f) continue;
    const float r = best + (noise_m > 0.0f ? noise(rng) : 0.0f);
    pts.push_back(Point2{r * std::cos(a), r * std::sin(a)});
  }
  return pts;
}

}  // namespace dpcr_bench
