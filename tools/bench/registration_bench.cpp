#include "tools/bench/registration_bench.hpp"

#include <valgrind/callgrind.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "core/registration/classic_plicp.hpp"
#include "core/registration/plicp.hpp"
#include "core/grid/ray_caster.hpp"
#include "core/registration/registration_reference.hpp"
#include "host_sim/carmen/carmen_reader.hpp"
#include "tools/bench/figure.hpp"
#include "tools/bench/scenes.hpp"

namespace dpcr_bench {
namespace {

using dpcr::Point2;
using dpcr::Pose2;
using Reference = dpcr::RegistrationReferenceStorage<256, 256, 4096, 512>;

constexpr float kDeg = dpcr::kPi / 180.0f;
constexpr float kSuccessM = 0.02f;
constexpr float kSuccessRad = 0.5f * kDeg;

enum class Method { kImproved, kClassic };
const char* Name(Method m) { return m == Method::kImproved ? "improved" : "classic"; }

dpcr::RegistrationResult Register(Method m, const dpcr::RegistrationReference& ref, const std::vector<Point2>& target,
                                  Pose2 initial) {
  const dpcr::Span<const Point2> span(target.data(), target.size());
  const dpcr::PlicpConfig config;
  return m == Method::kImproved ? dpcr::RegisterImproved(ref, span, initial, nullptr, config)
                                : dpcr::RegisterClassic(ref, span, initial, nullptr, config);
}

// A submap-like grid (256 x 256 cells at 5 cm, centred on `centre`) filled by ray casting.
struct Submap {
  std::unique_ptr<dpcr::TilePoolStorage<64>> pool = std::make_unique<dpcr::TilePoolStorage<64>>();
  std::unique_ptr<dpcr::TiledGridStorage<8, 8>> grid = std::make_unique<dpcr::TiledGridStorage<8, 8>>(pool.get());
  std::uint32_t stamp = 0;
  explicit Submap(Point2 centre) {
    const auto tile = [](float v) { return static_cast<std::int32_t>(std::floor(v / (0.05f * dpcr::kTileSide))) - 4; };
    grid->Reset(dpcr::CellIndex{tile(centre.x), tile(centre.y)});
  }
  void Insert(const std::vector<Point2>& scan, Pose2 pose) {
    std::vector<Point2> world;
    for (const Point2& p : scan) world.push_back(pose.Apply(p));
    std::vector<dpcr::CellIndex> scratch(world.size() + 1);
    (void)dpcr::InsertRays(*grid, Point2{pose.x, pose.y}, dpcr::Span<const Point2>(world.data(), world.size()),
                           dpcr::Span<const Point2>(), dpcr::GridConfig{}, ++stamp,
                           dpcr::Span<dpcr::CellIndex>(scratch.data(), scratch.size()));
  }
};

struct Run {
  bool success;       // within 2 cm and 0.5 deg of the ground truth
  bool success_self;  // ... of the same method's result from the unperturbed start (basin)
  int bin;  // 0 small (<= 0.2 m and <= 8 deg), 2 large (> 0.35 m or > 14 deg), 1 otherwise
  int iterations;
  bool accepted;
  bool at_cap;  // stopped by the iteration cap
  double micros;
  double unperturbed_error_m;  // the method's bias: its unperturbed result vs the ground truth
};

struct Perturbation {
  float dx, dy, dth;
  int bin;
};

std::vector<Perturbation> Perturbations(int n, std::mt19937* rng) {
  std::uniform_real_distribution<float> trans(0.05f, 0.5f), dir(-dpcr::kPi, dpcr::kPi), rot(2.0f * kDeg, 20.0f * kDeg);
  std::vector<Perturbation> out;
  for (int i = 0; i < n; ++i) {
    const float t = trans(*rng), d = dir(*rng);
    const float r = rot(*rng) * ((*rng)() % 2 == 0 ? 1.0f : -1.0f);
    const int bin = (t <= 0.2f && std::fabs(r) <= 8.0f * kDeg) ? 0 : ((t > 0.35f || std::fabs(r) > 14.0f * kDeg) ? 2 : 1);
    out.push_back({t * std::cos(d), t * std::sin(d), r, bin});
  }
  return out;
}

using Table = std::map<std::pair<std::string, std::string>, std::vector<Run>>;

void RunCase(const std::string& dataset, const dpcr::RegistrationReference& ref, const std::vector<Point2>& target,
             const Pose2 truth[2], const std::vector<Perturbation>& perturbations, Table* table) {
  for (Method m : {Method::kImproved, Method::kClassic}) {
    const Pose2 t = truth[m == Method::kImproved ? 0 : 1];
    const Pose2 self = Register(m, ref, target, t).pose;
    const auto near = [](Pose2 a, Pose2 b) {
      return std::hypot(a.x - b.x, a.y - b.y) < kSuccessM && std::fabs(dpcr::NormalizeAngle(a.theta - b.theta)) < kSuccessRad;
    };
    for (const Perturbation& p : perturbations) {
      const Pose2 init{t.x + p.dx, t.y + p.dy, dpcr::NormalizeAngle(t.theta + p.dth)};
      const auto start = std::chrono::steady_clock::now();
      const auto r = Register(m, ref, target, init);
      const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
      (*table)[{dataset, Name(m)}].push_back({near(r.pose, t), near(r.pose, self), p.bin, r.iterations,
                                              r.verdict == dpcr::Status::kOk,
                                              r.iterations >= dpcr::PlicpConfig{}.max_iterations, us,
                                              static_cast<double>(std::hypot(self.x - t.x, self.y - t.y))});
    }
  }
}

struct SimCase {
  std::string world;
  std::unique_ptr<Reference> ref;
  std::vector<Point2> target;
  Pose2 truth;
  double build_us = 0.0;
  dpcr::ReferenceBuildStats stats;
};

// Scan k of a world's path against the submap of scans k-10 .. k-1 at their true poses.
// `callgrind_build`: collect instructions around the reference build only (and dump them).
SimCase MakeSimCase(const Scene& w, std::size_t k, unsigned seed, bool callgrind_build = false) {
  SimCase c{w.name(), std::make_unique<Reference>(), {}, w.path[k], 0.0, {}};
  Submap submap(Point2{c.truth.x, c.truth.y});
  for (std::size_t j = k - 10; j < k; ++j) {
    submap.Insert(SimulateScan(w, w.path[j], 450, 0.02f, seed * 1000u + static_cast<unsigned>(j), 8.0f), w.path[j]);
  }
  const auto start = std::chrono::steady_clock::now();
  if (callgrind_build) CALLGRIND_TOGGLE_COLLECT;
  (void)c.ref->Build(*submap.grid, submap.grid->box(), dpcr::ReferenceConfig{}, &c.stats);
  if (callgrind_build) {
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_DUMP_STATS;
  }
  c.build_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  c.target = SimulateScan(w, c.truth, 450, 0.02f, seed * 7919u + static_cast<unsigned>(k), 8.0f);
  return c;
}

std::vector<std::size_t> SimIndices(const Scene& w, int n) {
  std::vector<std::size_t> out;
  if (n < 2) return {10};
  for (int i = 0; i < n; ++i) out.push_back(10 + (w.path.size() - 11) * static_cast<std::size_t>(i) / static_cast<std::size_t>(n - 1));
  return out;
}

// Figure 1: one hall case from a large perturbation (0.4 m, 15 deg), both results drawn.
void WriteFigure(const std::string& path, unsigned seed) {
  const auto scenes = MakeBuiltinScenes();
  const Scene& w = *scenes[0];  // hall
  const std::size_t k = w.path.size() / 3;
  const Pose2 truth = w.path[k];
  Submap submap(Point2{truth.x, truth.y});
  for (std::size_t j = k - 10; j < k; ++j) {
    submap.Insert(SimulateScan(w, w.path[j], 450, 0.02f, seed * 1000u + static_cast<unsigned>(j), 8.0f), w.path[j]);
  }
  auto ref = std::make_unique<Reference>();
  (void)ref->Build(*submap.grid, submap.grid->box(), dpcr::ReferenceConfig{}, nullptr);
  const auto scan = SimulateScan(w, truth, 450, 0.02f, seed * 7919u + static_cast<unsigned>(k), 8.0f);
  const Pose2 init{truth.x + 0.28f, truth.y - 0.28f, truth.theta + 15.0f * kDeg};
  const auto a = Register(Method::kImproved, *ref, scan, init);
  const auto b = Register(Method::kClassic, *ref, scan, init);
  std::fprintf(stderr, "figure: truth (%.3f %.3f %.2f deg) improved (%.3f %.3f %.2f deg, %d it.) classic (%.3f %.3f %.2f deg, %d it.)\n",
               static_cast<double>(truth.x), static_cast<double>(truth.y), static_cast<double>(truth.theta / kDeg),
               static_cast<double>(a.pose.x), static_cast<double>(a.pose.y), static_cast<double>(a.pose.theta / kDeg),
               a.iterations, static_cast<double>(b.pose.x), static_cast<double>(b.pose.y),
               static_cast<double>(b.pose.theta / kDeg), b.iterations);
  if (!WriteRegistrationFigure(path, *submap.grid, *ref, scan, init, a.pose, b.pose)) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
  }
}

struct ClfScan {
  std::vector<Point2> points;  // sensor frame
  Pose2 odom;
};

// The laser records of a CARMEN log, through host_sim's reader (empty when the file is missing).
std::vector<ClfScan> ReadClf(const std::string& path) {
  std::vector<ClfScan> scans;
  std::ifstream in(path);
  if (!in) return scans;
  dpcr::carmen::CarmenReader reader(in);
  dpcr::carmen::Record record;
  while (reader.Next(&record)) {
    if (record.kind != dpcr::carmen::Record::Kind::kLaser) continue;
    const dpcr::carmen::LaserRecord& laser = record.laser;
    ClfScan s;
    for (std::size_t i = 0; i < laser.ranges_m.size(); ++i) {
      const float r = laser.ranges_m[i];
      const float a = laser.angle_min_rad + static_cast<float>(i) * laser.angle_increment_rad;
      if (r > 0.05f && r < 20.0f) s.points.push_back(Point2{r * std::cos(a), r * std::sin(a)});
    }
    s.odom = laser.odom_pose;
    scans.push_back(std::move(s));
  }
  return scans;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

void PrintTable(const Table& table) {
  std::printf("| dataset | method | runs | success vs truth | success vs own unperturbed | small | medium | large | "
              "median it. | mean it. | at cap | accepted | false accepts | unperturbed error (median) | median µs |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& [key, runs] : table) {
    int succ = 0, self = 0, cap = 0, acc = 0, false_acc = 0, bin_n[3] = {}, bin_s[3] = {};
    std::vector<double> its, us, bias;
    for (const Run& r : runs) {
      succ += r.success;
      self += r.success_self;
      acc += r.accepted;
      cap += r.at_cap;
      false_acc += r.accepted && !r.success;
      ++bin_n[r.bin];
      bin_s[r.bin] += r.success_self;
      if (r.success_self) its.push_back(r.iterations);
      us.push_back(r.micros);
      bias.push_back(r.unperturbed_error_m);
    }
    double mean_it = 0.0;
    for (double i : its) mean_it += i / static_cast<double>(its.size());
    const auto pct = [](int a, int b) { return b > 0 ? 100.0 * a / b : 0.0; };
    const int n = static_cast<int>(runs.size());
    std::printf("| %s | %s | %d | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.0f | %.1f | %.1f %% | %.1f %% | %.1f %% | %.1f cm | %.0f |\n",
                key.first.c_str(), key.second.c_str(), n, pct(succ, n), pct(self, n), pct(bin_s[0], bin_n[0]),
                pct(bin_s[1], bin_n[1]), pct(bin_s[2], bin_n[2]), Median(its), mean_it, pct(cap, n), pct(acc, n),
                pct(false_acc, n), 100.0 * Median(bias), Median(us));
  }
}

// A 1.6 m corridor longer than the lidar range: along it, no scan can tell where the robot is.
// Odometry (the prior, info 20 per axis) says init = truth + perturbation; the registration must
// correct across the corridor and the heading, keep the prior's position along it, and flag the
// match as degenerate.
void RunCorridor(const RegistrationBenchOptions& o) {
  dpcr::sim::World corridor;
  corridor.name = "corridor";
  dpcr::sim::AddWall(&corridor, -30.0, 0.0, 30.0, 0.0);
  dpcr::sim::AddWall(&corridor, -30.0, 1.6, 30.0, 1.6);
  std::vector<Pose2> path;
  for (float x = -3.0f; x < 3.0f; x += 0.1f) path.push_back(Pose2{x, 0.8f, 0.0f});
  const Scene w(std::move(corridor), std::move(path));
  std::printf("\n| corridor | runs | flagged degenerate | accepted | median slide along (m) | "
              "across + heading corrected (2 cm, 0.5 deg) |\n|---|---|---|---|---|---|\n");
  for (int with_prior = 0; with_prior < 2; ++with_prior) {
    int runs = 0, degenerate = 0, accepted = 0, corrected = 0;
    std::vector<double> slide;
    std::mt19937 local(o.seed);
    for (std::size_t k = 10; k < w.path.size(); k += 5) {
      const SimCase c = MakeSimCase(w, k, o.seed);
      std::uniform_real_distribution<float> dy(-0.15f, 0.15f), dx(-0.4f, 0.4f), dth(-5.0f * kDeg, 5.0f * kDeg);
      for (int i = 0; i < o.perturbations; ++i) {
        const Pose2 init{c.truth.x + dx(local), c.truth.y + dy(local), c.truth.theta + dth(local)};
        const dpcr::PosePrior prior{init, 20.0f, 20.0f};
        const auto r = dpcr::RegisterImproved(*c.ref, dpcr::Span<const Point2>(c.target.data(), c.target.size()), init,
                                              with_prior ? &prior : nullptr, dpcr::PlicpConfig{});
        ++runs;
        degenerate += r.degenerate;
        accepted += r.verdict == dpcr::Status::kOk;
        slide.push_back(std::fabs(static_cast<double>(r.pose.x - init.x)));
        corrected += std::fabs(r.pose.y - c.truth.y) < kSuccessM &&
                     std::fabs(dpcr::NormalizeAngle(r.pose.theta - c.truth.theta)) < kSuccessRad;
      }
    }
    std::printf("| improved, prior %s | %d | %.1f %% | %.1f %% | %.3f | %.1f %% |\n", with_prior ? "on" : "off", runs,
                100.0 * degenerate / runs, 100.0 * accepted / runs, Median(slide), 100.0 * corrected / runs);
  }
}

// Spread over all worlds: every stride-th run of the sim part of the table, same seeds.
int RunCallgrind(const RegistrationBenchOptions& o) {
  const Method m = o.method == "classic" ? Method::kClassic : Method::kImproved;
  std::mt19937 rng(o.seed);
  const std::vector<std::unique_ptr<Scene>> scenes = MakeBuiltinScenes();
  if (o.method == "build") {  // reference builds (lines + table) instead of registrations
    int built = 0;
    for (const auto& w : scenes) {
      for (std::size_t k : SimIndices(*w, o.sim_poses_per_world)) {
        if (built++ == o.callgrind_count) return 0;
        const SimCase c = MakeSimCase(*w, k, o.seed, true);
        std::printf("%d %s cells %d lines %d\n", built, c.world.c_str(), c.stats.obstacle_cells, c.stats.lines);
      }
    }
    return 0;
  }
  const int total = static_cast<int>(scenes.size()) * o.sim_poses_per_world * o.perturbations;
  const int stride = std::max(1, total / o.callgrind_count);
  int index = 0, done = 0;
  for (const auto& w : scenes) {
    for (std::size_t k : SimIndices(*w, o.sim_poses_per_world)) {
      const SimCase c = MakeSimCase(*w, k, o.seed);
      for (const Perturbation& p : Perturbations(o.perturbations, &rng)) {
        if (index++ % stride != 0 || done == o.callgrind_count) continue;
        const Pose2 init{c.truth.x + p.dx, c.truth.y + p.dy, dpcr::NormalizeAngle(c.truth.theta + p.dth)};
        CALLGRIND_TOGGLE_COLLECT;
        const auto r = Register(m, *c.ref, c.target, init);
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_DUMP_STATS;
        std::printf("%d %s points %zu iterations %d\n", done, c.world.c_str(), c.target.size(), r.iterations);
        ++done;
      }
    }
  }
  return 0;
}

}  // namespace

int RunRegistrationBench(const RegistrationBenchOptions& o) {
  if (o.callgrind_count > 0) return RunCallgrind(o);
  if (!o.figure_path.empty()) WriteFigure(o.figure_path, o.seed);
  Table table;
  std::mt19937 rng(o.seed);
  std::size_t points = 0, cases = 0;
  std::vector<double> build_us, cells, lines;
  for (const auto& w : MakeBuiltinScenes()) {
    for (std::size_t k : SimIndices(*w, o.sim_poses_per_world)) {
      const SimCase c = MakeSimCase(*w, k, o.seed);
      const Pose2 truth[2] = {c.truth, c.truth};
      RunCase("sim " + w->name(), *c.ref, c.target, truth, Perturbations(o.perturbations, &rng), &table);
      points += c.target.size();
      build_us.push_back(c.build_us);
      cells.push_back(c.stats.obstacle_cells);
      lines.push_back(c.stats.lines);
      ++cases;
    }
  }
  std::fprintf(stderr, "sim: %zu scan->submap cases, %.0f points per scan; reference build median %.0f us, %.0f obstacle cells, %.0f lines\n",
               cases, static_cast<double>(points) / static_cast<double>(cases), Median(build_us), Median(cells), Median(lines));

  const std::vector<ClfScan> scans = ReadClf(o.clf_path);
  int kept = 0, tried = 0;
  if (scans.size() > 20) {
    const std::size_t step = (scans.size() - 20) / static_cast<std::size_t>(o.intel_pairs);
    for (std::size_t i = 10; i < scans.size() && tried < o.intel_pairs; i += step, ++tried) {
      // Reference: the previous scan's grid in its own frame; target: scan i; the ground truth is
      // each method's converged result from the odometry guess, kept where both agree and accept.
      Submap submap(Point2{0.0f, 0.0f});
      submap.Insert(scans[i - 1].points, Pose2{});
      auto ref = std::make_unique<Reference>();
      (void)ref->Build(*submap.grid, submap.grid->box(), dpcr::ReferenceConfig{}, nullptr);
      const Pose2 odom = dpcr::Between(scans[i - 1].odom, scans[i].odom);
      const auto a = Register(Method::kImproved, *ref, scans[i].points, odom);
      const auto b = Register(Method::kClassic, *ref, scans[i].points, odom);
      if (a.verdict != dpcr::Status::kOk || b.verdict != dpcr::Status::kOk) continue;
      if (std::hypot(a.pose.x - b.pose.x, a.pose.y - b.pose.y) > kSuccessM ||
          std::fabs(dpcr::NormalizeAngle(a.pose.theta - b.pose.theta)) > kSuccessRad) {
        continue;
      }
      const Pose2 truth[2] = {a.pose, b.pose};
      RunCase("intel.clf pairs", *ref, scans[i].points, truth, Perturbations(o.perturbations, &rng), &table);
      ++kept;
    }
  }
  std::fprintf(stderr, "intel: %zu scans read, %d of %d pairs kept (both methods accept and agree unperturbed)\n",
               scans.size(), kept, tried);
  PrintTable(table);
  RunCorridor(o);
  return 0;
}

}  // namespace dpcr_bench
