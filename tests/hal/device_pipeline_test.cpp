// The device pipeline: lidar bytes reach the sink as the revolutions a hand-driven LidarStream
// assembles, CAN frames as the odometry DiffDriveOdometry integrates, on the wheel board's clock
// and carrying the last gyro rate.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "hal/device_pipeline.hpp"
#include "lidar_stream_helpers.hpp"

namespace {

constexpr double kTwoPi = 6.283185307179586;

struct RecordingSink : dpcr::DeviceSink {
  void AddOdometry(const dpcr::OdometrySample& sample) override {
    odometry.push_back(sample);
    order.push_back('o');
  }
  void AddScan(const dpcr::DeviceScan& scan) override {
    scans.push_back(std::make_unique<dpcr::DeviceScan>(scan));
    order.push_back('s');
  }
  std::vector<dpcr::OdometrySample> odometry;
  std::vector<std::unique_ptr<dpcr::DeviceScan>> scans;
  std::vector<char> order;
};

dpcr::CanFrame Ticks(std::uint16_t left, std::uint16_t right, std::uint8_t sequence, std::uint32_t time_10us) {
  dpcr::WheelTicksFrame f;
  f.left_ticks = left;
  f.right_ticks = right;
  f.sequence = sequence;
  f.time_10us = time_10us;
  return dpcr::EncodeWheelFrame(f);
}

dpcr::CanFrame Gyro(std::int16_t mrad_s, std::uint8_t sequence, std::uint32_t time_10us) {
  dpcr::GyroFrame g;
  g.yaw_rate_mrad_s = mrad_s;
  g.sequence = sequence;
  g.time_10us = time_10us;
  return dpcr::EncodeGyroFrame(g);
}

dpcr::CanFrame Status(bool lifted, std::uint8_t sequence, std::uint32_t time_10us) {
  dpcr::StatusFrame f;
  f.flags = lifted ? dpcr::kStatusLiftedFlag : 0;
  f.sequence = sequence;
  f.time_10us = time_10us;
  return dpcr::EncodeStatusFrame(f);
}

// Ticks frames every 10 ms of device time from 0 (sequence k, 1 tick a frame), each received
// 1 ms after it was taken; `status_at(k)` is called before frame k to feed status frames.
template <class StatusAt>
std::vector<dpcr::OdometrySample> RunTicks(int frames, StatusAt status_at, dpcr::DevicePipelineCounters* counters = nullptr) {
  RecordingSink sink;
  auto pipeline = std::make_unique<dpcr::DevicePipeline>(dpcr::DevicePipelineConfig{}, &sink);
  for (int k = 0; k < frames; ++k) {
    const std::int64_t received_us = 1000000 + k * 10000 + 1000;
    status_at(k, pipeline.get(), received_us);
    const auto u = static_cast<std::uint16_t>(k);
    pipeline->FeedCan(Ticks(u, u, static_cast<std::uint8_t>(k), static_cast<std::uint32_t>(k * 1000)), received_us);
  }
  if (counters != nullptr) *counters = pipeline->counters();
  return sink.odometry;
}

// The indices of the samples marked lifted, as a string of 0/1.
std::string LiftedPattern(const std::vector<dpcr::OdometrySample>& odometry) {
  std::string s;
  for (const dpcr::OdometrySample& o : odometry) s += o.lifted ? '1' : '0';
  return s;
}

}  // namespace

