#include "core/grid/ray_caster.hpp"

#include <cmath>

#include "core/base/assert.hpp"
#include "core/base/float4.hpp"
#include "core/geometry/points4.hpp"

namespace dpcr {
namespace {

// Miss segments queued for the grid 12 at a time, their stats added to the scan's; with
// `may_unsettle` false they cannot unsettle a settled cell (TiledGrid::UpdateSegments).
// 12: two batches (strong and weak) and the four-lane ray set-up, which a Cortex-M7 (no vector
// unit) keeps on the stack, fit the core's 1 KiB stack budget (952 bytes there; 16 took 1080).
// Batch boundaries do not change the cells, only the cost: 16 saved 21 M of intel's 13.87 G.
class MissBatch {
 public:
  MissBatch(TiledGrid& grid, const GridConfig& config, std::uint32_t stamp, bool may_unsettle, InsertionStats* stats)
      : grid_(grid), config_(config), stamp_(stamp), may_unsettle_(may_unsettle), stats_(stats) {}
  void Queue(CellIndex from, CellIndex to) {
    segments_[queued_++] = CellSegment{from, to};
    if (queued_ == kBatch) Flush();
  }
  void Flush() {
    const TiledGrid::SegmentStats s = grid_.UpdateSegments(Span<const CellSegment>(segments_, queued_), config_.miss_delta,
                                                           config_.clamp_min, config_.clamp_max, stamp_, may_unsettle_);
    stats_->miss_cells += s.applied;
    stats_->out_of_box += s.out_of_box;
    stats_->dropped_pool_full += s.dropped_pool_full;
    queued_ = 0;
  }

 private:
  static constexpr std::size_t kBatch = 12;
  TiledGrid& grid_;
  const GridConfig& config_;
  std::uint32_t stamp_;
  bool may_unsettle_;
  InsertionStats* stats_;
  CellSegment segments_[kBatch];
  std::size_t queued_ = 0;
};

// Returns nearer than this many cells are not screened: range noise does not carry them two
// cells through a wall (LD06-class: 1 cm + 0.5 % of the range, 2 cm at 2 m = 40 cells of 5 cm),
// and skipping them halves the screen's cost.
constexpr float kScreenFromCells = 40.0f;

// Whether a hit lies behind a settled occupied cell along its ray from `origin`: one of the
// cells 2 to config.drop_hits_behind_settled_cells cells before it (the cell just before it is
// the wall's own thickness). Settled: at the clamp, or counting contrary scans below it.
class WallScreen {
 public:
  WallScreen(const TiledGrid& grid, Point2 origin, const GridConfig& config)
      : grid_(grid), origin_(origin), inv_res_(1.0f / config.resolution_m),
        settled_(grid.SettledOccupiedFloor(config.clamp_max)), back_cells_(config.drop_hits_behind_settled_cells) {}

  bool Behind(Point2 p, CellIndex cell) const {
    const float dx = p.x - origin_.x, dy = p.y - origin_.y;
    const float d = std::sqrt(dx * dx + dy * dy);
    if (d * inv_res_ < kScreenFromCells) return false;
    // A hit on a settled wall cell is the wall itself (a ray that grazes a wall has wall cells
    // behind it along its own line): kept.
    if (grid_.Get(cell) >= settled_) return false;
    // In cell units: the hit, and one cell's step back along the ray.
    const float cx = p.x * inv_res_, cy = p.y * inv_res_, sx = dx / d, sy = dy / d;
    for (int k = 2; k <= back_cells_; ++k) {
      const float back = static_cast<float>(k);
      if (grid_.Get(CellIndex{FloorToInt(cx - back * sx), FloorToInt(cy - back * sy)}) >= settled_) return true;
    }
    return false;
  }

