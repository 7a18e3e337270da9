// dpcr-replay: maps a recorded log through the core and writes map, trajectory and metrics.
//   dpcr-replay --carmen FILE.clf [--relations FILE] [--out DIR]
//   dpcr-replay --uart lidar.uart --candump wheels.log [--lidar ld06|xv11] [--out DIR]
//   either with [--load-map FILE [--start-pose X,Y,THETA] [--localise-only]] [--save-map FILE] [--region-width S]
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <vector>

#include "core/mapper.hpp"
#include "host_sim/apps/config_error.hpp"
#include "host_sim/apps/progress.hpp"
#include "host_sim/apps/scan_times.hpp"
#include "host_sim/carmen/carmen_reader.hpp"
#include "host_sim/carmen/laser_odometry.hpp"
#include "host_sim/carmen/laser_scan.hpp"
#include "host_sim/drivers/device_files.hpp"
#include "host_sim/output/map_file_io.hpp"
#include "host_sim/output/run_report.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string carmen;
  std::string uart;
  std::string candump;
  std::string lidar = "ld06";
  std::string lidar_timing = "arrival";
  float angle_sign = -1.0f;
  bool odometry_only = false;
  bool front_end_only = false;
  std::string relations;
  std::string out = "out/replay";
  std::string profile;  // default: building for CARMEN logs, vacuum for device files
  std::string odometry = "laser";
  float max_range_m = 20.0f;
  float laser_offset_m = NAN;  // NAN: the log's PARAM robot_frontlaser_offset, else 0
  std::string load_map;
  std::string save_map;
  std::vector<float> start_pose{0.0f, 0.0f, 0.0f};
  bool localise_only = false;
  float region_width_m = 0.0f;  // 0: the configuration's default (FrontEndConfig::region_width_m)
  float max_accel_mps2 = -1.0f;  // < 0: the configuration's (FrontEndConfig::max_acceleration_mps2)
  bool calibrate_odometry = true;  // FrontEndConfig::calibrate_odometry
  std::string scan_times;
  bool write_regions = false;
  bool refine_trajectory = true;  // host_sim/output/trajectory_refinement.hpp
  std::string heading = "model";  // FrontEndConfig::gyro_heading (model: ModelGyroHeading)
  float wheel_radius_m = 0.0f;
  float track_width_m = 0.0f;
  float ticks_per_rev = 0.0f;
  std::set<std::string> given;  // the options on the command line
};

// --uart: the device options: the firmware's defaults (hal/device_options.hpp), then the
// recording's device.json beside the capture, then the command line. The lidar kind likewise.
dpcr::DeviceOptions DeviceOptionsFor(const Options& opt, std::string* lidar, std::string* description) {
  dpcr::DeviceOptions d;
  *lidar = "ld06";
  *description = (std::filesystem::path(opt.uart).parent_path() / "device.json").string();
  std::string error;
  if (!dpcr::ReadDeviceDescription(*description, &d, lidar, &error)) throw std::runtime_error(error);
  if (!std::filesystem::exists(*description)) description->clear();
  const auto given = [&](const char* name) { return opt.given.count(name) > 0; };
  if (given("--lidar")) *lidar = opt.lidar;
  if (given("--angle-sign")) d.angle_sign = opt.angle_sign;
  if (given("--wheel-radius")) d.wheels.wheel_radius_m = opt.wheel_radius_m;
  if (given("--track-width")) d.wheels.track_width_m = opt.track_width_m;
  if (given("--ticks-per-rev")) d.wheels.ticks_per_rev = opt.ticks_per_rev;
  if (given("--max-range")) d.max_range_m = opt.max_range_m;
  if (given("--laser-offset")) d.laser_offset_m = opt.laser_offset_m;
  if (d.wheels.Validate() != dpcr::Status::kOk) throw std::runtime_error("invalid wheel geometry (radius, track, ticks)");
  return d;
}

