#include "core/registration/line_extractor.hpp"

#include <cmath>

#include "core/base/assert.hpp"

namespace dpcr {
namespace {

constexpr int kSplitStack = 64;


struct Range {
  std::uint32_t lo;
  std::uint32_t hi;
};

// Total least squares from central moments: the normal is the minor eigenvector, and the minor
// eigenvalue is the mean squared perpendicular distance.
void FitFromMoments(LineFeature* l) {
  const float phi = 0.5f * std::atan2(2.0f * l->cxy, l->cxx - l->cyy);
  l->normal = Point2{-std::sin(phi), std::cos(phi)};
  l->offset = l->normal.x * l->mean.x + l->normal.y * l->mean.y;
  const float half_sum = 0.5f * (l->cxx + l->cyy);
  const float half_diff = 0.5f * (l->cxx - l->cyy);
  const float lambda_min = half_sum - std::sqrt(half_diff * half_diff + l->cxy * l->cxy);
  l->rms = std::sqrt(lambda_min > 0.0f ? lambda_min : 0.0f);
}

LineFeature Moments(Span<ObstacleCell> cells, const std::uint16_t* perm, Range r) {
  LineFeature l;
  for (std::uint32_t i = r.lo; i < r.hi; ++i) {
    const ObstacleCell& c = cells[perm[i]];
    const Point2 p = ObstaclePosition(c);
    const float w = c.weight;
    l.mass += w;
    l.mean.x += w * p.x;
    l.mean.y += w * p.y;
  }
  l.mean.x /= l.mass;
  l.mean.y /= l.mass;
  for (std::uint32_t i = r.lo; i < r.hi; ++i) {
    const ObstacleCell& c = cells[perm[i]];
    const Point2 p = ObstaclePosition(c);
    const float w = c.weight;
    const float dx = p.x - l.mean.x, dy = p.y - l.mean.y;
    l.cxx += w * dx * dx;
    l.cxy += w * dx * dy;
    l.cyy += w * dy * dy;
  }
  l.cxx /= l.mass;
  l.cxy /= l.mass;
  l.cyy /= l.mass;
  l.support = static_cast<std::uint16_t>(r.hi - r.lo);
  FitFromMoments(&l);
  return l;
}

float DistanceToSegment(Point2 p, Point2 a, Point2 b) {
  const float vx = b.x - a.x, vy = b.y - a.y;
  const float len2 = vx * vx + vy * vy;
  float t = len2 > 1e-9f ? ((p.x - a.x) * vx + (p.y - a.y) * vy) / len2 : 0.0f;
  t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
  const float dx = p.x - (a.x + t * vx), dy = p.y - (a.y + t * vy);
  return std::sqrt(dx * dx + dy * dy);
}

// Moves the cells for which `left` holds to the front of r; returns the split point.
template <typename Pred>
std::uint32_t Partition(std::uint16_t* perm, Range r, Span<ObstacleCell> cells, Pred left) {
  std::uint32_t mid = r.lo;
  for (std::uint32_t i = r.lo; i < r.hi; ++i) {
    if (left(ObstaclePosition(cells[perm[i]]))) {
      const std::uint16_t t = perm[i];
      perm[i] = perm[mid];
      perm[mid++] = t;
    }
  }
  return mid;
}

// Douglas–Peucker on an unordered set: chord between the extreme cells along the fitted
// direction, split at the cell farthest from the chord, each cell going to the nearer of the two
// new chords. Returns false when the set cannot be split (it stays a leaf).
bool Split(Span<ObstacleCell> cells, std::uint16_t* perm, Range r, const LineFeature& fit, std::uint32_t* mid) {
  const Point2 d{fit.normal.y, -fit.normal.x};
  Point2 a{}, b{};
  float tmin = 1e30f, tmax = -1e30f;
  for (std::uint32_t i = r.lo; i < r.hi; ++i) {
    const Point2 p = ObstaclePosition(cells[perm[i]]);
    const float t = d.x * p.x + d.y * p.y;
    if (t < tmin) tmin = t, a = p;
    if (t > tmax) tmax = t, b = p;
  }
  Point2 f{};
  float best = -1.0f;
  for (std::uint32_t i = r.lo; i < r.hi; ++i) {
    const Point2 p = ObstaclePosition(cells[perm[i]]);
    const float dist = DistanceToSegment(p, a, b);
    if (dist > best) best = dist, f = p;
  }
  *mid = Partition(perm, r, cells, [&](Point2 p) { return DistanceToSegment(p, a, f) <= DistanceToSegment(p, f, b); });
  if (*mid == r.lo || *mid == r.hi) {  // degenerate: cut across the direction at f
    const float tf = d.x * f.x + d.y * f.y;
    *mid = Partition(perm, r, cells, [&](Point2 p) { return d.x * p.x + d.y * p.y < tf; });
  }
  return *mid != r.lo && *mid != r.hi;
}

bool Mergeable(const LineFeature& p, const LineFeature& q, const LineExtractorConfig& cfg) {
  const float cross = p.normal.x * q.normal.y - p.normal.y * q.normal.x;
  if (std::fabs(cross) > std::sin(cfg.merge_angle_rad)) return false;
  const auto off = [](const LineFeature& l, Point2 x) { return std::fabs(l.normal.x * x.x + l.normal.y * x.y - l.offset); };
  if (off(p, q.a) > cfg.merge_offset_cells || off(p, q.b) > cfg.merge_offset_cells) return false;
  if (off(q, p.a) > cfg.merge_offset_cells || off(q, p.b) > cfg.merge_offset_cells) return false;
  const Point2 d{p.normal.y, -p.normal.x};
  const auto t = [&](Point2 x) { return d.x * x.x + d.y * x.y; };
  const float p0 = std::fmin(t(p.a), t(p.b)), p1 = std::fmax(t(p.a), t(p.b));
  const float q0 = std::fmin(t(q.a), t(q.b)), q1 = std::fmax(t(q.a), t(q.b));
  return std::fmax(q0 - p1, p0 - q1) <= cfg.merge_gap_cells;
}

// Union of two supports by the parallel-axis rule; endpoints = extremes of the four old ones.
LineFeature Merged(const LineFeature& p, const LineFeature& q) {
  LineFeature m;
  const float np = p.mass, nq = q.mass, n = np + nq;
  m.mean = Point2{(np * p.mean.x + nq * q.mean.x) / n, (np * p.mean.y + nq * q.mean.y) / n};
  const float pdx = p.mean.x - m.mean.x, pdy = p.mean.y - m.mean.y;
  const float qdx = q.mean.x - m.mean.x, qdy = q.mean.y - m.mean.y;
  m.cxx = (np * (p.cxx + pdx * pdx) + nq * (q.cxx + qdx * qdx)) / n;
  m.cxy = (np * (p.cxy + pdx * pdy) + nq * (q.cxy + qdx * qdy)) / n;
  m.cyy = (np * (p.cyy + pdy * pdy) + nq * (q.cyy + qdy * qdy)) / n;
  m.mass = n;
  m.support = static_cast<std::uint16_t>(p.support + q.support);
  FitFromMoments(&m);
  const Point2 d{m.normal.y, -m.normal.x};
  const Point2 ends[4] = {p.a, p.b, q.a, q.b};
  float tmin = 1e30f, tmax = -1e30f;
  for (const Point2& e : ends) {
    const float t = d.x * (e.x - m.mean.x) + d.y * (e.y - m.mean.y);
    tmin = std::fmin(tmin, t);
    tmax = std::fmax(tmax, t);
  }
  m.a = Point2{m.mean.x + tmin * d.x, m.mean.y + tmin * d.y};
  m.b = Point2{m.mean.x + tmax * d.x, m.mean.y + tmax * d.y};
  return m;
}

// A normal's component (|v| <= 127) to the nearest integer, halves away from zero: lround's answer
// without its call.
std::int8_t NormalComponent(float v) { return static_cast<std::int8_t>(v + std::copysign(0.5f, v)); }

}  // namespace

void ComputeLocalNormals(Span<ObstacleCell> cells, const std::uint16_t* cell_at, int w, int h) {
  for (ObstacleCell& c : cells) {
    int sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0, n = 0;
    const auto add = [&](int dx, int dy) { sx += dx, sy += dy, sxx += dx * dx, sxy += dx * dy, syy += dy * dy, ++n; };
    if (c.x >= 2 && c.y >= 2 && c.x < w - 2 && c.y < h - 2) {
      // Most cells: the neighbourhood is inside the table, no bounds checks (integer sums, so
      // the result does not depend on the path taken).
      const std::uint16_t* centre = cell_at + c.y * w + c.x;
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
          if (centre[dy * w + dx] != kNoCell) add(dx, dy);
        }
      }
    } else {
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
          const int x = c.x + dx, y = c.y + dy;
          if (x < 0 || y < 0 || x >= w || y >= h || cell_at[y * w + x] == kNoCell) continue;
          add(dx, dy);
        }
      }
    }
    c.nx = c.ny = 0;
    if (n < 3) continue;
    const float inv_n = 1.0f / static_cast<float>(n);
    const float mx = static_cast<float>(sx) * inv_n, my = static_cast<float>(sy) * inv_n;
    const float cxx = static_cast<float>(sxx) * inv_n - mx * mx;
    const float cxy = static_cast<float>(sxy) * inv_n - mx * my;
    const float cyy = static_cast<float>(syy) * inv_n - my * my;
    const float hs = 0.5f * (cxx + cyy), hd = 0.5f * (cxx - cyy);
    const float root = std::sqrt(hd * hd + cxy * cxy);
    if (hs - root > 0.25f * (hs + root) || !(root > 0.0f)) continue;  // blob, not a line: no trustworthy normal
    // The principal axis (cos phi, sin phi), 2 phi = atan2(2 cxy, cxx - cyy) in (-pi, pi], from the
    // half-angle formulas: cos 2phi = hd / root, sin 2phi = cxy / root; cos phi >= 0 and sin phi has
    // the sign of sin 2phi (phi = pi/2 when cxy is 0 and cxx < cyy). No atan2, sin or cos: they
    // were 40 % of this function on intel.clf. root > 0 here (a blob, root 0, was skipped above).
    const float cos_2phi = hd / root;
    const float cos_phi = std::sqrt(std::fmax(0.0f, 0.5f * (1.0f + cos_2phi)));
    const float sin_phi = std::copysign(std::sqrt(std::fmax(0.0f, 0.5f * (1.0f - cos_2phi))), cxy);
    c.nx = NormalComponent(-127.0f * sin_phi);
    c.ny = NormalComponent(127.0f * cos_phi);
  }
}

