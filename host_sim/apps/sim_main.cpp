// dpcr-sim: runs the world simulator into the mapper and writes map, trajectories and metrics.
//   dpcr-sim --world apartment|office|hall|FILE [--minutes M] [--seed N] [--out DIR] [--emit-device DIR]
//            [--load-map FILE [--start-pose X,Y,THETA | --map-origin X,Y,THETA] [--localise-only]]
//            [--save-map FILE] [--region-width S] [--kidnaps N [--kidnap-from MIN]]
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <vector>

#include "core/mapper.hpp"
#include "hal/device_options.hpp"
#include "host_sim/apps/config_error.hpp"
#include "host_sim/apps/kidnap_report.hpp"
#include "host_sim/apps/map_truth_check.hpp"
#include "host_sim/apps/progress.hpp"
#include "host_sim/apps/scan_times.hpp"
#include "host_sim/drivers/device_files.hpp"
#include "host_sim/output/map_file_io.hpp"
#include "host_sim/output/run_report.hpp"
#include "host_sim/sim/heading_only_ticks.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string world = "apartment";
  double minutes = 35.0;
  std::uint64_t seed = 1;
  std::string out;
  std::string emit_device;
  bool odometry_only = false;
  bool front_end_only = false;
  bool fixed_plan = false;
  double start_heading_rad = std::numeric_limits<double>::quiet_NaN();
  double grid_turn_deg = -1.0;  // < 0: the configuration's
  double near_weight_m = -1.0;  // < 0: a vacuum lidar's (kVacuumNearWeightRangeM)
  double map_max_turn_dps = -1.0;  // < 0: the lidar model's (ApplyLidarModel)
  double max_accel_mps2 = -1.0;    // < 0: the configuration's (FrontEndConfig::max_acceleration_mps2)
  double weak_hold = -1.0;          // < 0: the configuration's (FrontEndConfig::weak_direction_information)
  double smoothing_gap_beams = -1.0;  // < 0: the lidar model's (ApplyLidarModel)
  double start_heading_window_s = -1.0;  // < 0: the configuration's
  std::string load_map;
  std::string save_map;
  std::vector<float> start_pose{0.0f, 0.0f, 0.0f};
  bool start_pose_given = false;  // without it, a loaded map's start pose is searched for
  std::vector<float> map_origin;  // the loaded map's frame in the simulated world (for the figures)
  bool localise_only = false;
  int kidnaps = 0;
  int people = 0;
  bool doors = false;  // the world's doors with a leaf open and close
  double kidnap_from_min = 0.0;
  float region_width_m = 0.0f;  // 0: the configuration's default (FrontEndConfig::region_width_m)
  std::string scan_times;
  bool write_regions = false;
  bool refine_trajectory = true;  // host_sim/output/trajectory_refinement.hpp
  std::string heading = "model";  // the prediction's heading: model (the lidar's: ModelGyroHeading), wheels, or gyro
  std::string lidar = "ld06";      // ld06, or xv11 (sim::Xv11LidarConfig)
  std::string odometry = "wheels";  // wheels (+ gyro), gyro (no wheel encoders), heading-ticks, none
  int spins = 0;                    // an in-place spin every this many waypoints (0: none)
  double lidar_min_hz = -1.0;       // the lowest revolution rate (-1: the lidar model's)
  double lidar_valid = -1.0;        // the share of returns that come (-1: the lidar model's)
  double wheel_clock_ppm = 35.0;    // --emit-device: the wheel board's clock drift (DeviceFilesConfig)
  bool ideal_bus = false;           // --emit-device: no latency, jitter or drift on the CAN bus
  std::vector<int> unsettle_after;  // GridConfig::unsettle_occupied_after, unsettle_free_after (empty: the defaults)
  float unsettle_margin_m = -1.0f;  // GridConfig::unsettle_miss_margin_m (< 0: the default)
  int drop_behind_cells = -1;       // GridConfig::drop_hits_behind_settled_cells (< 0: the default)
  bool hit_means = true;            // GridConfig::hit_means
  bool start_scans = true;          // StartScansConfig::enabled
  bool calibrate_odometry = true;   // FrontEndConfig::calibrate_odometry
  bool start_locate = true;         // StartScansConfig::locate
  std::vector<double> lidar_noise;  // range sigma base (m), fraction of the range (empty: the lidar model's)
  bool ideal_wheels = false;        // no calibration error, no slips (the wheels' ticks still quantise)
};

