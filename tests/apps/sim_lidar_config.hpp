// The mapper's lidar settings for a simulated run, as dpcr-sim makes them: the model's settings
// (hal/device_options.hpp) with the simulated range noise declared.
#pragma once

#include "core/config.hpp"
#include "hal/device_options.hpp"
#include "host_sim/sim/simulation.hpp"

namespace dpcr::test {

inline LidarConfig SimulatedLidarConfig(const sim::SimConfig& sim_config, LidarKind kind) {
  LidarConfig lidar = sim::MapperLidarConfig(sim_config);
  const float range_noise_m = lidar.range_noise_m;
  ApplyLidarModel(kind, &lidar);
  lidar.range_noise_m = range_noise_m;  // as dpcr-sim: the simulated noise
  return lidar;
}

}  // namespace dpcr::test