namespace {

// ObstacleCell::line of a cell of the component being collected, not yet owned by a line.
// Line ids stay below it (ExtractLines asserts lines.size() < kVisited).
constexpr std::uint16_t kVisited = kNoLine - 1;

// Step 1: the connected component of `seed` (cells within link_radius_cells), breadth first,
// appended to perm from `end` on (perm itself is the queue); its cells are marked kVisited.
Range CollectComponent(Span<ObstacleCell> cells, const std::uint16_t* cell_at, int w, int h, int link,
                       std::uint32_t seed, std::uint16_t* perm, std::uint32_t end) {
  const std::uint32_t start = end;
  perm[end++] = static_cast<std::uint16_t>(seed);
  cells[seed].line = kVisited;
  for (std::uint32_t q = start; q < end; ++q) {
    const ObstacleCell c = cells[perm[q]];
    // Neighbours clipped to the table (rows, then columns: the visiting order is the queue's).
    const int x0 = c.x - link < 0 ? 0 : c.x - link, x1 = c.x + link >= w ? w - 1 : c.x + link;
    const int y0 = c.y - link < 0 ? 0 : c.y - link, y1 = c.y + link >= h ? h - 1 : c.y + link;
    for (int y = y0; y <= y1; ++y) {
      const std::uint16_t* row = cell_at + y * w;
      for (int x = x0; x <= x1; ++x) {
        const std::uint16_t k = row[x];
        if (k == kNoCell || cells[k].line != kNoLine) continue;
        cells[k].line = kVisited;
        perm[end++] = k;
      }
    }
  }
  return Range{start, end};
}

// Largest distance of the range's cells from the fitted line.
float MaxDeviation(Span<ObstacleCell> cells, const std::uint16_t* perm, Range r, const LineFeature& fit) {
  float dev = 0.0f;
  for (std::uint32_t i = r.lo; i < r.hi; ++i) {
    const Point2 p = ObstaclePosition(cells[perm[i]]);
    dev = std::fmax(dev, std::fabs(fit.normal.x * p.x + fit.normal.y * p.y - fit.offset));
  }
  return dev;
}

// Step 3: a straight leaf becomes line `id` (its TLS fit, with endpoints) and owns its cells.
LineFeature LeafLine(Span<ObstacleCell> cells, const std::uint16_t* perm, Range r, const LineFeature& fit,
                     std::uint16_t id) {
  LineFeature l = fit;
  const Point2 d{l.normal.y, -l.normal.x};
  float tmin = 1e30f, tmax = -1e30f;
  for (std::uint32_t i = r.lo; i < r.hi; ++i) {
    const Point2 p = ObstaclePosition(cells[perm[i]]);
    const float t = d.x * (p.x - l.mean.x) + d.y * (p.y - l.mean.y);
    tmin = std::fmin(tmin, t);
    tmax = std::fmax(tmax, t);
    cells[perm[i]].line = id;
  }
  // The extreme cells cover half a cell beyond their centres: the wall ends there (±0.5 cell).
  tmin -= 0.5f;
  tmax += 0.5f;
  l.a = Point2{l.mean.x + tmin * d.x, l.mean.y + tmin * d.y};
  l.b = Point2{l.mean.x + tmax * d.x, l.mean.y + tmax * d.y};
  return l;
}

// Steps 2 and 3 for one component: split until every piece is straight within the tolerance
// (explicit stack, no recursion); pieces long and straight enough become lines from `count` on.
// Returns the new line count.
int SplitComponent(Span<ObstacleCell> cells, std::uint16_t* perm, Range component, Span<LineFeature> lines, int count,
                   const LineExtractorConfig& config, LineExtractionStats* st) {
  Range stack[kSplitStack];
  int top = 0;
  stack[top++] = component;
  while (top > 0) {
    const Range r = stack[--top];
    const LineFeature fit = Moments(cells, perm, r);
    std::uint32_t mid = 0;
    const bool splittable = MaxDeviation(cells, perm, r, fit) > config.split_tolerance_cells && r.hi - r.lo >= 3;
    if (splittable && top + 2 > kSplitStack) st->stack_full = true;
    if (splittable && top + 2 <= kSplitStack && Split(cells, perm, r, fit, &mid)) {
      stack[top++] = Range{r.lo, mid};
      stack[top++] = Range{mid, r.hi};
      continue;
    }
    ++st->leaves;
    if (fit.support < config.min_support || fit.rms > config.max_rms_cells) continue;
    if (count >= static_cast<int>(lines.size())) {
      st->lines_full = true;
      continue;
    }
    lines[static_cast<std::size_t>(count)] = LeafLine(cells, perm, r, fit, static_cast<std::uint16_t>(count));
    ++count;
  }
  return count;
}

// Step 4: merges collinear neighbours that the split separated (thick walls, small gaps) into
// the lower-numbered line; alias[j] = the line j went into (j itself if it survives).
void MergeCollinear(Span<LineFeature> lines, int count, std::uint16_t* alias, const LineExtractorConfig& config,
                    LineExtractionStats* st) {
  for (int i = 0; i < count; ++i) alias[i] = static_cast<std::uint16_t>(i);
  for (int pass = 0; pass < 4; ++pass) {
    bool merged_any = false;
    for (int i = 0; i < count; ++i) {
      if (alias[i] != i) continue;
      LineFeature& into = lines[static_cast<std::size_t>(i)];
      for (int j = i + 1; j < count; ++j) {
        const LineFeature& other = lines[static_cast<std::size_t>(j)];
        if (alias[j] != j || !Mergeable(into, other, config)) continue;
        const LineFeature m = Merged(into, other);
        if (m.rms > config.max_rms_cells) continue;
        into = m;
        alias[j] = static_cast<std::uint16_t>(i);
        ++st->merges;
        merged_any = true;
      }
    }
    if (!merged_any) break;
  }
}

// Step 5: compacts the surviving lines to the front and relabels the cells; returns their count.
// `final_id`: scratch of `count` entries.
int CompactLines(Span<ObstacleCell> cells, Span<LineFeature> lines, int count, const std::uint16_t* alias,
                 std::uint16_t* final_id) {
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    if (alias[i] == i) {
      final_id[i] = static_cast<std::uint16_t>(kept);
      lines[static_cast<std::size_t>(kept++)] = lines[static_cast<std::size_t>(i)];
    }
  }
  for (ObstacleCell& c : cells) {
    if (c.line == kNoLine) continue;
    std::uint16_t root = c.line;
    while (alias[root] != root) root = alias[root];
    c.line = final_id[root];
  }
  return kept;
}

}  // namespace

