// Mapper::AddScan and AddOdometry fed hostile scans and odometry (tiny profile). Each input starts
// from a fresh Init and feeds the first scans of the synthetic room run (fuzz/tiny_map_run.hpp)
// with their odometry, which it edits: ranges and angles NaN, infinite, negative, zero, huge or
// anything; time offsets anything; beams dropped (down to none), repeated or swapped (unsorted
// angles); scan stamps going backwards, jumping by hours or to the int64 extremes; odometry poses
// and gyro rates anything, stamps anywhere, wheels lifted or gone. No crash, no sanitizer
// report, every scan answered (kOk or kNotEnoughData; kInvalidArgument for a stamp before 1970 or
// past 2^56 us) and counted, the pose and the regions' anchors stay finite and the map's bounds
// lie around the anchors.
// Short runs with short submaps: 1-4 scans into submaps of 2-5 scans reach every step of a scan's
// way (first scan, first registration and its search on rejection, submap completion, second
// registration, region insertion and switch) at ~1 ms an input, where the run's own 10-scan
// submaps needed 16 scans at ~4 ms: 10^7 executions fit in two hours of two cores.
// Input: byte 0: bits 0-1 scans to feed - 1, bits 2-3 scans per submap - 2 (its lines rebuilt
// as often), bits 4-5 the odometry (0 wheels, 1 wheels and a gyro, 2 a gyro alone, 3 none: the
// lidar-only fixed-lag path), bits 6-7 scans between second registrations - 1. Then edits: a
// kind byte (low 4 bits the kind, high 4 bits the scan), a choice byte and what the edit consumes.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "core/mapper.hpp"
#include "fuzz/fuzz_check.hpp"
#include "fuzz/tiny_map_run.hpp"
#include "fuzz/value_mutator.hpp"

namespace {

using Tiny = dpcr::Mapper<dpcr::TinyProfile>;
constexpr std::size_t kMaxScans = 4;
constexpr std::size_t kOdometryPerScan = 10;  // the synthetic run's rate

enum class OdometryKind : std::uint8_t { kWheels, kWheelsAndGyro, kGyroOnly, kNone };

// One scan and the odometry samples before it, as the input leaves them.
struct Step {
  Tiny::ScanType scan;
  std::vector<dpcr::OdometrySample> odometry;
};

// stamp + step, wrapping (an edited stamp may already be an extreme).
std::int64_t Plus(std::int64_t stamp, std::int64_t step) {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(stamp) + static_cast<std::uint64_t>(step));
}

std::int64_t EditedStamp(FuzzedDataProvider& in, std::int64_t stamp, std::uint8_t choice) {
  constexpr std::int64_t kHourUs = 3600LL * 1000000LL;
  switch (choice % 6) {
    case 0: return Plus(stamp, -in.ConsumeIntegralInRange<std::int64_t>(1, 10 * kHourUs));  // backwards
    case 1: return Plus(stamp, in.ConsumeIntegralInRange<std::int64_t>(1, 1000) * kHourUs);  // hours ahead
    case 2: return (choice & 8) != 0 ? std::numeric_limits<std::int64_t>::max() : std::numeric_limits<std::int64_t>::min();
    case 3: return 0;
    case 4: return Plus(stamp, in.ConsumeIntegralInRange<std::int64_t>(-200000, 200000));  // jitter
    default: return in.ConsumeIntegral<std::int64_t>();
  }
}

void EditBeams(FuzzedDataProvider& in, std::uint8_t kind, std::uint8_t choice, Tiny::ScanType* scan) {
  dpcr::fuzz::ValueMutator mutate(in);
  auto& beams = scan->beams;
  const auto pick = [&] { return beams.empty() ? 0u : in.ConsumeIntegral<std::uint8_t>() % beams.size(); };
  switch (kind) {
    case 0: if (!beams.empty()) mutate(beams[pick()].range_m, choice); break;
    case 1: if (!beams.empty()) mutate(beams[pick()].angle_rad, choice); break;
    case 2: if (!beams.empty()) mutate.Integer(beams[pick()].offset_us, choice); break;
    case 3: {  // every range the same edit (all NaN, all behind the lidar, all zero)
      FuzzedDataProvider none(nullptr, 0);  // the same edit for all: nothing more consumed
      dpcr::fuzz::ValueMutator same(none);
      for (auto& b : beams) same(b.range_m, choice);
      break;
    }
    case 4: while (beams.size() > static_cast<std::size_t>(choice)) beams.pop_back(); break;  // dropped, to none
    case 5: if (!beams.empty()) { const auto a = pick(), b = pick(); std::swap(beams[a], beams[b]); } break;
    case 6: if (!beams.empty()) { const auto& b = beams[pick()]; while (!beams.full() && choice-- > 0) (void)beams.push_back(b); } break;
    default: scan->stamp_us = EditedStamp(in, scan->stamp_us, choice); break;
  }
}

