// Writes a fused map for robots (map.pgm + map.yaml, ROS map_server) and for people
// (map.png: the map with the estimated path, and the ground truth where known, drawn over it).
#pragma once

#include <cstdint>
#include <stdexcept>
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

// The largest fused map rendered: 2^26 cells (128 MB, a 400 m square at 5 cm). Past that the
// regions lie absurdly far apart (a pose that jumped kilometres), and a plain error beats a failed
// allocation.
constexpr std::size_t kMaxRenderedCells = std::size_t{1} << 26;

// Renders any Mapper's fused global map; std::runtime_error when it spans more than
// kMaxRenderedCells.
template <class MapperType>
FusedMap RenderFused(const MapperType& mapper) {
  FusedMap map;
  map.resolution_m = mapper.config().grid.resolution_m;
  map.box = mapper.MapBounds();
  if (map.box.width() <= 0 || map.box.height() <= 0) return map;
  const std::size_t cells = static_cast<std::size_t>(map.box.width()) * static_cast<std::size_t>(map.box.height());
  if (cells > kMaxRenderedCells) {
    const auto metres = [&](int n) { return std::to_string(static_cast<long long>(n * static_cast<double>(map.resolution_m))); };
    throw std::runtime_error("the map spans " + metres(map.box.width()) + " m x " + metres(map.box.height()) +
                             " m, too large to render: its regions lie far apart (did a pose jump?)");
  }
  map.cells.resize(cells);
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