TEST_CASE("pipeline: lidar bytes become the assembler's revolutions, one per FeedLidar call") {
  const std::vector<std::uint8_t> bytes = dpcr_test::EncodeAll(dpcr_test::MakeLd06Packets(3, 3600, 100));
  RecordingSink sink;
  auto pipeline = std::make_unique<dpcr::DevicePipeline>(dpcr::DevicePipelineConfig{}, &sink);
  const std::int64_t arrival_us = 5000000;
  const std::size_t first = pipeline->FeedLidar(bytes.data(), bytes.size(), arrival_us);
  CHECK(first < bytes.size());  // stopped at the end of the first revolution
  CHECK(first % dpcr::kLd06PacketBytes == 0);
  REQUIRE(sink.scans.size() == 1);
  pipeline->FeedAllLidar(bytes.data() + first, bytes.size() - first, arrival_us);

  // The oracle: the same bytes through a LidarStream driven by hand.
  auto stream = std::make_unique<dpcr::LidarStream>();
  auto expected = std::make_unique<dpcr::DeviceScan>();
  std::size_t used = 0, revolution = 0;
  while (used < bytes.size()) {
    used += stream->Feed(bytes.data() + used, bytes.size() - used, arrival_us);
    if (!stream->revolution_ready()) continue;
    stream->TakeScan(expected.get());
    REQUIRE(revolution < sink.scans.size());
    const dpcr::DeviceScan& got = *sink.scans[revolution++];
    CHECK(got.stamp_us == expected->stamp_us);
    REQUIRE(got.beams.size() == expected->beams.size());
    for (std::size_t i = 0; i < got.beams.size(); ++i) {
      REQUIRE(got.beams[i].range_m == expected->beams[i].range_m);
      REQUIRE(got.beams[i].angle_rad == expected->beams[i].angle_rad);
    }
  }
  CHECK(revolution == 2);  // the third revolution never closes
  CHECK(sink.scans.size() == 2);
  const dpcr::DevicePipelineCounters c = pipeline->counters();
  CHECK(c.scans == 2);
  CHECK(c.lidar.revolutions == 2);
  CHECK(c.lidar.packets == bytes.size() / dpcr::kLd06PacketBytes);
  CHECK(pipeline->last_lidar_packet_us() != 0);
}

TEST_CASE("pipeline: ticks frames become odometry, gyro frames set the rate the next samples carry") {
  RecordingSink sink;
  dpcr::DevicePipelineConfig config;
  config.wheels.wheel_radius_m = 0.05f;
  config.wheels.ticks_per_rev = 1000.0f;
  auto pipeline = std::make_unique<dpcr::DevicePipeline>(config, &sink);
  pipeline->FeedCan(Ticks(100, 100, 0, 0), 1000000);
  pipeline->FeedCan(Ticks(300, 300, 1, 1000), 1010000);   // 200 ticks forward
  pipeline->FeedCan(Gyro(-250, 0, 1500), 1015000);        // no sample of its own
  dpcr::CanFrame foreign = Ticks(0, 0, 2, 2000);
  foreign.id = 0x300;
  pipeline->FeedCan(foreign, 1018000);                    // ignored
  pipeline->FeedCan(Ticks(500, 500, 2, 2000), 1020000);   // 200 more

  REQUIRE(sink.odometry.size() == 3);
  const double m_per_tick = kTwoPi * 0.05 / 1000.0;
  CHECK(sink.odometry[0].pose.x == 0.0f);
  CHECK(sink.odometry[1].pose.x == Approx(200 * m_per_tick).epsilon(1e-5));
  CHECK(sink.odometry[2].pose.x == Approx(400 * m_per_tick).epsilon(1e-5));
  CHECK(sink.odometry[2].pose.y == Approx(0.0).margin(1e-6));
  CHECK_FALSE(sink.odometry[0].has_gyro);
  CHECK_FALSE(sink.odometry[1].has_gyro);
  CHECK(sink.odometry[2].has_gyro);
  CHECK(sink.odometry[2].gyro_yaw_rate == Approx(-0.25f));
  const dpcr::DevicePipelineCounters c = pipeline->counters();
  CHECK(c.odometry == 3);
  CHECK(c.can.ticks_frames == 3);
  CHECK(c.can.gyro_frames == 1);
  CHECK(c.can.foreign == 1);
}

TEST_CASE("pipeline: odometry stamps follow the wheel board's clock, anchored at the first frame") {
  RecordingSink sink;
  auto pipeline = std::make_unique<dpcr::DevicePipeline>(dpcr::DevicePipelineConfig{}, &sink);
  // Device time 0, 10, 20 ms; the middle frame reaches the host 3 ms late.
  pipeline->FeedCan(Ticks(0, 0, 0, 0), 7000000);
  pipeline->FeedCan(Ticks(10, 10, 1, 1000), 7013000);
  pipeline->FeedCan(Ticks(20, 20, 2, 2000), 7020000);
  REQUIRE(sink.odometry.size() == 3);
  CHECK(sink.odometry[0].stamp_us == 7000000);
  CHECK(sink.odometry[1].stamp_us == 7010000);
  CHECK(sink.odometry[2].stamp_us == 7020000);
}

