#include "host_sim/sim/coverage_planner.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <random>

namespace dpcr::sim {
namespace {

// The configuration-space grid: a cell is free when its centre keeps robot radius + margin.
class FreeGrid {
 public:
  FreeGrid(const WorldRayCaster& caster, const PlannerConfig& config) : caster_(caster), config_(config) {
    double x1, y1;
    caster.world().Bounds(&x0_, &y0_, &x1, &y1);
    nx_ = static_cast<int>(std::ceil((x1 - x0_) / config.grid_m)) + 1;
    ny_ = static_cast<int>(std::ceil((y1 - y0_) / config.grid_m)) + 1;
    free_.resize(static_cast<std::size_t>(nx_ * ny_));
    for (int j = 0; j < ny_; ++j) {
      for (int i = 0; i < nx_; ++i) free_[Index(i, j)] = PointFree(Centre(i, j)) ? 1 : 0;
    }
  }

  double Inflation() const { return config_.robot_radius_m + config_.margin_m; }
  bool PointFree(Vec2 p) const { return caster_.Clearance(p, Inflation() + 0.01) >= Inflation(); }
  // Exact check of a straight leg: samples every 2 cm keep radius + 1 cm, so the whole leg keeps the radius.
  bool LegFree(Vec2 a, Vec2 b) const {
    const double len = Norm(b - a);
    const int n = static_cast<int>(std::ceil(len / 0.02));
    const double need = config_.robot_radius_m + 0.01;
    for (int k = 0; k <= n; ++k) {
      const Vec2 p = a + (n == 0 ? 0.0 : static_cast<double>(k) / n) * (b - a);
      if (caster_.Clearance(p, need + 0.01) < need) return false;
    }
    return true;
  }
  std::size_t Index(int i, int j) const { return static_cast<std::size_t>(j * nx_ + i); }
  Vec2 Centre(int i, int j) const { return Vec2{x0_ + (i + 0.5) * config_.grid_m, y0_ + (j + 0.5) * config_.grid_m}; }
  bool CellFree(int i, int j) const { return i >= 0 && j >= 0 && i < nx_ && j < ny_ && free_[Index(i, j)]; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }

  // Nearest free cell to p that p reaches by a free straight leg; false if none within 0.5 m.
  bool Snap(Vec2 p, int* ci, int* cj) const {
    const int pi = static_cast<int>(std::floor((p.x - x0_) / config_.grid_m));
    const int pj = static_cast<int>(std::floor((p.y - y0_) / config_.grid_m));
    double best = 1e9;
    for (int dj = -10; dj <= 10; ++dj) {
      for (int di = -10; di <= 10; ++di) {
        const int i = pi + di, j = pj + dj;
        if (!CellFree(i, j)) continue;
        const double d = Norm(Centre(i, j) - p);
        if (d < best && LegFree(p, Centre(i, j))) {
          best = d;
          *ci = i;
          *cj = j;
        }
      }
    }
    return best < 1e8;
  }

 private:
  const WorldRayCaster& caster_;
  const PlannerConfig& config_;
  double x0_ = 0.0, y0_ = 0.0;
  int nx_ = 0, ny_ = 0;
  std::vector<unsigned char> free_;
};

// 8-connected A*; appends the smoothed path (excluding `a`, including `b`) to `out`.
// Moves between adjacent free cell centres keep >= inflation - half a cell diagonal (> radius).
bool Connect(const FreeGrid& g, Vec2 a, Vec2 b, std::vector<Vec2>* out) {
  if (g.LegFree(a, b)) {
    out->push_back(b);
    return true;
  }
  int ai = 0, aj = 0, bi = 0, bj = 0;
  if (!g.Snap(a, &ai, &aj) || !g.Snap(b, &bi, &bj)) return false;
  const std::size_t n = static_cast<std::size_t>(g.nx() * g.ny());
  std::vector<float> cost(n, 1e30f);
  std::vector<int> parent(n, -1);
  using Item = std::pair<float, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  const std::size_t start = g.Index(ai, aj), goal = g.Index(bi, bj);
  cost[start] = 0.0f;
  auto h = [&](int i, int j) { return static_cast<float>(std::hypot(i - bi, j - bj)); };
  open.push({h(ai, aj), static_cast<int>(start)});
  bool found = false;
  while (!open.empty()) {
    const auto [f, idx] = open.top();
    open.pop();
    const std::size_t u = static_cast<std::size_t>(idx);
    if (u == goal) {
      found = true;
      break;
    }
    const int i = idx % g.nx(), j = idx / g.nx();
    if (f > cost[u] + h(i, j) + 1e-3f) continue;
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        if ((di == 0 && dj == 0) || !g.CellFree(i + di, j + dj)) continue;
        const std::size_t v = g.Index(i + di, j + dj);
        const float c = cost[u] + (di != 0 && dj != 0 ? 1.41421356f : 1.0f);
        if (c < cost[v]) {
          cost[v] = c;
          parent[v] = idx;
          open.push({c + h(i + di, j + dj), static_cast<int>(v)});
        }
      }
    }
  }
  if (!found) return false;
  std::vector<Vec2> cells;
  for (int v = static_cast<int>(goal); v >= 0; v = parent[static_cast<std::size_t>(v)]) {
    cells.push_back(g.Centre(v % g.nx(), v / g.nx()));
  }
  std::reverse(cells.begin(), cells.end());
  cells.push_back(b);
  // Greedy line-of-sight smoothing; adjacent cells are always kept as a fallback.
  Vec2 cur = a;
  std::size_t k = 0;
  while (k < cells.size()) {
    std::size_t far = k;
    for (std::size_t m = cells.size(); m-- > k + 1;) {
      if (g.LegFree(cur, cells[m])) {
        far = m;
        break;
      }
    }
    out->push_back(cells[far]);
    cur = cells[far];
    k = far + 1;
  }
  return true;
}