// First registrations during the robot's in-place spins (metrics.json "spins").
struct SpinTally {
  std::uint32_t scans = 0;
  std::uint32_t rejected = 0;
  void Add(bool spinning, std::uint32_t rejected_now) {
    if (!spinning) return;
    ++scans;
    rejected += rejected_now;
  }
  nlohmann::json Metrics() const {
    return {{"scans", scans}, {"first_rejected", rejected},
            {"rejected_fraction", scans > 0 ? static_cast<double>(rejected) / scans : 0.0}};
  }
};

// The odometry the robot has (--odometry): false when it has none; gyro: the rate alone;
// heading-ticks: wheel ticks that only turn, by the gyro's integrated yaw (a recorder that turned
// its IMU's yaw into ticks, as real XV-11 recordings were converted): no translation, no gyro frame.
struct RobotOdometry {
  const Options& opt;
  dpcr::sim::HeadingOnlyTicks heading_ticks;
  bool Apply(dpcr::OdometrySample* sample) {
    if (opt.odometry == "none") return false;
    if (opt.odometry == "gyro") {
      sample->pose = dpcr::Pose2::Identity();
      sample->has_wheels = false;
    }
    if (opt.odometry == "heading-ticks") heading_ticks.Apply(sample);
    return true;
  }
};

dpcr::LidarKind LidarKindOf(const Options& opt) { return opt.lidar == "xv11" ? dpcr::LidarKind::kXv11 : dpcr::LidarKind::kLd06; }

// --heading: named, or the lidar model's (hal/device_options.hpp).
bool GyroHeading(const Options& opt) { return dpcr::GyroHeadingFor(opt.heading, LidarKindOf(opt)); }

std::unique_ptr<dpcr::DeviceEmitter> MakeEmitter(const Options& opt, const dpcr::MapperConfig& config,
                                                 const dpcr::sim::SimConfig& sim_config) {
  if (opt.emit_device.empty()) return nullptr;
  std::filesystem::create_directories(opt.emit_device);
  dpcr::DeviceFilesConfig files;
  files.max_range_m = config.lidar.max_range_m;
  files.laser_offset_m = config.lidar.mount.x;  // dpcr-sim's lidar faces forward on the robot's axis
  files.lidar = LidarKindOf(opt);
  files.xv11_rate_hz = static_cast<float>(sim_config.lidar.rate_hz);
  if (!opt.ideal_bus) dpcr::RealisticBus(&files, static_cast<std::uint32_t>(opt.seed), opt.wheel_clock_ppm);
  auto emitter = std::make_unique<dpcr::DeviceEmitter>(files);
  std::string error;
  if (!emitter->Open(opt.emit_device, &error)) throw std::runtime_error(error);
  return emitter;
}

// The summary line (stderr), and a warning when the run was lost most of the time.
template <class MapperType>
void PrintSummary(const Options& opt, const MapperType& mapper, const dpcr::output::RunRecord& run,
                  const nlohmann::json& metrics) {
  std::fprintf(stderr, "dpcr-sim: %s, %.0f min, %zu scans in %.1f s, mapper %s, %d regions%s",
               opt.world.c_str(), opt.minutes, run.estimate.size(), metrics["wall_seconds"].get<double>(), mapper.pipeline(),
               mapper.region_count(), dpcr::output::TrackingSummary(metrics).c_str());
  if (metrics.contains("accuracy")) {
    std::fprintf(stderr, ", LocErr_ave %.3f m, ATE %.3f m, max %.3f m", metrics["accuracy"]["loc_err_ave_m"].get<double>(),
                 metrics["accuracy"]["ate_rmse_m"].get<double>(), metrics["accuracy"]["max_err_m"].get<double>());
  }
  if (!opt.load_map.empty()) std::fprintf(stderr, ", loaded %s", opt.load_map.c_str());
  if (!opt.save_map.empty()) std::fprintf(stderr, ", map saved to %s (%zu bytes)", opt.save_map.c_str(), mapper.map_file_bytes());
  std::fprintf(stderr, " -> %s/\n", opt.out.c_str());
  const std::string warning = dpcr::output::TrackingWarning(metrics);
  if (!warning.empty()) std::fprintf(stderr, "dpcr-sim: %s\n", warning.c_str());
}

