// Writes a fused map for robots (map.pgm + map.yaml, ROS map_server) and for people
// (map.png: the map with the estimated path, and the ground truth where known, drawn over it).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/grid/tiled_grid.hpp"
#include "host_sim/eval/trajectory.hpp"

namespace dpcr::output {

struct FusedMap {
  dpcr::CellBox box;
  float resolution_m = 0.05f;
  std::vector<std::int16_t> cells;  // row-major from box.min.y; empty when nothing was mapped
  int width() const { return box.width(); }
  int height() const { return box.height(); }
};

// Renders any Mapper's fused global map.
template <class MapperType>
FusedMap RenderFused(const MapperType& mapper) {
  FusedMap map;
  map.resolution_m = mapper.config().grid.resolution_m;
  map.box = mapper.MapBounds();
  if (map.box.width() <= 0 || map.box.height() <= 0) return map;
  map.cells.resize(static_cast<std::size_t>(map.box.width()) * static_cast<std::size_t>(map.box.height()));
  (void)mapper.RenderMap(map.box, dpcr::Span<std::int16_t>(map.cells.data(), map.cells.size()));
  return map;
}

// Writes `<dir>/map.pgm` and `<dir>/map.yaml`; throws std::runtime_error naming the file.
void WriteRosMap(const std::string& dir, const FusedMap& map);
// Writes `<dir>/map.png`; `ground_truth` may be empty.
void WriteMapPng(const std::string& dir, const FusedMap& map, const dpcr::eval::Trajectory& estimate,
                 const dpcr::eval::Trajectory& ground_truth);

// Writes a whole file at once, throwing std::runtime_error with the path and errno text.
void WriteFile(const std::string& path, const void* data, std::size_t size);

}  // namespace dpcr::output
