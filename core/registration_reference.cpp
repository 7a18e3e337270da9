#include "core/registration_reference.hpp"

#include <cmath>
#include <cstdint>

#include "core/assert.hpp"

namespace dpcr {
namespace {

// Distance-transform skip mask: up to 32 x 32 blocks of 16 x 16 cells (windows up to 512 x 512 cells).
constexpr int kBlockShift = 4;
constexpr int kBlockCells = 1 << kBlockShift;
constexpr int kMaxBlocks = 1024;

std::int32_t Dist2(const ObstacleCell& c, int x, int y) {
  const std::int32_t dx = c.x - x, dy = c.y - y;
  return dx * dx + dy * dy;
}

// Neighbours read by each of the four raster sweeps, in the order they are tried (the order
// decides ties, so it is part of the result).
constexpr int kForward[4][2] = {{-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
constexpr int kBackward[4][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}};
constexpr int kRight[1][2] = {{1, 0}};
constexpr int kLeft[1][2] = {{-1, 0}};

// The nearest-seed table during the distance transform.
struct SeedTable {
  std::uint16_t* nearest;
  const ObstacleCell* cells;
  int w, h;

  // Takes the nearest of cell (x, y)'s seed and its neighbours' seeds (first wins on ties).
  // kInside: every neighbour is in the window (no bounds checks; most cells).
  template <bool kInside, int kN>
  void Relax(int x, int y, const int (&offsets)[kN][2]) const {
    std::uint16_t* slot = nearest + y * w + x;
    std::uint16_t cur = *slot;
    std::int32_t cur_d = cur == kNoCell ? INT32_MAX : Dist2(cells[cur], x, y);
    if (cur_d == 0) return;  // an obstacle cell is its own nearest
    for (int k = 0; k < kN; ++k) {
      const int nx = x + offsets[k][0], ny = y + offsets[k][1];
      if (!kInside && (nx < 0 || ny < 0 || nx >= w || ny >= h)) continue;
      const std::uint16_t cand = nearest[ny * w + nx];
      if (cand == kNoCell || cand == cur) continue;
      const std::int32_t d = Dist2(cells[cand], x, y);
      if (d < cur_d) cur = cand, cur_d = d;
    }
    *slot = cur;
  }

  // One row of a sweep, x ascending (dir > 0) or descending, over the active 16-cell blocks only
  // (inactive cells would be no-ops). `row_inside`: the rows the offsets reach exist.
  template <int kN>
  void SweepRow(int y, int dir, const int (&offsets)[kN][2], bool row_inside, const bool* active_row,
                int blocks_x) const {
    for (int i = 0; i < blocks_x; ++i) {
      const int bx = dir > 0 ? i : blocks_x - 1 - i;
      if (!active_row[bx]) continue;
      const int x0 = bx << kBlockShift, x1 = (x0 + kBlockCells < w ? x0 + kBlockCells : w);
      if (dir > 0) {
        for (int x = x0; x < x1; ++x) RelaxAt(x, y, offsets, row_inside);
      } else {
        for (int x = x1 - 1; x >= x0; --x) RelaxAt(x, y, offsets, row_inside);
      }
    }
  }

  template <int kN>
  void RelaxAt(int x, int y, const int (&offsets)[kN][2], bool row_inside) const {
    if (row_inside && x > 0 && x < w - 1) {
      Relax<true>(x, y, offsets);
    } else {
      Relax<false>(x, y, offsets);
    }
  }
};

}  // namespace

RegistrationReference::RegistrationReference(Span<ObstacleCell> cells, Span<std::uint16_t> nearest,
                                             Span<std::uint16_t> scratch, Span<LineFeature> lines,
                                             Span<RefitSums> refit, int max_w, int max_h)
    : cells_(cells), nearest_(nearest), scratch_(scratch), lines_(lines), refit_(refit), max_w_(max_w), max_h_(max_h) {
  DPCR_ASSERT(nearest.size() == static_cast<std::size_t>(max_w * max_h) && scratch.size() >= cells.size());
  DPCR_ASSERT(refit.empty() || refit.size() >= lines.size());
  DPCR_ASSERT(cells.size() < kNoCell);
  DPCR_ASSERT(((max_w + kBlockCells - 1) >> kBlockShift) * ((max_h + kBlockCells - 1) >> kBlockShift) <= kMaxBlocks);
}

std::uint16_t RegistrationReference::ObstacleAt(int x, int y) const {
  if (x < 0 || y < 0 || x >= w_ || y >= h_) return kNoCell;
  const std::uint16_t k = nearest_[static_cast<std::size_t>(y * w_ + x)];
  return (k != kNoCell && cells_[k].x == x && cells_[k].y == y) ? k : kNoCell;
}

Status RegistrationReference::Build(const TiledGrid& grid, CellBox window, const ReferenceConfig& config,
                                    ReferenceBuildStats* stats) {
  ReferenceBuildStats st;
  w_ = window.width() < max_w_ ? window.width() : max_w_;
  h_ = window.height() < max_h_ ? window.height() : max_h_;
  w_ = w_ > 0 ? w_ : 0;
  h_ = h_ > 0 ? h_ : 0;
  res_ = grid.resolution_m();
  inv_res_ = 1.0f / res_;
  origin_ = Point2{static_cast<float>(window.min.x) * res_, static_cast<float>(window.min.y) * res_};
  cell_count_ = line_count_ = 0;
  const std::size_t n_table = static_cast<std::size_t>(w_ * h_);
  for (std::size_t i = 0; i < n_table; ++i) nearest_[i] = kNoCell;

  // 1. Obstacle cells, tile by tile: only allocated tiles cost anything.
  const CellBox box = grid.box();
  for (int ty = 0; ty < grid.tiles_y(); ++ty) {
    for (int tx = 0; tx < grid.tiles_x(); ++tx) {
      const TileId id = grid.tile_at(tx, ty);
      if (id == kNoTile) continue;
      const std::int16_t* values = grid.pool()[id].cells;
      const int x0 = box.min.x + tx * kTileSide - window.min.x, y0 = box.min.y + ty * kTileSide - window.min.y;
      if (x0 >= w_ || y0 >= h_ || x0 + kTileSide <= 0 || y0 + kTileSide <= 0) continue;
      for (int ly = 0; ly < kTileSide; ++ly) {
        const int y = y0 + ly;
        if (y < 0 || y >= h_) continue;
        for (int lx = 0; lx < kTileSide; ++lx) {
          const int x = x0 + lx;
          const std::int16_t v = values[ly * kTileSide + lx];
          if (x < 0 || x >= w_ || v == kUnknownCell || v <= config.obstacle_threshold) continue;
          if (cell_count_ == cells_.size()) {
            ++st.dropped_cells;
            continue;
          }
          ObstacleCell& c = cells_[cell_count_];
          c = ObstacleCell{};
          c.x = static_cast<std::int16_t>(x);
          c.y = static_cast<std::int16_t>(y);
          // Q10 log-odds / 64: up to 511 for an unclamped submap sum, 56 at the regional clamp.
          if (config.weight_by_evidence) c.weight = static_cast<std::uint16_t>(1 + (v >> 6));
          nearest_[static_cast<std::size_t>(y * w_ + x)] = static_cast<std::uint16_t>(cell_count_++);
        }
      }
    }
  }
  st.obstacle_cells = static_cast<int>(cell_count_);

  // 2. Local normals and line features, while the table still marks obstacle cells only.
  const Span<ObstacleCell> used(cells_.data(), cell_count_);
  ComputeLocalNormals(used, nearest_.data(), w_, h_);
  const int n_lines = ExtractLines(used, nearest_.data(), w_, h_, scratch_, lines_, config.lines, &st.extraction);
  line_count_ = static_cast<std::size_t>(n_lines);
  st.lines = n_lines;
  for (std::size_t i = 0; i < line_count_; ++i) {  // cell units -> world metres
    LineFeature& l = lines_[i];
    const auto to_world = [&](Point2 p) { return Point2{origin_.x + p.x * res_, origin_.y + p.y * res_}; };
    l.a = to_world(l.a);
    l.b = to_world(l.b);
    l.mean = to_world(l.mean);
    l.offset = l.normal.x * l.mean.x + l.normal.y * l.mean.y;
    l.rms *= res_;
    l.cxx *= res_ * res_;
    l.cxy *= res_ * res_;
    l.cyy *= res_ * res_;
  }

  // 3. Nearest obstacle cell per window cell: two raster passes propagating seed ids (vector
  // distance transform, 8SSEDT-like; exact up to rare one-cell ties), then cut at the bound.
  // Per cell the current distance is computed once, and a neighbour holding the same seed is
  // skipped, so the usual cost is a few loads per cell.
  // Blocks of 16x16 cells farther than the bound from every obstacle cell keep kNoCell and are
  // not visited (any cell on the propagation path from a seed to a cell within the bound is itself
  // within the bound of that seed, so skipping them changes no answer).
  const float bound_cells = config.max_distance_m * inv_res_;
  const std::int32_t bound2 = static_cast<std::int32_t>(bound_cells * bound_cells);
  const int reach = static_cast<int>(bound_cells) + 1;
  const int blocks_x = (w_ + kBlockCells - 1) >> kBlockShift;
  bool active[kMaxBlocks];
  for (bool& a : active) a = false;
  for (std::size_t i = 0; i < cell_count_; ++i) {
    const int bx0 = (cells_[i].x - reach < 0 ? 0 : cells_[i].x - reach) >> kBlockShift;
    const int by0 = (cells_[i].y - reach < 0 ? 0 : cells_[i].y - reach) >> kBlockShift;
    const int bx1 = (cells_[i].x + reach >= w_ ? w_ - 1 : cells_[i].x + reach) >> kBlockShift;
    const int by1 = (cells_[i].y + reach >= h_ ? h_ - 1 : cells_[i].y + reach) >> kBlockShift;
    for (int by = by0; by <= by1; ++by) {
      for (int bx = bx0; bx <= bx1; ++bx) active[by * blocks_x + bx] = true;
    }
  }
  const SeedTable table{nearest_.data(), cells_.data(), w_, h_};
  for (int y = 0; y < h_; ++y) {
    const bool* row = active + (y >> kBlockShift) * blocks_x;
    table.SweepRow(y, +1, kForward, y > 0, row, blocks_x);
    table.SweepRow(y, -1, kRight, true, row, blocks_x);
  }
  for (int y = h_ - 1; y >= 0; --y) {
    const bool* row = active + (y >> kBlockShift) * blocks_x;
    table.SweepRow(y, -1, kBackward, y < h_ - 1, row, blocks_x);
    table.SweepRow(y, +1, kLeft, true, row, blocks_x);
  }
  // Cut at the bound (inactive blocks hold kNoCell already).
  for (int y = 0; y < h_; ++y) {
    const bool* row = active + (y >> kBlockShift) * blocks_x;
    for (int bx = 0; bx < blocks_x; ++bx) {
      if (!row[bx]) continue;
      const int x0 = bx << kBlockShift, x1 = (x0 + kBlockCells < w_ ? x0 + kBlockCells : w_);
      for (int x = x0; x < x1; ++x) {
        std::uint16_t& k = nearest_[static_cast<std::size_t>(y * w_ + x)];
        if (k != kNoCell && Dist2(cells_[k], x, y) > bound2) k = kNoCell;
      }
    }
  }
  if (stats != nullptr) *stats = st;
  return (st.dropped_cells > 0 || st.extraction.lines_full) ? Status::kCapacityExceeded : Status::kOk;
}

void RegistrationReference::BeginPointRefit() {
  DPCR_ASSERT(!refit_.empty());
  for (std::size_t i = 0; i < line_count_; ++i) refit_[i] = RefitSums{};
}

void RegistrationReference::AddRefitPoint(Point2 p, float gate_m) {
  const std::uint16_t k = Nearest(p);
  if (k == kNoCell || cells_[k].line == kNoLine) return;
  const LineFeature& l = lines_[cells_[k].line];
  const float dx = p.x - l.mean.x, dy = p.y - l.mean.y;
  const float v = l.normal.x * dx + l.normal.y * dy;
  if (v > gate_m || v < -gate_m) return;
  const float u = l.normal.y * dx - l.normal.x * dy;  // along d = (ny, -nx)
  RefitSums& s = refit_[cells_[k].line];
  s.n += 1.0f, s.u += u, s.v += v, s.uu += u * u, s.uv += u * v, s.vv += v * v;
}

int RegistrationReference::EndPointRefit(int min_points) {
  int refitted = 0;
  for (std::size_t i = 0; i < line_count_; ++i) {
    const RefitSums& s = refit_[i];
    if (s.n < static_cast<float>(min_points)) continue;
    LineFeature& l = lines_[i];
    // TLS in the line's own frame: mean (mu, mv), then the minor axis of the central moments.
    const float mu = s.u / s.n, mv = s.v / s.n;
    const float cuu = s.uu / s.n - mu * mu, cuv = s.uv / s.n - mu * mv, cvv = s.vv / s.n - mv * mv;
    const float phi = 0.5f * std::atan2(2.0f * cuv, cuu - cvv);  // direction angle in (u, v)
    const Point2 d{l.normal.y, -l.normal.x};
    const Point2 mean{l.mean.x + mu * d.x + mv * l.normal.x, l.mean.y + mu * d.y + mv * l.normal.y};
    const float c = std::cos(phi), sn = std::sin(phi);
    const Point2 dir{c * d.x + sn * l.normal.x, c * d.y + sn * l.normal.y};
    const Point2 normal{-dir.y, dir.x};
    // Keep the normal's orientation, and the extent: endpoints projected on the new line.
    const float sign = normal.x * l.normal.x + normal.y * l.normal.y < 0.0f ? -1.0f : 1.0f;
    l.normal = Point2{sign * normal.x, sign * normal.y};
    l.offset = l.normal.x * mean.x + l.normal.y * mean.y;
    const auto project = [&](Point2 e) {
      const float t = dir.x * (e.x - mean.x) + dir.y * (e.y - mean.y);
      return Point2{mean.x + t * dir.x, mean.y + t * dir.y};
    };
    l.a = project(l.a);
    l.b = project(l.b);
    l.mean = mean;
    ++refitted;
  }
  return refitted;
}

}  // namespace dpcr