TEST_CASE("pipeline: frames and revolutions reach the sink in the order they were fed") {
  // Three turns close two revolutions: a frame fed between them must arrive between them.
  const std::vector<std::uint8_t> bytes = dpcr_test::EncodeAll(dpcr_test::MakeLd06Packets(3, 3600, 100));
  RecordingSink sink;
  auto pipeline = std::make_unique<dpcr::DevicePipeline>(dpcr::DevicePipelineConfig{}, &sink);
  pipeline->FeedCan(Ticks(0, 0, 0, 0), 1000);
  const std::size_t used = pipeline->FeedLidar(bytes.data(), bytes.size(), 2000);
  pipeline->FeedCan(Ticks(5, 5, 1, 100), 3000);
  pipeline->FeedAllLidar(bytes.data() + used, bytes.size() - used, 4000);
  CHECK(std::string(sink.order.begin(), sink.order.end()) == "osos");
}

TEST_CASE("without wheel encoders, gyro frames become gyro-only odometry samples") {
  RecordingSink sink;
  auto pipeline = std::make_unique<dpcr::DevicePipeline>(dpcr::DevicePipelineConfig{}, &sink);
  pipeline->FeedCan(Gyro(100, 0, 0), 40000);  // the first one may yet be followed by ticks: no sample
  CHECK(sink.odometry.empty());
  pipeline->FeedCan(Gyro(500, 1, 1000), 50000);
  pipeline->FeedCan(Gyro(-250, 2, 2000), 60000);
  REQUIRE(sink.odometry.size() == 2);
  CHECK_FALSE(sink.odometry[0].has_wheels);
  CHECK(sink.odometry[0].has_gyro);
  CHECK(sink.odometry[0].gyro_yaw_rate == Approx(0.5f));
  CHECK(sink.odometry[1].gyro_yaw_rate == Approx(-0.25f));
  CHECK(sink.odometry[1].stamp_us - sink.odometry[0].stamp_us == 10000);  // the IMU's clock
  // Once wheel frames come, gyro frames only set the rate the wheel samples carry.
  pipeline->FeedCan(Ticks(0, 0, 0, 3000), 70000);
  pipeline->FeedCan(Gyro(100, 3, 4000), 80000);
  pipeline->FeedCan(Gyro(100, 4, 5000), 90000);
  REQUIRE(sink.odometry.size() == 3);
  CHECK(sink.odometry[2].has_wheels);
}

TEST_CASE("a gyro frame just before the first ticks frame makes no gyro-only sample") {
  RecordingSink sink;
  auto pipeline = std::make_unique<dpcr::DevicePipeline>(dpcr::DevicePipelineConfig{}, &sink);
  pipeline->FeedCan(Gyro(100, 0, 1000), 50000);
  pipeline->FeedCan(Ticks(0, 0, 0, 1000), 50000);
  REQUIRE(sink.odometry.size() == 1);
  CHECK(sink.odometry[0].has_wheels);
  CHECK(sink.odometry[0].has_gyro);
}

TEST_CASE("pipeline: samples from the lift's device time to the put-down's are marked lifted") {
  // Status every 50 ms (frames 0, 5, 10, ...): lifted at frame 3 (a change, sent at once), put
  // down at frame 12.
  std::uint8_t sequence = 0;
  const auto status_at = [&](int k, dpcr::DevicePipeline* p, std::int64_t received_us) {
    const bool lifted = k >= 3 && k < 12;
    if (k % 5 == 0 || k == 3 || k == 12) p->FeedCan(Status(lifted, sequence++, static_cast<std::uint32_t>(k * 1000)), received_us);
  };
  dpcr::DevicePipelineCounters c;
  const auto odometry = RunTicks(16, status_at, &c);
  CHECK(LiftedPattern(odometry) == "0001111111110000");
  CHECK(c.lifts == 1);
  CHECK(c.lifted_samples == 9);
  CHECK(c.can.status_frames == 6);
  CHECK(c.odometry == 16);
}