// What was simulated: metrics.json "input".
nlohmann::json InputMetrics(const Options& opt, const dpcr::sim::Simulation& sim, const dpcr::sim::SimConfig& sim_config) {
  const dpcr::sim::Pose2d& start = sim.start_pose();
  return {{"world", opt.world}, {"minutes", opt.minutes}, {"seed", opt.seed}, {"heading", GyroHeading(opt) ? "gyro" : "wheels"}, {"lidar", opt.lidar}, {"odometry", opt.odometry}, {"spins", opt.spins},
          {"plan", opt.fixed_plan ? "fixed" : "varied by the seed"}, {"start_pose_in_world", {start.x, start.y, start.theta}},
          {"slip_events", sim.slip_events()}, {"people", opt.people},
          {"lidar_noise", {sim_config.lidar.noise_base_m, sim_config.lidar.noise_fraction}},
          {"lidar_valid", 1.0 - sim_config.lidar.invalid_probability}, {"lidar_min_hz", sim_config.lidar.rate_min_hz}, {"ideal_wheels", opt.ideal_wheels},
          {"doors", {{"moving", sim.doors().size()}, {"scheduled_changes", sim.doors().scheduled_changes()}}}, {"kidnaps", opt.kidnaps}, {"coverage_tours", sim.tours_completed()}};
}

// The mapper settings a run's figures depend on, beside the simulation's in metrics.json `input`.
void AddMapperInputs(const dpcr::MapperConfig& config, nlohmann::json* input) {
  (*input)["unsettle_after"] = {config.grid.unsettle_occupied_after, config.grid.unsettle_free_after};
  (*input)["hit_means"] = config.grid.hit_means;
  (*input)["start_scans"] = config.front_end.start_scans.enabled;
  (*input)["calibrate_odometry"] = config.front_end.calibrate_odometry;
  (*input)["start_locate"] = config.front_end.start_scans.locate;
  (*input)["near_weight_range_m"] = config.lidar.near_weight_range_m;
  (*input)["map_max_turn_rate_dps"] = config.lidar.map_max_turn_rate_rad_s * 180.0 / M_PI;
  (*input)["max_acceleration_mps2"] = config.front_end.max_acceleration_mps2;
  (*input)["weak_direction_information"] = config.front_end.weak_direction_information;
}

// What to simulate: the options' seed, length, lidar (and its motor), spins, kidnaps and people.
dpcr::sim::SimConfig SimulationConfig(const Options& opt) {
  dpcr::sim::SimConfig c;
  c.seed = opt.seed;
  c.duration_min = opt.minutes;
  c.vary_plan = !opt.fixed_plan;
  c.start_heading_rad = opt.start_heading_rad;
  if (opt.lidar == "xv11") c.lidar = dpcr::sim::Xv11LidarConfig();
  if (opt.lidar_min_hz >= 0.0) c.lidar.rate_min_hz = opt.lidar_min_hz;
  if (opt.lidar_valid >= 0.0) c.lidar.invalid_probability = 1.0 - opt.lidar_valid;
  c.motion.spin_every_waypoints = opt.spins;
  c.kidnaps.count = opt.kidnaps;
  c.kidnaps.from_min = opt.kidnap_from_min;
  c.people.count = opt.people;
  c.doors.enabled = opt.doors;
  if (!opt.lidar_noise.empty()) {
    c.lidar.noise_base_m = opt.lidar_noise[0];
    c.lidar.noise_fraction = opt.lidar_noise[1];
  }
  if (opt.ideal_wheels) {
    c.odometry.systematic_error = false;
    c.odometry.slips_per_minute = 0.0;
  }
  return c;
}

