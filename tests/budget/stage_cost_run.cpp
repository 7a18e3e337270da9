// The fixed run of the per-stage instruction budgets (tests/budget/stage_cost.sh runs it under
// callgrind): `building` = the first 300 scans of intel.clf (180 beams), `vacuum` and `tiny` =
// 300 synthetic scans in each of four ~8 m rooms (450 and 256 beams). Prints the scan count and the
// profile's budgets (instructions per scan, core/capacity.hpp) for the script to compare.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "core/capacity.hpp"
#include "core/mapper.hpp"
#include "hal/device_options.hpp"
#include "host_sim/carmen/carmen_reader.hpp"
#include "host_sim/carmen/laser_scan.hpp"
#include "tests/budget/synthetic_run.hpp"
#include "tools/public_logs.hpp"

namespace {

constexpr int kScans = 300;

template <class Profile>
void PrintBudgets(int scans) {
  std::printf("scans %d\n", scans);
  std::printf("budget prediction %llu\n", static_cast<unsigned long long>(Profile::kBudgetPredictionInstr));
  std::printf("budget first_registration %llu\n", static_cast<unsigned long long>(Profile::kBudgetFirstRegistrationInstr));
  std::printf("budget second_registration %llu\n", static_cast<unsigned long long>(Profile::kBudgetSecondRegistrationInstr));
  std::printf("budget insertion %llu\n", static_cast<unsigned long long>(Profile::kBudgetInsertionInstr));
  std::printf("budget line_extraction %llu\n", static_cast<unsigned long long>(Profile::kBudgetLineExtractionInstr));
}

int RunIntel(const std::string& clf) {
  using MapperType = dpcr::Mapper<dpcr::BuildingProfile>;
  static MapperType mapper;
  static MapperType::ScanType scan;
  std::ifstream in(clf);
  if (!in) {
    std::printf("SKIP: %s not found (set DPCR_DATA_DIR; README \"Public logs\")\n", clf.c_str());
    return dpcr::kSkippedExitCode;
  }
  dpcr::carmen::CarmenReader reader(in);
  dpcr::carmen::Record rec;
  bool configured = false;
  int scans = 0;
  while (scans < kScans && reader.Next(&rec)) {
    if (!configured) {
      dpcr::MapperConfig config;
      config.lidar.max_range_m = 20.0f;  // as dpcr-replay
      config.lidar.mount = dpcr::Pose2{reader.front_laser_offset_m(), 0.0f, 0.0f};
      if (mapper.Init(config) != dpcr::Status::kOk) return 2;
      configured = true;
    }
    if (rec.kind != dpcr::carmen::Record::Kind::kLaser) continue;
    dpcr::OdometrySample s;
    s.stamp_us = rec.laser.stamp_us;
    s.pose = rec.laser.odom_pose;
    mapper.AddOdometry(s);
    (void)dpcr::carmen::ToScan(rec.laser, &scan);
    (void)mapper.AddScan(scan);
    ++scans;
  }
  PrintBudgets<dpcr::BuildingProfile>(scans);
  return 0;
}

// The synthetic room's walls are noise-free lines, so where they fall against the 5 cm cell
// lattice decides how thick they are in the maps, and the second registration's iterations
// with it: measured, 41 K instructions per scan with the walls on cell borders and 125 K with
// them mid-cell. The budgets are checked over four rooms whose far walls lie 0, 1/4, 1/2 and
// 3/4 of a cell past a border, so that no single placement decides them.
constexpr float kRoomM = 8.0f;
constexpr int kWallPlacements = 4;

template <class Profile>
int RunSynthetic(int beams) {
  using MapperType = dpcr::Mapper<Profile>;
  static MapperType mapper;
  dpcr::MapperConfig config;
  // The lidar is an LD06 as the firmware declares it (its range noise), so that the stages count
  // what runs on the robot (the returns' smoothing in the prediction, the noise-aware line fits and
  // trim floor); the walls themselves are exact.
  dpcr::ApplyLidarModel(dpcr::LidarKind::kLd06, &config.lidar);
  if (config.front_end.submap_scans > Profile::kSubmapMaxScans) config.front_end.submap_scans = Profile::kSubmapMaxScans;
  for (int placement = 0; placement < kWallPlacements; ++placement) {
    const float room_m = kRoomM + config.grid.resolution_m * static_cast<float>(placement) / kWallPlacements;
    const dpcr::test::SyntheticRun<MapperType> run(room_m, kScans, beams);
    if (mapper.Init(config) != dpcr::Status::kOk) return 2;
    for (std::size_t i = 0; i < run.scans.size(); ++i) {
      for (std::size_t k = 0; k < 10; ++k) mapper.AddOdometry(run.odometry[i * 10 + k]);
      (void)mapper.AddScan(run.scans[i]);
    }
  }
  PrintBudgets<Profile>(kScans * kWallPlacements);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "building") == 0) {
    return RunIntel(argc >= 3 ? std::string(argv[2]) : dpcr::PublicLogPath("intel.clf"));
  }
  if (argc >= 2 && std::strcmp(argv[1], "vacuum") == 0) return RunSynthetic<dpcr::VacuumProfile>(450);
  if (argc >= 2 && std::strcmp(argv[1], "tiny") == 0) return RunSynthetic<dpcr::TinyProfile>(256);
  std::fprintf(stderr, "usage: %s building [INTEL.clf] | vacuum | tiny\n", argv[0]);
  return 2;
}
