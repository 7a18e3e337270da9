#include "core/persistence/map_file_format.hpp"

#include <cmath>
#include <cstring>

#include "core/grid/cell.hpp"
#include "core/grid/tile_pool.hpp"
#include "core/persistence/crc32.hpp"

namespace dpcr {
namespace {

// Header layout (byte offsets).
constexpr std::size_t kVersionAt = 8, kHeaderSizeAt = 10, kProfileAt = 12, kMaxRegionsAt = 28, kPoolAt = 32,
                      kBoxAt = 36, kEdgesCapAt = 40, kTileSideAt = 44, kResolutionAt = 48, kWidthAt = 52,
                      kClampMinAt = 56, kClampMaxAt = 58, kOriginXAt = 60, kOriginYAt = 64, kRegionsAt = 68,
                      kTilesAt = 72, kVerticesAt = 76, kEdgeCountAt = 80, kPayloadAt = 84, kReservedAt = 88,
                      kHeaderCrcAt = 92;
static_assert(kHeaderCrcAt + 4 == kMapHeaderBytes, "header layout");

bool Finite(float v) { return std::isfinite(v); }

bool ProfileNameOk(const char (&name)[kMapProfileNameBytes]) {
  std::size_t n = 0;
  while (n < kMapProfileNameBytes && name[n] != '\0') {
    if (name[n] < 0x21 || name[n] > 0x7E) return false;
    ++n;
  }
  if (n == 0 || n == kMapProfileNameBytes) return false;
  for (std::size_t i = n; i < kMapProfileNameBytes; ++i) {
    if (name[i] != '\0') return false;
  }
  return true;
}

// Capacities and grid a sound header may state.
bool HeaderFieldsOk(const MapFileHeader& h) {
  const bool capacities = h.max_regions >= 1 && h.max_regions < (1u << 15) && h.tile_pool_tiles >= 1 &&
                          h.tile_pool_tiles < kTileInUse && h.region_box_tiles >= 1 && h.region_box_tiles <= 255 &&
                          h.max_graph_edges <= (1u << 20);
  const float box_m = static_cast<float>(h.region_box_tiles * kTileSide) * h.resolution_m;
  const bool grid = Finite(h.resolution_m) && h.resolution_m > 0.005f && h.resolution_m < 1.0f &&
                    Finite(h.region_width_m) && h.region_width_m > 0.5f && h.region_width_m <= box_m &&
                    h.clamp_min > INT16_MIN && h.clamp_min < 0 && h.clamp_max > 0;
  const bool origin = Finite(h.region_origin.x) && Finite(h.region_origin.y) &&
                      std::fabs(h.region_origin.x) <= kMapMaxCoordinateM && std::fabs(h.region_origin.y) <= kMapMaxCoordinateM;
  const bool counts = h.region_count <= h.max_regions && h.tile_count <= h.tile_pool_tiles &&
                      h.vertex_count <= h.region_count && h.edge_count <= h.max_graph_edges &&
                      std::uint64_t{h.tile_count} <= std::uint64_t{h.region_count} * h.region_box_tiles * h.region_box_tiles;
  // The payload the counts allow: every tile at least 16 bytes of runs, at most raw.
  const std::uint64_t fixed = std::uint64_t{h.region_count} * kMapRegionBytes + std::uint64_t{h.vertex_count} * kMapVertexBytes +
                              std::uint64_t{h.edge_count} * kMapEdgeBytes;
  const std::uint64_t least = fixed + std::uint64_t{h.tile_count} * (kMapTileHeaderBytes + kTileCells / 64);
  const std::uint64_t most = fixed + std::uint64_t{h.tile_count} * (kMapTileHeaderBytes + kMapRawTileBytes);
  const bool payload = h.payload_bytes >= least && h.payload_bytes <= most;
  return capacities && grid && origin && counts && payload;
}

}  // namespace

const char* Describe(MapFileError error) {
  switch (error) {
    case MapFileError::kNone: return "ok";
    case MapFileError::kUnreadable: return "cannot be read from the start again";
    case MapFileError::kTruncated: return "truncated: the file ends before the map it announces";
    case MapFileError::kTrailingData: return "unexpected bytes after the end of the map";
    case MapFileError::kBadMagic: return "not a dpcr map file (bad magic)";
    case MapFileError::kUnsupportedVersion: return "unsupported map format version";
    case MapFileError::kBadHeader: return "corrupt header (header CRC or a field out of range)";
    case MapFileError::kWrongProfile: return "saved by a build with another profile (name or capacities differ)";
    case MapFileError::kConfigMismatch: return "resolution, region width or clamp bounds differ from the mapper's configuration";
    case MapFileError::kBadChecksum: return "corrupt: CRC-32 mismatch";
    case MapFileError::kBadRegion: return "corrupt region record (key, anchor or tile count)";
    case MapFileError::kBadTile: return "corrupt tile (position, order or encoding)";
    case MapFileError::kBadCells: return "corrupt tile cells (value outside the clamp bounds)";
    case MapFileError::kBadGraph: return "corrupt pose graph (vertex or edge out of range)";
    case MapFileError::kWriteFailed: return "write failed";
    case MapFileError::kChangedDuringLoad: return "the file changed while it was loaded (map cleared)";
    case MapFileError::kBadStartPose: return "start pose not finite or out of range";
  }
  return "unknown error";
}

void PutF32(std::uint8_t* p, float v) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof(bits));
  PutU32(p, bits);
}

