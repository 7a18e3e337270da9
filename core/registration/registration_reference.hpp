// The reference side of a registration, built once per line re-extraction (every K1 scans for the
// submap, K2 for a regional map, paper §3.3–3.4) so that each correspondence costs O(1):
// obstacle cells of a window of a grid, their line features, a local normal per cell, and a
// nearest-obstacle-cell table over the window, filled cell by cell on first query (registration
// asks about a few thousand cells between builds, not the whole window).
// Size-erased: RegistrationReferenceStorage<W, H, Cells, Lines> owns the arrays.
#pragma once

#include <cstdint>

#include "core/registration/line_extractor.hpp"
#include "core/base/span.hpp"
#include "core/base/status.hpp"
#include "core/grid/tiled_grid.hpp"

namespace dpcr {

struct ReferenceConfig {
  // A cell is an obstacle above this log-odds (Q10). 0 = more likely occupied than free; one hit
  // (+867) passes, a hit followed by two misses (-830) does not.
  std::int16_t obstacle_threshold = 0;
  // Line fits weight each cell by its log-odds (ObstacleCell::weight); false: all cells alike.
  bool weight_by_evidence = true;
  // Beyond this distance a window cell has no nearest obstacle (the correspondence gate's bound).
  float max_distance_m = 1.0f;
  LineExtractorConfig lines;
};

struct ReferenceBuildStats {
  int obstacle_cells = 0;
  int dropped_cells = 0;  // obstacle cells beyond capacity (not in the reference)
  int lines = 0;
  LineExtractionStats extraction;
};

class RegistrationReference {
 public:
  // Running sums of the points near one line, in that line's frame (u along, v across).
  struct RefitSums {
    float n = 0.0f, u = 0.0f, v = 0.0f, uu = 0.0f, uv = 0.0f, vv = 0.0f;
  };

  RegistrationReference(Span<ObstacleCell> cells, Span<std::uint16_t> nearest, Span<std::uint64_t> obstacle_blocks,
                        Span<std::uint16_t> scratch, Span<LineFeature> lines, Span<RefitSums> refit, int max_w,
                        int max_h);
  RegistrationReference(const RegistrationReference&) = delete;
  RegistrationReference& operator=(const RegistrationReference&) = delete;

  // Rebuilds from `grid` over `window` (clipped to max_w x max_h cells from window.min).
  // kCapacityExceeded when obstacle cells were dropped or lines did not fit (the cells beyond the
  // line capacity stay clutter); the reference is still usable either way.
  Status Build(const TiledGrid& grid, CellBox window, const ReferenceConfig& config, ReferenceBuildStats* stats);

  // The same in three steps, for one reference over several grids on one cell lattice (the
  // regional maps of neighbouring regions, FrontEnd::BuildRegionReference): cells of `grid` are
  // shifted by `offset` cells into the window's frame; a cell that is an obstacle in two grids
  // is one cell with the larger weight. `stats` (not null) accumulates over the steps.
  void BeginBuild(CellBox window, float resolution_m);
  void AddGrid(const TiledGrid& grid, CellIndex offset, const ReferenceConfig& config, ReferenceBuildStats* stats);
  Status FinishBuild(const ReferenceConfig& config, ReferenceBuildStats* stats);
  // AddGrid for a grid placed anywhere: `grid_in_window` is its frame in the window grid's frame
  // (anchors the back end has moved or rotated). The exact AddGrid when it is a whole-cell shift.
  void AddPlacedGrid(const TiledGrid& grid, const Pose2& grid_in_window, const ReferenceConfig& config,
                     ReferenceBuildStats* stats);

  // Sub-cell refit (after Build): every line is refitted to the raw points near it, so that its
  // position is not the grid's quantisation of the wall (up to half a cell per wall, which
  // registration would turn into a pose offset). Points are in the grid's world frame; a point
  // counts for the line of its nearest obstacle cell if it lies within `gate_m` of that line.
  // Lines with fewer than `min_points` keep their cell fit. Only for storage with point-refit sums.
  void BeginPointRefit();
  void AddRefitPoint(Point2 p, float gate_m);
  // AddRefitPoint for each of a scan's points placed by `to_grid`: one call a scan, not one a point.
  void AddRefitPoints(Span<const Point2> points, const PointTransform& to_grid, float gate_m);
  int EndPointRefit(int min_points);

