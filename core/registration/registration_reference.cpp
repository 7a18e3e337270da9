#include "core/registration/registration_reference.hpp"

#include <cmath>
#include <cstdint>

#include "core/base/assert.hpp"

namespace dpcr {

RegistrationReference::RegistrationReference(Span<ObstacleCell> cells, Span<std::uint16_t> nearest,
                                             Span<std::uint64_t> obstacle_blocks, Span<std::uint16_t> scratch,
                                             Span<LineFeature> lines, Span<RefitSums> refit, int max_w, int max_h)
    : cells_(cells),
      nearest_(nearest),
      obstacle_blocks_(obstacle_blocks),
      scratch_(scratch),
      lines_(lines),
      refit_(refit),
      max_w_(max_w),
      max_h_(max_h) {
  DPCR_ASSERT(nearest.size() == static_cast<std::size_t>(max_w * max_h) &&
              scratch.size() >= cells.size() + 2 * lines.size());
  DPCR_ASSERT(refit.empty() || refit.size() >= lines.size());
  DPCR_ASSERT(cells.size() < kNoneNear);
  const int blocks_x = (max_w + 7) >> kBlockShift, blocks_y = (max_h + 7) >> kBlockShift;
  DPCR_ASSERT(obstacle_blocks.size() == static_cast<std::size_t>(blocks_x * blocks_y));
  DPCR_ASSERT(blocks_x <= 64 && blocks_y <= kMaxBlockRows);
  // The invariants Build relies on: the table is all kNotSearched, the blocks all clear, except
  // where written_blocks_ and occupied_blocks_ say otherwise.
  for (std::uint16_t& k : nearest_) k = kNotSearched;
  for (std::uint64_t& b : obstacle_blocks_) b = 0;
  for (std::uint64_t& row : occupied_blocks_) row = 0;
  for (std::uint64_t& row : written_blocks_) row = 0;
}

void RegistrationReference::ClearWritten() {
  // Only the 8 x 8-cell blocks of the table written since the last build (obstacle cells and
  // searched cells, near walls), not the whole 128 KiB table; only the obstacle blocks in rows
  // that hold any. Indices are those of the last build's window.
  for (int by = 0; by < kMaxBlockRows; ++by) {
    for (std::uint64_t bits = written_blocks_[by]; bits != 0; bits &= bits - 1) {
      const int x0 = __builtin_ctzll(bits) << kBlockShift, y0 = by << kBlockShift;
      const int x1 = x0 + 8 < w_ ? x0 + 8 : w_, y1 = y0 + 8 < h_ ? y0 + 8 : h_;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) nearest_[static_cast<std::size_t>(y * w_ + x)] = kNotSearched;
      }
    }
    written_blocks_[by] = 0;
    for (std::uint64_t bits = occupied_blocks_[by]; bits != 0; bits &= bits - 1) {
      obstacle_blocks_[static_cast<std::size_t>(by * blocks_x_ + __builtin_ctzll(bits))] = 0;
    }
    occupied_blocks_[by] = 0;
  }
}

std::uint16_t RegistrationReference::ObstacleAt(int x, int y) const {
  if (x < 0 || y < 0 || x >= w_ || y >= h_) return kNoCell;
  // Obstacle cells hold their own index; other entries are markers or another cell's index.
  const std::uint16_t k = nearest_[static_cast<std::size_t>(y * w_ + x)];
  return (k < cell_count_ && cells_[k].x == x && cells_[k].y == y) ? k : kNoCell;
}

Status RegistrationReference::Build(const TiledGrid& grid, CellBox window, const ReferenceConfig& config,
                                    ReferenceBuildStats* stats) {
  ReferenceBuildStats st;
  BeginBuild(window, grid.resolution_m());
  AddGrid(grid, CellIndex{0, 0}, config, &st);
  const Status s = FinishBuild(config, &st);
  if (stats != nullptr) *stats = st;
  return s;
}

