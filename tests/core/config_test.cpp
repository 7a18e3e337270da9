#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/mapper.hpp"
#include "core/config.hpp"

TEST_CASE("Default configuration carries the paper's parameters (K2 twice the paper's) and validates") {
  const dpcr::MapperConfig config;
  REQUIRE(dpcr::Validate(config) == dpcr::Status::kOk);
  REQUIRE(config.front_end.submap_scans == 20);
  REQUIRE(config.front_end.submap_line_period == 10);
  REQUIRE(config.front_end.region_line_period == 100);  // the paper's 50: docs/front-end-accuracy.md
  REQUIRE(config.front_end.second_registration_period == 5);
  REQUIRE(config.front_end.region_width_m == 4.0f);
  REQUIRE(config.grid.resolution_m == 0.05f);
}

TEST_CASE("Validate rejects meaningless parameters") {
  dpcr::MapperConfig bad;
  bad.front_end.region_line_period = 0;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  bad = dpcr::MapperConfig{};
  bad.grid.miss_delta = 10;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  bad = dpcr::MapperConfig{};
  bad.lidar.max_range_m = 0.0f;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  bad = dpcr::MapperConfig{};
  bad.grid.hit_margin_m = -0.01f;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  // A submap ray that starts inside the hit margin would have nothing to clear, or run backwards.
  bad = dpcr::MapperConfig{};
  bad.front_end.submap_miss_range_m = bad.grid.hit_margin_m;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  // Neighbouring regional maps must be a whole number of cells apart (4 m / 3 cm is not).
  bad = dpcr::MapperConfig{};
  bad.grid.resolution_m = 0.03f;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kInvalidArgument);
  bad.front_end.region_width_m = 3.6f;
  REQUIRE(dpcr::Validate(bad) == dpcr::Status::kOk);
}

// Every field, every bad value: a clear kInvalidArgument from Validate and from Init.

