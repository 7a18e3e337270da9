// Bench-local stand-in for the world simulator: three floor plans as wall segments and a
// ray-casting lidar (450 beams, Gaussian range noise). To be replaced by host_sim's simulator.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/pose2.hpp"

namespace dpcr_bench {

struct Wall {
  dpcr::Point2 a, b;
};

struct World {
  std::string name;
  std::vector<Wall> walls;
  std::vector<dpcr::Pose2> path;  // robot poses, ~10 cm / 2° apart
};

// "hall" (10x10 m, corridor + desks), "office" (21x5 m, three rooms), "apartment" (~100 m²).
std::vector<World> MakeWorlds();

// Endpoints in the sensor frame of a 360° scan from `pose`; beams with no wall within range are dropped.
std::vector<dpcr::Point2> SimulateScan(const World& world, dpcr::Pose2 pose, int beams, float noise_m,
                                       unsigned seed, float max_range_m);

}  // namespace dpcr_bench