// Free pieces of the line from p0 to p1 sampled every 5 cm: [first, last] point pairs.
std::vector<std::pair<Vec2, Vec2>> FreePieces(const FreeGrid& g, Vec2 p0, Vec2 p1, double min_len) {
  std::vector<std::pair<Vec2, Vec2>> pieces;
  const double len = Norm(p1 - p0);
  const int n = std::max(1, static_cast<int>(std::floor(len / 0.05)));
  int run = -1;
  for (int k = 0; k <= n + 1; ++k) {
    const bool free = k <= n && g.PointFree(p0 + (static_cast<double>(k) / n) * (p1 - p0));
    if (free && run < 0) run = k;
    if (!free && run >= 0) {
      const Vec2 a = p0 + (static_cast<double>(run) / n) * (p1 - p0);
      const Vec2 b = p0 + (static_cast<double>(k - 1) / n) * (p1 - p0);
      if (Norm(b - a) >= min_len && g.LegFree(a, b)) pieces.push_back({a, b});
      run = -1;
    }
  }
  return pieces;
}

// How one room is cleaned: which room, its lane axis, the side its lanes start from and the
// direction of its wall-following loop.
struct RoomPass {
  std::size_t room = 0;
  bool flip_axis = false;  // lanes along the shorter axis
  bool from_high = false;  // the first lane on the high side
  bool clockwise = false;  // walls followed clockwise
};

// The rooms in planning order. Variation 0: declared order, canonical passes; otherwise a
// shuffled order with the start room first (a vacuum cleans where it stands, then moves on).
std::vector<RoomPass> PlanRooms(const std::vector<Room>& rooms, Vec2 start, std::uint64_t variation) {
  std::vector<RoomPass> passes(rooms.size());
  for (std::size_t i = 0; i < rooms.size(); ++i) passes[i].room = i;
  if (variation == 0) return passes;
  std::mt19937_64 rng(variation);
  std::shuffle(passes.begin(), passes.end(), rng);
  const auto first = std::find_if(passes.begin(), passes.end(), [&](const RoomPass& p) { return rooms[p.room].Contains(start); });
  if (first != passes.end()) std::rotate(passes.begin(), first, first + 1);
  std::bernoulli_distribution coin(0.5), sometimes(0.3);
  for (RoomPass& p : passes) {
    p.flip_axis = sometimes(rng);
    p.from_high = coin(rng);
    p.clockwise = coin(rng);
  }
  return passes;
}

// Lanes span the free (inflated) part of a room: the bounding box of its free cells, so rooms
// drawn to the outside of thick walls (PGM plans) still get lanes along their walls.
Room FreeExtent(const FreeGrid& g, const Room& declared) {
  Room room{declared.name, 1e18, 1e18, -1e18, -1e18};
  for (int j = 0; j < g.ny(); ++j) {
    for (int i = 0; i < g.nx(); ++i) {
      const Vec2 c = g.Centre(i, j);
      if (!declared.Contains(c) || !g.CellFree(i, j)) continue;
      room = Room{declared.name, std::min(room.xmin, c.x), std::min(room.ymin, c.y), std::max(room.xmax, c.x),
                  std::max(room.ymax, c.y)};
    }
  }
  return room;
}

