#include "core/persistence/map_reader.hpp"

#include <cmath>

#include "core/grid/cell.hpp"
#include "core/persistence/crc32.hpp"

namespace dpcr {
namespace {

// Bytes from the source through a small buffer, with the running CRC of everything consumed.
class ChunkReader {
 public:
  explicit ChunkReader(MapByteSource& source) : source_(source) {}
  // False when the data ends first.
  bool Get(std::uint8_t* out, std::size_t size) { return GetUpTo(out, size) == size; }
  // The bytes there are, up to `size`.
  std::size_t GetUpTo(std::uint8_t* out, std::size_t size) {
    std::size_t n = 0;
    while (n < size && (head_ < size_ || Fill())) out[n++] = buffer_[head_++];
    crc_.Add(out, n);
    offset_ += n;
    return n;
  }
  bool Skip(std::uint64_t size) {
    while (size > 0) {
      if (head_ == size_ && !Fill()) return false;
      std::size_t n = size_ - head_;
      if (n > size) n = static_cast<std::size_t>(size);
      crc_.Add(buffer_ + head_, n);
      head_ += n;
      offset_ += n;
      size -= n;
    }
    return true;
  }
  bool AtEnd() { return head_ == size_ && !Fill(); }
  std::size_t offset() const { return offset_; }
  std::uint32_t crc() const { return crc_.value(); }

 private:
  bool Fill() {
    const std::size_t n = source_.Read(buffer_, sizeof(buffer_));
    size_ = n <= sizeof(buffer_) ? n : 0;
    head_ = 0;
    return size_ > 0;
  }

