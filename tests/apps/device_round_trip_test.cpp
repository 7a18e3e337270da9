// The device path end to end: a simulated run mapped directly, and the same run written as
// device files (LD06 UART capture + candump wheel log), decoded and mapped again, give the same
// trajectory within the devices' quantisation (1 mm range, 0.01 deg angle, one encoder tick); and
// with the lidar's bytes handed over in bursts, as a USB-serial adapter does.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "core/front_end/odometry_buffer.hpp"
#include "core/mapper.hpp"
#include "host_sim/drivers/device_files.hpp"
#include "host_sim/sim/simulation.hpp"
#include "host_sim/sim/world.hpp"
#include "tests/support/temp_dir.hpp"

namespace {
using MapperType = dpcr::Mapper<dpcr::VacuumProfile>;

std::unique_ptr<MapperType> NewMapper(bool registration) {
  auto m = std::make_unique<MapperType>();
  dpcr::MapperConfig config;
  config.front_end.enable_registration = registration;
  REQUIRE(m->Init(config) == dpcr::Status::kOk);
  return m;
}

struct RoundTrip {
  std::size_t scans = 0;
  std::size_t matched = 0;
  double max_diff_m = 0.0;
  double max_diff_rad = 0.0;
};

// Maps the replayed device files and compares each pose with the direct run's at its stamp.
class ComparingSink : public dpcr::DeviceSink {
 public:
  ComparingSink(MapperType* device, const std::map<std::int64_t, dpcr::Pose2>* direct_poses, RoundTrip* result,
                std::int64_t tolerance_us)
      : device_(device), direct_poses_(direct_poses), r_(result), tolerance_us_(tolerance_us) {}
  void AddOdometry(const dpcr::OdometrySample& sample) override { device_->AddOdometry(sample); }
  void AddScan(const dpcr::DeviceScan& scan) override {
    (void)device_->AddScan(scan);
    // Stamps are reproduced to a few microseconds: the direct scan's pose within 1 ms. Bunched
    // arrivals stamp a scan up to a burst late: the direct trajectory interpolated at its stamp.
    dpcr::Pose2 direct;
    auto near = direct_poses_->lower_bound(scan.stamp_us - 1000);
    if (near != direct_poses_->end() && std::llabs(near->first - scan.stamp_us) <= 1000) {
      direct = near->second;
    } else {
      auto after = direct_poses_->lower_bound(scan.stamp_us);
      if (after == direct_poses_->end() || after == direct_poses_->begin()) return;
      auto before = std::prev(after);
      if (after->first - scan.stamp_us > tolerance_us_ && scan.stamp_us - before->first > tolerance_us_) return;
      const float t = static_cast<float>(scan.stamp_us - before->first) / static_cast<float>(after->first - before->first);
      direct = dpcr::Interpolate(before->second, after->second, t);
    }
    // Each mapper's frame is its own first pose: compare motion since the first matched scan.
    if (r_->matched++ == 0) {
      first_direct_ = direct;
      first_device_ = device_->pose();
      return;
    }
    const dpcr::Pose2 a = dpcr::Between(first_direct_, direct);
    const dpcr::Pose2 b = dpcr::Between(first_device_, device_->pose());
    r_->max_diff_m = std::max(r_->max_diff_m, static_cast<double>(std::hypot(a.x - b.x, a.y - b.y)));
    r_->max_diff_rad =
        std::max(r_->max_diff_rad, static_cast<double>(std::fabs(dpcr::NormalizeAngle(a.theta - b.theta))));
  }

 private:
  MapperType* device_;
  const std::map<std::int64_t, dpcr::Pose2>* direct_poses_;
  RoundTrip* r_;
  std::int64_t tolerance_us_;
  dpcr::Pose2 first_direct_, first_device_;
};

// A USB-serial adapter hands the lidar's bytes over in bursts (an FTDI's latency timer: 16 ms):
// every chunk of the capture is stamped at the end of its burst instead of when it arrived.
void BunchArrivals(const std::string& path, double burst_s) {
  std::ifstream in(path);
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t space = line.find(' ');
    if (line.empty() || line[0] == '#' || space == std::string::npos) {
      out << line << '\n';
      continue;
    }
    const double t = std::stod(line.substr(0, space));
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "%.6f", std::ceil(t / burst_s) * burst_s);
    out << stamp << line.substr(space) << '\n';
  }
  in.close();
  std::ofstream(path) << out.str();
}

