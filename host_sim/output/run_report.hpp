// Everything a run writes to its output directory: map.pgm, map.yaml, map.png,
// trajectory.tum, ground_truth.tum (when known) and metrics.json.
#pragma once

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host_sim/output/map_files.hpp"
#include "host_sim/eval/accuracy.hpp"
#include "host_sim/eval/trajectory.hpp"

namespace dpcr::output {

struct RunRecord {
  dpcr::eval::Trajectory estimate;
  dpcr::eval::Trajectory ground_truth;      // empty when unknown
  std::vector<double> per_scan_ms;          // time inside Mapper::AddScan, one per scan
  const std::vector<dpcr::eval::Relation>* relations = nullptr;  // with --relations
  double wall_seconds = 0.0;                // the whole run, parsing included
};

// Feeds one scan to the mapper, timing only the core's work, and records the pose it gives.
template <class MapperType>
void AddTimedScan(MapperType& mapper, const typename MapperType::ScanType& scan, RunRecord* run) {
  const auto t0 = std::chrono::steady_clock::now();
  (void)mapper.AddScan(scan);
  run->per_scan_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  run->estimate.push_back({scan.stamp_us, mapper.pose()});
}

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
  const auto& f = mapper.front_end_counters();
  j["front_end"] = {{"first_registrations", f.first_registrations}, {"first_rejected", f.first_rejected},
                    {"second_registrations", f.second_registrations}, {"second_rejected", f.second_rejected},
                    {"submap_line_builds", f.submap_line_builds}, {"region_line_builds", f.region_line_builds},
                    {"reference_cells_dropped", f.reference_cells_dropped}};
  return j;
}

}  // namespace dpcr::output
