// Does the map hold walls where the simulated world has none (a duplicated wall, a smeared copy
// of a room after a kidnap, a person who stood still)? Each occupied cell of the fused map is
// carried into the world frame and its clearance to the true surfaces measured; metrics.json
// "map_check".
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/geometry/pose2.hpp"
#include "host_sim/output/map_files.hpp"
#include "host_sim/sim/world_ray_caster.hpp"

namespace dpcr::apps {

// What changed in the home during the run: where a door that opened and closed stands when
// closed (either state is the truth there), and where people stood still.
struct HomeChanges {
  std::vector<dpcr::sim::Segment> door_leaves;
  std::vector<dpcr::sim::Vec2> standing_spots;
  double person_radius_m = 0.12;
};

// `map_to_world`: the map frame in the simulated world. A cell counts as occupied above
// `occupied` (Q10 log-odds), as off the walls farther than `off_m` from every true surface.
// Occupied cells within off_m of a door leaf are neither wall nor ghost: counted apart
// (door_cells), in neither figure. Off-wall cells within a person's radius + off_m of where
// someone stood are also counted as stood_cells (ghosts of people standing).
inline nlohmann::json MapTruthCheck(const dpcr::output::FusedMap& map, const dpcr::Pose2& map_to_world,
                                    const dpcr::sim::WorldRayCaster& caster, const HomeChanges& changes = {},
                                    std::int16_t occupied = 1024, double off_m = 0.15) {
  std::size_t cells = 0, off = 0, door = 0, stood = 0;
  const auto near_door = [&](dpcr::sim::Vec2 p) {
    for (const dpcr::sim::Segment& s : changes.door_leaves) {
      if (dpcr::sim::PointSegmentDistance(p, s.a, s.b) <= off_m) return true;
    }
    return false;
  };
  const auto near_stand = [&](dpcr::sim::Vec2 p) {
    for (const dpcr::sim::Vec2& s : changes.standing_spots) {
      if (dpcr::sim::Norm(p - s) <= changes.person_radius_m + off_m) return true;
    }
    return false;
  };
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      if (map.cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(map.width()) + static_cast<std::size_t>(x)] <= occupied) continue;
      const float px = (static_cast<float>(map.box.min.x + x) + 0.5f) * map.resolution_m;
      const float py = (static_cast<float>(map.box.min.y + y) + 0.5f) * map.resolution_m;
      const dpcr::Point2 w = map_to_world.Apply(dpcr::Point2{px, py});
      const dpcr::sim::Vec2 p{w.x, w.y};
      if (near_door(p)) {
        ++door;
        continue;
      }
      ++cells;
      if (caster.Clearance(p, 1.0) > off_m) {
        ++off;
        if (near_stand(p)) ++stood;
      }
    }
  }
  nlohmann::json j = {{"occupied_cells", cells}, {"off_wall_cells", off}, {"off_wall_threshold_m", off_m},
                      {"off_wall_fraction", cells > 0 ? static_cast<double>(off) / static_cast<double>(cells) : 0.0}};
  if (!changes.door_leaves.empty()) j["door_cells"] = door;
  if (!changes.standing_spots.empty()) j["stood_cells"] = stood;
  return j;
}

}  // namespace dpcr::apps
