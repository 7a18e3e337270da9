#include "core/persistence/map_writer.hpp"

#include "core/grid/tile_pool.hpp"
#include "core/grid/tiled_grid.hpp"
#include "core/persistence/crc32.hpp"

namespace dpcr {
namespace {

// Bytes to the sink through a small buffer, with the running CRC of everything written.
class ChunkWriter {
 public:
  explicit ChunkWriter(MapByteSink& sink) : sink_(sink) {}
  void Put(const std::uint8_t* data, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) {
      if (used_ == sizeof(buffer_)) Flush();
      buffer_[used_++] = data[i];
    }
  }
  void PutU16(std::uint16_t v) {
    std::uint8_t b[2];
    dpcr::PutU16(b, v);
    Put(b, 2);
  }
  void Flush() {
    if (used_ == 0) return;
    crc_.Add(buffer_, used_);
    if (status_ == Status::kOk) status_ = sink_.Write(buffer_, used_);
    written_ += used_;
    used_ = 0;
  }
  std::uint32_t crc() const { return crc_.value(); }
  Status status() const { return status_; }
  std::size_t written() const { return written_; }

 private:
  MapByteSink& sink_;
  std::uint8_t buffer_[kMapWriteChunkBytes];
  std::size_t used_ = 0;
  std::size_t written_ = 0;
  Crc32 crc_;
  Status status_ = Status::kOk;
};

const std::int16_t* TileCells(const TiledGrid& grid, int tx, int ty) {
  const TileId id = grid.tile_at(tx, ty);
  return id == kNoTile ? nullptr : grid.pool()[id].cells;
}

// Bytes a tile's cells take and how they are coded.
std::size_t TileBytes(const std::int16_t* cells, const MapFileLimits& l, TileEncoding* encoding) {
  const std::size_t runs = TileRunBytes(cells, l.clamp_min, l.clamp_max);
  *encoding = runs < kMapRawTileBytes ? TileEncoding::kRuns : TileEncoding::kRaw;
  return *encoding == TileEncoding::kRuns ? runs : kMapRawTileBytes;
}

void WriteTile(ChunkWriter& w, int tx, int ty, const std::int16_t* cells, const MapFileLimits& l) {
  TileEncoding encoding = TileEncoding::kRaw;
  const std::size_t bytes = TileBytes(cells, l, &encoding);
  const std::uint8_t head[4] = {static_cast<std::uint8_t>(tx), static_cast<std::uint8_t>(ty),
                                static_cast<std::uint8_t>(encoding), 0};
  w.Put(head, sizeof(head));
  w.PutU16(static_cast<std::uint16_t>(bytes));
  if (encoding == TileEncoding::kRaw) {
    for (int i = 0; i < kTileCells; ++i) w.PutU16(static_cast<std::uint16_t>(MapFileValue(cells[i], l.clamp_max)));
    return;
  }
  for (int i = 0; i < kTileCells;) {
    const TileToken t = NextTileToken(cells, i, l.clamp_min, l.clamp_max);
    w.Put(&t.code, 1);
    for (int k = 0; k < t.values; ++k) w.PutU16(static_cast<std::uint16_t>(MapFileValue(cells[i + k], l.clamp_max)));
    i += t.cells;
  }
}

void WriteRegion(ChunkWriter& w, const RegionalMap& r, const MapFileLimits& l) {
  const TiledGrid& g = *r.grid;
  std::uint8_t rec[kMapRegionBytes];
  PutU32(rec + 0, static_cast<std::uint32_t>(r.key.i));
  PutU32(rec + 4, static_cast<std::uint32_t>(r.key.j));
  PutF32(rec + 8, r.anchor.x);
  PutF32(rec + 12, r.anchor.y);
  PutF32(rec + 16, r.anchor.theta);
  PutU32(rec + 20, r.scans_inserted);
  PutU32(rec + 24, static_cast<std::uint32_t>(g.allocated_tiles()));
  w.Put(rec, sizeof(rec));
  for (int ty = 0; ty < g.tiles_y(); ++ty) {
    for (int tx = 0; tx < g.tiles_x(); ++tx) {
      const std::int16_t* cells = TileCells(g, tx, ty);
      if (cells != nullptr) WriteTile(w, tx, ty, cells, l);
    }
  }
}

void WritePose(std::uint8_t* p, const Pose2& pose) {
  PutF32(p, pose.x);
  PutF32(p + 4, pose.y);
  PutF32(p + 8, pose.theta);
}

void WriteGraph(ChunkWriter& w, const PoseGraph& g) {
  for (int i = 0; i < g.vertex_count(); ++i) {
    std::uint8_t rec[kMapVertexBytes];
    WritePose(rec, g.vertex(i));
    w.Put(rec, sizeof(rec));
  }
  for (int i = 0; i < g.edge_count(); ++i) {
    const GraphEdge& e = g.edge(i);
    std::uint8_t rec[kMapEdgeBytes] = {};
    dpcr::PutU16(rec, static_cast<std::uint16_t>(e.from));
    dpcr::PutU16(rec + 2, static_cast<std::uint16_t>(e.to));
    rec[4] = static_cast<std::uint8_t>(e.kind);
    WritePose(rec + 8, e.measurement);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) PutF32(rec + 20 + 4 * (3 * r + c), e.information(r, c));
    }
    w.Put(rec, sizeof(rec));
  }
}

}  // namespace

MapFileHeader MapFileHeaderOf(const MapFileContent& content) {
  MapFileHeader h = HeaderFor(content.limits, content.region_origin);
  std::uint64_t payload = 0;
  for (const RegionalMap& r : content.regions) {
    const TiledGrid& g = *r.grid;
    payload += kMapRegionBytes;
    for (int ty = 0; ty < g.tiles_y(); ++ty) {
      for (int tx = 0; tx < g.tiles_x(); ++tx) {
        const std::int16_t* cells = TileCells(g, tx, ty);
        if (cells == nullptr) continue;
        TileEncoding encoding = TileEncoding::kRaw;
        payload += kMapTileHeaderBytes + TileBytes(cells, content.limits, &encoding);
        ++h.tile_count;
      }
    }
  }
  h.region_count = static_cast<std::uint32_t>(content.regions.size());
  if (content.graph != nullptr) {
    h.vertex_count = static_cast<std::uint32_t>(content.graph->vertex_count());
    h.edge_count = static_cast<std::uint32_t>(content.graph->edge_count());
  }
  payload += std::uint64_t{h.vertex_count} * kMapVertexBytes + std::uint64_t{h.edge_count} * kMapEdgeBytes;
  h.payload_bytes = static_cast<std::uint32_t>(payload);
  return h;
}

MapFileResult WriteMapFile(const MapFileContent& content, MapByteSink& sink) {
  ChunkWriter w(sink);
  std::uint8_t header[kMapHeaderBytes];
  EncodeMapHeader(MapFileHeaderOf(content), header);
  w.Put(header, sizeof(header));
  for (const RegionalMap& r : content.regions) WriteRegion(w, r, content.limits);
  if (content.graph != nullptr) WriteGraph(w, *content.graph);
  w.Flush();
  std::uint8_t trailer[kMapTrailerBytes];
  PutU32(trailer, w.crc());
  w.Put(trailer, sizeof(trailer));
  w.Flush();
  MapFileResult result;
  result.offset = w.written();
  if (w.status() != Status::kOk) {
    result.status = w.status();
    result.error = MapFileError::kWriteFailed;
  }
  return result;
}

}  // namespace dpcr
