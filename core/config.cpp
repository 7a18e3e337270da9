#include "core/config.hpp"

#include <cmath>

namespace dpcr {

Status Validate(const MapperConfig& c) {
  const bool grid_ok = c.grid.resolution_m > 0.005f && c.grid.resolution_m < 1.0f &&
                       c.grid.hit_delta > 0 && c.grid.miss_delta < 0 && c.grid.clamp_max > 0 &&
                       c.grid.clamp_min < 0 && c.grid.clamp_max > c.grid.hit_delta &&
                       c.grid.clamp_min < c.grid.miss_delta && c.grid.hit_margin_m >= 0.0f;
  const bool lidar_ok = c.lidar.min_range_m >= 0.0f && c.lidar.max_range_m > c.lidar.min_range_m &&
                        c.lidar.no_return_free_m >= 0.0f;
  const FrontEndConfig& f = c.front_end;
  // Regions tile one cell lattice, so neighbouring regional maps are a whole number of cells apart
  // (FrontEnd::BuildRegionReference merges two of them by shifting cells).
  const float cells_per_region = f.region_width_m / c.grid.resolution_m;
  const bool lattice_ok = std::fabs(cells_per_region - std::round(cells_per_region)) < 1e-3f;
  const bool front_ok = lattice_ok && f.submap_scans > 0 && f.submap_line_period > 0 && f.region_line_period > 0 &&
                        f.second_registration_period > 0 && f.region_width_m > 0.5f &&
                        (f.submap_miss_range_m == 0.0f || f.submap_miss_range_m > c.grid.hit_margin_m) &&
                        (f.region_miss_range_m == 0.0f || f.region_miss_range_m > c.grid.hit_margin_m) &&
                        f.region_hysteresis_m >= 0.0f && f.region_hysteresis_m < f.region_width_m / 2 &&
                        f.region_mature_scans > 0 && f.submap_refit_gate_m >= 0.0f && f.submap_refit_min_points > 0 && f.reference_inner_margin_m >= 0.0f;
  return grid_ok && lidar_ok && front_ok ? Status::kOk : Status::kInvalidArgument;
}

}  // namespace dpcr