void RegistrationReference::BeginBuild(CellBox window, float resolution_m) {
  if (table_lent_) {
    // Lent as bytes to another stage: restore every invariant, not only what the last build wrote.
    for (std::uint16_t& k : nearest_) k = kNotSearched;
    for (std::uint64_t& b : obstacle_blocks_) b = 0;
    for (std::uint64_t& row : occupied_blocks_) row = 0;
    for (std::uint64_t& row : written_blocks_) row = 0;
    table_lent_ = false;
  }
  ClearWritten();  // with the last build's window size, before it changes
  window_min_ = window.min;
  w_ = window.width() < max_w_ ? window.width() : max_w_;
  h_ = window.height() < max_h_ ? window.height() : max_h_;
  w_ = w_ > 0 ? w_ : 0;
  h_ = h_ > 0 ? h_ : 0;
  res_ = resolution_m;
  inv_res_ = 1.0f / res_;
  origin_ = Point2{static_cast<float>(window.min.x) * res_, static_cast<float>(window.min.y) * res_};
  cell_count_ = line_count_ = 0;
  blocks_x_ = (w_ + 7) >> kBlockShift;
}

std::uint16_t RegistrationReference::EvidenceWeight(const TiledGrid& grid, std::int16_t v, const ReferenceConfig& config) {
  if (!config.weight_by_evidence) return 1;
  // Q10 log-odds / 64: up to 511 for an unclamped submap sum, 57 at the regional clamp.
  const int w = 1 + (grid.LogOdds(v) >> 6);
  // A hit mean holds about 2^k returns (its class): the cells that range noise reaches now and
  // then, beside a wall's core, weigh that much less in its line (at most 57 x 64).
  return static_cast<std::uint16_t>(grid.HasHitMean(v) ? w << (DecodeHitMean(v).k - 1) : w);
}

void RegistrationReference::AddGrid(const TiledGrid& grid, CellIndex offset, const ReferenceConfig& config,
                                    ReferenceBuildStats* stats) {
  // 1. Obstacle cells, tile by tile: only allocated tiles cost anything.
  const CellBox box = grid.box();
  for (int ty = 0; ty < grid.tiles_y(); ++ty) {
    for (int tx = 0; tx < grid.tiles_x(); ++tx) {
      const TileId id = grid.tile_at(tx, ty);
      if (id == kNoTile) continue;
      const std::int16_t* values = grid.pool()[id].cells;
      const int x0 = box.min.x + offset.x + tx * kTileSide - window_min_.x;
      const int y0 = box.min.y + offset.y + ty * kTileSide - window_min_.y;
      if (x0 >= w_ || y0 >= h_ || x0 + kTileSide <= 0 || y0 + kTileSide <= 0) continue;
      const int lx0 = x0 < 0 ? -x0 : 0, lx1 = x0 + kTileSide > w_ ? w_ - x0 : kTileSide;  // columns inside the window
      for (int ly = 0; ly < kTileSide; ++ly) {
        const int y = y0 + ly;
        if (y < 0 || y >= h_) continue;
        // Most rows hold no obstacle cell: a branch-free (vectorised) pass says so: the row's
        // maximum (a max reduction is a few SIMD instructions, unlike an or of comparisons).
        // kUnknownCell is below any threshold.
        const std::int16_t* row = values + ly * kTileSide;
        std::int16_t row_max = row[0];
        for (int lx = 1; lx < kTileSide; ++lx) row_max = row[lx] > row_max ? row[lx] : row_max;
        if (row_max <= config.obstacle_threshold) continue;
        for (int lx = lx0; lx < lx1; ++lx) {
          const int x = x0 + lx;
          const std::int16_t v = row[lx];
          if (v <= config.obstacle_threshold) continue;  // kUnknownCell included
          AddObstacleCell(x, y, EvidenceWeight(grid, v, config), grid.HasHitMean(v) ? SubCellOf(v) : SubCell{}, stats);
        }
      }
    }
  }
  stats->obstacle_cells = static_cast<int>(cell_count_);
}

