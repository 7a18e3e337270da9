#include "tools/bench/mapper_bench.hpp"

#include <valgrind/callgrind.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "core/mapper.hpp"
#include "host_sim/carmen/carmen_reader.hpp"
#include "host_sim/carmen/laser_scan.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "host_sim/eval/accuracy.hpp"

namespace dpcr_bench {
namespace {

// What the mapper is fed, in order: before scan i, odometry[odometry_end[i - 1] .. odometry_end[i]).
template <class MapperType>
struct Input {
  dpcr::MapperConfig config;
  std::vector<dpcr::OdometrySample> odometry;
  std::vector<std::size_t> odometry_end;
  std::vector<typename MapperType::ScanType> scans;
  dpcr::eval::Trajectory truth;      // simulated runs: the true pose at each scan
};

// Same feeding as dpcr-replay --carmen (odometry "laser", decimation beyond kMaxBeams).
template <class MapperType>
void LoadCarmen(const MapperBenchOptions& o, Input<MapperType>* in) {
  std::ifstream file(o.clf_path);
  if (!file) throw std::runtime_error(o.clf_path + ": cannot open");
  dpcr::carmen::CarmenReader reader(file);
  dpcr::carmen::Record rec;
  while (reader.Next(&rec)) {
    if (rec.kind != dpcr::carmen::Record::Kind::kLaser) continue;
    const dpcr::carmen::LaserRecord& laser = rec.laser;
    dpcr::OdometrySample s;
    s.stamp_us = laser.stamp_us;
    s.pose = laser.odom_pose;
    in->odometry.push_back(s);
    in->odometry_end.push_back(in->odometry.size());
    typename MapperType::ScanType scan;
    (void)dpcr::carmen::ToScan(laser, &scan);
    in->scans.push_back(scan);
    if (o.scans > 0 && static_cast<int>(in->scans.size()) == o.scans) break;
  }
  in->config.lidar.max_range_m = o.max_range_m;
  in->config.lidar.mount = dpcr::Pose2{reader.front_laser_offset_m(), 0.0f, 0.0f};
}

// Same feeding as dpcr-sim (100 Hz wheel odometry between 10 Hz revolutions).
template <class MapperType>
void LoadSimulation(const MapperBenchOptions& o, Input<MapperType>* in) {
  const dpcr::sim::World world = dpcr::sim::LoadWorld(o.world);
  dpcr::sim::SimConfig sim_config;
  sim_config.seed = o.seed;
  sim_config.duration_min = o.minutes;
  sim_config.vary_plan = !o.fixed_plan;
  dpcr::sim::Simulation sim(world, sim_config);
  dpcr::sim::SimEvent event;
  while (sim.Step(&event)) {
    if (event.type == dpcr::sim::SimEventType::kOdometry) {
      in->odometry.push_back(event.odometry);
      continue;
    }
    in->odometry_end.push_back(in->odometry.size());
    in->scans.push_back(event.scan);
    in->truth.push_back({event.scan.stamp_us, event.truth.ToPose2()});
    if (o.scans > 0 && static_cast<int>(in->scans.size()) == o.scans) break;
  }
  in->config.lidar = dpcr::sim::MapperLidarConfig(sim_config);
}

template <class MapperType>
int Run(const MapperBenchOptions& o, Input<MapperType>& input) {
  static MapperType mapper;
  dpcr::MapperConfig config = input.config;
  if (o.submap_miss_range_m >= 0.0f) config.front_end.submap_miss_range_m = o.submap_miss_range_m;
  if (o.region_miss_range_m >= 0.0f) config.front_end.region_miss_range_m = o.region_miss_range_m;
  if (o.reference_max_distance_m > 0.0f) {
    config.front_end.submap_reference.max_distance_m = o.reference_max_distance_m;
    config.front_end.region_reference.max_distance_m = o.reference_max_distance_m;
  }
  if (o.k1 > 0) config.front_end.submap_line_period = o.k1;
  if (o.k2 > 0) config.front_end.region_line_period = o.k2;
  if (o.ks > 0) config.front_end.second_registration_period = o.ks;
  if (o.n > 0) config.front_end.submap_scans = o.n;
  if (o.submap_threshold >= 0) config.front_end.submap_reference.obstacle_threshold = static_cast<std::int16_t>(o.submap_threshold);
  if (o.region_threshold >= 0) config.front_end.region_reference.obstacle_threshold = static_cast<std::int16_t>(o.region_threshold);
  if (o.settle >= 0) config.grid.settle_at_clamp = o.settle != 0;
  if (o.hit_margin_m >= 0.0f) config.grid.hit_margin_m = o.hit_margin_m;
  if (o.inner_margin_m >= 0.0f) config.front_end.reference_inner_margin_m = o.inner_margin_m;
  if (o.mature_scans > 0) config.front_end.region_mature_scans = o.mature_scans;
  if (mapper.Init(config) != dpcr::Status::kOk) throw std::runtime_error("invalid mapper configuration");
  std::vector<double> us;
  us.reserve(input.scans.size());
  dpcr::eval::Trajectory estimate;
  estimate.reserve(input.scans.size());
  const auto start = std::chrono::steady_clock::now();
  std::size_t next_odometry = 0;
  for (std::size_t i = 0; i < input.scans.size(); ++i) {
    for (; next_odometry < input.odometry_end[i]; ++next_odometry) mapper.AddOdometry(input.odometry[next_odometry]);
    const bool counted = o.callgrind_stride > 0 && i % static_cast<std::size_t>(o.callgrind_stride) == 0;
    const auto t0 = std::chrono::steady_clock::now();
    if (counted) CALLGRIND_TOGGLE_COLLECT;
    (void)mapper.AddScan(input.scans[i]);
    if (counted) {
      CALLGRIND_TOGGLE_COLLECT;
      CALLGRIND_DUMP_STATS;
    }
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    estimate.push_back({input.scans[i].stamp_us, mapper.pose()});
  }
  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.trajectory_path.empty()) {
    std::ofstream tum(o.trajectory_path);
    dpcr::eval::WriteTum(tum, estimate);
  }
  std::vector<double> sorted = us;
  std::sort(sorted.begin(), sorted.end());
  const auto& c = mapper.front_end_counters();
  std::printf("scans %zu  AddScan total %.3f s  median %.1f us  p90 %.1f us  max %.1f us\n", us.size(), total_s,
              sorted[sorted.size() / 2], sorted[sorted.size() * 9 / 10], sorted.back());
  std::printf("first registrations %u (rejected %u), second %u (rejected %u), submap line builds %u, region line builds %u, regions %d\n",
              c.first_registrations, c.first_rejected, c.second_registrations, c.second_rejected, c.submap_line_builds,
              c.region_line_builds, mapper.region_count());
  if (!input.truth.empty()) {
    const dpcr::eval::AccuracyResult a = dpcr::eval::EvaluateAgainstGroundTruth(estimate, input.truth);
    std::printf("LocErr_ave %.3f m  ATE %.3f m  max %.3f m\n", a.loc_err_ave_m, a.ate_rmse_m, a.max_err_m);
  }
  return 0;
}

}  // namespace

int RunMapperBench(const MapperBenchOptions& o) {
  if (!o.world.empty()) {
    using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;
    static Input<MapperType> input;
    LoadSimulation(o, &input);
    return Run(o, input);
  }
  using MapperType = dpcr::Mapper<dpcr::BuildingProfile>;
  static Input<MapperType> input;
  LoadCarmen(o, &input);
  return Run(o, input);
}

}  // namespace dpcr_bench
