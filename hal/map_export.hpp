// ROS map_server encoding of a fused occupancy map: a PGM image (P5) and its YAML description.
// Pure functions over caller buffers: the board writes the bytes with its atomic file store,
// host apps with ordinary files.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/grid/cell.hpp"
#include "core/base/span.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr {

// map_saver's trinary values: occupied 0, free 254, unknown 205 (with negate 0,
// occupied_thresh 0.65 and free_thresh 0.196 these read back as the same classes).
constexpr std::uint8_t kPgmOccupied = 0;
constexpr std::uint8_t kPgmFree = 254;
constexpr std::uint8_t kPgmUnknown = 205;
constexpr float kOccupiedThreshold = 0.65f;
constexpr float kFreeThreshold = 0.196f;

std::uint8_t PgmValue(std::int16_t cell);

// Bytes needed by EncodePgm for a w x h map.
std::size_t PgmSize(int width, int height);

// Writes P5 PGM bytes; row 0 of the image is the map's top (max y), as map_server expects.
// `cells` row-major from min y (as Mapper::RenderMap gives them). Returns bytes written, 0 if
// `out` is too small.
std::size_t EncodePgm(Span<const std::int16_t> cells, int width, int height, Span<std::uint8_t> out);

// Writes the YAML text (NUL-terminated); returns its length, 0 if `out` is too small.
std::size_t EncodeMapYaml(const char* image_file, float resolution_m, CellBox box, Span<char> out);

}  // namespace dpcr