// The mapper's configuration for the options and the simulated sensors.
dpcr::MapperConfig MapperConfigFor(const Options& opt, const dpcr::sim::SimConfig& sim_config) {
  dpcr::MapperConfig config;
  config.lidar = dpcr::sim::MapperLidarConfig(sim_config);
  // As the device path tells the mapper of the model (junk filter, turning scans), with the
  // simulated range noise.
  const float range_noise_m = config.lidar.range_noise_m;
  dpcr::ApplyLidarModel(LidarKindOf(opt), &config.lidar);
  config.lidar.range_noise_m = range_noise_m;
  if (opt.near_weight_m >= 0.0) config.lidar.near_weight_range_m = static_cast<float>(opt.near_weight_m);
  if (opt.map_max_turn_dps >= 0.0) config.lidar.map_max_turn_rate_rad_s = static_cast<float>(opt.map_max_turn_dps * M_PI / 180.0);
  if (opt.max_accel_mps2 >= 0.0) config.front_end.max_acceleration_mps2 = static_cast<float>(opt.max_accel_mps2);
  if (opt.weak_hold >= 0.0) config.front_end.weak_direction_information = static_cast<float>(opt.weak_hold);
  if (opt.smoothing_gap_beams >= 0.0) config.lidar.smoothing_max_gap_beams = static_cast<float>(opt.smoothing_gap_beams);
  if (opt.start_heading_window_s >= 0.0) config.front_end.start_heading.window_s = static_cast<float>(opt.start_heading_window_s);
  config.front_end.enable_registration = !opt.odometry_only;
  config.back_end.enable = !opt.front_end_only;
  config.front_end.gyro_heading = GyroHeading(opt);
  if (opt.region_width_m > 0.0f) config.front_end.region_width_m = opt.region_width_m;
  if (opt.grid_turn_deg == 0.0) config.front_end.grid_turn_rad = 0.0f;
  if (opt.grid_turn_deg > 0.0) {
    config.front_end.grid_turn_rad = static_cast<float>(opt.grid_turn_deg * M_PI / 180.0);
    config.front_end.grid_turn_band_rad = std::fmin(config.front_end.grid_turn_band_rad, 0.5f * config.front_end.grid_turn_rad);
  }
  config.localisation.unknown_start = !opt.load_map.empty() && !opt.start_pose_given;
  config.localisation.localise_only = opt.localise_only;
  if (!opt.unsettle_after.empty()) {
    config.grid.unsettle_occupied_after = static_cast<std::uint8_t>(opt.unsettle_after[0]);
    config.grid.unsettle_free_after = static_cast<std::uint8_t>(opt.unsettle_after[1]);
  }
  if (opt.unsettle_margin_m >= 0.0f) config.grid.unsettle_miss_margin_m = opt.unsettle_margin_m;
  if (opt.drop_behind_cells >= 0) config.grid.drop_hits_behind_settled_cells = static_cast<std::uint8_t>(opt.drop_behind_cells);
  config.grid.hit_means = opt.hit_means;
  config.front_end.start_scans.enabled = opt.start_scans;
  config.front_end.calibrate_odometry = opt.calibrate_odometry;
  config.front_end.start_scans.locate = opt.start_locate;
  return config;
}

// What changed in the home during the run, for map_check: the doors' leaves, where people stood.
dpcr::apps::HomeChanges HomeChangesOf(const dpcr::sim::Simulation& sim, const dpcr::sim::SimConfig& sim_config) {
  dpcr::apps::HomeChanges changes;
  changes.door_leaves = sim.doors().leaves();
  changes.standing_spots = sim.people().StandingSpots();
  changes.person_radius_m = sim_config.people.radius_m;
  return changes;
}

// The ground truth's frame to the map's: the robot's first pose is the map's origin (or, given,
// where the loaded map lies in the world).
dpcr::Pose2 WorldToMap(const Options& opt, const dpcr::output::RunRecord& run) {
  if (!opt.map_origin.empty()) return dpcr::Pose2{opt.map_origin[0], opt.map_origin[1], opt.map_origin[2]}.Inverse();
  if (run.ground_truth.empty()) return dpcr::Pose2::Identity();
  return run.estimate.front().pose * run.ground_truth.front().pose.Inverse();
}

// Issue targets the relocalisation figures are measured against: a kidnap recovered within 3 s of
// motion, no fix farther off than 0.3 m.
constexpr double kRecoverWithinS = 3.0;
constexpr double kWrongFixM = 0.3;

