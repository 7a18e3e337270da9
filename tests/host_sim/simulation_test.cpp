#include "host_sim/sim/simulation.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace dpcr::sim;

namespace {

struct RunResult {
  std::vector<Pose2d> truth;  // at every odometry sample
  Pose2d last_odometry;
  Pose2d start;  // the run's start pose in the world (the odometry frame's origin)
  double min_clearance_m = 1e9;
  double seconds = 0.0;
  long scans = 0;
};

RunResult Run(const World& world, const SimConfig& config) {
  RunResult r;
  const WorldRayCaster caster(world);
  const auto t0 = std::chrono::steady_clock::now();
  Simulation sim(world, config);
  r.start = sim.start_pose();
  SimEvent ev;
  while (sim.Step(&ev)) {
    if (ev.type == SimEventType::kScan) {
      ++r.scans;
    } else {
      r.truth.push_back(ev.truth);
      const dpcr::Pose2& o = ev.odometry.pose;
      r.last_odometry = Pose2d{static_cast<double>(o.x), static_cast<double>(o.y), static_cast<double>(o.theta)};
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const Pose2d& p : r.truth) r.min_clearance_m = std::min(r.min_clearance_m, caster.Clearance({p.x, p.y}, 1.0));
  return r;
}

// Ground truth relative to the start pose: the odometry frame's origin.
Pose2d RelativeToStart(const Pose2d& start, const Pose2d& p) {
  const double c = std::cos(start.theta), s = std::sin(start.theta);
  const double dx = p.x - start.x, dy = p.y - start.y;
  return Pose2d{c * dx + s * dy, -s * dx + c * dy, WrapAngle(p.theta - start.theta)};
}

// Share of the free floor inside rooms (reachable from the start, 5 cm cells) that came within
// two robot radii of the robot's centre.
double Coverage(const World& w, const std::vector<Pose2d>& path, double radius_m) {
  const WorldRayCaster caster(w);
  const double res = 0.05;
  double x0, y0, x1, y1;
  w.Bounds(&x0, &y0, &x1, &y1);
  const int nx = static_cast<int>((x1 - x0) / res) + 1, ny = static_cast<int>((y1 - y0) / res) + 1;
  auto centre = [&](int i, int j) { return Vec2{x0 + (i + 0.5) * res, y0 + (j + 0.5) * res}; };
  std::vector<char> open(static_cast<std::size_t>(nx * ny)), reached(open.size()), seen(open.size());
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) open[static_cast<std::size_t>(j * nx + i)] = caster.Clearance(centre(i, j), 0.03) >= 0.025;
  }
  std::vector<int> stack{static_cast<int>((w.start.y - y0) / res) * nx + static_cast<int>((w.start.x - x0) / res)};
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    const std::size_t u = static_cast<std::size_t>(k);
    if (reached[u] || !open[u]) continue;
    reached[u] = 1;
    const int i = k % nx, j = k / nx;
    if (i > 0) stack.push_back(k - 1);
    if (i + 1 < nx) stack.push_back(k + 1);
    if (j > 0) stack.push_back(k - nx);
    if (j + 1 < ny) stack.push_back(k + nx);
  }
  const int reach = static_cast<int>(std::ceil(2.0 * radius_m / res));
  for (std::size_t s = 0; s < path.size(); s += 5) {
    const int pi = static_cast<int>((path[s].x - x0) / res), pj = static_cast<int>((path[s].y - y0) / res);
    for (int j = std::max(0, pj - reach); j <= std::min(ny - 1, pj + reach); ++j) {
      for (int i = std::max(0, pi - reach); i <= std::min(nx - 1, pi + reach); ++i) {
        const Vec2 c = centre(i, j);
        if (std::hypot(c.x - path[s].x, c.y - path[s].y) <= 2.0 * radius_m) seen[static_cast<std::size_t>(j * nx + i)] = 1;
      }
    }
  }
  long free_cells = 0, covered = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j * nx + i);
      bool in_room = false;
      for (const Room& r : w.rooms) in_room = in_room || r.Contains(centre(i, j));
      if (!in_room || !reached[k]) continue;
      ++free_cells;
      covered += seen[k];
    }
  }
  return free_cells > 0 ? static_cast<double>(covered) / static_cast<double>(free_cells) : 0.0;
}

}  // namespace

TEST_CASE("Same seed gives the same stream, another seed a different one", "[sim]") {
  const World w = LoadBuiltinWorld("office");
  SimConfig config;
  config.duration_min = 0.5;
  auto collect = [&](std::uint64_t seed) {
    config.seed = seed;
    Simulation sim(w, config);
    std::vector<float> values;
    SimEvent ev;
    while (sim.Step(&ev)) {
      values.push_back(static_cast<float>(ev.time_us));
      if (ev.type == SimEventType::kScan) {
        for (const dpcr::Beam& b : ev.scan.beams) values.push_back(b.range_m);
      } else {
        values.push_back(ev.odometry.pose.x);
        values.push_back(ev.odometry.gyro_yaw_rate);
        values.push_back(static_cast<float>(ev.ticks.left));
      }
    }
    return values;
  };
  const std::vector<float> a = collect(1), b = collect(1), c = collect(2);
  CHECK(a.size() > 300 * 450);
  CHECK(a == b);
  CHECK(a != c);
}

