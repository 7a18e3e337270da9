// The map file (format version 1): everything a robot needs to map on from where it stopped, in
// one little-endian byte stream. docs/map-file-format.md describes it for other readers.
//
//   header   96 bytes   magic "DPCRMAP\x1a", version, header size, profile name and capacities,
//                       resolution, region width, clamp bounds, the world centre of region (0, 0),
//                       counts (regions, tiles, vertices, edges), payload size, header CRC-32
//   regions  per region: key (i, j), anchor (x, y, theta), scans inserted, tile count (28 bytes),
//                       then its observed tiles in box order: slot (tx, ty), encoding, size, cells
//   graph    vertices (x, y, theta; 12 bytes each), edges (from, to, kind, measurement, 3x3
//                       information row-major; 56 bytes each)
//   trailer  CRC-32 of every byte before it (header and payload)
//
// A tile's 1024 cells go raw (int16 each) or as runs, whichever is shorter: most cells of a
// regional map are unknown or settled at a clamp bound, which the runs code in one byte per run
// (TileToken). Readers validate everything before a mapper is touched (map_reader.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/base/status.hpp"
#include "core/capacity.hpp"
#include "core/geometry/pose2.hpp"

namespace dpcr {

constexpr std::uint8_t kMapFileMagic[8] = {'D', 'P', 'C', 'R', 'M', 'A', 'P', 0x1A};
constexpr std::uint16_t kMapFileVersion = 1;
constexpr std::size_t kMapProfileNameBytes = 16;
constexpr std::size_t kMapHeaderBytes = 96;
constexpr std::size_t kMapRegionBytes = 28;
constexpr std::size_t kMapTileHeaderBytes = 6;
constexpr std::size_t kMapRawTileBytes = 2 * kTileCells;
constexpr std::size_t kMapVertexBytes = 12;
constexpr std::size_t kMapEdgeBytes = 56;
constexpr std::size_t kMapTrailerBytes = 4;
// Plausibility bounds of what a file may hold (a home, or a building, with room to spare).
constexpr float kMapMaxCoordinateM = 100000.0f;
constexpr std::int32_t kMapMaxRegionKey = 1 << 20;

enum class TileEncoding : std::uint8_t { kRaw = 0, kRuns = 1 };

// Why a map file was refused (or a save failed). Describe() gives the one-line message.
enum class MapFileError : std::uint8_t {
  kNone = 0,
  kUnreadable,        // the source could not start over (Rewind failed)
  kTruncated,         // the data ends before the structure it announces
  kTrailingData,      // bytes after the trailer
  kBadMagic,          // not a dpcr map file
  kUnsupportedVersion,
  kBadHeader,         // header CRC mismatch or a header field out of range
  kWrongProfile,      // saved by a build with another profile (name or capacities)
  kConfigMismatch,    // resolution, region width or clamp bounds differ from the mapper's
  kBadChecksum,       // CRC-32 of the file does not match its trailer
  kBadRegion,         // a region record out of range (key, anchor, duplicate key, tile count)
  kBadTile,           // a tile outside its box, out of order, or badly encoded
  kBadCells,          // a cell value outside the clamp bounds
  kBadGraph,          // a vertex or edge out of range
  kWriteFailed,       // the sink refused bytes
  kChangedDuringLoad, // the data differed between the check and the load (mapper emptied)
  kBadStartPose,      // LoadMap's start pose is not finite or out of range
};

const char* Describe(MapFileError error);

struct MapFileResult {
  Status status = Status::kOk;
  MapFileError error = MapFileError::kNone;
  std::size_t offset = 0;  // where in the file the error was found
  bool ok() const { return error == MapFileError::kNone; }
};

// What the header says.
struct MapFileHeader {
  std::uint16_t version = kMapFileVersion;
  char profile[kMapProfileNameBytes] = {};
  std::uint32_t max_regions = 0;
  std::uint32_t tile_pool_tiles = 0;
  std::uint32_t region_box_tiles = 0;
  std::uint32_t max_graph_edges = 0;
  float resolution_m = 0.0f;
  float region_width_m = 0.0f;
  std::int16_t clamp_min = 0;
  std::int16_t clamp_max = 0;
  Point2 region_origin;  // world centre of region (0, 0): the region lattice
  std::uint32_t region_count = 0;
  std::uint32_t tile_count = 0;
  std::uint32_t vertex_count = 0;
  std::uint32_t edge_count = 0;
  std::uint32_t payload_bytes = 0;  // between the header and the trailer
  std::uint64_t file_bytes() const { return kMapHeaderBytes + std::uint64_t{payload_bytes} + kMapTrailerBytes; }
};

// What a mapper can take: its profile and the grid it maps with.
struct MapFileLimits {
  const char* profile = "";
  std::uint32_t max_regions = 0;
  std::uint32_t tile_pool_tiles = 0;
  std::uint32_t region_box_tiles = 0;
  std::uint32_t max_graph_edges = 0;
  float resolution_m = 0.0f;
  float region_width_m = 0.0f;
  std::int16_t clamp_min = 0;
  std::int16_t clamp_max = 0;
};

template <class Profile>
MapFileLimits ProfileMapLimits(float resolution_m, float region_width_m, std::int16_t clamp_min, std::int16_t clamp_max) {
  MapFileLimits l;
  l.profile = Profile::kName;
  l.max_regions = static_cast<std::uint32_t>(Profile::kMaxRegions);
  l.tile_pool_tiles = static_cast<std::uint32_t>(Profile::kTilePoolTiles);
  l.region_box_tiles = static_cast<std::uint32_t>(Profile::kRegionBoxTiles);
  l.max_graph_edges = static_cast<std::uint32_t>(Profile::kMaxGraphEdges);
  l.resolution_m = resolution_m;
  l.region_width_m = region_width_m;
  l.clamp_min = clamp_min;
  l.clamp_max = clamp_max;
  return l;
}

// The largest file a mapper with these limits can write (every pool tile raw): a reader need not
// read further.
inline std::uint64_t MaxMapFileBytes(const MapFileLimits& l) {
  return kMapHeaderBytes + std::uint64_t{l.max_regions} * (kMapRegionBytes + kMapVertexBytes) +
         std::uint64_t{l.tile_pool_tiles} * (kMapTileHeaderBytes + kMapRawTileBytes) +
         std::uint64_t{l.max_graph_edges} * kMapEdgeBytes + kMapTrailerBytes;
}

// The header of a map a mapper with these limits writes (counts and payload size zero).
MapFileHeader HeaderFor(const MapFileLimits& limits, Point2 region_origin);

// Header bytes, header CRC included.
void EncodeMapHeader(const MapFileHeader& header, std::uint8_t (&out)[kMapHeaderBytes]);
// Magic, version, header CRC, then every field's range and the counts against the capacities the
// header states. kNone when the header is sound.
MapFileError DecodeMapHeader(const std::uint8_t (&in)[kMapHeaderBytes], MapFileHeader* out);
// kWrongProfile / kConfigMismatch when a sound header does not fit a mapper with `limits`.
MapFileError CheckMapFits(const MapFileHeader& header, const MapFileLimits& limits);

// Tile runs: one byte per token; n = (token & 63) + 1 for the first three kinds, (token & 31) + 1
// for the last two.
//   0x00-0x3F  n unknown cells          0x40-0x7F  n cells at clamp_min   0x80-0xBF  n at clamp_max
//   0xC0-0xDF  n cells of the int16 that follows                          0xE0-0xFF  n int16 follow
struct TileToken {
  std::uint8_t code = 0;  // the token byte
  int cells = 0;          // cells it covers
  int values = 0;         // int16 values that follow it (0, 1 or cells)
};
// A cell as the file stores it: a hit mean (core/grid/hit_mean.hpp) as the clamp it settled at.
// The file keeps the log-odds only; a loaded map's walls learn their hit means again.
inline std::int16_t MapFileValue(std::int16_t v, std::int16_t clamp_max) { return v > clamp_max ? clamp_max : v; }
// The token that codes the cells from `i` on (i < kTileCells); hit means coded as MapFileValue.
TileToken NextTileToken(const std::int16_t* cells, int i, std::int16_t clamp_min, std::int16_t clamp_max);
// Bytes of the run encoding of a tile.
std::size_t TileRunBytes(const std::int16_t* cells, std::int16_t clamp_min, std::int16_t clamp_max);

// Little-endian fields.
inline void PutU16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
inline void PutU32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void PutF32(std::uint8_t* p, float v);
inline std::uint16_t GetU16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
inline std::uint32_t GetU32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24);
}
inline std::int16_t GetI16(const std::uint8_t* p) { return static_cast<std::int16_t>(GetU16(p)); }
inline std::int32_t GetI32(const std::uint8_t* p) { return static_cast<std::int32_t>(GetU32(p)); }
float GetF32(const std::uint8_t* p);

// A pose a file may hold: finite, within kMapMaxCoordinateM, theta in [-pi, pi].
bool PlausiblePose(const Pose2& p);

}  // namespace dpcr