// metrics.json relocalisation: kidnaps, the start fix, the accuracy of the scans placed.
template <class MapperType>
void AddRelocalisationFigures(const Options& opt, const MapperType& mapper, const dpcr::sim::Simulation& sim,
                              const dpcr::output::RunRecord& run, const std::vector<dpcr::apps::Recovery>& recoveries,
                              const std::vector<bool>& lost, const dpcr::Pose2& align, nlohmann::json* metrics) {
  nlohmann::json& r = (*metrics)["relocalisation"];
  if (opt.kidnaps > 0) r["kidnaps"] = dpcr::apps::KidnapMetrics(sim.kidnaps(), recoveries, align, kRecoverWithinS, kWrongFixM);
  if (mapper.config().localisation.unknown_start && !run.estimate.empty()) {
    r["start_fix"] = dpcr::apps::UnknownStartMetrics(run.estimate.front().stamp_us, recoveries, align);
  }
  r["all_fixes"] = dpcr::apps::FixMetrics(recoveries, align, kWrongFixM);
  if (!run.ground_truth.empty()) r["accuracy_when_placed"] = dpcr::apps::PlacedAccuracy(run.estimate, run.ground_truth, lost);
}

int Run(const Options& opt) {
  using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;
  static MapperType mapper;  // ~2 MiB: static storage, as on the robot

  const dpcr::sim::World world = dpcr::sim::LoadWorld(opt.world);
  const dpcr::sim::SimConfig sim_config = SimulationConfig(opt);
  dpcr::sim::Simulation sim(world, sim_config);

  const dpcr::MapperConfig config = MapperConfigFor(opt, sim_config);
  if (mapper.Init(config) != dpcr::Status::kOk) throw std::runtime_error(dpcr::apps::InitError<MapperType>(config));
  // A second session: the saved map, the robot at a known pose in its frame (the world's start
  // pose is the saved frame's origin when the map came from a run in the same world).
  if (!opt.load_map.empty()) {
    dpcr::output::LoadMapFile(mapper, opt.load_map, dpcr::Pose2{opt.start_pose[0], opt.start_pose[1], opt.start_pose[2]});
  }

  std::unique_ptr<dpcr::DeviceEmitter> emitter = MakeEmitter(opt, config, sim_config);

  const auto start = Clock::now();
  dpcr::output::RunRecord run;
  run.write_regions = opt.write_regions;
  run.refine_trajectory = opt.refine_trajectory;
  dpcr::apps::Progress progress("sim " + opt.world);
  dpcr::sim::SimEvent event;
  SpinTally spins;
  const double total_us = opt.minutes * 60e6;
  std::vector<dpcr::apps::Recovery> recoveries;
  std::vector<bool> lost;  // per scan: the status after it was lost
  RobotOdometry robot_odometry{opt, {}};
  while (sim.Step(&event)) {
    if (event.type == dpcr::sim::SimEventType::kOdometry) {
      if (!robot_odometry.Apply(&event.odometry)) continue;
      mapper.AddOdometry(event.odometry);
      if (emitter) emitter->AddOdometry(event.odometry);
      continue;
    }
    if (emitter && !emitter->AddScan(event.scan)) throw std::runtime_error("device emitter rejected a scan");
    const std::uint32_t fixes = mapper.counters().relocalisations;
    const std::uint32_t rejected_before = mapper.front_end_counters().first_rejected;
    dpcr::output::AddTimedScan(mapper, event.scan, &run);  // a SimScan is the vacuum mapper's scan type
    if (mapper.counters().relocalisations != fixes) recoveries.push_back({event.scan.stamp_us, mapper.pose(), event.truth.ToPose2()});
    lost.push_back(mapper.status() == dpcr::MapperStatus::kLost);
    spins.Add(event.spinning, mapper.front_end_counters().first_rejected - rejected_before);
    run.ground_truth.push_back({event.scan.stamp_us, event.truth.ToPose2()});
    if ((run.estimate.size() & 63) == 0) progress.Update(static_cast<double>(event.time_us) / total_us);
  }
  progress.Done();
  if (emitter) {
    std::string error;
    if (!emitter->Close(&error)) throw std::runtime_error(error);
  }
  run.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();

  // An unknown start in a loaded map: measured from the first fix (before it the pose is a guess,
  // and a start-aligned LocErr_ave would carry that guess through the whole run).
  if (mapper.config().localisation.unknown_start && !recoveries.empty()) run.accuracy_from_us = recoveries.front().stamp_us;
  const dpcr::Pose2 align = WorldToMap(opt, run);
  if (!run.ground_truth.empty()) {
    dpcr::eval::Trajectory gt_in_map = run.ground_truth;
    for (auto& p : gt_in_map) p.pose = align * p.pose;
    run.ground_truth.swap(gt_in_map);
  }
  std::filesystem::create_directories(opt.out);
  dpcr::output::FinalizeTrajectory(mapper, &run);
  nlohmann::json metrics = dpcr::output::MapperMetrics(mapper);
  metrics["input"] = InputMetrics(opt, sim, sim_config);
  AddMapperInputs(config, &metrics["input"]);
  AddRelocalisationFigures(opt, mapper, sim, run, recoveries, lost, align, &metrics);
  if (opt.spins > 0) metrics["spins"] = spins.Metrics();
  const dpcr::output::FusedMap fused = dpcr::output::RenderFused(mapper);
  const dpcr::sim::WorldRayCaster caster(world);
  metrics["map_check"] = dpcr::apps::MapTruthCheck(fused, align.Inverse(), caster, HomeChangesOf(sim, sim_config));
  metrics = dpcr::output::WriteRunOutputs(opt.out, fused, run, metrics);
  if (!opt.save_map.empty()) dpcr::output::SaveMapFile(mapper, opt.save_map);
  dpcr::apps::WriteScanTimes(opt.scan_times, run);

  PrintSummary(opt, mapper, run, metrics);
  return 0;
}

