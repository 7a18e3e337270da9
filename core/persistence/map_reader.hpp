// Loading map files (map_file_format.hpp). Nothing in a file is trusted: a load reads the source
// three times through a small buffer on the stack, and only the third pass writes:
//   1 the header (magic, version, header CRC, every field, the profile and grid against the
//     mapper's), then the CRC-32 of the whole file and its exact length;
//   2 every record: region keys in range and unique, anchors finite and plausible, tiles inside
//     their box in increasing order, encodings that decode to exactly 1024 cells, cells within the
//     clamp bounds, counts as the header says, graph vertices plausible, edges between existing
//     vertices with a finite, positive-diagonal information matrix;
//   3 (ApplyMapFile) the maps and graph into the mapper, the CRC checked again.
// A file refused by 1 or 2 leaves the mapper as it was. Should the source change between 2 and 3
// (a file rewritten in place), 3 notices and the caller empties the mapper (kChangedDuringLoad).
#pragma once

#include <cstdint>

#include "core/back_end/pose_graph.hpp"
#include "core/base/span.hpp"
#include "core/front_end/front_end.hpp"
#include "core/persistence/map_file_format.hpp"
#include "core/persistence/map_stream.hpp"

namespace dpcr {

constexpr std::size_t kMapReadChunkBytes = 256;

// What a checked file holds, for tools (dpcr-map info).
struct MapFileSummary {
  std::uint32_t raw_tiles = 0;
  std::uint32_t run_tiles = 0;
  std::uint64_t tile_bytes = 0;   // tile records, headers included
  std::uint64_t known_cells = 0;  // cells not unknown
  std::uint32_t edges_by_kind[3] = {0, 0, 0};  // EdgeKind order
};

// Reads just the header (pass 1's first step): for tools that show a file whatever its state.
MapFileResult ReadMapFileHeader(MapByteSource& source, MapFileHeader* header);

// Passes 1 and 2. `limits`: the mapper the file is meant for (null: any profile and grid).
// `key_scratch`: at least as many entries as the file has regions (duplicate-key check).
// `summary` may be null.
MapFileResult CheckMapFile(MapByteSource& source, const MapFileLimits* limits, Span<Point2> key_scratch,
                           MapFileHeader* header, MapFileSummary* summary);

// Pass 3, after CheckMapFile accepted `header` from the same source, the source was rewound and
// the front end Init'ed: restores the regional maps through `front_end` and the vertices and
// edges into `graph` (the back end's, cleared by Init). Any difference from what pass 2 saw gives
// kChangedDuringLoad; the caller then re-Inits (the state is partial).
MapFileResult ApplyMapFile(MapByteSource& source, const MapFileHeader& header, FrontEnd& front_end, PoseGraph& graph);

}  // namespace dpcr