// The free pieces a room's pass drives, in order: boustrophedon lanes, then the wall loop.
std::vector<std::pair<Vec2, Vec2>> RoomPieces(const FreeGrid& g, const PlannerConfig& config, const Room& room,
                                              const RoomPass& pass) {
  std::vector<std::pair<Vec2, Vec2>> out;
  const bool along_x = (room.xmax - room.xmin >= room.ymax - room.ymin) != pass.flip_axis;
  const double lo = along_x ? room.ymin : room.xmin, hi = along_x ? room.ymax : room.xmax;
  const double a0 = along_x ? room.xmin : room.ymin, a1 = along_x ? room.xmax : room.ymax;
  if (hi < lo || a1 < a0) return out;
  const int lanes = static_cast<int>(std::ceil((hi - lo) / config.lane_spacing_m)) + 1;
  for (int l = 0; l < lanes; ++l) {
    const double offset = std::min(hi - lo, l * config.lane_spacing_m);
    const double c = pass.from_high ? hi - offset : lo + offset;
    const Vec2 p0 = along_x ? Vec2{a0, c} : Vec2{c, a0};
    const Vec2 p1 = along_x ? Vec2{a1, c} : Vec2{c, a1};
    auto pieces = FreePieces(g, p0, p1, config.min_piece_m);
    if (l % 2 == 1) {
      std::reverse(pieces.begin(), pieces.end());
      for (auto& pc : pieces) std::swap(pc.first, pc.second);
    }
    out.insert(out.end(), pieces.begin(), pieces.end());
  }
  if (!config.wall_following) return out;
  const Vec2 corners[4] = {{room.xmin, room.ymin}, {room.xmax, room.ymin}, {room.xmax, room.ymax}, {room.xmin, room.ymax}};
  for (int k = 0; k < 4; ++k) {
    // Counter-clockwise: corner k to k + 1; clockwise: the same sides, walked backwards.
    const int side = pass.clockwise ? 3 - k : k;
    Vec2 from = corners[side], to = corners[(side + 1) % 4];
    if (pass.clockwise) std::swap(from, to);
    const auto pieces = FreePieces(g, from, to, config.min_piece_m);
    out.insert(out.end(), pieces.begin(), pieces.end());
  }
  return out;
}

}  // namespace

bool FindFreePoint(const WorldRayCaster& caster, const PlannerConfig& config, Vec2 near, Vec2* out) {
  const FreeGrid g(caster, config);
  double best = 1e18;
  for (int j = 0; j < g.ny(); ++j) {
    for (int i = 0; i < g.nx(); ++i) {
      const double d = Norm(g.Centre(i, j) - near);
      if (d < best && g.CellFree(i, j)) {
        best = d;
        *out = g.Centre(i, j);
      }
    }
  }
  return best < 1e17;
}

CoveragePlan PlanCoverage(const WorldRayCaster& caster, const PlannerConfig& config, Vec2 start) {
  const FreeGrid g(caster, config);
  CoveragePlan plan;
  int si = 0, sj = 0;
  if (!g.PointFree(start)) {
    if (!g.Snap(start, &si, &sj)) return plan;
    start = g.Centre(si, sj);
  }
  plan.waypoints.push_back(start);
  const auto visit_piece = [&](Vec2 a, Vec2 b) {
    std::vector<Vec2> path;
    if (!Connect(g, plan.waypoints.back(), a, &path)) {
      ++plan.skipped_pieces;
      return;
    }
    plan.waypoints.insert(plan.waypoints.end(), path.begin(), path.end());
    plan.waypoints.push_back(b);
    ++plan.lane_pieces;
  };
  for (const RoomPass& pass : PlanRooms(caster.world().rooms, start, config.variation)) {
    for (const auto& [a, b] : RoomPieces(g, config, FreeExtent(g, caster.world().rooms[pass.room]), pass)) visit_piece(a, b);
  }
  // Close the tour so the plan can restart.
  std::vector<Vec2> back;
  if (plan.waypoints.size() > 1 && Connect(g, plan.waypoints.back(), plan.waypoints.front(), &back)) {
    plan.waypoints.insert(plan.waypoints.end(), back.begin(), back.end());
  }
  return plan;
}

}  // namespace dpcr::sim