// The run: world, plan, device files, maps, what happens in the home.
void AddRunOptions(CLI::App& app, Options& opt) {
  std::string names;
  for (const auto& n : dpcr::sim::BuiltinWorldNames()) names += (names.empty() ? "" : "|") + n;
  app.add_option("--world", opt.world, "built-in world (" + names + ") or a world file (.txt or .pgm)")->capture_default_str();
  app.add_option("--minutes", opt.minutes, "simulated run time")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--seed", opt.seed, "random seed: the noise and the cleaning plan (start pose, room order, lanes); same seed, same run")
      ->capture_default_str();
  app.add_flag("--fixed-plan", opt.fixed_plan, "every seed drives the world's own start pose and canonical plan (only the noise varies)");
  app.add_option("--start-heading", opt.start_heading_rad, "the robot's heading at the start in the world (rad; default: the world's or the seed's); 0: square to the built-in worlds' walls, as from a dock")->check(CLI::Range(-10.0, 10.0));
  app.add_option("--out", opt.out, "output directory (default: out/<world>)");
  app.add_option("--emit-device", opt.emit_device, "also write the run as device files: DIR/lidar.uart (LD06) + DIR/wheels.log (candump: ticks 0x120, gyro 0x121, wheel-lift status 0x122)");
  app.add_option("--wheel-clock-ppm", opt.wheel_clock_ppm,
                 "--emit-device: the wheel board's clock runs this fast against the host's (ppm); the bus adds "
                 "0.2 ms latency, 0.5 ms mean jitter and 1 % of frames up to 20 ms late")
      ->check(CLI::Range(-1000.0, 1000.0))->capture_default_str();
  app.add_flag("--ideal-bus", opt.ideal_bus, "--emit-device: wheel frames arrive at their device time (no latency, jitter or drift)");
  app.add_flag("--odometry-only", opt.odometry_only, "map with dead reckoning only (for comparison)");
  app.add_flag("--front-end-only", opt.front_end_only, "map without the back end (no region graph, no loop closures; for comparison)");
  app.add_option("--load-map", opt.load_map, "start from this saved map (a second session; dpcr-map info FILE shows it)");
  app.add_option("--start-pose", opt.start_pose, "with --load-map: the robot's start pose in the saved map's frame (x,y,theta); "
                 "without it the start pose is unknown and searched for in the maps")
      ->expected(3)->delimiter(',');
  app.add_option("--map-origin", opt.map_origin, "with --load-map: where the saved map's frame lies in the simulated world (x,y,theta: "
                 "input.start_pose_in_world of the run that made it), to measure against the truth")
      ->expected(3)->delimiter(',');
  app.add_flag("--localise-only", opt.localise_only, "with --load-map: maps frozen (nothing inserted, no new region, graph unchanged)");
  app.add_option("--kidnaps", opt.kidnaps, "carry the robot this many times to a random waypoint of its plan (wheels lifted meanwhile), "
                 "spread from --kidnap-from to the end; metrics.json relocalisation.kidnaps")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--people", opt.people, "people walking through the home along the robot's tour (a home that changes)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--doors", opt.doors, "the world's doors with a leaf open and close on a schedule drawn from the seed (a home that "
               "changes); a closed door opens for the robot within 1 m of it");
  app.add_option("--kidnap-from", opt.kidnap_from_min, "minute of the run from which kidnaps happen")->check(CLI::NonNegativeNumber);
  app.add_option("--save-map", opt.save_map, "save the map at the end (atomically), for --load-map and dpcr-map");
  app.add_option("--region-width", opt.region_width_m, "region width S in metres (default: the configuration's, 4 m)")
      ->check(CLI::PositiveNumber);
  app.add_option("--scan-times", opt.scan_times, "write the time of every AddScan call (ms, one per line) to this file");
  app.add_flag("--write-regions", opt.write_regions,
               "also write regions.tsv (each scan's map and pose in it) and graph.tsv (final anchors and edges)");
  app.add_option("--refine-trajectory", opt.refine_trajectory,
                 "register each scan again in its finished map at the end (trajectory.tum; the maps are the same "
                 "either way); false: each scan as the run placed it")
      ->default_val(true);
}

