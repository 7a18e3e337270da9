#include "host_sim/sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dpcr::sim {

int World::FindMaterial(const std::string& material_name) const {
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].name == material_name) return static_cast<int>(i);
  }
  return -1;
}

int World::SetMaterial(const std::string& material_name, double return_probability) {
  const int existing = FindMaterial(material_name);
  if (existing >= 0) {
    materials[static_cast<std::size_t>(existing)].return_probability = return_probability;
    return existing;
  }
  materials.push_back(Material{material_name, return_probability});
  return static_cast<int>(materials.size()) - 1;
}

void CheckWorldLimits(const World& world, const std::string& source) {
  double x0, y0, x1, y1;
  world.Bounds(&x0, &y0, &x1, &y1);
  const auto far = [](double v) { return !(std::fabs(v) <= kMaxWorldCoordinateM); };
  if (far(x0) || far(y0) || far(x1) || far(y1) || (world.has_start && (far(world.start.x) || far(world.start.y)))) {
    throw WorldError(source + ": world reaches past " + std::to_string(static_cast<int>(kMaxWorldCoordinateM)) +
                     " m from the origin (the limit of a simulated floor)");
  }
  if (x1 - x0 > kMaxWorldExtentM || y1 - y0 > kMaxWorldExtentM) {
    throw WorldError(source + ": world spans " + std::to_string(static_cast<int>(x1 - x0)) + " m x " +
                     std::to_string(static_cast<int>(y1 - y0)) + " m, more than the " +
                     std::to_string(static_cast<int>(kMaxWorldExtentM)) + " m a side a simulated floor may");
  }
}

void World::Bounds(double* xmin, double* ymin, double* xmax, double* ymax) const {
  double x0 = std::numeric_limits<double>::max();
  double y0 = x0;
  double x1 = -x0;
  double y1 = -x0;
  auto grow = [&](double x, double y) {
    x0 = std::min(x0, x);
    y0 = std::min(y0, y);
    x1 = std::max(x1, x);
    y1 = std::max(y1, y);
  };
  for (const Segment& s : segments) {
    grow(s.a.x, s.a.y);
    grow(s.b.x, s.b.y);
  }
  for (const Circle& c : circles) {
    grow(c.centre.x - c.radius_m, c.centre.y - c.radius_m);
    grow(c.centre.x + c.radius_m, c.centre.y + c.radius_m);
  }
  for (const Room& r : rooms) {
    grow(r.xmin, r.ymin);
    grow(r.xmax, r.ymax);
  }
  if (x0 > x1) x0 = y0 = x1 = y1 = 0.0;
  *xmin = x0;
  *ymin = y0;
  *xmax = x1;
  *ymax = y1;
}

void AddWall(World* world, double x1, double y1, double x2, double y2, int material) {
  world->segments.push_back(Segment{Vec2{x1, y1}, Vec2{x2, y2}, material});
}

void AddBox(World* world, double xmin, double ymin, double xmax, double ymax, int material) {
  AddWall(world, xmin, ymin, xmax, ymin, material);
  AddWall(world, xmax, ymin, xmax, ymax, material);
  AddWall(world, xmax, ymax, xmin, ymax, material);
  AddWall(world, xmin, ymax, xmin, ymin, material);
}

void AddLegs(World* world, double cx, double cy, double w, double h, double leg_radius_m,
             bool centre_leg, int material) {
  const double dx = w / 2.0 - leg_radius_m;
  const double dy = h / 2.0 - leg_radius_m;
  for (int sx = -1; sx <= 1; sx += 2) {
    for (int sy = -1; sy <= 1; sy += 2) {
      world->circles.push_back(Circle{Vec2{cx + sx * dx, cy + sy * dy}, leg_radius_m, material});
    }
  }
  if (centre_leg) world->circles.push_back(Circle{Vec2{cx, cy}, leg_radius_m, material});
}

void CutDoors(World* world) {
  constexpr double kTolerance = 0.01;
  for (const Door& door : world->doors) {
    std::vector<Segment> out;
    for (const Segment& s : world->segments) {
      const Vec2 e = s.b - s.a;
      const double len = Norm(e);
      const bool collinear = len > 0.0 && std::fabs(Cross(e, door.a - s.a)) / len < kTolerance &&
                             std::fabs(Cross(e, door.b - s.a)) / len < kTolerance;
      if (!collinear) {
        out.push_back(s);
        continue;
      }
      // Door interval in the wall's parameter u in [0, 1].
      double u0 = Dot(door.a - s.a, e) / (len * len);
      double u1 = Dot(door.b - s.a, e) / (len * len);
      if (u0 > u1) std::swap(u0, u1);
      if (u1 <= 0.0 || u0 >= 1.0) {
        out.push_back(s);
        continue;
      }
      if (u0 > 0.0) out.push_back(Segment{s.a, s.a + u0 * e, s.material});
      if (u1 < 1.0) out.push_back(Segment{s.a + u1 * e, s.b, s.material});
    }
    world->segments = std::move(out);
  }
}

}  // namespace dpcr::sim