// Options that one input does not use are an error, not silently ignored.
void CheckApplicable(const Options& opt) {
  const std::vector<std::string> device_only = {"--candump",     "--lidar",       "--lidar-timing", "--angle-sign",
                                                "--wheel-radius", "--track-width", "--ticks-per-rev", "--heading"};
  const std::vector<std::string> carmen_only = {"--odometry", "--relations"};
  for (const std::string& name : opt.uart.empty() ? device_only : carmen_only) {
    if (opt.given.count(name) == 0) continue;
    throw std::runtime_error(name + " does not apply to " + (opt.uart.empty() ? "--carmen" : "--uart") +
                             " (only to " + (opt.uart.empty() ? "--uart" : "--carmen") + ")");
  }
}

// --load-map: the start pose unknown (searched for in the maps) unless --start-pose gives it;
// --localise-only: the maps frozen.
void ApplyLocalisationOptions(const Options& opt, dpcr::MapperConfig* config) {
  config->localisation.unknown_start = !opt.load_map.empty() && opt.given.count("--start-pose") == 0;
  config->localisation.localise_only = opt.localise_only;
}

// --load-map after Init: a second session in the saved map's frame, at the given start pose.
template <class MapperType>
void LoadMapIfAsked(const Options& opt, MapperType* mapper) {
  if (opt.load_map.empty()) return;
  dpcr::output::LoadMapFile(*mapper, opt.load_map, dpcr::Pose2{opt.start_pose[0], opt.start_pose[1], opt.start_pose[2]});
}

// --save-map at the end of the run.
template <class MapperType>
void SaveMapIfAsked(const Options& opt, const MapperType& mapper) {
  if (opt.save_map.empty()) return;
  dpcr::output::SaveMapFile(mapper, opt.save_map);
  std::fprintf(stderr, "dpcr-replay: map saved to %s (%zu bytes)\n", opt.save_map.c_str(), mapper.map_file_bytes());
}

void PrintSummary(const dpcr::output::RunRecord& run, const nlohmann::json& metrics, const std::string& out) {
  const double wall = metrics["wall_seconds"].get<double>();  // the trajectory's refinement included
  std::fprintf(stderr, "dpcr-replay: %zu scans in %.2f s (%.0f scans/s), mapper %s, %d regions%s",
               run.estimate.size(), wall, static_cast<double>(run.estimate.size()) / wall,
               metrics["mapper"].get<std::string>().c_str(), metrics["regions"].get<int>(),
               dpcr::output::TrackingSummary(metrics).c_str());
  if (metrics.contains("relations")) {
    const auto& r = metrics["relations"];
    std::fprintf(stderr, ", relations %.3f +- %.3f m / %.2f +- %.2f deg (%d matched, %d unmatched)",
                 r["trans_mean_m"].get<double>(), r["trans_std_m"].get<double>(), r["rot_mean_deg"].get<double>(),
                 r["rot_std_deg"].get<double>(), r["matched"].get<int>(), r["unmatched"].get<int>());
  }
  std::fprintf(stderr, " -> %s/\n", out.c_str());
  const std::string warning = dpcr::output::TrackingWarning(metrics);
  if (!warning.empty()) std::fprintf(stderr, "dpcr-replay: %s\n", warning.c_str());
}

// The mapper for a CARMEN log: the lidar mount from --laser-offset, else from the log's PARAM.
dpcr::MapperConfig CarmenMapperConfig(const Options& opt, float log_laser_offset_m) {
  dpcr::MapperConfig config;
  config.lidar.max_range_m = opt.max_range_m;
  config.front_end.enable_registration = !opt.odometry_only;
  config.back_end.enable = !opt.front_end_only;
  const float offset = std::isnan(opt.laser_offset_m) ? log_laser_offset_m : opt.laser_offset_m;
  config.lidar.mount = dpcr::Pose2{offset, 0.0f, 0.0f};
  if (opt.region_width_m > 0.0f) config.front_end.region_width_m = opt.region_width_m;
  if (opt.max_accel_mps2 >= 0.0f) config.front_end.max_acceleration_mps2 = opt.max_accel_mps2;
  config.front_end.calibrate_odometry = opt.calibrate_odometry;
  ApplyLocalisationOptions(opt, &config);
  return config;
}

dpcr::OdometrySample Odometry(std::int64_t stamp_us, dpcr::Pose2 pose) {
  dpcr::OdometrySample s;
  s.stamp_us = stamp_us;
  s.pose = pose;
  return s;
}

struct CarmenInputCounts {
  long decimated_scans = 0;
  long repeated_odometry = 0;  // laser records whose odometry pose repeated the last (LaserOdometry)
};

