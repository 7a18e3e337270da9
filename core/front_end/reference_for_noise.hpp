// The line extraction's fit tolerance for the lidar's range noise. A wall mapped from noisy returns
// is a band of obstacle cells two to three cells thick (LD06: 1 cm + 0.5 % of the range, 2.5 cm at
// 3 m, on 5 cm cells); with the clean-lidar tolerance (LineExtractorConfig::max_rms_cells, 0.75)
// most of such a wall's fits fail and it stays clutter, and the registrations against it lean on
// the walls that happened to fit. Measured (docs/back-end.md, "Noisy walls that were not lines"):
// the maps built from exact ranges give 0.021 m on the apartment, from LD06 returns 0.032 m; most
// of the gap closes when the tolerance grows with the noise.
#pragma once

#include "core/config.hpp"
#include "core/registration/registration_reference.hpp"

namespace dpcr {

// How many of the lidar's range sigmas a noisy wall's cells add, in quadrature, to a clean wall's
// fit tolerance: the sweep's best for the LD06 (1.0 cells) and close to it for the XV-11 (1.3).
constexpr float kNoiseSigmasInLineFit = 4.0f / 3.0f;

// `base` with its line fit tolerance widened for LidarConfig::range_noise_m at the grid's
// resolution: sqrt(max_rms^2 + (k sigma / resolution)^2). Unchanged when the noise is not known
// (0: the public logs, whose SICK lasers are near the clean case).
ReferenceConfig ReferenceForNoise(const ReferenceConfig& base, const MapperConfig& config);

}  // namespace dpcr
