// Everything a run writes to its output directory: map.pgm, map.yaml, map.png,
// trajectory.tum, ground_truth.tum (when known) and metrics.json.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host_sim/output/map_files.hpp"
#include "tools/eval/accuracy.hpp"
#include "tools/eval/trajectory.hpp"

namespace dpcr::output {

struct RunRecord {
  dpcr::eval::Trajectory estimate;
  dpcr::eval::Trajectory ground_truth;      // empty when unknown
  std::vector<double> per_scan_ms;          // time inside Mapper::AddScan, one per scan
  const std::vector<dpcr::eval::Relation>* relations = nullptr;  // with --relations
  double wall_seconds = 0.0;                // the whole run, parsing included
};

// Writes the files; returns metrics.json's content. Throws std::runtime_error on I/O errors.
nlohmann::json WriteRunOutputs(const std::string& dir, const FusedMap& map, const RunRecord& run,
                               nlohmann::json mapper_metrics);

// The metrics a Mapper reports about itself.
template <class MapperType>
nlohmann::json MapperMetrics(const MapperType& mapper) {
  const auto& c = mapper.counters();
  nlohmann::json j;
  j["mapper"] = mapper.pipeline();
  j["profile"] = MapperType::ProfileType::kName;
  j["status"] = dpcr::ToString(mapper.status());
  j["scans"] = c.scans;
  j["scans_rejected"] = c.scans_rejected;
  j["regions"] = mapper.region_count();
  j["static_ram_bytes"] = sizeof(MapperType);
  j["map_storage_bytes"] = mapper.map_storage_bytes();
  j["tiles_used"] = mapper.tiles_used();
  j["backend"] = {{"runs", 0}, {"total_ms", 0.0}, {"max_ms", 0.0}};
  j["counters"] = {{"scans_without_odometry", c.scans_without_odometry},
                   {"odometry_samples", c.odometry_samples},
                   {"odometry_steps_back", c.odometry_steps_back},
                   {"beams_invalid", c.beams_invalid},
                   {"regions_created", c.regions_created},
                   {"region_pool_full", c.region_pool_full},
                   {"updates_out_of_box", c.updates_out_of_box},
                   {"updates_dropped_pool_full", c.updates_dropped_pool_full}};
  return j;
}

// Renders, then writes all outputs of a finished run.
template <class MapperType>
nlohmann::json FinishRun(const std::string& dir, const MapperType& mapper, const RunRecord& run) {
  return WriteRunOutputs(dir, RenderFused(mapper), run, MapperMetrics(mapper));
}

}  // namespace dpcr::output
