// Helpers of the map-file tests: mappers fed a synthetic room run, saved into bytes, and a
// fingerprint of everything a load restores (to compare two mappers, or one before and after).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/mapper.hpp"
#include "core/persistence/crc32.hpp"
#include "tests/budget/synthetic_run.hpp"

namespace dpcr::test {

class VectorSink final : public MapByteSink {
 public:
  Status Write(const std::uint8_t* data, std::size_t size) override {
    bytes.insert(bytes.end(), data, data + size);
    ++chunks;
    if (size > largest_chunk) largest_chunk = size;
    return Status::kOk;
  }
  std::vector<std::uint8_t> bytes;
  std::size_t chunks = 0;
  std::size_t largest_chunk = 0;
};

template <class Profile>
MapperConfig TestConfig() {
  MapperConfig config;
  config.front_end.submap_scans = Profile::kSubmapMaxScans;
  return config;
}

template <class Profile>
std::unique_ptr<Mapper<Profile>> MakeMapper(const MapperConfig& config = TestConfig<Profile>()) {
  auto m = std::make_unique<Mapper<Profile>>();
  if (m->Init(config) != Status::kOk) return nullptr;
  return m;
}

template <class M, class Run>
void Feed(M& mapper, const Run& run, std::size_t first = 0, std::size_t count = SIZE_MAX) {
  std::size_t odom = 0;
  for (std::size_t i = first; i < run.scans.size() && i - first < count; ++i) {
    const auto& scan = run.scans[i];
    while (odom < run.odometry.size() && run.odometry[odom].stamp_us <= scan.stamp_us) mapper.AddOdometry(run.odometry[odom++]);
    (void)mapper.AddScan(scan);
  }
}

template <class M>
std::vector<std::uint8_t> SaveToBytes(const M& mapper) {
  VectorSink sink;
  const MapFileResult r = mapper.SaveMap(sink);
  if (!r.ok()) return {};
  return sink.bytes;
}

// Regions (keys, anchors, scans, tiles), graph (vertices, edges) and the fused map's cells, hashed.
template <class M>
std::uint32_t Fingerprint(const M& m) {
  Crc32 crc;
  const auto add = [&crc](const void* p, std::size_t n) { crc.Add(static_cast<const std::uint8_t*>(p), n); };
  const int regions = m.region_count();
  add(&regions, sizeof(regions));
  const MapFileContent content = m.map_file_content();
  for (const RegionalMap& r : content.regions) {
    add(&r.key, sizeof(r.key));
    add(&r.anchor, sizeof(r.anchor));
    add(&r.scans_inserted, sizeof(r.scans_inserted));
    const std::size_t tiles = r.grid->allocated_tiles();
    add(&tiles, sizeof(tiles));
  }
  const PoseGraph& g = m.back_end().graph();
  for (int i = 0; i < g.vertex_count(); ++i) add(&g.vertex(i), sizeof(Pose2));
  for (int i = 0; i < g.edge_count(); ++i) {
    const GraphEdge& e = g.edge(i);
    add(&e.from, sizeof(e.from));
    add(&e.to, sizeof(e.to));
    add(&e.kind, sizeof(e.kind));
    add(&e.measurement, sizeof(e.measurement));
    add(e.information.data(), 9 * sizeof(float));
  }
  const CellBox box = m.MapBounds();
  if (box.width() > 0 && box.height() > 0) {
    std::vector<std::int16_t> cells(static_cast<std::size_t>(box.width()) * static_cast<std::size_t>(box.height()));
    (void)m.RenderMap(box, Span<std::int16_t>(cells.data(), cells.size()));
    add(&box, sizeof(box));
    add(cells.data(), cells.size() * sizeof(std::int16_t));
  }
  return crc.value();
}

}  // namespace dpcr::test
