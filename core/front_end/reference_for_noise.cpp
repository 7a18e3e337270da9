#include "core/front_end/reference_for_noise.hpp"

#include <cmath>

namespace dpcr {

ReferenceConfig ReferenceForNoise(const ReferenceConfig& base, const MapperConfig& config) {
  ReferenceConfig c = base;
  if (config.lidar.range_noise_m <= 0.0f) return c;
  const float noise_cells = kNoiseSigmasInLineFit * config.lidar.range_noise_m / config.grid.resolution_m;
  c.lines.max_rms_cells = std::sqrt(c.lines.max_rms_cells * c.lines.max_rms_cells + noise_cells * noise_cells);
  return c;
}

}  // namespace dpcr