RoundTrip MapBothWays(bool registration, double burst_s = 0.0, dpcr::LidarTiming timing = dpcr::LidarTiming::kArrival) {
  const dpcr::test::ScopedTempDir temp(registration ? "round_trip_front_end" : "round_trip_odometry");
  const auto& dir = temp.path();
  dpcr::sim::SimConfig config;
  config.duration_min = 0.5;
  config.seed = 7;
  const dpcr::sim::World world = dpcr::sim::LoadBuiltinWorld("apartment");  // outlives the simulation
  dpcr::sim::Simulation sim(world, config);

  auto direct = NewMapper(registration);
  dpcr::DeviceEmitter emitter;
  std::string error;
  REQUIRE(emitter.Open(dir.string(), &error));
  std::map<std::int64_t, dpcr::Pose2> direct_poses;
  dpcr::sim::SimEvent e;
  static MapperType::ScanType scan;
  while (sim.Step(&e)) {
    if (e.type == dpcr::sim::SimEventType::kOdometry) {
      direct->AddOdometry(e.odometry);
      emitter.AddOdometry(e.odometry);
      continue;
    }
    REQUIRE(emitter.AddScan(e.scan));
    scan.stamp_us = e.scan.stamp_us;
    scan.beams.clear();
    for (const auto& b : e.scan.beams) (void)scan.beams.push_back(b);
    (void)direct->AddScan(scan);
    direct_poses[scan.stamp_us] = direct->pose();
  }
  REQUIRE(emitter.Close(&error));
  if (burst_s > 0.0) BunchArrivals((dir / "lidar.uart").string(), burst_s);

  dpcr::DeviceFilesConfig files;
  dpcr::LidarStreamConfig lidar;
  lidar.assembler.angle_map = files.angle_map;
  lidar.timing = timing;
  auto device = NewMapper(registration);
  RoundTrip r;
  r.scans = direct_poses.size();
  ComparingSink sink(device.get(), &direct_poses, &r, 1000 + static_cast<std::int64_t>(burst_s * 1e6));
  dpcr::DeviceReplay replay(files, lidar, &sink);
  REQUIRE(replay.Open((dir / "lidar.uart").string(), (dir / "wheels.log").string(), &error));
  replay.Run();
  return r;
}

}  // namespace

TEST_CASE("The device path reproduces the direct simulation's odometry-pipeline trajectory") {
  // Dead reckoning + de-skew: the only differences are the devices' quantisation.
  const RoundTrip r = MapBothWays(false);
  INFO("matched " << r.matched << " of " << r.scans << " scans; max difference " << r.max_diff_m << " m, "
                  << r.max_diff_rad << " rad");
  REQUIRE(r.matched + 3 >= r.scans);  // the device path may drop a partial first/last revolution
  CHECK(r.max_diff_m < 0.002);
  CHECK(r.max_diff_rad < 0.002);
}

TEST_CASE("The device path gives the direct simulation's trajectory through the full front end") {
  // Registration is iterative (trimming, gates): quantised inputs may converge a little apart.
  const RoundTrip r = MapBothWays(true);
  INFO("matched " << r.matched << " of " << r.scans << " scans; max difference " << r.max_diff_m << " m, "
                  << r.max_diff_rad << " rad");
  REQUIRE(r.matched + 3 >= r.scans);
  CHECK(r.max_diff_m < 0.03);
  CHECK(r.max_diff_rad < 0.015);
}

TEST_CASE("Lidar bytes in 16 ms bursts keep their timing when stamped by the LD06 clock") {
  // A USB-serial adapter's latency timer hands the bytes over in bursts: arrival stamps (the
  // default, LidarTiming::kArrival) put about six LD06 packets at one time, up to 16 ms late, and
  // the de-skew of a turning robot with them; the LD06's own millisecond clock, mapped to host
  // time by its least-delayed packets (DeviceTimeBase), does not care when the bytes came.
  const RoundTrip arrival = MapBothWays(true, 0.016, dpcr::LidarTiming::kArrival);
  const RoundTrip device = MapBothWays(true, 0.016, dpcr::LidarTiming::kDeviceClock);
  INFO("arrival: matched " << arrival.matched << " of " << arrival.scans << "; max difference " << arrival.max_diff_m
                           << " m, " << arrival.max_diff_rad << " rad");
  INFO("device clock: matched " << device.matched << " of " << device.scans << "; max difference "
                                << device.max_diff_m << " m, " << device.max_diff_rad << " rad");
  REQUIRE(device.matched + 3 >= device.scans);
  REQUIRE(arrival.matched + 3 >= arrival.scans);
  CHECK(device.max_diff_m < 0.02);
  CHECK(device.max_diff_rad < 0.008);
  CHECK(device.max_diff_rad < 0.5 * arrival.max_diff_rad);
}