TEST_CASE("Seeds vary the cleaning plan, a fixed plan is the world's own", "[sim]") {
  const World w = LoadBuiltinWorld("apartment");
  SimConfig config;
  config.duration_min = 0.1;
  const auto plan = [&](std::uint64_t seed, bool vary) {
    config.seed = seed;
    config.vary_plan = vary;
    const Simulation sim(w, config);
    std::vector<double> flat;  // the waypoints' coordinates, comparable with ==
    for (const Vec2& p : sim.plan().waypoints) flat.insert(flat.end(), {p.x, p.y});
    return std::make_pair(sim.start_pose(), flat);
  };
  const auto [start_a, plan_a] = plan(1, true);
  const auto [start_b, plan_b] = plan(2, true);
  const auto [start_a2, plan_a2] = plan(1, true);
  // The same seed, the same plan; another seed, another start and another route.
  CHECK(plan_a == plan_a2);
  CHECK(std::hypot(start_a.x - start_b.x, start_a.y - start_b.y) > 0.1);
  CHECK(plan_a != plan_b);
  // Fixed: every seed starts at the world's start pose and drives the canonical plan.
  const auto [fixed_start1, fixed_plan1] = plan(1, false);
  const auto [fixed_start2, fixed_plan2] = plan(2, false);
  CHECK(fixed_start1.x == w.start.x);
  CHECK(fixed_start1.theta == w.start.theta);
  CHECK(fixed_plan1 == fixed_plan2);
  // A varied plan still covers every room: each room holds waypoints of it.
  for (const Room& room : w.rooms) {
    INFO(room.name);
    bool visited = false;
    for (std::size_t i = 0; i + 1 < plan_b.size(); i += 2) visited = visited || room.Contains(Vec2{plan_b[i], plan_b[i + 1]});
    CHECK(visited);
  }
}

TEST_CASE("Events are time ordered with LD06-like scans", "[sim]") {
  SimConfig config;
  config.duration_min = 0.2;
  Simulation sim(LoadBuiltinWorld("hall"), config);
  SimEvent ev;
  std::int64_t last = -1;
  int scans = 0, odometry = 0;
  while (sim.Step(&ev)) {
    REQUIRE(ev.time_us >= last);
    last = ev.time_us;
    if (ev.type == SimEventType::kOdometry) {
      REQUIRE(ev.odometry.stamp_us == ev.time_us);
      REQUIRE(ev.ticks.stamp_us == ev.time_us);
      ++odometry;
      continue;
    }
    ++scans;
    REQUIRE(ev.scan.beams.size() == 450);
    REQUIRE(ev.scan.stamp_us == 100000 * (scans - 1));
    CHECK(ev.scan.beams[0].offset_us == 0);
    CHECK(ev.scan.beams.back().offset_us > 99000);
    CHECK(ev.scan.beams.back().offset_us < 100000);
    for (const dpcr::Beam& b : ev.scan.beams) REQUIRE((b.range_m == 0.0f || (b.range_m > 0.02f && b.range_m <= 12.0f)));
  }
  CHECK(scans == 120);
  CHECK(odometry == 1201);
}

TEST_CASE("Each beam is cast from the pose at its own time", "[sim]") {
  const World w = LoadBuiltinWorld("apartment");
  SimConfig config;
  config.duration_min = 1.0;
  config.lidar.noise_base_m = 0.0;
  config.lidar.noise_fraction = 0.0;
  config.lidar.dropouts = false;
  config.lidar.mount = Pose2d{0.05, 0.0, 0.3};
  const WorldRayCaster caster(w);
  Simulation sim(w, config);
  SimEvent ev;
  int moving_scans_checked = 0;
  Pose2d previous;
  while (sim.Step(&ev) && moving_scans_checked < 20) {
    if (ev.type != SimEventType::kScan) continue;
    const Pose2d s = ev.sensor_truth;
    const Pose2d expected_sensor = ev.truth * config.lidar.mount;
    REQUIRE(s.x == Approx(expected_sensor.x));
    // Beam 0 is taken at the stamp: exactly the cast from the stamp's sensor pose.
    const RayHit first = caster.Cast({s.x, s.y}, s.theta + static_cast<double>(ev.scan.beams[0].angle_rad), 12.0);
    REQUIRE(static_cast<double>(ev.scan.beams[0].range_m) == Approx(first.range_m).margin(1e-4));
    const double moved = std::hypot(ev.truth.x - previous.x, ev.truth.y - previous.y) +
                         std::fabs(WrapAngle(ev.truth.theta - previous.theta));
    previous = ev.truth;
    if (moved < 0.02) continue;
    // While moving, later beams disagree with a cast from the stamp pose: the scan is distorted.
    int differing = 0;
    for (const dpcr::Beam& b : ev.scan.beams) {
      const RayHit h = caster.Cast({s.x, s.y}, s.theta + static_cast<double>(b.angle_rad), 12.0);
      differing += std::fabs(h.range_m - static_cast<double>(b.range_m)) > 0.005 ? 1 : 0;
    }
    CHECK(differing > 100);
    ++moving_scans_checked;
  }
  CHECK(moving_scans_checked == 20);
}