// Maps a whole CARMEN log; returns how many scans had to be decimated and how many odometry
// poses were repeats. CarmenError becomes a runtime_error naming the file and line.
template <class MapperType>
CarmenInputCounts MapCarmenLog(const Options& opt, std::ifstream& in, MapperType* mapper, dpcr::carmen::CarmenReader* reader,
                               dpcr::output::RunRecord* run) {
  static typename MapperType::ScanType scan;  // ~MiBs for big profiles: not on the stack
  const auto file_size = std::filesystem::file_size(opt.carmen);
  dpcr::carmen::Record rec;
  bool configured = false;
  dpcr::apps::Progress progress("replay");
  CarmenInputCounts counts;
  dpcr::carmen::LaserOdometry laser_odometry;
  try {
    while (reader->Next(&rec)) {
      if (!configured) {  // PARAM lines come first in CARMEN logs; the mount is fixed at the first record
        const dpcr::MapperConfig config = CarmenMapperConfig(opt, reader->front_laser_offset_m());
        if (mapper->Init(config) != dpcr::Status::kOk) throw std::runtime_error(dpcr::apps::InitError<MapperType>(config));
        LoadMapIfAsked(opt, mapper);
        configured = true;
      }
      if (rec.kind == dpcr::carmen::Record::Kind::kOdom) {
        if (opt.odometry == "odom") mapper->AddOdometry(Odometry(rec.odom.stamp_us, rec.odom.pose));
        continue;
      }
      // The odometry pose logged with the scan: exactly aligned in time with it, unless repeated.
      if (opt.odometry == "laser" && laser_odometry.IsNewMeasurement(rec.laser.odom_pose)) {
        mapper->AddOdometry(Odometry(rec.laser.stamp_us, rec.laser.odom_pose));
      }
      if (dpcr::carmen::ToScan(rec.laser, &scan)) ++counts.decimated_scans;
      dpcr::output::AddTimedScan(*mapper, scan, run);
      if ((run->estimate.size() & 63) == 0) progress.Update(static_cast<double>(in.tellg()) / static_cast<double>(file_size));
    }
  } catch (const dpcr::carmen::CarmenError& e) {
    progress.Done();
    throw std::runtime_error(opt.carmen + ":" + std::to_string(e.line()) + ": " +
                             std::string(e.what()).substr(std::string(e.what()).find(':') + 2));
  }
  progress.Done();
  counts.repeated_odometry = laser_odometry.repeats();
  return counts;
}

template <class Profile>
int ReplayCarmen(const Options& opt) {
  using MapperType = dpcr::Mapper<Profile>;
  static MapperType mapper;  // ~MiBs: static storage, as on the robot

  std::ifstream in(opt.carmen);
  if (!in) throw std::runtime_error(opt.carmen + ": cannot open");
  std::vector<dpcr::eval::Relation> relations;
  if (!opt.relations.empty()) relations = dpcr::eval::ReadRelationsFile(opt.relations);

  const auto start = Clock::now();
  dpcr::carmen::CarmenReader reader(in);
  dpcr::output::RunRecord run;
  run.write_regions = opt.write_regions;
  run.refine_trajectory = opt.refine_trajectory;
  const CarmenInputCounts counts = MapCarmenLog(opt, in, &mapper, &reader, &run);
  if (run.estimate.empty()) throw std::runtime_error(opt.carmen + ": no laser scans in the log");
  run.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (!opt.relations.empty()) run.relations = &relations;

  std::filesystem::create_directories(opt.out);
  dpcr::output::FinalizeTrajectory(mapper, &run);
  nlohmann::json metrics = dpcr::output::MapperMetrics(mapper);
  const auto& rc = reader.counters();
  metrics["input"] = {{"file", opt.carmen}, {"laser_records", rc.laser_records}, {"odom_records", rc.odom_records},
                      {"laser_timestamp_steps_back", rc.laser_steps_back}, {"other_messages", rc.other_messages},
                      {"decimated_scans", counts.decimated_scans}, {"odometry_source", opt.odometry},
                      {"repeated_odometry_poses_skipped", counts.repeated_odometry}};
  metrics = dpcr::output::WriteRunOutputs(opt.out, dpcr::output::RenderFused(mapper), run, metrics);

  PrintSummary(run, metrics, opt.out);
  SaveMapIfAsked(opt, mapper);
  dpcr::apps::WriteScanTimes(opt.scan_times, run);
  return 0;
}