  MapByteSource& source_;
  std::uint8_t buffer_[kMapReadChunkBytes];
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  std::size_t offset_ = 0;
  Crc32 crc_;
};

MapFileResult Fail(MapFileError error, std::size_t offset) {
  MapFileResult r;
  r.error = error;
  r.offset = offset;
  const bool mismatch = error == MapFileError::kWrongProfile || error == MapFileError::kConfigMismatch;
  r.status = mismatch ? Status::kRejected : Status::kInvalidArgument;
  return r;
}

// Where pass 2 records keys (check) or pass 3 writes (apply: front_end and graph set).
struct WalkTarget {
  Span<Point2> keys;
  FrontEnd* front_end = nullptr;
  PoseGraph* graph = nullptr;
  MapFileSummary* summary = nullptr;
};

struct RegionRecord {
  RegionKey key;
  Pose2 anchor;
  std::uint32_t scans = 0;
  std::uint32_t tiles = 0;
};

struct TileRecord {
  int tx = 0;
  int ty = 0;
  TileEncoding encoding = TileEncoding::kRaw;
  std::size_t bytes = 0;
};

bool KeyInRange(std::int32_t k) { return k >= -kMapMaxRegionKey && k <= kMapMaxRegionKey; }

MapFileError ReadHeader(ChunkReader& r, const MapFileLimits* limits, MapFileHeader* header) {
  std::uint8_t raw[kMapHeaderBytes];
  const std::size_t n = r.GetUpTo(raw, sizeof(raw));
  if (n < sizeof(raw)) {
    // Too short for a header: a map cut short, or not a map at all.
    for (std::size_t i = 0; i < n && i < sizeof(kMapFileMagic); ++i) {
      if (raw[i] != kMapFileMagic[i]) return MapFileError::kBadMagic;
    }
    return MapFileError::kTruncated;
  }
  const MapFileError e = DecodeMapHeader(raw, header);
  if (e != MapFileError::kNone || limits == nullptr) return e;
  return CheckMapFits(*header, *limits);
}

// The header again (passes 2 and 3): byte for byte the one pass 1 decoded.
bool SameHeader(ChunkReader& r, const MapFileHeader& expected) {
  std::uint8_t raw[kMapHeaderBytes];
  std::uint8_t want[kMapHeaderBytes];
  if (!r.Get(raw, sizeof(raw))) return false;
  EncodeMapHeader(expected, want);
  for (std::size_t i = 0; i < kMapHeaderBytes; ++i) {
    if (raw[i] != want[i]) return false;
  }
  return true;
}

MapFileError ReadRegionRecord(ChunkReader& r, const MapFileHeader& h, RegionRecord* out) {
  std::uint8_t b[kMapRegionBytes];
  if (!r.Get(b, sizeof(b))) return MapFileError::kTruncated;
  out->key = RegionKey{GetI32(b), GetI32(b + 4)};
  out->anchor = Pose2{GetF32(b + 8), GetF32(b + 12), GetF32(b + 16)};
  out->scans = GetU32(b + 20);
  out->tiles = GetU32(b + 24);
  const bool ok = KeyInRange(out->key.i) && KeyInRange(out->key.j) && PlausiblePose(out->anchor) &&
                  out->tiles <= h.region_box_tiles * h.region_box_tiles;
  return ok ? MapFileError::kNone : MapFileError::kBadRegion;
}

// A key seen before: in the keys recorded (check) or the maps restored (apply).
bool DuplicateKey(const WalkTarget& t, std::uint32_t count, RegionKey key) {
  for (std::uint32_t k = 0; k < count; ++k) {
    const bool same = t.front_end != nullptr
                          ? t.front_end->region(static_cast<int>(k)).key == key
                          : t.keys[k].x == static_cast<float>(key.i) && t.keys[k].y == static_cast<float>(key.j);
    if (same) return true;
  }
  return false;
}

MapFileError ReadTileHeader(ChunkReader& r, const MapFileHeader& h, int last_slot, TileRecord* out) {
  std::uint8_t b[kMapTileHeaderBytes];
  if (!r.Get(b, sizeof(b))) return MapFileError::kTruncated;
  out->tx = b[0];
  out->ty = b[1];
  out->bytes = GetU16(b + 4);
  const int box = static_cast<int>(h.region_box_tiles);
  const bool placed = out->tx < box && out->ty < box && out->ty * box + out->tx > last_slot;
  bool sized = false;
  if (b[2] == static_cast<std::uint8_t>(TileEncoding::kRaw)) {
    out->encoding = TileEncoding::kRaw;
    sized = out->bytes == kMapRawTileBytes;
  } else if (b[2] == static_cast<std::uint8_t>(TileEncoding::kRuns)) {
    out->encoding = TileEncoding::kRuns;
    sized = out->bytes >= kTileCells / 64 && out->bytes < kMapRawTileBytes;
  }
  return placed && sized && b[3] == 0 ? MapFileError::kNone : MapFileError::kBadTile;
}

// Reads `n` int16 cell values into out[0..n) (when out is set), each unknown or within the clamps.
MapFileError ReadValues(ChunkReader& r, const MapFileHeader& h, int n, std::int16_t* out, std::int16_t* last) {
  for (int k = 0; k < n; ++k) {
    std::uint8_t b[2];
    if (!r.Get(b, 2)) return MapFileError::kTruncated;
    const std::int16_t v = GetI16(b);
    if (v != kUnknownCell && (v < h.clamp_min || v > h.clamp_max)) return MapFileError::kBadCells;
    if (out != nullptr) out[k] = v;
    *last = v;
  }
  return MapFileError::kNone;
}

MapFileError ReadRuns(ChunkReader& r, const MapFileHeader& h, std::size_t bytes, std::int16_t* out) {
  int cells = 0;
  while (cells < kTileCells) {
    std::uint8_t code = 0;
    if (bytes < 1) return MapFileError::kBadTile;
    if (!r.Get(&code, 1)) return MapFileError::kTruncated;
    const bool literal = code >= 0xC0;
    const int n = literal ? (code & 31) + 1 : (code & 63) + 1;
    const int values = code >= 0xE0 ? n : (literal ? 1 : 0);
    if (cells + n > kTileCells || bytes < 1 + 2 * static_cast<std::size_t>(values)) return MapFileError::kBadTile;
    bytes -= 1 + 2 * static_cast<std::size_t>(values);
    std::int16_t v = code < 0x40 ? kUnknownCell : (code < 0x80 ? h.clamp_min : h.clamp_max);
    if (code >= 0xE0) {
      const MapFileError e = ReadValues(r, h, n, out != nullptr ? out + cells : nullptr, &v);
      if (e != MapFileError::kNone) return e;
    } else {
      if (literal) {
        const MapFileError e = ReadValues(r, h, 1, nullptr, &v);
        if (e != MapFileError::kNone) return e;
      }
      for (int k = 0; out != nullptr && k < n; ++k) out[cells + k] = v;
    }
    cells += n;
  }
  return bytes == 0 ? MapFileError::kNone : MapFileError::kBadTile;
}

MapFileError ReadTiles(ChunkReader& r, const MapFileHeader& h, std::uint32_t count, RegionalMap* map,
                       MapFileSummary* summary) {
  int last_slot = -1;
  for (std::uint32_t n = 0; n < count; ++n) {
    TileRecord t;
    MapFileError e = ReadTileHeader(r, h, last_slot, &t);
    if (e != MapFileError::kNone) return e;
    last_slot = t.ty * static_cast<int>(h.region_box_tiles) + t.tx;
    std::int16_t* out = nullptr;
    if (map != nullptr) {
      const Span<std::int16_t> cells = map->grid->RestoreTile(t.tx, t.ty);
      if (cells.size() != static_cast<std::size_t>(kTileCells)) return MapFileError::kBadTile;
      out = cells.data();
    }
    std::int16_t last = 0;
    e = t.encoding == TileEncoding::kRaw ? ReadValues(r, h, kTileCells, out, &last) : ReadRuns(r, h, t.bytes, out);
    if (e != MapFileError::kNone) return e;
    if (summary != nullptr) {
      ++(t.encoding == TileEncoding::kRaw ? summary->raw_tiles : summary->run_tiles);
      summary->tile_bytes += kMapTileHeaderBytes + t.bytes;
    }
  }
  return MapFileError::kNone;
}

MapFileError WalkRegions(ChunkReader& r, const MapFileHeader& h, const WalkTarget& t) {
  std::uint32_t tiles = 0;
  for (std::uint32_t i = 0; i < h.region_count; ++i) {
    RegionRecord rec;
    const MapFileError e = ReadRegionRecord(r, h, &rec);
    if (e != MapFileError::kNone) return e;
    if (rec.tiles > h.tile_count - tiles || DuplicateKey(t, i, rec.key)) return MapFileError::kBadRegion;
    tiles += rec.tiles;
    RegionalMap* map = nullptr;
    if (t.front_end != nullptr) {
      map = t.front_end->RestoreRegion(rec.key, rec.anchor, rec.scans);
      if (map == nullptr) return MapFileError::kBadRegion;
    } else {
      t.keys[i] = Point2{static_cast<float>(rec.key.i), static_cast<float>(rec.key.j)};
    }
    const MapFileError te = ReadTiles(r, h, rec.tiles, map, t.summary);
    if (te != MapFileError::kNone) return te;
  }
  return tiles == h.tile_count ? MapFileError::kNone : MapFileError::kBadRegion;
}

bool InformationOk(const Eigen::Matrix3f& m) {
  for (int i = 0; i < 9; ++i) {
    if (!std::isfinite(m(i / 3, i % 3))) return false;
  }
  return m(0, 0) > 0.0f && m(1, 1) > 0.0f && m(2, 2) > 0.0f;
}

MapFileError ReadEdge(ChunkReader& r, const MapFileHeader& h, GraphEdge* e) {
  std::uint8_t b[kMapEdgeBytes];
  if (!r.Get(b, sizeof(b))) return MapFileError::kTruncated;
  e->from = GetU16(b);
  e->to = GetU16(b + 2);
  e->kind = static_cast<EdgeKind>(b[4]);
  e->measurement = Pose2{GetF32(b + 8), GetF32(b + 12), GetF32(b + 16)};
  for (int i = 0; i < 9; ++i) e->information(i / 3, i % 3) = GetF32(b + 20 + 4 * i);
  const int vertices = static_cast<int>(h.vertex_count);
  const bool ok = e->from < vertices && e->to < vertices && e->from != e->to && b[4] <= 2 && b[5] == 0 && b[6] == 0 &&
                  b[7] == 0 && PlausiblePose(e->measurement) && InformationOk(e->information);
  return ok ? MapFileError::kNone : MapFileError::kBadGraph;
}

MapFileError WalkGraph(ChunkReader& r, const MapFileHeader& h, const WalkTarget& t) {
  for (std::uint32_t i = 0; i < h.vertex_count; ++i) {
    std::uint8_t b[kMapVertexBytes];
    if (!r.Get(b, sizeof(b))) return MapFileError::kTruncated;
    const Pose2 p{GetF32(b), GetF32(b + 4), GetF32(b + 8)};
    if (!PlausiblePose(p)) return MapFileError::kBadGraph;
    if (t.graph != nullptr && t.graph->AddVertex(p) != Status::kOk) return MapFileError::kBadGraph;
  }
  for (std::uint32_t i = 0; i < h.edge_count; ++i) {
    GraphEdge e;
    const MapFileError err = ReadEdge(r, h, &e);
    if (err != MapFileError::kNone) return err;
    if (t.summary != nullptr) ++t.summary->edges_by_kind[static_cast<int>(e.kind)];
    if (t.graph != nullptr && t.graph->AddOrReplaceEdge(e) != Status::kOk) return MapFileError::kBadGraph;
  }
  return MapFileError::kNone;
}

// Pass 1: header, length and CRC-32.
MapFileResult ChecksumPass(MapByteSource& source, const MapFileLimits* limits, MapFileHeader* header) {
  if (!source.Rewind()) return Fail(MapFileError::kUnreadable, 0);
  ChunkReader r(source);
  const MapFileError e = ReadHeader(r, limits, header);
  if (e != MapFileError::kNone) return Fail(e, r.offset());
  if (!r.Skip(header->payload_bytes)) return Fail(MapFileError::kTruncated, r.offset());
  const std::uint32_t crc = r.crc();
  std::uint8_t trailer[kMapTrailerBytes];
  if (!r.Get(trailer, sizeof(trailer))) return Fail(MapFileError::kTruncated, r.offset());
  if (GetU32(trailer) != crc) return Fail(MapFileError::kBadChecksum, r.offset() - kMapTrailerBytes);
  if (!r.AtEnd()) return Fail(MapFileError::kTrailingData, r.offset());
  return MapFileResult{};
}

// Passes 2 and 3: every record, checked (and applied when `t` has a front end).
MapFileResult RecordPass(ChunkReader& r, const MapFileHeader& h, const WalkTarget& t) {
  MapFileError e = WalkRegions(r, h, t);
  if (e == MapFileError::kNone) e = WalkGraph(r, h, t);
  if (e != MapFileError::kNone) return Fail(e, r.offset());
  if (r.offset() != kMapHeaderBytes + h.payload_bytes) return Fail(MapFileError::kBadRegion, r.offset());
  const std::uint32_t crc = r.crc();
  std::uint8_t trailer[kMapTrailerBytes];
  if (!r.Get(trailer, sizeof(trailer))) return Fail(MapFileError::kTruncated, r.offset());
  if (GetU32(trailer) != crc) return Fail(MapFileError::kBadChecksum, r.offset() - kMapTrailerBytes);
  return MapFileResult{};
}

}  // namespace

MapFileResult ReadMapFileHeader(MapByteSource& source, MapFileHeader* header) {
  if (!source.Rewind()) return Fail(MapFileError::kUnreadable, 0);
  ChunkReader r(source);
  const MapFileError e = ReadHeader(r, nullptr, header);
  return e == MapFileError::kNone ? MapFileResult{} : Fail(e, r.offset());
}

MapFileResult CheckMapFile(MapByteSource& source, const MapFileLimits* limits, Span<Point2> key_scratch,
                           MapFileHeader* header, MapFileSummary* summary) {
  MapFileResult res = ChecksumPass(source, limits, header);
  if (!res.ok()) return res;
  if (key_scratch.size() < header->region_count) return Fail(MapFileError::kWrongProfile, 0);
  if (!source.Rewind()) return Fail(MapFileError::kUnreadable, 0);
  ChunkReader r(source);
  if (!SameHeader(r, *header)) return Fail(MapFileError::kChangedDuringLoad, r.offset());
  WalkTarget t;
  t.keys = key_scratch;
  t.summary = summary;
  if (summary != nullptr) *summary = MapFileSummary{};
  return RecordPass(r, *header, t);
}

MapFileResult ApplyMapFile(MapByteSource& source, const MapFileHeader& header, FrontEnd& front_end, PoseGraph& graph) {
  ChunkReader r(source);
  MapFileResult res;
  if (!SameHeader(r, header)) {
    res = Fail(MapFileError::kChangedDuringLoad, r.offset());
  } else {
    WalkTarget t;
    t.front_end = &front_end;
    t.graph = &graph;
    res = RecordPass(r, header, t);
    if (res.ok() && !r.AtEnd()) res = Fail(MapFileError::kTrailingData, r.offset());
  }
  if (!res.ok()) res.error = MapFileError::kChangedDuringLoad;
  return res;
}

}  // namespace dpcr