TEST_CASE("pipeline: a lost lift frame is made good by the next periodic status") {
  std::uint8_t sequence = 0;
  const auto status_at = [&](int k, dpcr::DevicePipeline* p, std::int64_t received_us) {
    const bool lifted = k >= 3;
    const bool sent = k % 5 == 0 || k == 3;
    if (!sent) return;
    const dpcr::CanFrame f = Status(lifted, sequence++, static_cast<std::uint32_t>(k * 1000));
    if (k != 3) p->FeedCan(f, received_us);  // the lift itself is lost on the bus
  };
  dpcr::DevicePipelineCounters c;
  const auto odometry = RunTicks(12, status_at, &c);
  CHECK(LiftedPattern(odometry) == "000001111111");  // lifted from the resend at frame 5
  CHECK(c.can.lost == 1);
  CHECK(c.lifts == 1);
}

TEST_CASE("pipeline: a late status frame is dropped and does not lift the robot again") {
  const auto status_at = [&](int k, dpcr::DevicePipeline* p, std::int64_t received_us) {
    if (k == 0) p->FeedCan(Status(false, 0, 0), received_us);
    if (k == 2) p->FeedCan(Status(true, 1, 2000), received_us);
    if (k == 6) p->FeedCan(Status(false, 3, 6000), received_us);  // the put-down...
    if (k == 7) p->FeedCan(Status(true, 2, 5000), received_us);   // ...overtook the periodic resend before it
  };
  dpcr::DevicePipelineCounters c;
  const auto odometry = RunTicks(10, status_at, &c);
  CHECK(LiftedPattern(odometry) == "0011110000");
  CHECK(c.can.reordered == 1);
  CHECK(c.can.lost == 0);
}

TEST_CASE("pipeline: a ticks frame overtaken by a status frame gets the state of its own instant") {
  RecordingSink sink;
  auto pipeline = std::make_unique<dpcr::DevicePipeline>(dpcr::DevicePipelineConfig{}, &sink);
  pipeline->FeedCan(Status(false, 0, 0), 1000000);
  pipeline->FeedCan(Ticks(0, 0, 0, 0), 1000000);
  pipeline->FeedCan(Status(true, 1, 2000), 1020500);  // lifted at 20 ms...
  pipeline->FeedCan(Ticks(1, 1, 1, 1000), 1021000);   // ...the 10 ms ticks frame arrives after it
  pipeline->FeedCan(Ticks(2, 2, 2, 2000), 1021500);
  CHECK(LiftedPattern(sink.odometry) == "001");
}

TEST_CASE("pipeline: a log without status frames is never lifted") {
  dpcr::DevicePipelineCounters c;
  const auto odometry = RunTicks(300, [](int, dpcr::DevicePipeline*, std::int64_t) {}, &c);
  CHECK(LiftedPattern(odometry) == std::string(300, '0'));
  CHECK(c.lifts == 0);
  CHECK(c.lifted_samples == 0);
  CHECK(c.can.status_frames == 0);
}

TEST_CASE("pipeline: status frames that stop while lifted lift no sample after kStaleUs") {
  const auto status_at = [&](int k, dpcr::DevicePipeline* p, std::int64_t received_us) {
    if (k == 0) p->FeedCan(Status(true, 0, 0), received_us);  // then silence
  };
  const auto odometry = RunTicks(110, status_at);
  REQUIRE(odometry.size() == 110);
  CHECK(odometry[100].lifted);  // 1 s after the last status
  CHECK_FALSE(odometry[101].lifted);
}

TEST_CASE("pipeline: gyro-only samples are marked lifted too") {
  RecordingSink sink;
  auto pipeline = std::make_unique<dpcr::DevicePipeline>(dpcr::DevicePipelineConfig{}, &sink);
  pipeline->FeedCan(Gyro(100, 0, 0), 40000);
  pipeline->FeedCan(Status(true, 0, 1000), 50000);
  pipeline->FeedCan(Gyro(100, 1, 1000), 50000);
  pipeline->FeedCan(Status(false, 1, 2000), 60000);
  pipeline->FeedCan(Gyro(100, 2, 2000), 60000);
  REQUIRE(sink.odometry.size() == 2);
  CHECK_FALSE(sink.odometry[0].has_wheels);
  CHECK(sink.odometry[0].lifted);
  CHECK_FALSE(sink.odometry[1].lifted);
}
