#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "host_sim/drivers/device_files.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

// A simulator-like run: 3 s on an arc (0.3 m/s, 0.4 rad/s), odometry at 100 Hz, scans at 10 Hz.
struct Run {
  std::vector<dpcr::OdometrySample> odometry;
  std::vector<std::unique_ptr<dpcr::DeviceScan>> scans;
};

Run MakeRun() {
  Run run;
  const std::int64_t t0 = 1700000000000000;
  for (int i = 0; i <= 300; ++i) {
    const double t = i * 0.01;
    dpcr::OdometrySample s;
    s.stamp_us = t0 + i * 10000;
    const double th = 0.4 * t;
    s.pose = dpcr::Pose2{static_cast<float>(0.75 * std::sin(th)), static_cast<float>(0.75 * (1 - std::cos(th))),
                         static_cast<float>(th)};
    s.has_gyro = true;
    s.gyro_yaw_rate = 0.4f;
    run.odometry.push_back(s);
  }
  for (int k = 0; k < 30; ++k) {
    auto scan = std::make_unique<dpcr::DeviceScan>();
    scan->stamp_us = t0 + 5000 + k * 100000;
    for (int i = 0; i < 450; ++i) {
      dpcr::Beam b;
      b.angle_rad = dpcr::NormalizeAngle(2 * dpcr::kPi * static_cast<float>(i) / 450.0f);  // dpcr-sim order: from 0
      b.range_m = 1.0f + 0.5f * std::sin(static_cast<float>(i + k) * 0.1f);
      b.offset_us = static_cast<std::int32_t>(std::lround(100000.0 * i / 450));
      REQUIRE(scan->beams.push_back(b) == dpcr::Status::kOk);
    }
    run.scans.push_back(std::move(scan));
  }
  return run;
}

// Keeps the replay's odometry; checks each scan against the emitted one as it arrives.
class CheckingSink : public dpcr::DeviceSink {
 public:
  explicit CheckingSink(const Run* run) : run_(run) {}
  void AddOdometry(const dpcr::OdometrySample& sample) override { odometry.push_back(sample); }
  void AddScan(const dpcr::DeviceScan& out) override {
    // Matches the emitted scan, and comes after the odometry up to its end.
    REQUIRE(scans < run_->scans.size());
    const dpcr::DeviceScan& in = *run_->scans[scans];
    CHECK(out.stamp_us == Approx(in.stamp_us).margin(3));
    REQUIRE(out.beams.size() == in.beams.size());
    for (std::size_t i = 0; i < in.beams.size(); ++i) {
      REQUIRE(std::fabs(out.beams[i].range_m - in.beams[i].range_m) < 0.0006f);
    }
    REQUIRE_FALSE(odometry.empty());
    CHECK(odometry.back().stamp_us >= out.stamp_us + out.beams.back().offset_us - 10000);
    ++scans;
  }

  std::vector<dpcr::OdometrySample> odometry;
  std::size_t scans = 0;

 private:
  const Run* run_;
};

}  // namespace

TEST_CASE("emit device files then replay gives the same scans and trajectory") {
  const Run run = MakeRun();
  const dpcr::test::ScopedTempDir temp("device_files");
  const std::string dir = temp.str();
  dpcr::DeviceFilesConfig files;
  {
    dpcr::DeviceEmitter emitter(files);
    std::string error;
    REQUIRE(emitter.Open(dir, &error));
    for (const auto& s : run.scans) REQUIRE(emitter.AddScan(*s));
    for (const auto& o : run.odometry) emitter.AddOdometry(o);
    REQUIRE(emitter.Close(&error));
  }
  dpcr::LidarStreamConfig lidar;
  lidar.assembler.angle_map = files.angle_map;
  CheckingSink sink(&run);
  dpcr::DeviceReplay replay(files, lidar, &sink);
  std::string error;
  REQUIRE(replay.Open(dir + "/lidar.uart", dir + "/wheels.log", &error));
  replay.Run();
  const std::vector<dpcr::OdometrySample>& odo = sink.odometry;
  CHECK(sink.scans == run.scans.size());  // the last revolution too (DevicePipeline::FlushLidar)
  REQUIRE(odo.size() == run.odometry.size());
  double max_err = 0.0;
  for (std::size_t i = 0; i < odo.size(); ++i) {
    CHECK(odo[i].stamp_us == run.odometry[i].stamp_us);
    CHECK(odo[i].has_gyro);
    CHECK(odo[i].gyro_yaw_rate == Approx(0.4f));
    // Replay odometry starts at the origin; the run starts at the origin too.
    const double e = std::hypot(static_cast<double>(odo[i].pose.x - run.odometry[i].pose.x),
                                static_cast<double>(odo[i].pose.y - run.odometry[i].pose.y));
    max_err = e > max_err ? e : max_err;
    REQUIRE(std::fabs(dpcr::NormalizeAngle(odo[i].pose.theta - run.odometry[i].pose.theta)) < 1e-3f);
  }
  std::printf("device round trip: max position difference %.6f m over %zu odometry samples\n", max_err, odo.size());
  CHECK(max_err < 1e-3);
  const dpcr::DevicePipelineCounters c = replay.counters();
  CHECK(c.lidar.bad_packets == 0);
  CHECK(c.can.lost == 0);
  CHECK(c.scans == 30);  // the last revolution included
}

TEST_CASE("the emitter describes the device in device.json, which reads back as the device options") {
  const dpcr::test::ScopedTempDir temp("device_json");
  const std::string dir = temp.str();
  dpcr::DeviceFilesConfig files;
  files.max_range_m = 8.0f;
  files.laser_offset_m = 0.05f;
  {
    dpcr::DeviceEmitter emitter(files);
    std::string error;
    REQUIRE(emitter.Open(dir, &error));
    REQUIRE(emitter.Close(&error));
  }
  dpcr::DeviceOptions options;  // the firmware's defaults: clockwise, 1000 ticks
  REQUIRE(options.angle_sign == -1.0f);
  std::string lidar = "xv11", error;
  REQUIRE(dpcr::ReadDeviceDescription(dir + "/device.json", &options, &lidar, &error));
  CHECK(lidar == "ld06");
  CHECK(options.angle_sign == files.angle_map.angle_sign);
  CHECK(options.wheels.ticks_per_rev == files.wheels.ticks_per_rev);
  CHECK(options.wheels.wheel_radius_m == files.wheels.wheel_radius_m);
  CHECK(options.wheels.track_width_m == files.wheels.track_width_m);
  CHECK(options.max_range_m == 8.0f);
  CHECK(options.laser_offset_m == 0.05f);
  // No description: nothing changes, no error; a malformed one: an error naming it.
  dpcr::DeviceOptions untouched;
  REQUIRE(dpcr::ReadDeviceDescription(dir + "/none.json", &untouched, &lidar, &error));
  CHECK(untouched.wheels.ticks_per_rev == dpcr::DeviceOptions{}.wheels.ticks_per_rev);
  {
    std::ofstream bad(dir + "/bad.json");
    bad << "{ \"angle_sign\": ";
  }
  REQUIRE_FALSE(dpcr::ReadDeviceDescription(dir + "/bad.json", &untouched, &lidar, &error));
  CHECK(error.find("bad.json") != std::string::npos);
}