void RegistrationReference::AddObstacleCell(int x, int y, std::uint16_t weight, SubCell sub, ReferenceBuildStats* stats) {
  std::uint16_t& entry = nearest_[static_cast<std::size_t>(y * w_ + x)];
  if (entry != kNotSearched) {  // already an obstacle cell of an earlier grid: one cell, the larger weight
    if (weight > cells_[entry].weight) {
      cells_[entry].weight = weight;
      cells_[entry].sub_x = sub.x & 63u;
      cells_[entry].sub_y = sub.y & 63u;
    }
    return;
  }
  if (cell_count_ == cells_.size()) {
    ++stats->dropped_cells;
    return;
  }
  ObstacleCell& c = cells_[cell_count_];
  c = ObstacleCell{};
  c.x = static_cast<std::uint16_t>(x) & 1023u;
  c.y = static_cast<std::uint16_t>(y) & 1023u;
  c.sub_x = sub.x & 63u;
  c.sub_y = sub.y & 63u;
  c.weight = weight;
  entry = static_cast<std::uint16_t>(cell_count_++);
  written_blocks_[y >> kBlockShift] |= std::uint64_t{1} << (x >> kBlockShift);
  obstacle_blocks_[static_cast<std::size_t>((y >> kBlockShift) * blocks_x_ + (x >> kBlockShift))] |=
      std::uint64_t{1} << (((y & 7) << 3) | (x & 7));
  occupied_blocks_[y >> kBlockShift] |= std::uint64_t{1} << (x >> kBlockShift);
}

void RegistrationReference::AddPlacedGrid(const TiledGrid& grid, const Pose2& grid_in_window, const ReferenceConfig& config,
                                          ReferenceBuildStats* stats) {
  // On the window's lattice (no rotation, a whole number of cells away): the exact cell shift.
  const float fx = grid_in_window.x * inv_res_, fy = grid_in_window.y * inv_res_;
  const float rx = std::round(fx), ry = std::round(fy);
  if (grid_in_window.theta == 0.0f && std::fabs(fx - rx) < 1e-3f && std::fabs(fy - ry) < 1e-3f) {
    AddGrid(grid, CellIndex{static_cast<std::int32_t>(rx), static_cast<std::int32_t>(ry)}, config, stats);
    return;
  }
  // Otherwise each obstacle cell's obstacle (its hit mean, or its centre) is carried into the
  // window's frame and lands in the cell containing it (a rotated map's walls stay one cell
  // thick): at the same place in that cell where the grid has hit means, at its centre otherwise.
  const PointTransform to_window(grid_in_window);
  ForEachCellAbove(grid, config.obstacle_threshold, [&](CellIndex local, std::int16_t v) {
    float ox = 0.5f, oy = 0.5f;
    ObstacleOffsetInCell(v, grid.HasHitMean(v), &ox, &oy);
    const Point2 p = to_window(Point2{(static_cast<float>(local.x) + ox) * res_, (static_cast<float>(local.y) + oy) * res_});
    const float gx = p.x * inv_res_, gy = p.y * inv_res_;
    const int cx = FloorToInt(gx), cy = FloorToInt(gy);
    const int x = cx - window_min_.x, y = cy - window_min_.y;
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
    const SubCell sub = grid.hit_means_settled() != 0 ? SubCell{static_cast<std::uint16_t>(HitMeanLevel(gx - static_cast<float>(cx))),
                                                                static_cast<std::uint16_t>(HitMeanLevel(gy - static_cast<float>(cy)))}
                                                       : SubCell{};
    AddObstacleCell(x, y, EvidenceWeight(grid, v, config), sub, stats);
  });
  stats->obstacle_cells = static_cast<int>(cell_count_);
}

Status RegistrationReference::FinishBuild(const ReferenceConfig& config, ReferenceBuildStats* stats) {
  ReferenceBuildStats& st = *stats;
  // 2. (after every grid's step 1) Local normals and line features, while the table still marks obstacle cells only.
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

  // 3. The nearest-obstacle table: every other cell (kNotSearched, as ClearWritten left it) is
  // searched on its first query (Search).
  const float bound_cells = config.max_distance_m * inv_res_;
  bound2_ = static_cast<std::int32_t>(bound_cells * bound_cells);
  reach_ = 0;
  while ((reach_ + 1) * (reach_ + 1) <= bound2_) ++reach_;
  return (st.dropped_cells > 0 || st.extraction.lines_full) ? Status::kCapacityExceeded : Status::kOk;
}