float GetF32(const std::uint8_t* p) {
  const std::uint32_t bits = GetU32(p);
  float v = 0.0f;
  std::memcpy(&v, &bits, sizeof(v));
  return v;
}

bool PlausiblePose(const Pose2& p) {
  return Finite(p.x) && Finite(p.y) && Finite(p.theta) && std::fabs(p.x) <= kMapMaxCoordinateM &&
         std::fabs(p.y) <= kMapMaxCoordinateM && std::fabs(p.theta) <= kPi + 1e-4f;
}

MapFileHeader HeaderFor(const MapFileLimits& limits, Point2 region_origin) {
  MapFileHeader h;
  for (std::size_t i = 0; i + 1 < kMapProfileNameBytes && limits.profile[i] != '\0'; ++i) h.profile[i] = limits.profile[i];
  h.max_regions = limits.max_regions;
  h.tile_pool_tiles = limits.tile_pool_tiles;
  h.region_box_tiles = limits.region_box_tiles;
  h.max_graph_edges = limits.max_graph_edges;
  h.resolution_m = limits.resolution_m;
  h.region_width_m = limits.region_width_m;
  h.clamp_min = limits.clamp_min;
  h.clamp_max = limits.clamp_max;
  h.region_origin = region_origin;
  return h;
}

void EncodeMapHeader(const MapFileHeader& h, std::uint8_t (&out)[kMapHeaderBytes]) {
  for (std::uint8_t& b : out) b = 0;
  for (std::size_t i = 0; i < sizeof(kMapFileMagic); ++i) out[i] = kMapFileMagic[i];
  PutU16(out + kVersionAt, h.version);
  PutU16(out + kHeaderSizeAt, static_cast<std::uint16_t>(kMapHeaderBytes));
  for (std::size_t i = 0; i < kMapProfileNameBytes; ++i) out[kProfileAt + i] = static_cast<std::uint8_t>(h.profile[i]);
  PutU32(out + kMaxRegionsAt, h.max_regions);
  PutU32(out + kPoolAt, h.tile_pool_tiles);
  PutU32(out + kBoxAt, h.region_box_tiles);
  PutU32(out + kEdgesCapAt, h.max_graph_edges);
  PutU32(out + kTileSideAt, static_cast<std::uint32_t>(kTileSide));
  PutF32(out + kResolutionAt, h.resolution_m);
  PutF32(out + kWidthAt, h.region_width_m);
  PutU16(out + kClampMinAt, static_cast<std::uint16_t>(h.clamp_min));
  PutU16(out + kClampMaxAt, static_cast<std::uint16_t>(h.clamp_max));
  PutF32(out + kOriginXAt, h.region_origin.x);
  PutF32(out + kOriginYAt, h.region_origin.y);
  PutU32(out + kRegionsAt, h.region_count);
  PutU32(out + kTilesAt, h.tile_count);
  PutU32(out + kVerticesAt, h.vertex_count);
  PutU32(out + kEdgeCountAt, h.edge_count);
  PutU32(out + kPayloadAt, h.payload_bytes);
  PutU32(out + kHeaderCrcAt, Crc32Of(out, kHeaderCrcAt));
}