void EditOdometry(FuzzedDataProvider& in, std::uint8_t kind, std::uint8_t choice, std::vector<dpcr::OdometrySample>* odometry) {
  if (odometry->empty()) return;
  dpcr::OdometrySample& s = (*odometry)[in.ConsumeIntegral<std::uint8_t>() % odometry->size()];
  dpcr::fuzz::ValueMutator mutate(in);
  switch (kind) {
    case 8: mutate(s.pose.x, choice); break;
    case 9: mutate(s.pose.y, choice); break;
    case 10: mutate(s.pose.theta, choice); break;
    case 11: mutate(s.gyro_yaw_rate, choice); break;
    case 12: s.stamp_us = EditedStamp(in, s.stamp_us, choice); break;
    case 13: s.lifted = !s.lifted; break;
    case 14: s.has_wheels = !s.has_wheels; break;
    default: s.has_gyro = !s.has_gyro; break;
  }
}

// The run's first `count` scans with their odometry, of the kind asked for.
std::vector<Step> Steps(const dpcr::fuzz::TinyMapRun& run, std::size_t count, OdometryKind kind) {
  std::vector<Step> steps(count);
  for (std::size_t i = 0; i < count; ++i) {
    steps[i].scan = run.run.scans[i];
    if (kind == OdometryKind::kNone) continue;
    for (std::size_t k = 0; k < kOdometryPerScan; ++k) {
      dpcr::OdometrySample s = run.run.odometry[i * kOdometryPerScan + k];
      s.has_gyro = kind != OdometryKind::kWheels;
      s.has_wheels = kind != OdometryKind::kGyroOnly;
      s.gyro_yaw_rate = 0.0f;  // the run turns at lane ends only, between samples
      steps[i].odometry.push_back(s);
    }
  }
  return steps;
}

bool Finite(const dpcr::Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const dpcr::fuzz::TinyMapRun run;
  static Tiny* mapper = new Tiny();
  const std::uint8_t head = size > 0 ? data[0] : 0;
  FuzzedDataProvider in(size > 0 ? data + 1 : data, size > 0 ? size - 1 : 0);
  const std::size_t count = 1u + (head & 3u);
  static_assert(kMaxScans == 4 && kMaxScans <= 60, "two bits of scans; the synthetic run has 60");
  dpcr::MapperConfig config = run.config;
  // Submaps of 2-5 scans; a submap's cells must reach its obstacle threshold (config.cpp).
  config.front_end.submap_scans = 2 + ((head >> 2) & 3);
  auto& threshold = config.front_end.submap_reference.obstacle_threshold;
  threshold = static_cast<std::int16_t>(std::min<int>(threshold, config.front_end.submap_scans * config.grid.hit_delta - 1));
  config.front_end.submap_line_period = config.front_end.submap_scans;
  config.front_end.second_registration_period = 1 + ((head >> 6) & 3);
  const auto kind = static_cast<OdometryKind>((head >> 4) & 3);
  std::vector<Step> steps = Steps(run, count, kind);
  while (in.remaining_bytes() >= 2) {
    const std::uint8_t edit = in.ConsumeIntegral<std::uint8_t>();
    const std::uint8_t choice = in.ConsumeIntegral<std::uint8_t>();
    Step& step = steps[(edit >> 4) % count];
    if ((edit & 15) < 8) {
      EditBeams(in, edit & 15, choice, &step.scan);
    } else {
      EditOdometry(in, edit & 15, choice, &step.odometry);
    }
  }
  FUZZ_CHECK(mapper->Init(config) == dpcr::Status::kOk);
  for (const Step& step : steps) {
    for (const auto& s : step.odometry) mapper->AddOdometry(s);
    const dpcr::Status verdict = mapper->AddScan(step.scan);
    FUZZ_CHECK(dpcr::PlausibleStamp(step.scan.stamp_us) ? verdict == dpcr::Status::kOk || verdict == dpcr::Status::kNotEnoughData
                        : verdict == dpcr::Status::kInvalidArgument);
    FUZZ_CHECK(Finite(mapper->pose()));
  }
  FUZZ_CHECK(mapper->counters().scans == count);
  for (int r = 0; r < mapper->region_count(); ++r) FUZZ_CHECK(Finite(mapper->region_anchor(r)));
  // The fused map's bounds lie around the regions' anchors: not wild, not overflowed. (How far
  // apart the anchors lie is the odometry's to say: a jump of 24 m in one sample, within the
  // 100 km the core accepts, is followed.)
  if (mapper->region_count() == 0) return 0;
  float lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  for (int r = 0; r < mapper->region_count(); ++r) {
    const dpcr::Pose2 a = mapper->region_anchor(r);
    lo_x = std::fmin(lo_x, a.x), lo_y = std::fmin(lo_y, a.y), hi_x = std::fmax(hi_x, a.x), hi_y = std::fmax(hi_y, a.y);
  }
  const dpcr::CellBox box = mapper->MapBounds();
  const float res = config.grid.resolution_m;
  const float reach_m = static_cast<float>(dpcr::TinyProfile::kRegionBoxTiles * dpcr::kTileSide) * res;  // a box side
  FUZZ_CHECK(static_cast<float>(box.min.x) * res >= lo_x - reach_m && static_cast<float>(box.max.x) * res <= hi_x + reach_m);
  FUZZ_CHECK(static_cast<float>(box.min.y) * res >= lo_y - reach_m && static_cast<float>(box.max.y) * res <= hi_y + reach_m);
  return 0;
}