// The robot's sensors and the mapper's knobs measured with them.
void AddSensorOptions(CLI::App& app, Options& opt) {
  app.add_option("--heading", opt.heading, "the prediction's heading increment: wheels, or the integrated gyro (wheels keep the translation); "
                 "model: the gyro for an xv11, the wheels for an ld06")
      ->check(CLI::IsMember({"model", "wheels", "gyro"}))->capture_default_str();
  app.add_option("--lidar", opt.lidar, "simulated lidar: ld06 (10 Hz, 450 beams, 12 m) or xv11 (5 Hz, 360 at 1 deg, 0.15-6 m, "
                 "invalid and junk readings, spin-up); --emit-device writes its own packets")
      ->check(CLI::IsMember({"ld06", "xv11"}))->capture_default_str();
  app.add_option("--odometry", opt.odometry, "what the robot has: wheels (+ gyro), gyro (no wheel encoders), "
                 "heading-ticks (wheel ticks carrying only the heading, no gyro: an IMU's yaw turned into ticks), none")
      ->check(CLI::IsMember({"wheels", "gyro", "heading-ticks", "none"}))->capture_default_str();
  app.add_option("--spins", opt.spins, "an in-place spin (360 deg at 120 deg/s) after every N waypoints reached (0: none); "
                 "metrics.json \"spins\" counts the first registrations rejected during them")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--lidar-min-hz", opt.lidar_min_hz, "the lowest revolution rate of a wandering lidar motor (default: the model's; "
                 "xv11 4.5 Hz, ld06 none)")->check(CLI::NonNegativeNumber);
  app.add_option("--lidar-valid", opt.lidar_valid, "the share of a revolution's readings that come back valid, before junk "
                 "(default: the model's; xv11 0.7, ld06 1 less the materials' dropouts)")->check(CLI::Range(0.05, 1.0));
  app.add_option("--unsettle-after", opt.unsettle_after, "settled regional cells learn again after this many scans in a row "
                 "contradict them: occupied,free (0: never; GridConfig::unsettle_occupied_after, unsettle_free_after)")
      ->expected(2)->delimiter(',')->check(CLI::Range(0, 255));
  app.add_option("--calibrate-odometry", opt.calibrate_odometry, "calibrate the wheels' step and turn scales online from the "
                 "registrations and predict with them (FrontEndConfig::calibrate_odometry; core/front_end/odometry_calibration.hpp)")
      ->default_str("true");
  app.add_option("--start-scans", opt.start_scans, "keep scans of the first seconds with the gyro's turn and, at the end, place "
                 "the start in the finished first map with them (StartScansConfig::enabled; core/front_end/start_scans.hpp)")
      ->default_str("true");
  app.add_option("--start-locate", opt.start_locate, "without wheels measuring the translation, search for the start scan "
                 "in the finished first map within 3 m of where it was recorded and move the start there when found 0.1 m or "
                 "more away (StartScansConfig::locate)")
      ->default_str("true");
  app.add_option("--hit-means", opt.hit_means, "regional maps' wall cells learn where in them the returns fall, and their lines "
                 "are fitted there (GridConfig::hit_means; only with a lidar that declares its range noise)")
      ->default_str("true");
  app.add_option("--unsettle-margin", opt.unsettle_margin_m, "only a ray's cells farther than this before its return count against "
                 "a settled occupied cell (metres; GridConfig::unsettle_miss_margin_m)")->check(CLI::Range(0.0, 100.0));
  app.add_option("--drop-behind", opt.drop_behind_cells, "drop returns 2 to N cells behind a settled wall along their ray "
                 "(range noise through the wall; GridConfig::drop_hits_behind_settled_cells, 0: none)")->check(CLI::Range(0, 255));
  app.add_option("--lidar-noise", opt.lidar_noise, "range noise of the simulated lidar: sigma = BASE + FRACTION x range "
                 "(metres, fraction; default: the model's, ld06 0.01,0.005, xv11 0.01,0.01); 0,0: exact ranges")
      ->expected(2)->delimiter(',')->check(CLI::Range(0.0, 1.0));
  app.add_option("--grid-turn", opt.grid_turn_deg, "turn a new map's grid this far off walls that lie along its axes at the start "
                 "(degrees; FrontEndConfig::grid_turn_rad, default 15; 0: never)")->check(CLI::Range(0.0, 40.0));
  app.add_option("--near-weight", opt.near_weight_m, "returns within this distance of the robot weigh distance / this in the "
                 "first registration (metres; LidarConfig::near_weight_range_m, default 0.5; 0: all alike)")->check(CLI::Range(0.0, 10.0));
  app.add_option("--smoothing-gap", opt.smoothing_gap_beams, "the widest angle, in beams, between two returns that the range-noise "
                 "smoothing takes as neighbours on one wall (LidarConfig::smoothing_max_gap_beams, default: ld06 1.5, xv11 3.5)")
      ->check(CLI::Range(1.0, 10.0));
  app.add_option("--start-heading-window", opt.start_heading_window_s, "with a gyro's turns or heading-only ticks, refine the start's "
                 "heading from the scans of this many seconds after it (StartHeadingConfig::window_s, default 30; 0: never)")
      ->check(CLI::Range(0.0, 600.0));
  app.add_option("--max-accel", opt.max_accel_mps2, "the robot's largest acceleration (m/s^2): without wheel translation the "
                 "constant-velocity guess changes by no more (FrontEndConfig::max_acceleration_mps2, default 0.5; 0: no limit)");
  app.add_option("--weak-hold", opt.weak_hold, "without wheel translation, a first registration keeps near the constant-velocity "
                 "guess along directions whose information per inlier is below this (FrontEndConfig::weak_direction_information, "
                 "default 0.1; 0: never)")
      ->check(CLI::Range(0.0, 1000.0));
  app.add_option("--map-max-turn", opt.map_max_turn_dps, "scans taken turning faster than this go into the submap but not the "
                 "regional maps (deg/s; LidarConfig::map_max_turn_rate_rad_s, default: ld06 60, xv11 0; 0: every scan)")
      ->check(CLI::Range(0.0, 5000.0));
  app.add_flag("--ideal-wheels", opt.ideal_wheels, "wheel odometry without calibration error or slips (ticks still quantise)");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dpcr-sim: simulate a vacuum run and map it; writes map.pgm/.yaml/.png, trajectory.tum, ground_truth.tum, metrics.json"};
  Options opt;
  AddRunOptions(app, opt);
  AddSensorOptions(app, opt);
  CLI11_PARSE(app, argc, argv);
  opt.start_pose_given = app.count("--start-pose") > 0;
  if ((opt.localise_only || !opt.map_origin.empty()) && opt.load_map.empty()) {
    std::fprintf(stderr, "dpcr-sim: error: --localise-only and --map-origin need --load-map\n");
    return 2;
  }
  if (opt.out.empty()) opt.out = "out/" + std::filesystem::path(opt.world).stem().string();
  try {
    if (!opt.save_map.empty()) dpcr::output::PrepareMapFileDir(opt.save_map);
    return Run(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dpcr-sim: error: %s\n", e.what());
    return 1;
  }
}
