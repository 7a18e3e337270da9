// A world file (host_sim/sim/world.hpp, docs/world-format.md), text or PGM floor plan (the first
// byte chooses) -> the parser: no crash; either a WorldError naming the source or a world the
// simulator can use (walls or circles, a room, known materials, finite geometry within the size
// limits), whose bucketed ray caster agrees with the brute-force one.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_check.hpp"
#include "host_sim/sim/world.hpp"
#include "host_sim/sim/world_ray_caster.hpp"

namespace {

using dpcr::sim::World;

bool Near(double v) { return std::isfinite(v) && std::fabs(v) <= dpcr::sim::kMaxWorldCoordinateM; }
bool Near(dpcr::sim::Vec2 p) { return Near(p.x) && Near(p.y); }

void CheckUsable(const World& w) {
  FUZZ_CHECK(!w.segments.empty() || !w.circles.empty());
  FUZZ_CHECK(!w.rooms.empty());
  for (const dpcr::sim::Material& m : w.materials) FUZZ_CHECK(m.return_probability >= 0.0 && m.return_probability <= 1.0);
  const auto known = [&](int material) { return material >= 0 && static_cast<std::size_t>(material) < w.materials.size(); };
  for (const dpcr::sim::Segment& s : w.segments) FUZZ_CHECK(Near(s.a) && Near(s.b) && known(s.material));
  for (const dpcr::sim::Circle& c : w.circles) {
    FUZZ_CHECK(Near(c.centre) && c.radius_m > 0.0 && known(c.material));
  }
  for (const dpcr::sim::Room& r : w.rooms) FUZZ_CHECK(r.xmin < r.xmax && r.ymin < r.ymax);
  double x0, y0, x1, y1;
  w.Bounds(&x0, &y0, &x1, &y1);
  FUZZ_CHECK(x1 - x0 <= dpcr::sim::kMaxWorldExtentM && y1 - y0 <= dpcr::sim::kMaxWorldExtentM);
  if (w.has_start) FUZZ_CHECK(Near(dpcr::sim::Vec2{w.start.x, w.start.y}) && std::isfinite(w.start.theta));
}

// Rays from the first room's centre: the bucket walk must find what testing every primitive finds.
void CheckRays(const World& w) {
  const dpcr::sim::WorldRayCaster caster(w);
  const dpcr::sim::Room& room = w.rooms.front();
  const dpcr::sim::Vec2 centre{0.5 * (room.xmin + room.xmax), 0.5 * (room.ymin + room.ymax)};
  for (int k = 0; k < 16; ++k) {
    const double angle = 0.39269908169872414 * k + 0.01;
    const dpcr::sim::RayHit fast = caster.Cast(centre, angle, 50.0);
    const dpcr::sim::RayHit slow = caster.CastBruteForce(centre, angle, 50.0);
    FUZZ_CHECK(fast.hit == slow.hit);
    if (fast.hit) FUZZ_CHECK(std::fabs(fast.range_m - slow.range_m) <= 1e-9 && fast.range_m >= 0.0);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool pgm = (data[0] & 1) != 0;
  const std::string source = pgm ? "fuzz.pgm" : "fuzz.world";
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  World world;
  try {
    world = pgm ? dpcr::sim::ParsePgmWorld(bytes, source, 0.05, dpcr::sim::Vec2{-2.0, -2.0})
                : dpcr::sim::ParseWorldText(bytes, source);
  } catch (const dpcr::sim::WorldError& e) {
    FUZZ_CHECK(std::string(e.what()).rfind(source + ":", 0) == 0);
    return 0;
  }
  CheckUsable(world);
  CheckRays(world);
  return 0;
}