  // Index of the obstacle cell nearest to world point p (among equally near ones the heaviest,
  // then the first), kNoCell outside the window or bound. A cell's first query searches, later
  // ones read the cached answer.
  std::uint16_t Nearest(Point2 p) const {
    const float fx = (p.x - origin_.x) * inv_res_, fy = (p.y - origin_.y) * inv_res_;
    if (!(fx >= 0.0f && fy >= 0.0f && fx < static_cast<float>(w_) && fy < static_cast<float>(h_))) return kNoCell;
    const int x = static_cast<int>(fx), y = static_cast<int>(fy);
    const std::uint16_t k = nearest_[static_cast<std::size_t>(y * w_ + x)];
    if (k < kNoneNear) return k;
    return k == kNotSearched ? Search(x, y) : kNoCell;
  }
  // The obstacle cell occupying window-local (x, y), or kNoCell.
  std::uint16_t ObstacleAt(int x, int y) const;

  // The nearest-obstacle table's memory lent out as bytes (the loop-closure search grid uses it
  // between two builds: stages that never run at once share storage). Lending it spoils the
  // table: the next BeginBuild clears all of it, and the caller rebuilds before any query.
  Span<std::uint8_t> LendTable() {
    table_lent_ = true;
    return Span<std::uint8_t>(reinterpret_cast<std::uint8_t*>(nearest_.data()), nearest_.size() * sizeof(std::uint16_t));
  }
  std::size_t table_bytes() const { return nearest_.size() * sizeof(std::uint16_t); }

  // World position of an obstacle cell's obstacle: its hit mean if the grid had one, else its centre.
  Point2 ObstaclePoint(std::uint16_t i) const {
    const Point2 p = ObstaclePosition(cells_[i]);
    return Point2{origin_.x + p.x * res_, origin_.y + p.y * res_};
  }
  const ObstacleCell& cell(std::uint16_t i) const { return cells_[i]; }
  std::size_t cell_count() const { return cell_count_; }
  // Lines in world metres (normal·p = offset, a/b endpoints, rms in metres).
  const LineFeature& line(std::uint16_t i) const { return lines_[i]; }
  std::size_t line_count() const { return line_count_; }
  float resolution_m() const { return res_; }

 private:
  // Table entries besides cell indices. Not searched yet: every entry but the obstacle cells'
  // after a build, which hold their own index. While a build runs the table is also the cell_at
  // table of ComputeLocalNormals and ExtractLines (a cell's index, kNoCell elsewhere), and AddObstacleCell
  // finds an earlier grid's cell by it: "not searched" must read as "no obstacle cell here".
  static constexpr std::uint16_t kNotSearched = 0xFFFF;
  static_assert(kNotSearched == kNoCell, "during a build the table is the line extractor's cell_at table");
  // Searched, with no obstacle cell within the bound.
  static constexpr std::uint16_t kNoneNear = 0xFFFE;
  // Obstacle cells are also marked in 8 x 8-cell blocks, one bit per cell (bit 8 * ly + lx), and
  // the blocks holding any in one bit per block of a row of blocks (windows up to 512 cells).
  static constexpr int kBlockShift = 3;
  static constexpr int kMaxBlockRows = 64;

