// A regional map (paper §3.4): the scans made inside one region of width S, fused in a tiled grid
// in the frame of its anchor. The back end moves anchors; cells are never resampled.
#pragma once

#include <cstdint>

#include "core/front_end/region_tracker.hpp"
#include "core/geometry/pose2.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr {

struct RegionalMap {
  RegionKey key;
  Pose2 anchor;              // the map's frame in the world; the back end moves it
  TiledGrid* grid = nullptr;  // points into the Mapper's storage
  std::uint32_t scans_inserted = 0;
};

}  // namespace dpcr