std::uint16_t RegistrationReference::Search(int x, int y) const {
  // Rows of blocks from the query's outwards; in each, only the blocks holding obstacle cells that
  // could hold one no farther than the best so far. Among equally near cells the one with more
  // evidence wins (the wall's core over a cell that range noise reached), then the smaller index:
  // the answer does not depend on the visiting order.
  std::int32_t best_d2 = bound2_;
  std::uint16_t best = kNoCell;
  const int by = y >> kBlockShift;
  const int bx0 = (x - reach_ < 0 ? 0 : x - reach_) >> kBlockShift;
  const int by0 = (y - reach_ < 0 ? 0 : y - reach_) >> kBlockShift;
  const int bx1 = (x + reach_ >= w_ ? w_ - 1 : x + reach_) >> kBlockShift;
  const int by1 = (y + reach_ >= h_ ? h_ - 1 : y + reach_) >> kBlockShift;
  const std::uint64_t columns = (~std::uint64_t{0} >> (63 - bx1)) & (~std::uint64_t{0} << bx0);
  const auto open_block = [&](int ix, int iy, std::int32_t gy2) {
    const int x0 = ix << kBlockShift, y0 = iy << kBlockShift;
    const int gx = x < x0 ? x0 - x : (x > x0 + 7 ? x - x0 - 7 : 0);
    if (gx * gx + gy2 > best_d2) return;
    std::uint64_t bits = obstacle_blocks_[static_cast<std::size_t>(iy * blocks_x_ + ix)];
    while (bits != 0) {
      const int b = __builtin_ctzll(bits);
      bits &= bits - 1;
      const int dx = x0 + (b & 7) - x, dy = y0 + (b >> 3) - y;
      const std::int32_t d2 = dx * dx + dy * dy;
      if (d2 > best_d2) continue;
      const std::uint16_t k = nearest_[static_cast<std::size_t>((y0 + (b >> 3)) * w_ + x0 + (b & 7))];
      if (d2 < best_d2 || best == kNoCell) {
        best = k, best_d2 = d2;
      } else {
        const std::uint16_t kw = cells_[k].weight, bw = cells_[best].weight;
        if (kw > bw || (kw == bw && k < best)) best = k;
      }
    }
  };
  // Rows by, by - 1, by + 1, by - 2, ...: each farther row is at least as far from the query.
  const int rows = (by - by0 > by1 - by ? by - by0 : by1 - by);
  for (int r = 0; r <= rows; ++r) {
    const std::int32_t gap = r == 0 ? 0 : ((r - 1) << kBlockShift) + 1;  // a lower bound on |dy|
    if (gap * gap > best_d2) break;
    for (int side = 0; side < (r == 0 ? 1 : 2); ++side) {
      const int iy = side == 0 ? by - r : by + r;
      if (iy < by0 || iy > by1) continue;
      const int y0 = iy << kBlockShift;
      const int gy = y < y0 ? y0 - y : (y > y0 + 7 ? y - y0 - 7 : 0);
      const std::int32_t gy2 = gy * gy;
      for (std::uint64_t blocks = occupied_blocks_[iy] & columns; blocks != 0; blocks &= blocks - 1) {
        open_block(__builtin_ctzll(blocks), iy, gy2);
      }
    }
  }
  nearest_[static_cast<std::size_t>(y * w_ + x)] = best == kNoCell ? kNoneNear : best;
  written_blocks_[by] |= std::uint64_t{1} << (x >> kBlockShift);
  return best;
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

void RegistrationReference::AddRefitPoints(Span<const Point2> points, const PointTransform& to_grid, float gate_m) {
  for (const Point2& p : points) AddRefitPoint(to_grid(p), gate_m);
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