  // The nearest obstacle cell to window cell (x, y) within the bound; caches it in the table.
  std::uint16_t Search(int x, int y) const;
  // Resets what the last build and its searches wrote: table entries, obstacle blocks.
  void ClearWritten();
  // Where in the cell its obstacle lies (ObstacleCell::sub_x, sub_y): the centre, or a hit mean.
  struct SubCell {
    std::uint16_t x = ObstacleCell::kCentre;
    std::uint16_t y = ObstacleCell::kCentre;
  };
  static_assert(ObstacleCell::kSubCells == kHitMeanLevels, "a hit mean's level is the obstacle cell's sub-cell position");
  static SubCell SubCellOf(std::int16_t code) {  // a hit-mean code
    const HitMean m = DecodeHitMean(code);
    return SubCell{static_cast<std::uint16_t>(m.qx), static_cast<std::uint16_t>(m.qy)};
  }
  // Window cell (x, y) becomes an obstacle cell (or keeps the larger weight, and its sub-cell
  // position, if it is one).
  inline void AddObstacleCell(int x, int y, std::uint16_t weight, SubCell sub, ReferenceBuildStats* stats);
  // ObstacleCell::weight of a cell of `grid` with value `v`.
  static std::uint16_t EvidenceWeight(const TiledGrid& grid, std::int16_t v, const ReferenceConfig& config);

  Span<ObstacleCell> cells_;
  // A cache that Search fills, also through a const reference (queries are single-threaded).
  Span<std::uint16_t> nearest_;
  Span<std::uint64_t> obstacle_blocks_;
  std::uint64_t occupied_blocks_[kMaxBlockRows];  // bit bx of row by: block (bx, by) has an obstacle cell
  // Bit bx of row by: table block (bx, by) holds entries other than kNotSearched (Search sets it).
  mutable std::uint64_t written_blocks_[kMaxBlockRows];
  Span<std::uint16_t> scratch_;
  Span<LineFeature> lines_;
  Span<RefitSums> refit_;
  int max_w_, max_h_;
  int w_ = 0, h_ = 0;
  int blocks_x_ = 0;
  std::int32_t bound2_ = 0;  // squared distance bound, cells^2
  int reach_ = 0;            // the largest per-axis offset within the bound, cells
  std::size_t cell_count_ = 0, line_count_ = 0;
  Point2 origin_;  // world position of the window's lower-left corner
  CellIndex window_min_;
  float res_ = 0.05f, inv_res_ = 20.0f;
  bool table_lent_ = false;  // LendTable: the whole table must be cleared before the next build
};

// 256 x 256 window, 4096 cells, 512 lines: 128 KiB table + 8 KiB obstacle bits + 1 KiB of
// block-row masks + 40 KiB cells + 10 KiB scratch + 30 KiB lines, + 12 KiB of point-refit sums when
// kPointRefit (a reference built from a grid alone, e.g. a regional map's, has no raw points to
// refit to and carries none).
template <int kW, int kH, int kCells, int kLines, bool kPointRefit = true>
class RegistrationReferenceStorage : public RegistrationReference {
  static_assert(kCells < 0xFFFE, "cell ids are 16-bit below the table's two markers (kNoneNear, kNotSearched)");
  static_assert(kLines < 0xFFFE, "line ids are 16-bit below the line extractor's two markers");
  static_assert(kW <= ObstacleCell::kMaxSide && kH <= ObstacleCell::kMaxSide, "obstacle cells hold 10-bit coordinates");
  static constexpr int kBlocks = ((kW + 7) / 8) * ((kH + 7) / 8);
  static constexpr int kScratch = kCells + 2 * kLines;  // ExtractLines: cells, then lines twice

 public:
  RegistrationReferenceStorage()
      : RegistrationReference(Span<ObstacleCell>(cells_, kCells), Span<std::uint16_t>(nearest_, kW * kH),
                              Span<std::uint64_t>(obstacle_blocks_, kBlocks), Span<std::uint16_t>(scratch_, kScratch),
                              Span<LineFeature>(lines_, kLines),
                              Span<RefitSums>(refit_, kPointRefit ? kLines : 0), kW, kH) {}

 private:
  ObstacleCell cells_[kCells];
  std::uint16_t nearest_[kW * kH];
  std::uint64_t obstacle_blocks_[kBlocks];
  std::uint16_t scratch_[kScratch];
  LineFeature lines_[kLines];
  RefitSums refit_[kPointRefit ? kLines : 1];  // C++ has no empty arrays: one unused entry
};

}  // namespace dpcr