 private:
  const TiledGrid& grid_;
  Point2 origin_;
  float inv_res_;
  std::int32_t settled_;
  int back_cells_;
};

// Marks a dropped hit in the scratch cells: outside every grid's box.
constexpr CellIndex kDroppedHit{INT32_MIN, INT32_MIN};

// Rays are set up four at a time (core/geometry/points4.hpp: lane by lane the scalar code's
// operations, so the same cells). CellOf lane by lane:
struct Cells4 {
  Int4 x;
  Int4 y;
  CellIndex operator[](int lane) const { return CellIndex{x[lane], y[lane]}; }
};
Cells4 CellsOf4(Float4 x_m, Float4 y_m, float resolution_m) {
  return Cells4{FloorToInt4(x_m / resolution_m), FloorToInt4(y_m / resolution_m)};
}

// Each hit's cell into scratch[i], kDroppedHit for a hit behind a settled wall when the grid
// drops those (GridConfig::drop_hits_behind_settled_cells); returns how many were dropped.
int HitCells(const TiledGrid& grid, Point2 origin, Span<const Point2> hits, const GridConfig& config,
             Span<CellIndex> scratch) {
  const bool screen = grid.settle_at_bounds() && config.drop_hits_behind_settled_cells > 1;
  const WallScreen walls(grid, origin, config);
  int dropped = 0;
  for (std::size_t i = 0; i < hits.size(); i += 4) {
    const Points4 p = LoadPoints4(hits, i);
    const Cells4 cells = CellsOf4(p.x, p.y, config.resolution_m);
    for (int lane = 0, n = LanesAt(i, hits.size()); lane < n; ++lane) {
      const std::size_t k = i + static_cast<std::size_t>(lane);
      const bool behind = screen && walls.Behind(hits[k], cells[lane]);
      scratch[k] = behind ? kDroppedHit : cells[lane];
      dropped += behind ? 1 : 0;
    }
  }
  return dropped;
}

}  // namespace

InsertionStats InsertRays(TiledGrid& grid, Point2 origin, Span<const Point2> hits, Span<const Point2> free_ends,
                          const GridConfig& config, std::uint32_t stamp, Span<CellIndex> scratch, float miss_range_m) {
  DPCR_ASSERT(stamp != 0 && scratch.size() >= hits.size());
  InsertionStats stats;
  const float res = config.resolution_m;
  const CellIndex start = CellOf(origin.x, origin.y, res);

  // 1. The hits, each distinct cell once. They are marked as updated in this scan, so no ray of
  // this scan can clear them (a miss would be skipped as a repeat).
  const int dropped = HitCells(grid, origin, hits, config, scratch);
  const TiledGrid::SegmentStats h = grid.UpdateCells(Span<const CellIndex>(scratch.data(), hits.size()), config.hit_delta,
                                                     config.clamp_min, config.clamp_max, stamp);
  stats.hit_cells = h.applied;
  stats.out_of_box += h.out_of_box - dropped;  // the dropped ones fell outside on purpose
  stats.dropped_pool_full += h.dropped_pool_full;

  // 2. Misses along every ray, each cell once. The box is convex and rays start inside it:
  // a ray that leaves it never comes back, so tracing stops there (one out_of_box per ray).
  // Rays go to the grid in batches (the walk is set up once per batch, and the cells of a batch's
  // rays, a chain of square root and divisions each, are computed back to back).
  // On a grid whose settled walls can be unlearnt (TiledGrid::set_settle_rule), the last
  // unsettle_miss_margin_m of each ray goes in a batch of its own that cannot unsettle them
  // (GridConfig::unsettle_miss_margin_m).
  MissBatch strong(grid, config, stamp, true, &stats), weak(grid, config, stamp, false, &stats);
  const bool split = grid.settle_at_bounds() && grid.unsettle_occupied_after() > 0 &&
                     config.unsettle_miss_margin_m > config.hit_margin_m;  // a ray clears nothing nearer anyway
  const float range2 = miss_range_m * miss_range_m;
  const float margin2 = config.hit_margin_m * config.hit_margin_m;
  // The cells a ray to hit p clears: from `start` (or miss_range_m before the hit) up to
  // hit_margin_m before it; none when the hit is within the margin.
  // Four rays at a time: both candidate ends of each (a lane whose ray clears nothing, or that
  // starts at `start`, has its cells computed and unused; a hit on the origin gives NaN there).
  for (std::size_t i = 0; i < hits.size(); i += 4) {
    const Points4 p = LoadPoints4(hits, i);
    const Float4 dx4 = p.x - origin.x, dy4 = p.y - origin.y;
    const Float4 d2_4 = dx4 * dx4 + dy4 * dy4;
    const Float4 d4 = Sqrt4(d2_4);
    const Float4 end_k = 1.0f - config.hit_margin_m / d4;
    const Cells4 ends = CellsOf4(origin.x + end_k * dx4, origin.y + end_k * dy4, res);
    // Start miss_range_m before the hit (a cell of the full ray's neighbourhood, not always on it).
    const Float4 start_k = 1.0f - miss_range_m / d4;
    const Cells4 starts = CellsOf4(origin.x + start_k * dx4, origin.y + start_k * dy4, res);
    for (int lane = 0, n = LanesAt(i, hits.size()); lane < n; ++lane) {
      const CellIndex hit_cell = scratch[i + static_cast<std::size_t>(lane)];
      if (hit_cell == kDroppedHit) continue;
      const float d2 = d2_4[lane];
      if (d2 <= margin2) continue;
      const CellIndex to = config.hit_margin_m > 0.0f ? ends[lane] : hit_cell;  // exactly the hit's cell
      CellIndex from = start;
      float from_d = d4[lane];  // how far before the hit the segment starts
      if (miss_range_m > 0.0f && d2 > range2) {
        from = starts[lane];
        from_d = miss_range_m;
      }
      if (!split) {
        strong.Queue(from, to);
      } else if (from_d <= config.unsettle_miss_margin_m) {
        weak.Queue(from, to);
      } else {
        const float dx = dx4[lane], dy = dy4[lane];
        const float k = 1.0f - config.unsettle_miss_margin_m / d4[lane];
        const CellIndex mid = CellOf(origin.x + k * dx, origin.y + k * dy, res);
        strong.Queue(from, mid);
        weak.Queue(mid, to);
      }
    }
  }
  for (const Point2& p : free_ends) strong.Queue(start, CellOf(p.x, p.y, res));
  strong.Flush();
  weak.Flush();
  return stats;
}

}  // namespace dpcr
