// The simulated scenes of `dpcr-bench registration`: host_sim's built-in worlds (hall, office,
// apartment), each with a path along its coverage plan, scanned with host_sim's lidar model.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/geometry/pose2.hpp"
#include "host_sim/sim/world.hpp"
#include "host_sim/sim/world_ray_caster.hpp"

namespace dpcr_bench {

struct Scene {
  // The caster points into `world`: a Scene is built in place and never copied or moved.
  Scene(dpcr::sim::World scene_world, std::vector<dpcr::Pose2> scene_path);
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  const std::string& name() const { return world.name; }

  dpcr::sim::World world;
  dpcr::sim::WorldRayCaster caster;
  std::vector<dpcr::Pose2> path;  // robot poses 10 cm apart, heading along the path
};

// hall, office, apartment (host_sim/sim/builtin_worlds.cpp), each path its coverage plan.
std::vector<std::unique_ptr<Scene>> MakeBuiltinScenes();

// Poses every `step_m` along the polyline through `waypoints`, heading along each leg.
std::vector<dpcr::Pose2> PathAlong(const std::vector<dpcr::sim::Vec2>& waypoints, double step_m);

// Endpoints in the sensor frame of a 360° scan of `beams` beams from `pose` (host_sim's
// SimulateBeam: range noise sigma `noise_m`, no dropouts); beams without a return are dropped.
std::vector<dpcr::Point2> SimulateScan(const Scene& scene, dpcr::Pose2 pose, int beams, float noise_m,
                                       unsigned seed, float max_range_m);

}  // namespace dpcr_bench
