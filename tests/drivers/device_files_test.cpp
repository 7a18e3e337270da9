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

// The run written as device files into `dir`.
void Emit(const Run& run, const dpcr::DeviceFilesConfig& files, const std::string& dir) {
  dpcr::DeviceEmitter emitter(files);
  std::string error;
  REQUIRE(emitter.Open(dir, &error));
  for (const auto& s : run.scans) REQUIRE(emitter.AddScan(*s));
  for (const auto& o : run.odometry) emitter.AddOdometry(o);
  REQUIRE(emitter.Close(&error));
}

}  // namespace

TEST_CASE("emit device files then replay gives the same scans and trajectory") {
  const Run run = MakeRun();
  const dpcr::test::ScopedTempDir temp("device_files");
  const std::string dir = temp.str();
  dpcr::DeviceFilesConfig files;
  Emit(run, files, dir);
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

namespace {
// Overwrites one character of every `every`-th line of `path` past its first with `c`.
void SpoilLines(const std::string& path, int every, char c) {
  std::ifstream in(path);
  std::string text, line;
  for (int n = 0; std::getline(in, line); ++n) {
    if (n > 0 && n % every == 0) line[3] = c;
    text += line + "\n";
  }
  in.close();
  std::ofstream(path) << text;
}

struct CountingSink : dpcr::DeviceSink {
  std::size_t odometry = 0, scans = 0;
  void AddOdometry(const dpcr::OdometrySample&) override { ++odometry; }
  void AddScan(const dpcr::DeviceScan&) override { ++scans; }
};
}  // namespace

TEST_CASE("a flipped byte costs the replay its line and a file of bad lines is refused") {
  const Run run = MakeRun();
  const dpcr::test::ScopedTempDir temp("device_skips");
  const std::string dir = temp.str();
  dpcr::DeviceFilesConfig files;
  Emit(run, files, dir);
  SpoilLines(dir + "/lidar.uart", 40, 'Z');  // a handful of chunks
  SpoilLines(dir + "/wheels.log", 100, 'Z');
  dpcr::LidarStreamConfig lidar;
  lidar.assembler.angle_map = files.angle_map;
  CountingSink sink;
  std::string error;
  {
    dpcr::DeviceReplay replay(files, lidar, &sink);
    REQUIRE(replay.Open(dir + "/lidar.uart", dir + "/wheels.log", &error));
    CHECK(replay.uart_skipped().count > 0);
    CHECK(replay.can_skipped().count > 0);
    CHECK(replay.can_skipped().first.find("wheels.log:") != std::string::npos);
    replay.Run();
    // The rest is read: the revolutions and the odometry samples but for a few.
    CHECK(sink.scans + 3 >= run.scans.size());
    CHECK(sink.odometry + 10 >= run.odometry.size());
  }
  SpoilLines(dir + "/wheels.log", 1, 'Z');  // every line
  dpcr::DeviceReplay replay(files, lidar, &sink);
  CHECK_FALSE(replay.Open(dir + "/lidar.uart", dir + "/wheels.log", &error));
  CHECK(error.find("lines do not parse") != std::string::npos);
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

namespace {

// The run with the wheels lifted from sample `from` to before `to`.
Run MakeLiftedRun(int from, int to) {
  Run run = MakeRun();
  for (int i = from; i < to; ++i) run.odometry[static_cast<std::size_t>(i)].lifted = true;
  return run;
}

struct Replayed {
  std::vector<dpcr::OdometrySample> odometry;
  dpcr::DevicePipelineCounters counters;
};

// Only the odometry (on a realistic bus scans and samples interleave by arrival, not device time).
struct OdometrySink : dpcr::DeviceSink {
  void AddOdometry(const dpcr::OdometrySample& sample) override { odometry.push_back(sample); }
  void AddScan(const dpcr::DeviceScan&) override {}
  std::vector<dpcr::OdometrySample> odometry;
};

Replayed Replay(const dpcr::DeviceFilesConfig& files, const std::string& dir) {
  dpcr::LidarStreamConfig lidar;
  lidar.assembler.angle_map = files.angle_map;
  OdometrySink sink;
  dpcr::DeviceReplay replay(files, lidar, &sink);
  std::string error;
  REQUIRE(replay.Open(dir + "/lidar.uart", dir + "/wheels.log", &error));
  replay.Run();
  return Replayed{sink.odometry, replay.counters()};
}

std::vector<dpcr::CandumpRecord> ReadLog(const std::string& path) {
  std::vector<dpcr::CandumpRecord> records;
  std::string error;
  REQUIRE(dpcr::ReadCandumpLog(path, &records, &error));
  return records;
}

}  // namespace

TEST_CASE("the emitter's status frames carry the lift flag through the replay, on an ideal and a realistic bus") {
  const Run run = MakeLiftedRun(125, 185);  // lifted 1.25 s to 1.85 s
  dpcr::DeviceFilesConfig files;
  const bool realistic = GENERATE(false, true);
  if (realistic) dpcr::RealisticBus(&files, 7);
  const dpcr::test::ScopedTempDir temp("device_lift");
  Emit(run, files, temp.str());
  // A status frame at the start, on each change, and never more than 100 ms of device time apart.
  std::vector<std::uint32_t> times;
  std::string flags;
  for (const dpcr::CandumpRecord& r : ReadLog(temp.str() + "/wheels.log")) {
    if (r.frame.id != dpcr::kStatusCanId) continue;
    flags += static_cast<char>('0' + r.frame.data[0]);
    times.push_back(static_cast<std::uint32_t>(r.frame.data[2] | r.frame.data[3] << 8 | r.frame.data[4] << 16));
  }
  // 0, 0.1, .., 1.2 s down; 1.25 (the lift), 1.35, .., 1.75 up; 1.85 (the put-down), 1.95, .., 2.95 down.
  CHECK(flags == std::string(13, '0') + std::string(6, '1') + std::string(12, '0'));
  for (std::size_t i = 1; i < times.size(); ++i) CHECK(times[i] - times[i - 1] <= 10000 + (realistic ? 1 : 0));
  const Replayed replayed = Replay(files, temp.str());
  REQUIRE(replayed.odometry.size() == run.odometry.size());
  for (std::size_t i = 0; i < run.odometry.size(); ++i) {
    INFO("sample " << i);
    CHECK(replayed.odometry[i].lifted == run.odometry[i].lifted);
  }
  CHECK(replayed.counters.lifts == 1);
  CHECK(replayed.counters.lifted_samples == 60);
  CHECK(replayed.counters.can.status_frames == times.size());
  CHECK(replayed.counters.can.lost == 0);
}

TEST_CASE("status frames leave every other frame's arrival as it was (logs from before them replay the same)") {
  const Run run = MakeLiftedRun(120, 180);
  dpcr::DeviceFilesConfig files;
  dpcr::RealisticBus(&files, 3);
  const dpcr::test::ScopedTempDir with("device_status_on");
  const dpcr::test::ScopedTempDir without("device_status_off");
  Emit(run, files, with.str());
  files.status_period_us = 0;  // a robot without the status frame
  Emit(run, files, without.str());
  std::vector<dpcr::CandumpRecord> stripped;
  for (const dpcr::CandumpRecord& r : ReadLog(with.str() + "/wheels.log")) {
    if (r.frame.id != dpcr::kStatusCanId) stripped.push_back(r);
  }
  const std::vector<dpcr::CandumpRecord> old = ReadLog(without.str() + "/wheels.log");
  REQUIRE(stripped.size() == old.size());
  for (std::size_t i = 0; i < old.size(); ++i) {
    REQUIRE(dpcr::FormatCandumpLine(stripped[i]) == dpcr::FormatCandumpLine(old[i]));
  }
  // Without status frames the replay never lifts the robot, whatever the run did.
  const Replayed replayed = Replay(files, without.str());
  CHECK(replayed.counters.lifted_samples == 0);
  CHECK(replayed.counters.can.status_frames == 0);
  REQUIRE(replayed.odometry.size() == run.odometry.size());
  for (const dpcr::OdometrySample& o : replayed.odometry) REQUIRE_FALSE(o.lifted);
}