// The device replay's outputs into the mapper, each AddScan timed and its pose recorded.
template <class MapperType>
class TimedMapperSink : public dpcr::DeviceSink {
 public:
  TimedMapperSink(MapperType* mapper, dpcr::output::RunRecord* run) : mapper_(mapper), run_(run) {}
  void AddOdometry(const dpcr::OdometrySample& sample) override { mapper_->AddOdometry(sample); }
  void AddScan(const dpcr::DeviceScan& scan) override {
    dpcr::output::AddTimedScan(*mapper_, scan, run_);  // a DeviceScan is the mapper's scan type
  }

 private:
  MapperType* mapper_;
  dpcr::output::RunRecord* run_;
};

// dpcr-replay --uart --candump: the whole device decode path (LD06/XV-11 bytes, CAN wheel frames).
template <class Profile>
int ReplayDevice(const Options& opt) {
  using MapperType = dpcr::Mapper<Profile>;
  static MapperType mapper;
  std::string lidar_name, description;
  const dpcr::DeviceOptions device = DeviceOptionsFor(opt, &lidar_name, &description);
  dpcr::DeviceFilesConfig files;
  files.angle_map = device.angle_map();
  files.wheels = device.wheels;
  dpcr::LidarStreamConfig lidar;
  if (lidar_name != "ld06" && lidar_name != "xv11") throw std::runtime_error(description + ": unknown lidar " + lidar_name);
  lidar.kind = lidar_name == "xv11" ? dpcr::LidarKind::kXv11 : dpcr::LidarKind::kLd06;
  lidar.assembler.angle_map = files.angle_map;
  lidar.timing = opt.lidar_timing == "device" ? dpcr::LidarTiming::kDeviceClock : dpcr::LidarTiming::kArrival;
  dpcr::output::RunRecord run;
  run.write_regions = opt.write_regions;
  run.refine_trajectory = opt.refine_trajectory;
  TimedMapperSink<MapperType> sink(&mapper, &run);
  dpcr::DeviceReplay replay(files, lidar, &sink);
  std::string error;
  if (!replay.Open(opt.uart, opt.candump, &error)) throw std::runtime_error(error);
  for (const dpcr::SkippedLines* s : {&replay.uart_skipped(), &replay.can_skipped()}) {
    if (s->count > 0) std::fprintf(stderr, "dpcr-replay: warning: %d line(s) skipped, first %s\n", s->count, s->first.c_str());
  }
  dpcr::MapperConfig config;
  device.ApplyTo(&config.lidar);
  dpcr::ApplyLidarModel(lidar.kind, &config.lidar);
  config.front_end.enable_registration = !opt.odometry_only;
  config.back_end.enable = !opt.front_end_only;
  // --heading: named, or the lidar model's (hal/device_options.hpp).
  config.front_end.gyro_heading = dpcr::GyroHeadingFor(opt.heading, lidar.kind);
  if (opt.region_width_m > 0.0f) config.front_end.region_width_m = opt.region_width_m;
  if (opt.max_accel_mps2 >= 0.0f) config.front_end.max_acceleration_mps2 = opt.max_accel_mps2;
  config.front_end.calibrate_odometry = opt.calibrate_odometry;
  ApplyLocalisationOptions(opt, &config);
  if (mapper.Init(config) != dpcr::Status::kOk) throw std::runtime_error(dpcr::apps::InitError<MapperType>(config));
  LoadMapIfAsked(opt, &mapper);
  const auto start = Clock::now();
  replay.Run();
  if (run.estimate.empty()) throw std::runtime_error(opt.uart + ": no complete lidar revolution decoded");
  run.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::filesystem::create_directories(opt.out);
  dpcr::output::FinalizeTrajectory(mapper, &run);
  nlohmann::json metrics = dpcr::output::MapperMetrics(mapper);
  const auto c = replay.counters();
  metrics["device"] = {{"description", description.empty() ? "none (defaults)" : description},
                       {"angle_sign", device.angle_sign}, {"wheel_radius_m", device.wheels.wheel_radius_m},
                       {"track_width_m", device.wheels.track_width_m}, {"ticks_per_rev", device.wheels.ticks_per_rev},
                       {"max_range_m", device.max_range_m}, {"laser_offset_m", device.laser_offset_m},
                       {"lidar_range_noise_m", config.lidar.range_noise_m},
                       {"lidar_smoothing_max_gap_beams", config.lidar.smoothing_max_gap_beams},
                       {"lidar_near_weight_range_m", config.lidar.near_weight_range_m},
                       {"lidar_map_max_turn_rate_dps", config.lidar.map_max_turn_rate_rad_s * 180.0 / M_PI},
                       {"heading", config.front_end.gyro_heading ? "gyro" : "wheels"},
                       {"max_acceleration_mps2", config.front_end.max_acceleration_mps2},
                       {"calibrate_odometry", config.front_end.calibrate_odometry}};
  metrics["input"] = {{"uart", opt.uart}, {"candump", opt.candump}, {"lidar", lidar_name},
                      {"packets", c.lidar.packets}, {"bad_packets", c.lidar.bad_packets}, {"resyncs", c.lidar.resyncs},
                      {"discarded_bytes", c.lidar.discarded_bytes}, {"revolutions", c.lidar.revolutions},
                      {"gaps", c.lidar.gaps}, {"decimated", c.lidar.decimated}, {"odometry", c.odometry},
                      {"status_frames", c.can.status_frames}, {"lifts", c.lifts}, {"lifted_odometry", c.lifted_samples},
                      {"uart_lines_skipped", replay.uart_skipped().count},
                      {"candump_lines_skipped", replay.can_skipped().count}};
  if (!opt.candump.empty() && c.odometry == 0) {
    std::fprintf(stderr, "dpcr-replay: warning: %s gave no odometry: the lidar mapped alone\n", opt.candump.c_str());
  }
  metrics = dpcr::output::WriteRunOutputs(opt.out, dpcr::output::RenderFused(mapper), run, metrics);
  PrintSummary(run, metrics, opt.out);
  SaveMapIfAsked(opt, mapper);
  dpcr::apps::WriteScanTimes(opt.scan_times, run);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dpcr-replay: map a recorded log and write map.pgm/.yaml/.png, trajectory.tum, metrics.json"};
  Options opt;
  app.add_option("--carmen", opt.carmen, "CARMEN log (FLASER / ROBOTLASER1 / ODOM lines)")->check(CLI::ExistingFile);
  app.add_option("--relations", opt.relations, "ground-truth relations file (t1 t2 x y z roll pitch yaw)")
      ->check(CLI::ExistingFile);
  app.add_option("--out", opt.out, "output directory")->capture_default_str();
  app.add_option("--profile", opt.profile, "capacity profile (default: building for --carmen, vacuum for --uart)")
      ->check(CLI::IsMember({"building", "vacuum"}));
  app.add_option("--odometry", opt.odometry, "odometry source: the pose logged with each scan, or ODOM lines")
      ->check(CLI::IsMember({"laser", "odom"}))->capture_default_str();
  app.add_option("--max-range", opt.max_range_m, "ignore returns farther than this (m); default: 20 for --carmen, "
                 "device.json or dpcr-firmware's for --uart");
  app.add_option("--laser-offset", opt.laser_offset_m, "lidar ahead of the robot centre (m); default: the log's PARAM (--carmen), "
                 "device.json or 0 (--uart)");
  app.add_option("--uart", opt.uart, "lidar UART capture (docs/uart-capture-format.md)")->check(CLI::ExistingFile);
  app.add_option("--candump", opt.candump, "wheel-encoder CAN log (candump -l format)")->check(CLI::ExistingFile);
  app.add_option("--lidar", opt.lidar, "lidar protocol in the UART capture")->check(CLI::IsMember({"ld06", "xv11"}))->capture_default_str();
  app.add_option("--lidar-timing", opt.lidar_timing, "LD06 packet times: arrival (the capture's stamps) or device (the packets' own clock)")
      ->check(CLI::IsMember({"arrival", "device"}))->capture_default_str();
  app.add_option("--angle-sign", opt.angle_sign, "+1: device angles counter-clockwise (dpcr-sim), -1: clockwise (an upright LD06); "
                 "default: device.json beside the capture, else -1 (as dpcr-firmware)")
      ->check(CLI::IsMember({1.0f, -1.0f}));
  app.add_option("--wheel-radius", opt.wheel_radius_m, "--uart: wheel radius (m); default: device.json, else dpcr-firmware's")
      ->check(CLI::PositiveNumber);
  app.add_option("--track-width", opt.track_width_m, "--uart: distance between the wheels (m); default: device.json, else dpcr-firmware's")
      ->check(CLI::PositiveNumber);
  app.add_option("--ticks-per-rev", opt.ticks_per_rev, "--uart: encoder ticks per wheel revolution; default: device.json, else dpcr-firmware's")
      ->check(CLI::PositiveNumber);
  app.add_flag("--odometry-only", opt.odometry_only, "map with dead reckoning only (for comparison)");
  app.add_flag("--front-end-only", opt.front_end_only, "map without the back end (no region graph, no loop closures; for comparison)");
  app.add_option("--load-map", opt.load_map, "start from this saved map (same --profile; dpcr-map info FILE shows it)");
  app.add_option("--start-pose", opt.start_pose, "with --load-map: the robot's start pose in the saved map's frame (x,y,theta); "
                 "without it the start pose is unknown and searched for in the maps")
      ->expected(3)->delimiter(',');
  app.add_flag("--localise-only", opt.localise_only, "with --load-map: maps frozen (nothing inserted, no new region, graph unchanged)");
  app.add_option("--save-map", opt.save_map, "save the map at the end (atomically), for --load-map and dpcr-map");
  app.add_option("--max-accel", opt.max_accel_mps2, "the robot's largest acceleration (m/s^2): without wheel translation the "
                 "constant-velocity guess changes by no more (default: the configuration's, 0.5; 0: no limit)");
  app.add_option("--region-width", opt.region_width_m, "region width S in metres (default: the configuration's, 4 m)")
      ->check(CLI::PositiveNumber);
  app.add_option("--calibrate-odometry", opt.calibrate_odometry, "calibrate the wheels' step and turn scales online from the "
                 "registrations and predict with them (FrontEndConfig::calibrate_odometry; core/front_end/odometry_calibration.hpp)")
      ->default_str("true");
  app.add_option("--scan-times", opt.scan_times, "write the time of every AddScan call (ms, one per line) to this file");
  app.add_flag("--write-regions", opt.write_regions,
               "also write regions.tsv (each scan's map and pose in it) and graph.tsv (final anchors and edges)");
  app.add_option("--refine-trajectory", opt.refine_trajectory,
                 "register each scan again in its finished map at the end (trajectory.tum; the maps are the same "
                 "either way); false: each scan as the run placed it")
      ->default_val(true);
  app.add_option("--heading", opt.heading, "--uart: the prediction's heading increment: wheels, or the integrated gyro frames (0x121); "
                 "model: the gyro for an xv11, the wheels for an ld06")
      ->check(CLI::IsMember({"model", "wheels", "gyro"}))->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  for (const CLI::Option* o : app.get_options()) {
    if (o->count() > 0) opt.given.insert(o->get_name());
  }
  if (opt.localise_only && opt.load_map.empty()) {
    std::fprintf(stderr, "dpcr-replay: error: --localise-only needs --load-map\n");
    return 2;
  }
  if (opt.carmen.empty() == opt.uart.empty()) {
    std::fprintf(stderr, "dpcr-replay: give either --carmen FILE or --uart FILE [--candump FILE]\n%s", app.help().c_str());
    return 2;
  }
  try {
    CheckApplicable(opt);
    if (!opt.save_map.empty()) dpcr::output::PrepareMapFileDir(opt.save_map);
    if (!opt.uart.empty()) {
      return opt.profile == "building" ? ReplayDevice<dpcr::BuildingProfile>(opt) : ReplayDevice<dpcr::VacuumProfile>(opt);
    }
    return opt.profile == "vacuum" ? ReplayCarmen<dpcr::VacuumProfile>(opt) : ReplayCarmen<dpcr::BuildingProfile>(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dpcr-replay: error: %s\n", e.what());
    return 1;
  }
}