namespace {

struct BadField {
  std::string name;
  std::function<void(dpcr::MapperConfig&, double)> set;
  std::vector<double> values;
};

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
// Bad values by kind of field.
const std::vector<double> kPositive = {0.0, -1.0, kNaN, kInf, -kInf, 1e30};  // (0, bound]
const std::vector<double> kNonNegative = {-1.0, kNaN, kInf, -kInf, 1e30};    // [0, bound]
const std::vector<double> kRatio = {-1.0, kNaN, kInf, 2.0};                  // [0, 1]
const std::vector<double> kPositiveRatio = {0.0, -1.0, kNaN, kInf, 2.0};     // (0, 1]
const std::vector<double> kCount = {0.0, -1.0, -2e9, 1e9};                    // 1..bound
const std::vector<double> kOffset = {kNaN, kInf, -kInf, 1e30, -1e30};         // finite, bounded

#define FLOAT_FIELD(path, bad) \
  BadField { #path, [](dpcr::MapperConfig& c, double v) { c.path = static_cast<float>(v); }, bad }
#define INT_FIELD(path, bad) \
  BadField { #path, [](dpcr::MapperConfig& c, double v) { c.path = static_cast<int>(v); }, bad }
#define INT16_FIELD(path, ...) \
  BadField { #path, [](dpcr::MapperConfig& c, double v) { c.path = static_cast<std::int16_t>(v); }, {__VA_ARGS__} }

void AddPlicp(std::vector<BadField>* t, const std::string& prefix, dpcr::PlicpConfig& (*of)(dpcr::MapperConfig&)) {
  const auto f = [&](const char* name, float dpcr::PlicpConfig::*field, std::vector<double> bad) {
    t->push_back({prefix + name, [of, field](dpcr::MapperConfig& c, double v) { of(c).*field = static_cast<float>(v); }, bad});
  };
  const auto i = [&](const char* name, int dpcr::PlicpConfig::*field, std::vector<double> bad) {
    t->push_back({prefix + name, [of, field](dpcr::MapperConfig& c, double v) { of(c).*field = static_cast<int>(v); }, bad});
  };
  i("max_iterations", &dpcr::PlicpConfig::max_iterations, kCount);
  f("gate_m", &dpcr::PlicpConfig::gate_m, kPositive);
  f("trim_floor_m", &dpcr::PlicpConfig::trim_floor_m, kNonNegative);
  f("fine_phase_step_m", &dpcr::PlicpConfig::fine_phase_step_m, kNonNegative);
  f("fine_phase_step_rad", &dpcr::PlicpConfig::fine_phase_step_rad, kNonNegative);
  f("huber_m", &dpcr::PlicpConfig::huber_m, kPositive);
  f("near_weight_range_m", &dpcr::PlicpConfig::near_weight_range_m, kNonNegative);
  f("local_line_weight", &dpcr::PlicpConfig::local_line_weight, kNonNegative);
  f("point_weight", &dpcr::PlicpConfig::point_weight, kNonNegative);
  f("min_step_m", &dpcr::PlicpConfig::min_step_m, kNonNegative);
  f("min_step_rad", &dpcr::PlicpConfig::min_step_rad, kNonNegative);
  i("min_correspondences", &dpcr::PlicpConfig::min_correspondences, {0.0, -1.0, 2.0, 1e9});
  f("min_inlier_ratio", &dpcr::PlicpConfig::min_inlier_ratio, kRatio);
  f("max_mean_residual_m", &dpcr::PlicpConfig::max_mean_residual_m, kPositive);
  f("min_translation_information", &dpcr::PlicpConfig::min_translation_information, kNonNegative);
  f("max_correction_m", &dpcr::PlicpConfig::max_correction_m, kPositive);
  f("max_correction_rad", &dpcr::PlicpConfig::max_correction_rad, kPositive);
}

void AddReference(std::vector<BadField>* t, const std::string& prefix, dpcr::ReferenceConfig& (*of)(dpcr::MapperConfig&)) {
  t->push_back({prefix + "obstacle_threshold",
                [of](dpcr::MapperConfig& c, double v) { of(c).obstacle_threshold = static_cast<std::int16_t>(v); },
                {-1.0, -32768.0, 32767.0}});
  t->push_back({prefix + "max_distance_m", [of](dpcr::MapperConfig& c, double v) { of(c).max_distance_m = static_cast<float>(v); }, kPositive});
  const auto f = [&](const char* name, float dpcr::LineExtractorConfig::*field, std::vector<double> bad) {
    t->push_back({prefix + "lines." + name, [of, field](dpcr::MapperConfig& c, double v) { of(c).lines.*field = static_cast<float>(v); }, bad});
  };
  const auto i = [&](const char* name, int dpcr::LineExtractorConfig::*field, std::vector<double> bad) {
    t->push_back({prefix + "lines." + name, [of, field](dpcr::MapperConfig& c, double v) { of(c).lines.*field = static_cast<int>(v); }, bad});
  };
  i("link_radius_cells", &dpcr::LineExtractorConfig::link_radius_cells, kCount);
  f("split_tolerance_cells", &dpcr::LineExtractorConfig::split_tolerance_cells, kPositive);
  i("min_support", &dpcr::LineExtractorConfig::min_support, {0.0, -1.0, 1.0, 1e9});
  f("max_rms_cells", &dpcr::LineExtractorConfig::max_rms_cells, kPositive);
  f("merge_angle_rad", &dpcr::LineExtractorConfig::merge_angle_rad, kNonNegative);
  f("merge_offset_cells", &dpcr::LineExtractorConfig::merge_offset_cells, kNonNegative);
  f("merge_gap_cells", &dpcr::LineExtractorConfig::merge_gap_cells, kNonNegative);
}

std::vector<BadField> BadFields() {
  std::vector<BadField> t = {
      FLOAT_FIELD(grid.resolution_m, kPositive),
      INT16_FIELD(grid.hit_delta, 0, -1, 32767),  // 32767: no clamp above it
      INT16_FIELD(grid.miss_delta, 0, 1, -32768),
      INT16_FIELD(grid.clamp_max, 0, -1, 800),  // at or below hit_delta
      INT16_FIELD(grid.clamp_min, 0, 1, -32768),  // -32768 is the unknown cell
      FLOAT_FIELD(grid.hit_margin_m, kNonNegative),
      FLOAT_FIELD(grid.unsettle_miss_margin_m, kNonNegative),
      FLOAT_FIELD(lidar.min_range_m, kNonNegative),
      FLOAT_FIELD(lidar.max_range_m, kPositive),
      FLOAT_FIELD(lidar.no_return_free_m, kNonNegative),
      FLOAT_FIELD(lidar.range_noise_m, kNonNegative),
      FLOAT_FIELD(lidar.smoothing_max_gap_beams, (std::vector<double>{0.5, -1.0, kNaN, kInf, 11.0})),
      FLOAT_FIELD(lidar.near_weight_range_m, kNonNegative),
      FLOAT_FIELD(lidar.map_max_turn_rate_rad_s, kNonNegative),
      FLOAT_FIELD(lidar.mount.x, kOffset),
      FLOAT_FIELD(lidar.mount.y, kOffset),
      FLOAT_FIELD(lidar.mount.theta, kOffset),
      // 38 x 867 > 32767: the submap's exact removal would fail (also without profile limits).
      BadField{"front_end.submap_scans", [](dpcr::MapperConfig& c, double v) { c.front_end.submap_scans = static_cast<int>(v); },
               {0.0, -1.0, 38.0, 1e9}},
      INT_FIELD(front_end.submap_line_period, kCount),
      INT_FIELD(front_end.region_line_period, kCount),
      INT_FIELD(front_end.second_registration_period, kCount),
      FLOAT_FIELD(front_end.submap_miss_range_m, (std::vector<double>{-1.0, kNaN, kInf, 1e30, 0.05})),
      FLOAT_FIELD(front_end.region_miss_range_m, (std::vector<double>{-1.0, kNaN, kInf, 1e30, 0.05})),
      FLOAT_FIELD(front_end.submap_refit_gate_m, kNonNegative),
      INT_FIELD(front_end.submap_refit_min_points, kCount),
      FLOAT_FIELD(front_end.region_width_m, kPositive),
      FLOAT_FIELD(front_end.region_hysteresis_m, (std::vector<double>{-1.0, kNaN, kInf, 1e30, 2.0})),
      INT_FIELD(front_end.region_mature_scans, kCount),
      INT_FIELD(front_end.region_slow_learning_scans, kCount),
      // 1e-4: the deltas round to 0 at that rate, and a map would learn nothing more.
      FLOAT_FIELD(front_end.region_slow_learning_rate, (std::vector<double>{0.0, -1.0, kNaN, kInf, 2.0, 1e-4})),
      FLOAT_FIELD(front_end.reference_inner_margin_m, kNonNegative),
      INT_FIELD(front_end.lost_after_rejections, kCount),
      INT_FIELD(front_end.lidar_only_lost_after_second_rejections, (std::vector<double>{-1.0, -2e9, 1e9})),
      INT_FIELD(front_end.submap_restart_after_rejections, kCount),
      FLOAT_FIELD(front_end.uncertain_turn_rad, (std::vector<double>{-1.0, kNaN, kInf, 4.0})),
      FLOAT_FIELD(front_end.prior_info_xy, kNonNegative),
      FLOAT_FIELD(front_end.prior_info_theta, kNonNegative),
      FLOAT_FIELD(front_end.max_acceleration_mps2, (std::vector<double>{-1.0, kNaN, kInf, 101.0})),
      FLOAT_FIELD(front_end.weak_direction_information, (std::vector<double>{-1.0, kNaN, kInf, 2e6})),
      FLOAT_FIELD(front_end.odometry_doubt_m, kNonNegative),
      FLOAT_FIELD(front_end.odometry_doubt_rad, (std::vector<double>{-1.0, kNaN, kInf, 4.0})),
      INT_FIELD(front_end.second_registration_max_points, kCount),  // 0 divided by zero in SubmapTarget
      INT_FIELD(front_end.min_start_hits, (std::vector<double>{-1.0, -2e9, 1e9})),
      FLOAT_FIELD(front_end.sparse_scan_share, (std::vector<double>{-0.1, 1.1, 1e9})),
      FLOAT_FIELD(front_end.sparse_reference_full_share, (std::vector<double>{-0.1, 1.1, 1e9})),
      FLOAT_FIELD(front_end.sparse_residual_noise_factor, (std::vector<double>{-0.1, 10.5, 1e9})),
      FLOAT_FIELD(front_end.redeskew_min_m, kNonNegative),
      FLOAT_FIELD(front_end.redeskew_min_rad, kNonNegative),
      // A turn past 40 degrees would put the walls near the grid's diagonals; a band wider than half
      // the turn would leave walls that needed it near the axes.
      FLOAT_FIELD(front_end.grid_turn_rad, (std::vector<double>{-1.0, kNaN, kInf, 1.0, 0.2})),
      FLOAT_FIELD(front_end.grid_turn_band_rad, (std::vector<double>{-1.0, kNaN, kInf, 0.2})),
      // The start heading's fit: a window past ten minutes, a skip past the window, a floor over the
      // ceiling, a ceiling past 20 degrees or a bias past 1 rad/s is no fit of a start's noise.
      FLOAT_FIELD(front_end.start_heading.window_s, (std::vector<double>{-1.0, kNaN, kInf, 1000.0, 0.5})),
      FLOAT_FIELD(front_end.start_heading.skip_s, (std::vector<double>{-1.0, kNaN, kInf, 31.0})),
      INT_FIELD(front_end.start_heading.min_samples, (std::vector<double>{-1.0, 0.0, 1.0, 1e5})),
      FLOAT_FIELD(front_end.start_heading.min_offset_rad, (std::vector<double>{-1.0, kNaN, kInf, 0.1})),
      FLOAT_FIELD(front_end.start_heading.max_offset_rad, (std::vector<double>{-1.0, kNaN, kInf, 1.0, 0.001})),
      FLOAT_FIELD(front_end.start_heading.max_bias_rad_s, (std::vector<double>{-1.0, kNaN, kInf, 2.0})),
      FLOAT_FIELD(front_end.start_scans.window_s, (std::vector<double>{-1.0, 0.0, kNaN, kInf, 31.0})),
      FLOAT_FIELD(front_end.start_scans.every_s, (std::vector<double>{-1.0, 0.0, kNaN, kInf, 11.0})),
      INT_FIELD(front_end.start_scans.min_scans, (std::vector<double>{-1.0, 0.0, 2.0, 1e5})),
      FLOAT_FIELD(front_end.start_scans.max_offset_rad, (std::vector<double>{-1.0, 0.0, kNaN, kInf, 1.0})),
      FLOAT_FIELD(front_end.start_scans.max_bias_rad_s, (std::vector<double>{-1.0, 0.0, kNaN, kInf, 2.0})),
      // The coarse pose search and the weak-match rebuild, unchecked until fuzz/fuzz_mapper_config.cpp
      // found e.g. kernel_radius_cells = INT_MIN, sigma_m = NaN or 1e-30, or angle_window_rad = NaN
      // overflowing int casts in rotation_search.cpp after a rejected registration.
      FLOAT_FIELD(front_end.search.resolution_m, (std::vector<double>{0.0, -1.0, kNaN, kInf, 1e-30, 0.001, 2.0})),
      FLOAT_FIELD(front_end.search.sigma_m, (std::vector<double>{0.0, -1.0, kNaN, kInf, 1e30, 1e-30, 1e-4})),
      INT_FIELD(front_end.search.kernel_radius_cells, (std::vector<double>{0.0, -1.0, -2147483648.0, 7.0})),
      FLOAT_FIELD(front_end.search.angle_window_rad, (std::vector<double>{-1.0, kNaN, kInf, 4.0})),
      FLOAT_FIELD(front_end.search.angle_step_rad, (std::vector<double>{-1.0, kNaN, kInf, 1e-30, 1e-4, 4.0})),
      FLOAT_FIELD(front_end.search.xy_window_m, kNonNegative),
      INT_FIELD(front_end.search.max_points, kCount),
      FLOAT_FIELD(front_end.search.step_penalty, kRatio),
      FLOAT_FIELD(front_end.search.min_gain, kRatio),
      FLOAT_FIELD(front_end.search_turn_rad, (std::vector<double>{-1.0, kNaN, kInf, 4.0})),
      FLOAT_FIELD(front_end.weak_match_inlier_ratio, kRatio),
      INT16_FIELD(front_end.weak_match_obstacle_threshold, -1, -32768),
      FLOAT_FIELD(back_end.neighbour_factor, kPositive),
      INT_FIELD(back_end.min_scans, kCount),
      FLOAT_FIELD(back_end.min_match_rate, kRatio),
      INT_FIELD(back_end.max_cloud_points, kCount),
      FLOAT_FIELD(back_end.residual_sigma_m, kPositive),
      FLOAT_FIELD(back_end.correlated_points, kPositive),
      FLOAT_FIELD(back_end.floor_sigma_m, kPositive),
      FLOAT_FIELD(back_end.floor_sigma_rad, kPositive),
      FLOAT_FIELD(back_end.sequence_sigma_m, kPositive),
      FLOAT_FIELD(back_end.sequence_sigma_rad, kPositive),
      FLOAT_FIELD(back_end.loop_min_path_m, kNonNegative),
      INT_FIELD(back_end.loop_retry_scans, kCount),
      FLOAT_FIELD(back_end.loop_retry_path_m, kNonNegative),
      FLOAT_FIELD(back_end.search_base_m, kNonNegative),
      FLOAT_FIELD(back_end.search_per_metre_m, kNonNegative),
      FLOAT_FIELD(back_end.search_max_m, kPositive),
      FLOAT_FIELD(back_end.search_base_rad, kNonNegative),
      FLOAT_FIELD(back_end.search_per_metre_rad, kNonNegative),
      FLOAT_FIELD(back_end.search_max_rad, kPositive),
      INT_FIELD(back_end.search_points, kCount),
      INT_FIELD(back_end.search_evaluations_per_step, kCount),
      INT_FIELD(back_end.match_grid_coarsen, (std::vector<double>{0.0, -1.0, 1.0, 1e9})),
      FLOAT_FIELD(back_end.large_closure_max_residual_m, kPositive),
      FLOAT_FIELD(back_end.closure_prior_info, kNonNegative),
      FLOAT_FIELD(back_end.ridge_information, kRatio),
      FLOAT_FIELD(back_end.ridge_fit_tolerance, kRatio),
      FLOAT_FIELD(back_end.unfollowed_closure_min_score, kRatio),
      FLOAT_FIELD(back_end.confirm_second_ratio, kRatio),
      FLOAT_FIELD(back_end.confirm_guess_window_m, kNonNegative),
      FLOAT_FIELD(back_end.search.min_angle_step_rad, kPositive),
      FLOAT_FIELD(back_end.search.max_angle_step_rad, kPositive),
      FLOAT_FIELD(back_end.search.min_score, kPositiveRatio),
      FLOAT_FIELD(back_end.search.max_second_ratio, kPositiveRatio),
      FLOAT_FIELD(back_end.search.peak_separation_m, kNonNegative),
      FLOAT_FIELD(back_end.search.peak_separation_rad, kNonNegative),
      FLOAT_FIELD(back_end.max_edge_chi2, kPositive),
      INT_FIELD(back_end.optimizer.max_iterations, kCount),
      FLOAT_FIELD(back_end.optimizer.min_step_m, kNonNegative),
      FLOAT_FIELD(back_end.optimizer.min_step_rad, kNonNegative),
      FLOAT_FIELD(back_end.optimizer.kernel_phi, kPositive),
      FLOAT_FIELD(back_end.optimizer.damping, kNonNegative),
      INT_FIELD(localisation.angles_per_step, kCount),
      INT_FIELD(localisation.coarsen, (std::vector<double>{0.0, -1.0, 1.0, 1e9})),
      FLOAT_FIELD(localisation.coarse_angle_step_rad, kPositive),
      FLOAT_FIELD(localisation.window_margin_m, kNonNegative),
      INT_FIELD(localisation.cloud_points, (std::vector<double>{0.0, -1.0, 9.0, 201.0, 1e9})),
      FLOAT_FIELD(localisation.max_second_ratio, kPositiveRatio),
      FLOAT_FIELD(localisation.min_inlier_ratio, kRatio),
      FLOAT_FIELD(localisation.near_window_m, kNonNegative),
      FLOAT_FIELD(localisation.near_window_mps, kNonNegative),
      FLOAT_FIELD(localisation.clear_min_score, kRatio),
      FLOAT_FIELD(localisation.clear_max_ratio, kRatio),
      FLOAT_FIELD(localisation.heading_window_rad, (std::vector<double>{-0.1, 3.2, 1e9})),
      FLOAT_FIELD(localisation.heading_window_rad_s, (std::vector<double>{-0.1, 1.1, 1e9})),
  };
  AddPlicp(&t, "front_end.first_registration.", [](dpcr::MapperConfig& c) -> dpcr::PlicpConfig& { return c.front_end.first_registration; });
  AddPlicp(&t, "front_end.second_registration.", [](dpcr::MapperConfig& c) -> dpcr::PlicpConfig& { return c.front_end.second_registration; });
  AddPlicp(&t, "back_end.registration.", [](dpcr::MapperConfig& c) -> dpcr::PlicpConfig& { return c.back_end.registration; });
  AddPlicp(&t, "back_end.closure_registration.", [](dpcr::MapperConfig& c) -> dpcr::PlicpConfig& { return c.back_end.closure_registration; });
  AddReference(&t, "front_end.submap_reference.", [](dpcr::MapperConfig& c) -> dpcr::ReferenceConfig& { return c.front_end.submap_reference; });
  AddReference(&t, "front_end.region_reference.", [](dpcr::MapperConfig& c) -> dpcr::ReferenceConfig& { return c.front_end.region_reference; });
  return t;
}

}  // namespace

TEST_CASE("Validate and Init refuse every field set to each of its bad values") {
  auto mapper = std::make_unique<dpcr::Mapper<dpcr::TinyProfile>>();
  dpcr::MapperConfig good;
  good.front_end.submap_scans = dpcr::TinyProfile::kSubmapMaxScans;
  REQUIRE(mapper->Init(good) == dpcr::Status::kOk);
  int cases = 0;
  for (const BadField& field : BadFields()) {
    for (const double v : field.values) {
      dpcr::MapperConfig c = good;
      field.set(c, v);
      INFO(field.name << " = " << v);
      CHECK(dpcr::Validate(c) == dpcr::Status::kInvalidArgument);
      CHECK(mapper->Init(c) == dpcr::Status::kInvalidArgument);
      ++cases;
    }
  }
  // A refused Init leaves a mapper that Init takes again.
  REQUIRE(mapper->Init(good) == dpcr::Status::kOk);
  std::printf("config validation: %d bad field values refused\n", cases);
}

TEST_CASE("Init checks the profile's capacities against the configuration") {
  auto tiny = std::make_unique<dpcr::Mapper<dpcr::TinyProfile>>();
  dpcr::MapperConfig c;
  c.front_end.submap_scans = dpcr::TinyProfile::kSubmapMaxScans;
  const auto refused = [&](auto edit) {
    dpcr::MapperConfig e = c;
    edit(e);
    return dpcr::Validate(e) == dpcr::Status::kOk && tiny->Init(e) == dpcr::Status::kInvalidArgument;
  };
  CHECK(refused([](dpcr::MapperConfig& e) { e.front_end.submap_scans = dpcr::TinyProfile::kSubmapMaxScans + 1; }));
  CHECK(refused([](dpcr::MapperConfig& e) { e.front_end.second_registration_max_points = 601; }));
  CHECK(refused([](dpcr::MapperConfig& e) { e.back_end.max_cloud_points = 601; }));
  CHECK(refused([](dpcr::MapperConfig& e) { e.back_end.search_points = 201; }));
  // A 6 m region (plus its hysteresis) does not fit the tiny profile's 6.4 m box.
  CHECK(refused([](dpcr::MapperConfig& e) { e.front_end.region_width_m = 6.0f; }));
}

TEST_CASE("The search and weak-match settings' off values validate") {
  dpcr::MapperConfig c;
  c.front_end.search.angle_step_rad = 0.0f;  // translations only
  c.front_end.search_turn_rad = 0.0f;        // no search before PLICP
  c.front_end.weak_match_inlier_ratio = 0.0f;  // no early rebuild
  c.front_end.search.kernel_radius_cells = 6;
  REQUIRE(dpcr::Validate(c) == dpcr::Status::kOk);
}