TEST_CASE("Lidar range noise and dropouts follow the model", "[sim]") {
  World w;
  const int black = w.SetMaterial("black", 0.1);
  AddWall(&w, 5, -5, 5, 5);
  AddWall(&w, -5, -5, -5, 5, black);
  const WorldRayCaster caster(w);
  LidarConfig config;
  std::mt19937_64 rng(3);
  double sum = 0.0, sum2 = 0.0;
  int black_returns = 0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const double r = SimulateBeam(caster, config, Pose2d{}, 0.0, &rng);
    sum += r;
    sum2 += r * r;
    black_returns += SimulateBeam(caster, config, Pose2d{}, kPiD, &rng) > 0.0f ? 1 : 0;
  }
  const double mean = sum / n, sigma = std::sqrt(sum2 / n - mean * mean);
  CHECK(mean == Approx(5.0).margin(0.002));
  CHECK(sigma == Approx(0.01 + 0.005 * 5.0).epsilon(0.05));
  CHECK(static_cast<double>(black_returns) / n == Approx(0.1).margin(0.01));
  config.max_range_m = 4.0;
  CHECK(SimulateBeam(caster, config, Pose2d{}, 0.0, &rng) == 0.0f);
}

TEST_CASE("Odometry without errors follows ground truth, with errors it drifts", "[sim]") {
  const World w = LoadBuiltinWorld("apartment");
  SimConfig config;
  config.duration_min = 5.0;
  config.odometry.systematic_error = false;
  config.odometry.slips_per_minute = 0.0;
  RunResult exact = Run(w, config);
  const Pose2d truth = RelativeToStart(exact.start, exact.truth.back());
  const double exact_error = std::hypot(truth.x - exact.last_odometry.x, truth.y - exact.last_odometry.y);
  CHECK(exact_error < 0.02);
  CHECK(std::fabs(WrapAngle(truth.theta - exact.last_odometry.theta)) < 0.005);

  config.odometry.systematic_error = true;
  config.odometry.slips_per_minute = 0.5;
  RunResult drifting = Run(w, config);
  const double drift = std::hypot(truth.x - drifting.last_odometry.x, truth.y - drifting.last_odometry.y);
  std::printf("odometry after 5 min: exact %.4f m, with errors %.3f m\n", exact_error, drift);
  CHECK(drift > 0.2);
}

TEST_CASE("Simulation rejects an unusable lidar config", "[sim]") {
  SimConfig config;
  config.lidar.beams_per_revolution = 100000;
  CHECK_THROWS_AS(Simulation(LoadBuiltinWorld("office"), config), WorldError);
}

TEST_CASE("Built-in worlds: 35-minute runs never collide and cover the rooms", "[sim][slow]") {
  for (const std::string& name : BuiltinWorldNames()) {
    const World w = LoadBuiltinWorld(name);
    SimConfig config;
    config.duration_min = 35.0;
    const RunResult r = Run(w, config);
    const double coverage = Coverage(w, r.truth, config.planner.robot_radius_m);
    std::printf("%s: 35 min simulated in %.2f s (%ld scans), min clearance %.3f m, coverage %.1f %%\n", name.c_str(),
                r.seconds, r.scans, r.min_clearance_m, 100.0 * coverage);
    INFO(name);
    CHECK(r.scans == 21000);
    CHECK(r.min_clearance_m >= config.planner.robot_radius_m);
    CHECK(coverage >= 0.70);
  }
}