MapFileError DecodeMapHeader(const std::uint8_t (&in)[kMapHeaderBytes], MapFileHeader* out) {
  for (std::size_t i = 0; i < sizeof(kMapFileMagic); ++i) {
    if (in[i] != kMapFileMagic[i]) return MapFileError::kBadMagic;
  }
  // The version before the header CRC: another version may lay its header out differently.
  MapFileHeader h;
  h.version = GetU16(in + kVersionAt);
  if (h.version != kMapFileVersion) return MapFileError::kUnsupportedVersion;
  if (GetU32(in + kHeaderCrcAt) != Crc32Of(in, kHeaderCrcAt)) return MapFileError::kBadHeader;
  for (std::size_t i = 0; i < kMapProfileNameBytes; ++i) h.profile[i] = static_cast<char>(in[kProfileAt + i]);
  h.max_regions = GetU32(in + kMaxRegionsAt);
  h.tile_pool_tiles = GetU32(in + kPoolAt);
  h.region_box_tiles = GetU32(in + kBoxAt);
  h.max_graph_edges = GetU32(in + kEdgesCapAt);
  h.resolution_m = GetF32(in + kResolutionAt);
  h.region_width_m = GetF32(in + kWidthAt);
  h.clamp_min = GetI16(in + kClampMinAt);
  h.clamp_max = GetI16(in + kClampMaxAt);
  h.region_origin = Point2{GetF32(in + kOriginXAt), GetF32(in + kOriginYAt)};
  h.region_count = GetU32(in + kRegionsAt);
  h.tile_count = GetU32(in + kTilesAt);
  h.vertex_count = GetU32(in + kVerticesAt);
  h.edge_count = GetU32(in + kEdgeCountAt);
  h.payload_bytes = GetU32(in + kPayloadAt);
  const bool layout = GetU16(in + kHeaderSizeAt) == kMapHeaderBytes && GetU32(in + kTileSideAt) == kTileSide &&
                      GetU32(in + kReservedAt) == 0;
  if (!layout || !ProfileNameOk(h.profile) || !HeaderFieldsOk(h)) return MapFileError::kBadHeader;
  *out = h;
  return MapFileError::kNone;
}

MapFileError CheckMapFits(const MapFileHeader& h, const MapFileLimits& l) {
  const bool same_profile = std::strncmp(h.profile, l.profile, kMapProfileNameBytes) == 0 &&
                            h.max_regions == l.max_regions && h.tile_pool_tiles == l.tile_pool_tiles &&
                            h.region_box_tiles == l.region_box_tiles && h.max_graph_edges == l.max_graph_edges;
  if (!same_profile) return MapFileError::kWrongProfile;
  const bool same_grid = h.resolution_m == l.resolution_m && h.region_width_m == l.region_width_m &&
                         h.clamp_min == l.clamp_min && h.clamp_max == l.clamp_max;
  return same_grid ? MapFileError::kNone : MapFileError::kConfigMismatch;
}

TileToken NextTileToken(const std::int16_t* raw, int i, std::int16_t clamp_min, std::int16_t clamp_max) {
  const auto cells = [&](int j) { return MapFileValue(raw[j], clamp_max); };
  const std::int16_t v = cells(i);
  const auto run_of = [&](int j, int most) {
    int n = 1;
    while (n < most && j + n < kTileCells && cells(j + n) == cells(j)) ++n;
    return n;
  };
  TileToken t;
  if (v == kUnknownCell || v == clamp_min || v == clamp_max) {
    t.cells = run_of(i, 64);
    const std::uint8_t kind = v == kUnknownCell ? 0x00 : (v == clamp_min ? 0x40 : 0x80);
    t.code = static_cast<std::uint8_t>(kind | (t.cells - 1));
    return t;
  }
  const int run = run_of(i, 32);
  if (run >= 2) {
    t.cells = run;
    t.values = 1;
    t.code = static_cast<std::uint8_t>(0xC0 | (run - 1));
    return t;
  }
  // Literals: up to the next special value or the next run of two.
  int n = 1;
  while (n < 32 && i + n < kTileCells) {
    const std::int16_t w = cells(i + n);
    if (w == kUnknownCell || w == clamp_min || w == clamp_max) break;
    if (i + n + 1 < kTileCells && cells(i + n + 1) == w) break;
    ++n;
  }
  t.cells = t.values = n;
  t.code = static_cast<std::uint8_t>(0xE0 | (n - 1));
  return t;
}

std::size_t TileRunBytes(const std::int16_t* cells, std::int16_t clamp_min, std::int16_t clamp_max) {
  std::size_t bytes = 0;
  for (int i = 0; i < kTileCells;) {
    const TileToken t = NextTileToken(cells, i, clamp_min, clamp_max);
    bytes += 1 + 2 * static_cast<std::size_t>(t.values);
    i += t.cells;
  }
  return bytes;
}

}  // namespace dpcr
