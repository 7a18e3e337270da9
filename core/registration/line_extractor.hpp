// Line features from the obstacle cells of an int16 occupancy grid, standing in for RM-Line
// (the paper's §3.2.1 step 1, which has no public code). Pipeline:
//   connected components of obstacle cells (gaps up to link_radius_cells - 1 bridged)  ->  iterative end-point split of each component
//   (Douglas–Peucker on an unordered cell set, explicit stack)  ->  total-least-squares refit
//   ->  merge of collinear neighbours  ->  a line id per obstacle cell.
// Everything is in window-local cell units (cell (x, y) has its centre at (x + 0.5, y + 0.5));
// RegistrationReference converts the result to metres. O(cells · split depth), no heap.
#pragma once

#include <cstdint>

#include "core/geometry/pose2.hpp"
#include "core/base/span.hpp"

namespace dpcr {

// Obstacle cells and line features are numbered by 16-bit ids whose top values are markers.
// No obstacle cell: in a cell_at table, as a nearest-cell answer, in a correspondence.
constexpr std::uint16_t kNoCell = 0xFFFF;
// No line feature: ObstacleCell::line of clutter. Cell ids and line ids never meet in one
// variable, so the two markers sharing a value means nothing; no code relies on it.
constexpr std::uint16_t kNoLine = 0xFFFF;

struct ObstacleCell {
  // Window-local cell coordinates (windows up to 1024 cells a side), and where in the cell the
  // obstacle lies, in 1/64 cell: the centre (32) unless the grid knew its returns' mean
  // (core/grid/hit_mean.hpp). Packed: the cell stays 10 bytes.
  std::uint16_t x : 10;
  std::uint16_t sub_x : 6;
  std::uint16_t y : 10;
  std::uint16_t sub_y : 6;
  std::uint16_t line = kNoLine;  // owning line feature, kNoLine for clutter
  std::int8_t nx = 0;            // local unit normal * 127 from the 5x5 neighbourhood; (0, 0) = none
  std::int8_t ny = 0;
  // Weight in the line fits: the cell's evidence (log-odds; with a hit mean, times the returns it
  // holds), so that the solid core of a wall steers a line and the cells that range noise reaches
  // now and then barely do.
  std::uint16_t weight = 1;

  ObstacleCell() : x(0), sub_x(kCentre), y(0), sub_y(kCentre) {}
  static constexpr int kSubCells = 64;
  static constexpr int kCentre = kSubCells / 2;
  static constexpr int kMaxSide = 1024;
};
static_assert(sizeof(ObstacleCell) == 10, "an obstacle cell is 10 bytes");

// Where in the window (cell units) the obstacle of cell `c` lies: its centre, or its hit mean.
inline Point2 ObstaclePosition(const ObstacleCell& c) {
  constexpr float kStep = 1.0f / static_cast<float>(ObstacleCell::kSubCells);
  return Point2{static_cast<float>(c.x) + static_cast<float>(c.sub_x) * kStep,
                static_cast<float>(c.y) + static_cast<float>(c.sub_y) * kStep};
}

struct LineFeature {
  Point2 a;              // endpoints: extreme cells' outer edges projected on the fitted line
  Point2 b;
  Point2 normal;         // unit normal; points p on the line satisfy normal·p = offset
  float offset = 0.0f;
  float rms = 0.0f;      // fit residual (RMS perpendicular distance of the support cells)
  std::uint16_t support = 0;  // obstacle cells owning this line
  // Weighted centroid and central second moments (per unit weight) of the support, and the
  // total weight: merging two lines is O(1).
  float mass = 0.0f;
  Point2 mean;
  float cxx = 0.0f, cxy = 0.0f, cyy = 0.0f;
};

struct LineExtractorConfig {
  // Cells this close (Chebyshev) are linked into one component. 1 = 8-connected; 2 bridges the
  // one-cell gaps of walls seen at grazing angles, which otherwise fall apart into clutter.
  int link_radius_cells = 2;
  float split_tolerance_cells = 1.5f;  // Douglas–Peucker epsilon, cells
  int min_support = 5;                 // fewer cells are clutter (chair legs), not a line
  // A leaf or merge fitting worse than this is not a line. A rasterised slanted wall alone has
  // ~0.3 cells; 1.5 cm range noise at 5 cm cells adds ~0.3 more.
  float max_rms_cells = 0.75f;
  // Collinear merge of pieces the split cut apart (noisy walls are split at their outliers):
  float merge_angle_rad = 0.12f;    // direction difference
  float merge_offset_cells = 1.5f;  // each endpoint within this of the other line
  float merge_gap_cells = 3.0f;     // at most this gap between the segments (a door is ~16)
};

struct LineExtractionStats {
  int components = 0;
  int leaves = 0;
  int merges = 0;
  bool lines_full = false;  // more lines than capacity: the rest stay clutter
  bool stack_full = false;  // split depth beyond the stack: a leaf kept unsplit
};

// `cells`: obstacle cells (their `line` fields are overwritten). `cell_at`: a w x h table holding,
// for each obstacle cell's position, its index in `cells`, and kNoCell elsewhere.
// `scratch`: at least cells.size() + 2 * lines.size() entries. `lines`: output capacity (fewer
// than 0xFFFE); returns the count used.
int ExtractLines(Span<ObstacleCell> cells, const std::uint16_t* cell_at, int w, int h,
                 Span<std::uint16_t> scratch, Span<LineFeature> lines, const LineExtractorConfig& config,
                 LineExtractionStats* stats);

// Fills each cell's local normal (nx, ny) from the obstacle cells in its 5x5 neighbourhood,
// left (0, 0) where they do not look like a line (fewer than 3, or not elongated).
void ComputeLocalNormals(Span<ObstacleCell> cells, const std::uint16_t* cell_at, int w, int h);

}  // namespace dpcr