TEST_CASE("A PGM floor plan without a start pose can be simulated", "[sim]") {
  // 3 m x 2 m room at 10 cm per pixel: a one-pixel dark frame.
  const int w = 30, h = 20;
  std::string pgm = "P5 " + std::to_string(w) + " " + std::to_string(h) + " 255\n";
  for (int row = 0; row < h; ++row) {
    for (int col = 0; col < w; ++col) pgm.push_back(row == 0 || col == 0 || row == h - 1 || col == w - 1 ? '\0' : '\xff');
  }
  const World world = ParsePgmWorld(pgm, "frame.pgm", 0.1, Vec2{-1.0, -1.0});
  SimConfig config;
  config.duration_min = 4.0;
  const RunResult r = Run(world, config);
  CHECK(r.scans == 2400);
  CHECK(r.min_clearance_m >= config.planner.robot_radius_m);
  Pose2d lo{1e9, 1e9, 0}, hi{-1e9, -1e9, 0};
  for (const Pose2d& p : r.truth) {
    lo = Pose2d{std::min(lo.x, p.x), std::min(lo.y, p.y), 0};
    hi = Pose2d{std::max(hi.x, p.x), std::max(hi.y, p.y), 0};
  }
  CHECK(hi.x - lo.x > 2.0);  // it covers the room, not just sits at the start
  CHECK(hi.y - lo.y > 1.2);
}

TEST_CASE("In-place spins: full turns on the spot at 120 deg/s, flagged on their scans", "[sim]") {
  SimConfig config;
  config.duration_min = 2.0;
  config.motion.spin_every_waypoints = 2;
  Simulation sim(LoadBuiltinWorld("apartment"), config);
  SimEvent ev;
  Pose2d last;
  bool have_last = false;
  int spinning_scans = 0;
  double fastest = 0.0, spin_travel = 0.0;
  while (sim.Step(&ev)) {
    if (ev.type != SimEventType::kScan) continue;
    if (have_last && ev.spinning) {
      const double turn = std::fabs(WrapAngle(ev.truth.theta - last.theta));
      fastest = std::max(fastest, turn / 0.1);
      // On the spot (a revolution that began as a drive ended decelerated within millimetres).
      REQUIRE(std::hypot(ev.truth.x - last.x, ev.truth.y - last.y) < 0.01);
      spin_travel += turn;
      ++spinning_scans;
    }
    last = ev.truth;
    have_last = true;
  }
  CHECK(spinning_scans > 30);
  CHECK(fastest == Approx(config.motion.spin_yaw_rate_rps).epsilon(0.01));
  CHECK(spin_travel > 4.0 * dpcr::sim::kPiD);  // at least two full turns
  // Without spins, no scan says spinning.
  config.motion.spin_every_waypoints = 0;
  Simulation plain(LoadBuiltinWorld("apartment"), config);
  while (plain.Step(&ev)) REQUIRE(!(ev.type == SimEventType::kScan && ev.spinning));
}

TEST_CASE("A wandering lidar motor: revolution rates vary within their bounds", "[sim]") {
  SimConfig config;
  config.duration_min = 1.0;
  config.lidar = Xv11LidarConfig();
  config.lidar.rate_min_hz = 3.5;
  config.lidar.rate_step_hz = 0.2;
  Simulation sim(LoadBuiltinWorld("hall"), config);
  SimEvent ev;
  std::int64_t last_stamp = -1, last_offset = 0, shortest = 1 << 30, longest = 0;
  while (sim.Step(&ev)) {
    if (ev.type != SimEventType::kScan) continue;
    REQUIRE(ev.scan.beams.size() == 360);
    if (last_stamp >= 0) {
      const std::int64_t period = ev.scan.stamp_us - last_stamp;
      shortest = std::min(shortest, period);
      longest = std::max(longest, period);
      // The last revolution's beams spanned it: 359 of its 360 steps.
      REQUIRE(last_offset == period * 359 / 360);
    }
    last_stamp = ev.scan.stamp_us;
    last_offset = ev.scan.beams.back().offset_us;
  }
  CHECK(shortest >= 199999);  // 5 Hz at most
  CHECK(longest <= 285715);   // 3.5 Hz at least
  CHECK(longest - shortest > 30000);
}

TEST_CASE("The robot waits out its lidar's spin-up before it drives", "[sim]") {
  // A turn made while the lidar saw almost nothing could be measured by no mapper without
  // odometry: the plan starts after the spin-up revolution (an LD06 has none: it starts at once).
  SimConfig config;
  config.duration_min = 0.1;
  config.lidar = Xv11LidarConfig();
  Simulation sim(LoadBuiltinWorld("apartment"), config);
  SimEvent ev;
  std::vector<dpcr::sim::Pose2d> scan_truths;
  while (sim.Step(&ev) && scan_truths.size() < 3) {
    if (ev.type == SimEventType::kScan) scan_truths.push_back(ev.truth);
  }
  REQUIRE(scan_truths.size() == 3);
  // The spin-up revolution and the first full one start at the same pose; then it moves.
  CHECK(scan_truths[1].theta == scan_truths[0].theta);
  CHECK(scan_truths[1].x == scan_truths[0].x);
  const bool moved = scan_truths[2].theta != scan_truths[1].theta || scan_truths[2].x != scan_truths[1].x ||
                     scan_truths[2].y != scan_truths[1].y;
  CHECK(moved);
}
