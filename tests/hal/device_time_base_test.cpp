// DeviceTimeBase: the wheel board's clock in host time, from frame arrivals that come late by a
// jittered latency while the two crystals drift apart.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include "hal/device_time_base.hpp"

namespace {

// Frames every 10 ms for `minutes`: device time runs `ppm` fast from 5 s; each arrives 0.2 ms
// plus an exponential jitter of mean 0.5 ms late, 1 % of them up to 20 ms more. Returns the
// largest |estimated host time - true sampling time| after the first `settle_s` seconds, and
// the error at the end.
struct OffsetErrors {
  double max_ms = 0.0;
  double end_ms = 0.0;
};

OffsetErrors RunClock(dpcr::DeviceTimeBase::Mode mode, double ppm, double minutes, double settle_s, std::uint32_t seed) {
  dpcr::DeviceTimeBase base(mode);
  std::mt19937 random(seed);
  std::exponential_distribution<double> jitter(1.0 / 500.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  OffsetErrors e;
  std::int64_t last_arrival = INT64_MIN;
  const std::int64_t frames = static_cast<std::int64_t>(minutes * 60.0 * 100.0);
  for (std::int64_t i = 0; i < frames; ++i) {
    const std::int64_t t = 1000000 + i * 10000;  // the true sampling time, host clock
    const std::int64_t device = 5000000 + static_cast<std::int64_t>(std::llround(static_cast<double>(t) * (1.0 + ppm * 1e-6)));
    double late = 200.0 + jitter(random);
    if (unit(random) < 0.01) late += 20000.0 * unit(random);
    std::int64_t arrival = t + static_cast<std::int64_t>(std::llround(late));
    if (arrival < last_arrival) arrival = last_arrival;
    last_arrival = arrival;
    const double error_ms = static_cast<double>(base.ToHostUs(device, arrival) - t) / 1000.0;
    if (static_cast<double>(i) * 0.01 >= settle_s && std::fabs(error_ms) > e.max_ms) e.max_ms = std::fabs(error_ms);
    e.end_ms = error_ms;
  }
  return e;
}

}  // namespace

TEST_CASE("device time base: over 70 minutes the tracked offset stays within a millisecond, the first frame's drifts away") {
  for (const double ppm : {20.0, 35.0, 50.0, -50.0}) {
    const OffsetErrors tracked = RunClock(dpcr::DeviceTimeBase::Mode::kTracked, ppm, 70.0, 10.0, 3);
    const OffsetErrors first = RunClock(dpcr::DeviceTimeBase::Mode::kFirstFrame, ppm, 70.0, 10.0, 3);
    std::printf("device time base, %+.0f ppm, 70 min: tracked max %.2f ms (end %.2f ms); first frame max %.1f ms (end %.1f ms)\n",
                ppm, tracked.max_ms, tracked.end_ms, first.max_ms, first.end_ms);
    INFO(ppm << " ppm");
    // The minimum latency (0.2 ms) stays: a constant the lidar's arrival stamps share.
    CHECK(tracked.max_ms < 1.0);
    // 20-50 ppm over 70 minutes: 84-210 ms.
    CHECK(first.max_ms > std::fabs(ppm) * 4.0);
  }
}

TEST_CASE("device time base: the first frame maps as before, a late first frame is forgotten") {
  dpcr::DeviceTimeBase base;
  CHECK(base.ToHostUs(1000, 51000) == 51000);  // the first frame: its own offset
  // The first frame was 30 ms late: the next, less delayed frames bring the offset down.
  for (int i = 1; i <= 10; ++i) base.ToHostUs(1000 + i * 10000, 21000 + 1000 + i * 10000);
  CHECK(base.offset_us() == 21000);
}

TEST_CASE("device time base: a reader stalled for seconds moves no stamp, a device clock that steps back restarts it") {
  dpcr::DeviceTimeBase base;
  for (int i = 0; i < 1000; ++i) base.ToHostUs(7000000 + i * 10000, 1000000 + i * 10000 + 300);
  // A reader stalled for 4 s: the frames it then reads are late, their stamps stay right.
  for (int i = 1000; i < 1400; ++i) CHECK(base.ToHostUs(7000000 + i * 10000, 15000000 + 300) == 1000000 + i * 10000 + 300);
  CHECK(base.restarts() == 0);
  // The board rebooted: its clock starts again near zero.
  CHECK(base.ToHostUs(2000, 20000300) == 20000300);
  CHECK(base.restarts() == 1);
  CHECK(base.ToHostUs(12000, 20010300) == 20010300);
}

TEST_CASE("device time base: the drift is fitted from the window's minima") {
  dpcr::DeviceTimeBase base;
  std::mt19937 random(7);
  std::exponential_distribution<double> jitter(1.0 / 500.0);
  for (int i = 0; i < 20000; ++i) {  // 200 s
    const std::int64_t t = i * 10000;
    const std::int64_t device = static_cast<std::int64_t>(std::llround(static_cast<double>(t) * (1.0 - 40e-6)));
    base.ToHostUs(device, t + 200 + static_cast<std::int64_t>(jitter(random)));
  }
  // The device clock runs 40 ppm slow: host time gains 40 ppm on it.
  CHECK(base.drift_ppm() == Approx(40.0).margin(3.0));
}
