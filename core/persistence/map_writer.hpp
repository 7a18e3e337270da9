// Saving a Mapper's maps and region graph as a map file (map_file_format.hpp), streamed into a
// caller's sink in chunks of at most kMapWriteChunkBytes through a buffer on the stack: a save
// needs no RAM beyond the mapper's own, however large the map.
#pragma once

#include <cstddef>

#include "core/back_end/pose_graph.hpp"
#include "core/base/span.hpp"
#include "core/front_end/regional_map.hpp"
#include "core/persistence/map_file_format.hpp"
#include "core/persistence/map_stream.hpp"

namespace dpcr {

constexpr std::size_t kMapWriteChunkBytes = 256;

// What a save writes: views into a mapper's state (Mapper::map_file_content()).
struct MapFileContent {
  MapFileLimits limits;
  Point2 region_origin;  // world centre of region (0, 0)
  Span<const RegionalMap> regions;
  const PoseGraph* graph = nullptr;  // null: no graph
};

// The header of the file (counts and payload size filled in).
MapFileHeader MapFileHeaderOf(const MapFileContent& content);
// Writes the whole file. kWriteFailed (with the sink's status) when the sink refused bytes.
MapFileResult WriteMapFile(const MapFileContent& content, MapByteSink& sink);

}  // namespace dpcr