int ExtractLines(Span<ObstacleCell> cells, const std::uint16_t* cell_at, int w, int h,
                 Span<std::uint16_t> scratch, Span<LineFeature> lines, const LineExtractorConfig& config,
                 LineExtractionStats* stats) {
  DPCR_ASSERT(scratch.size() >= cells.size() + 2 * lines.size() && lines.size() < kVisited);
  LineExtractionStats local;
  LineExtractionStats& st = stats != nullptr ? *stats : local;
  st = LineExtractionStats{};
  std::uint16_t* perm = scratch.data();
  for (ObstacleCell& c : cells) c.line = kNoLine;
  int count = 0;
  std::uint32_t end = 0;
  for (std::uint32_t seed = 0; seed < cells.size(); ++seed) {
    if (cells[seed].line != kNoLine) continue;
    const Range component = CollectComponent(cells, cell_at, w, h, config.link_radius_cells, seed, perm, end);
    end = component.hi;
    ++st.components;
    count = SplitComponent(cells, perm, component, lines, count, config, &st);
  }
  for (ObstacleCell& c : cells) {
    if (c.line == kVisited) c.line = kNoLine;
  }
  // After the cells' permutation, the lines' merge aliases and final ids.
  std::uint16_t* alias = perm + cells.size();
  std::uint16_t* final_id = alias + lines.size();
  MergeCollinear(lines, count, alias, config, &st);
  return CompactLines(cells, lines, count, alias, final_id);
}

}  // namespace dpcr
