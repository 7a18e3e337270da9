#include "tools/bench/scenes.hpp"

#include <cmath>
#include <random>

#include "host_sim/sim/coverage_planner.hpp"
#include "host_sim/sim/sensors.hpp"

namespace dpcr_bench {

Scene::Scene(dpcr::sim::World scene_world, std::vector<dpcr::Pose2> scene_path)
    : world(std::move(scene_world)), caster(world), path(std::move(scene_path)) {}

std::vector<dpcr::Pose2> PathAlong(const std::vector<dpcr::sim::Vec2>& waypoints, double step_m) {
  std::vector<dpcr::Pose2> out;
  double to_next = 0.0;  // distance along the polyline to the next pose
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    const dpcr::sim::Vec2 a = waypoints[i - 1], b = waypoints[i];
    const double length = dpcr::sim::Norm(b - a);
    if (length <= 0.0) continue;
    const float heading = static_cast<float>(std::atan2(b.y - a.y, b.x - a.x));
    for (; to_next < length; to_next += step_m) {
      const dpcr::sim::Vec2 p = a + (to_next / length) * (b - a);
      out.push_back(dpcr::Pose2{static_cast<float>(p.x), static_cast<float>(p.y), heading});
    }
    to_next -= length;
  }
  return out;
}

std::vector<std::unique_ptr<Scene>> MakeBuiltinScenes() {
  std::vector<std::unique_ptr<Scene>> scenes;
  for (const std::string& name : dpcr::sim::BuiltinWorldNames()) {
    auto scene = std::make_unique<Scene>(dpcr::sim::LoadBuiltinWorld(name), std::vector<dpcr::Pose2>{});
    const dpcr::sim::Pose2d& start = scene->world.start;
    const dpcr::sim::CoveragePlan plan =
        dpcr::sim::PlanCoverage(scene->caster, dpcr::sim::PlannerConfig{}, dpcr::sim::Vec2{start.x, start.y});
    scene->path = PathAlong(plan.waypoints, 0.1);
    scenes.push_back(std::move(scene));
  }
  return scenes;
}

std::vector<dpcr::Point2> SimulateScan(const Scene& scene, dpcr::Pose2 pose, int beams, float noise_m,
                                       unsigned seed, float max_range_m) {
  dpcr::sim::LidarConfig lidar;
  lidar.beams_per_revolution = beams;
  lidar.max_range_m = max_range_m;
  lidar.noise_base_m = noise_m;
  lidar.noise_fraction = 0.0;
  lidar.dropouts = false;  // the bench compares registrations, not sensor models
  const dpcr::sim::Pose2d sensor{pose.x, pose.y, pose.theta};
  std::mt19937_64 rng(seed);
  std::vector<dpcr::Point2> points;
  points.reserve(static_cast<std::size_t>(beams));
  for (int i = 0; i < beams; ++i) {
    const float a = -dpcr::kPi + 2.0f * dpcr::kPi * static_cast<float>(i) / static_cast<float>(beams);
    const float r = dpcr::sim::SimulateBeam(scene.caster, lidar, sensor, a, &rng);
    if (r > 0.0f) points.push_back(dpcr::Point2{r * std::cos(a), r * std::sin(a)});
  }
  return points;
}

}  // namespace dpcr_bench
