// The device path end to end: a simulated run mapped directly, and the same run written as
// device files (LD06 UART capture + candump wheel log), decoded and mapped again, give the same
// trajectory within the devices' quantisation (1 mm range, 0.01 deg angle, one encoder tick).
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <memory>
#include <string>

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

// Maps the replayed device files and compares each pose with the direct run's at the same scan.
class ComparingSink : public dpcr::DeviceSink {
 public:
  ComparingSink(MapperType* device, const std::map<std::int64_t, dpcr::Pose2>* direct_poses, RoundTrip* result)
      : device_(device), direct_poses_(direct_poses), r_(result) {}
  void AddOdometry(const dpcr::OdometrySample& sample) override { device_->AddOdometry(sample); }
  void AddScan(const dpcr::DeviceScan& scan) override {
    (void)device_->AddScan(scan);
    // Stamps are reproduced to a few microseconds: match the nearest direct scan.
    auto it = direct_poses_->lower_bound(scan.stamp_us - 1000);
    if (it == direct_poses_->end() || std::llabs(it->first - scan.stamp_us) > 1000) return;
    // Each mapper's frame is its own first pose: compare motion since the first matched scan.
    if (r_->matched++ == 0) {
      first_direct_ = it->second;
      first_device_ = device_->pose();
      return;
    }
    const dpcr::Pose2 a = dpcr::Between(first_direct_, it->second);
    const dpcr::Pose2 b = dpcr::Between(first_device_, device_->pose());
    r_->max_diff_m = std::max(r_->max_diff_m, static_cast<double>(std::hypot(a.x - b.x, a.y - b.y)));
    r_->max_diff_rad =
        std::max(r_->max_diff_rad, static_cast<double>(std::fabs(dpcr::NormalizeAngle(a.theta - b.theta))));
  }

 private:
  MapperType* device_;
  const std::map<std::int64_t, dpcr::Pose2>* direct_poses_;
  RoundTrip* r_;
  dpcr::Pose2 first_direct_, first_device_;
};

RoundTrip MapBothWays(bool registration) {
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

  dpcr::DeviceFilesConfig files;
  dpcr::LidarStreamConfig lidar;
  lidar.assembler.angle_map = files.angle_map;
  auto device = NewMapper(registration);
  RoundTrip r;
  r.scans = direct_poses.size();
  ComparingSink sink(device.get(), &direct_poses, &r);
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
