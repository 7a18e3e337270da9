// Does the map hold walls where the simulated world has none (a duplicated wall, a smeared copy
// of a room after a kidnap)? Each occupied cell of the fused map is carried into the world frame
// and its clearance to the true surfaces measured; metrics.json "map_check".
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>

#include "core/geometry/pose2.hpp"
#include "host_sim/output/map_files.hpp"
#include "host_sim/sim/world_ray_caster.hpp"

namespace dpcr::apps {

// `map_to_world`: the map frame in the simulated world. A cell counts as occupied above
// `occupied` (Q10 log-odds), as off the walls farther than `off_m` from every true surface.
inline nlohmann::json MapTruthCheck(const dpcr::output::FusedMap& map, const dpcr::Pose2& map_to_world,
                                    const dpcr::sim::WorldRayCaster& caster, std::int16_t occupied = 1024,
                                    double off_m = 0.15) {
  std::size_t cells = 0, off = 0;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      if (map.cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(map.width()) + static_cast<std::size_t>(x)] <= occupied) continue;
      ++cells;
      const float px = (static_cast<float>(map.box.min.x + x) + 0.5f) * map.resolution_m;
      const float py = (static_cast<float>(map.box.min.y + y) + 0.5f) * map.resolution_m;
      const dpcr::Point2 w = map_to_world.Apply(dpcr::Point2{px, py});
      if (caster.Clearance(dpcr::sim::Vec2{w.x, w.y}, 1.0) > off_m) ++off;
    }
  }
  return {{"occupied_cells", cells}, {"off_wall_cells", off}, {"off_wall_threshold_m", off_m},
          {"off_wall_fraction", cells > 0 ? static_cast<double>(off) / static_cast<double>(cells) : 0.0}};
}

}  // namespace dpcr::apps
