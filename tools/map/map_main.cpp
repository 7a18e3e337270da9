// dpcr-map: what a map file (core/persistence, docs/map-file-format.md) holds, and its exports.
//   dpcr-map info FILE              header, regions, tiles, sizes, graph, CRC status (exit 1: not sound)
//   dpcr-map export FILE --out DIR  map.pgm + map.yaml (ROS map_server) + map.png
//   dpcr-map check FILE             exit status only: 0 sound, 1 not (any profile)
#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/mapper.hpp"
#include "host_sim/output/map_file_io.hpp"
#include "host_sim/output/map_files.hpp"

namespace {

constexpr std::uint64_t kMaxFileBytes = 256u << 20;  // larger than any profile's largest map

std::vector<std::uint8_t> ReadMapBytes(const std::string& path) {
  dpcr::output::MapFilePlace place(path);
  std::vector<std::uint8_t> bytes;
  const dpcr::IoStatus io = dpcr::board::ReadBlob(place.store, place.name.c_str(), kMaxFileBytes, &bytes);
  if (io == dpcr::IoStatus::kNotFound) throw std::runtime_error(path + ": no such file");
  if (io != dpcr::IoStatus::kOk) throw std::runtime_error(place.store.last_error());
  return bytes;
}

dpcr::MemoryMapSource SourceOf(const std::vector<std::uint8_t>& bytes) {
  return dpcr::MemoryMapSource(dpcr::Span<const std::uint8_t>(bytes.data(), bytes.size()));
}

// The header, the checksum and every record, for any profile.
dpcr::MapFileResult Check(const std::vector<std::uint8_t>& bytes, dpcr::MapFileHeader* header, dpcr::MapFileSummary* summary) {
  dpcr::MemoryMapSource source = SourceOf(bytes);
  const dpcr::MapFileResult h = dpcr::ReadMapFileHeader(source, header);
  if (!h.ok()) return h;
  std::vector<dpcr::Point2> keys(header->region_count);
  return dpcr::CheckMapFile(source, nullptr, dpcr::Span<dpcr::Point2>(keys.data(), keys.size()), header, summary);
}

// A mapper of the file's profile and grid, the file loaded into it.
template <class Profile>
std::unique_ptr<dpcr::Mapper<Profile>> LoadInto(const std::string& path, const std::vector<std::uint8_t>& bytes,
                                                const dpcr::MapFileHeader& h) {
  auto mapper = std::make_unique<dpcr::Mapper<Profile>>();
  dpcr::MapperConfig config;
  config.grid.resolution_m = h.resolution_m;
  config.grid.clamp_min = h.clamp_min;
  config.grid.clamp_max = h.clamp_max;
  config.front_end.region_width_m = h.region_width_m;
  if (config.front_end.submap_scans > Profile::kSubmapMaxScans) config.front_end.submap_scans = Profile::kSubmapMaxScans;
  if (mapper->Init(config) != dpcr::Status::kOk) throw std::runtime_error(path + ": no mapper configuration fits its grid");
  dpcr::MemoryMapSource source = SourceOf(bytes);
  const dpcr::MapFileResult r = mapper->LoadMap(source);
  if (!r.ok()) throw std::runtime_error(path + ": " + dpcr::Describe(r.error) + " (at byte " + std::to_string(r.offset) + ")");
  return mapper;
}

// Calls f(mapper) with the file loaded into a mapper of its profile; false for a profile this
// build does not have.
template <class F>
bool WithLoadedMap(const std::string& path, const std::vector<std::uint8_t>& bytes, const dpcr::MapFileHeader& h, F f) {
  const std::string profile = h.profile;
  if (profile == dpcr::VacuumProfile::kName) {
    f(*LoadInto<dpcr::VacuumProfile>(path, bytes, h));
  } else if (profile == dpcr::BuildingProfile::kName) {
    f(*LoadInto<dpcr::BuildingProfile>(path, bytes, h));
  } else if (profile == dpcr::TinyProfile::kName) {
    f(*LoadInto<dpcr::TinyProfile>(path, bytes, h));
  } else {
    return false;
  }
  return true;
}

void PrintHeader(const std::string& path, std::size_t size, const dpcr::MapFileHeader& h) {
  std::printf("file:     %s (%zu bytes)\n", path.c_str(), size);
  std::printf("format:   dpcr map version %u, profile %s (capacities: %u regions, %u tiles, %ux%u-tile region box, %u edges)\n",
              h.version, h.profile, h.max_regions, h.tile_pool_tiles, h.region_box_tiles, h.region_box_tiles, h.max_graph_edges);
  std::printf("grid:     %.3f m cells, %.2f m regions, clamp [%d, %d], region (0, 0) centred at (%.3f, %.3f)\n",
              static_cast<double>(h.resolution_m), static_cast<double>(h.region_width_m), h.clamp_min, h.clamp_max,
              static_cast<double>(h.region_origin.x), static_cast<double>(h.region_origin.y));
  std::printf("counts:   %u regions, %u tiles, %u vertices, %u edges\n", h.region_count, h.tile_count, h.vertex_count,
              h.edge_count);
}

void PrintSummary(const dpcr::MapFileHeader& h, const dpcr::MapFileSummary& s) {
  std::printf("sizes:    header %zu, regions %zu, tiles %" PRIu64 " (%u as runs, %u raw; raw would be %zu), graph %zu, trailer %zu bytes\n",
              dpcr::kMapHeaderBytes, h.region_count * dpcr::kMapRegionBytes, s.tile_bytes, s.run_tiles, s.raw_tiles,
              h.tile_count * (dpcr::kMapTileHeaderBytes + dpcr::kMapRawTileBytes),
              h.vertex_count * dpcr::kMapVertexBytes + h.edge_count * dpcr::kMapEdgeBytes, dpcr::kMapTrailerBytes);
  std::printf("graph:    %u vertices, %u edges (%u sequence, %u map-to-map, %u loop closures)\n", h.vertex_count,
              h.edge_count, s.edges_by_kind[0], s.edges_by_kind[1], s.edges_by_kind[2]);
}

template <class MapperType>
void PrintRegions(const MapperType& m) {
  const dpcr::MapFileContent c = m.map_file_content();
  std::printf("regions:  key        anchor (x, y, theta)        scans  tiles\n");
  for (const dpcr::RegionalMap& r : c.regions) {
    std::printf("          (%3d,%3d)  (%8.3f, %8.3f, %7.4f)  %6u  %5zu\n", r.key.i, r.key.j, static_cast<double>(r.anchor.x),
                static_cast<double>(r.anchor.y), static_cast<double>(r.anchor.theta), r.scans_inserted, r.grid->allocated_tiles());
  }
  const dpcr::CellBox box = m.MapBounds();
  std::printf("extent:   %d x %d cells (%.1f x %.1f m)\n", box.width(), box.height(),
              static_cast<double>(box.width()) * static_cast<double>(m.config().grid.resolution_m),
              static_cast<double>(box.height()) * static_cast<double>(m.config().grid.resolution_m));
}

int Info(const std::string& path) {
  const std::vector<std::uint8_t> bytes = ReadMapBytes(path);
  dpcr::MapFileHeader h;
  dpcr::MapFileSummary s;
  const dpcr::MapFileResult r = Check(bytes, &h, &s);
  if (r.ok() || (r.error != dpcr::MapFileError::kBadMagic && r.error != dpcr::MapFileError::kBadHeader &&
                 r.error != dpcr::MapFileError::kUnsupportedVersion && r.error != dpcr::MapFileError::kTruncated)) {
    PrintHeader(path, bytes.size(), h);
  }
  if (!r.ok()) {
    std::printf("check:    FAILED: %s (at byte %zu)\n", dpcr::Describe(r.error), r.offset);
    return 1;
  }
  PrintSummary(h, s);
  const bool listed = WithLoadedMap(path, bytes, h, [](const auto& m) { PrintRegions(m); });
  if (!listed) std::printf("regions:  (profile %s is not in this build: not listed)\n", h.profile);
  std::printf("check:    ok (header and file CRC-32 match, every record in range)\n");
  return 0;
}

int Export(const std::string& path, const std::string& out) {
  const std::vector<std::uint8_t> bytes = ReadMapBytes(path);
  dpcr::MapFileHeader h;
  dpcr::MapFileSummary s;
  const dpcr::MapFileResult r = Check(bytes, &h, &s);
  if (!r.ok()) throw std::runtime_error(path + ": " + dpcr::Describe(r.error) + " (at byte " + std::to_string(r.offset) + ")");
  std::filesystem::create_directories(out);
  int width = 0, height = 0;
  const bool done = WithLoadedMap(path, bytes, h, [&](const auto& m) {
    const dpcr::output::FusedMap map = dpcr::output::RenderFused(m);
    if (map.cells.empty()) throw std::runtime_error(path + ": the map is empty, nothing to export");
    dpcr::output::WriteRosMap(out, map);
    dpcr::output::WriteMapPng(out, map, {}, {});
    width = map.width();
    height = map.height();
  });
  if (!done) throw std::runtime_error(path + ": profile " + h.profile + " is not in this build");
  std::fprintf(stderr, "dpcr-map: %s -> %s/map.pgm, map.yaml, map.png (%d x %d cells)\n", path.c_str(), out.c_str(), width,
               height);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dpcr-map: inspect, check and export dpcr map files (map.dpcr)"};
  app.require_subcommand(1);
  std::string file, out;
  CLI::App* info = app.add_subcommand("info", "header, regions, tiles, sizes, graph and CRC status (exit 1 if not sound)");
  info->add_option("FILE", file, "map file")->required();
  CLI::App* exp = app.add_subcommand("export", "write map.pgm + map.yaml (ROS map_server) and map.png");
  exp->add_option("FILE", file, "map file")->required();
  exp->add_option("--out", out, "output directory")->required();
  CLI::App* check = app.add_subcommand("check", "exit status only: 0 sound, 1 not");
  check->add_option("FILE", file, "map file")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    if (*check) {
      dpcr::MapFileHeader h;
      dpcr::MapFileSummary s;
      return Check(ReadMapBytes(file), &h, &s).ok() ? 0 : 1;
    }
    if (*info) return Info(file);
    return Export(file, out);
  } catch (const std::exception& e) {
    if (*check) return 1;
    std::fprintf(stderr, "dpcr-map: error: %s\n", e.what());
    return 1;
  }
}
