// MapperConfig (core/config.hpp) with fuzzed fields -> Validate against the tiny profile's
// storage. Validate must refuse whatever would crash the mapper: a configuration it accepts is
// Init'ed and maps a short synthetic run (tiny profile) without a crash, an assert or a sanitizer
// report. The input edits a few fields each (fuzz/value_mutator.hpp).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <variant>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "core/config.hpp"
#include "core/mapper.hpp"
#include "fuzz/fuzz_check.hpp"
#include "fuzz/tiny_map_run.hpp"
#include "fuzz/value_mutator.hpp"

namespace {

// Every field of the configuration, by address, in a fixed order.
class FieldList {
 public:
  using Field = std::variant<float*, int*, std::int16_t*, std::uint8_t*, bool*>;
  template <class T>
  void operator()(T& field) {
    fields_.push_back(Field(&field));
  }
  void operator()(dpcr::Pose2& p) {
    (*this)(p.x);
    (*this)(p.y);
    (*this)(p.theta);
  }
  const std::vector<Field>& fields() const { return fields_; }

 private:
  std::vector<Field> fields_;
};

template <class M>
void Lines(M& m, dpcr::LineExtractorConfig& c) {
  m(c.link_radius_cells), m(c.split_tolerance_cells), m(c.min_support), m(c.max_rms_cells), m(c.merge_angle_rad),
      m(c.merge_offset_cells), m(c.merge_gap_cells);
}

template <class M>
void Reference(M& m, dpcr::ReferenceConfig& c) {
  m(c.obstacle_threshold), m(c.weight_by_evidence), m(c.max_distance_m);
  Lines(m, c.lines);
}

template <class M>
void Plicp(M& m, dpcr::PlicpConfig& c) {
  m(c.max_iterations), m(c.gate_m), m(c.trim), m(c.accept_partial_overlap), m(c.trim_floor_m), m(c.fine_phase_step_m), m(c.fine_phase_step_rad),
      m(c.huber_m), m(c.near_weight_range_m), m(c.local_line_weight), m(c.point_weight), m(c.min_step_m), m(c.min_step_rad),
      m(c.min_correspondences), m(c.min_inlier_ratio), m(c.max_mean_residual_m), m(c.min_translation_information),
      m(c.max_correction_m), m(c.max_correction_rad);
}

template <class M>
void ForEachField(M& m, dpcr::MapperConfig& c) {
  dpcr::GridConfig& g = c.grid;
  m(g.resolution_m), m(g.hit_delta), m(g.miss_delta), m(g.clamp_max), m(g.clamp_min), m(g.settle_at_clamp), m(g.hit_margin_m);
  m(g.unsettle_occupied_after), m(g.unsettle_free_after), m(g.drop_hits_behind_settled_cells), m(g.unsettle_miss_margin_m), m(g.hit_means);
  dpcr::LidarConfig& l = c.lidar;
  m(l.min_range_m), m(l.max_range_m), m(l.no_return_free_m), m(l.mount), m(l.drop_isolated_returns), m(l.range_noise_m), m(l.smoothing_max_gap_beams),
      m(l.near_weight_range_m), m(l.map_max_turn_rate_rad_s);
  dpcr::FrontEndConfig& f = c.front_end;
  m(f.submap_scans), m(f.submap_line_period), m(f.region_line_period), m(f.second_registration_period),
      m(f.submap_miss_range_m), m(f.region_miss_range_m), m(f.submap_refit_gate_m), m(f.submap_refit_min_points),
      m(f.region_width_m), m(f.region_hysteresis_m), m(f.region_mature_scans), m(f.reference_inner_margin_m),
      m(f.region_slow_learning_scans), m(f.region_slow_learning_rate),
      m(f.enable_registration), m(f.lost_after_rejections), m(f.lidar_only_lost_after_second_rejections), m(f.prior_info_xy), m(f.prior_info_theta), m(f.max_acceleration_mps2), m(f.weak_direction_information), m(f.odometry_doubt_m), m(f.odometry_doubt_rad),
      m(f.second_registration_max_points), m(f.min_start_hits), m(f.sparse_scan_share), m(f.sparse_reference_full_share), m(f.sparse_residual_noise_factor), m(f.redeskew_min_m), m(f.redeskew_min_rad), m(f.lidar_only_fixed_lag);
  Plicp(m, f.first_registration);
  m(f.search_on_rejection), m(f.search_turn_rad), m(f.degenerate_guess_forward), m(f.turn_holds_translation),
      m(f.calibrate_odometry), m(f.accept_partial_overlap);
  m(f.search.resolution_m), m(f.search.sigma_m), m(f.search.kernel_radius_cells), m(f.search.angle_window_rad),
      m(f.search.angle_step_rad), m(f.search.xy_window_m), m(f.search.max_points), m(f.search.step_penalty),
      m(f.search.min_gain);
  m(f.weak_match_inlier_ratio), m(f.weak_match_obstacle_threshold);
  m(f.grid_turn_rad), m(f.grid_turn_band_rad);
  m(f.start_heading.window_s), m(f.start_heading.skip_s), m(f.start_heading.min_samples),
      m(f.start_heading.min_offset_rad), m(f.start_heading.max_offset_rad), m(f.start_heading.max_bias_rad_s);
  m(f.start_scans.enabled), m(f.start_scans.window_s), m(f.start_scans.every_s), m(f.start_scans.min_scans),
      m(f.start_scans.max_offset_rad), m(f.start_scans.max_bias_rad_s), m(f.start_scans.locate);
  Plicp(m, f.second_registration);
  Reference(m, f.submap_reference);
  Reference(m, f.region_reference);
  dpcr::BackEndConfig& b = c.back_end;
  m(b.enable), m(b.neighbour_factor), m(b.min_scans), m(b.min_match_rate), m(b.max_cloud_points), m(b.residual_sigma_m),
      m(b.correlated_points), m(b.floor_sigma_m), m(b.floor_sigma_rad), m(b.sequence_sigma_m), m(b.sequence_sigma_rad),
      m(b.loop_min_path_m), m(b.loop_retry_scans), m(b.loop_retry_path_m), m(b.search_base_m), m(b.search_per_metre_m),
      m(b.search_max_m), m(b.search_base_rad), m(b.search_per_metre_rad), m(b.search_max_rad), m(b.search_points),
      m(b.search_evaluations_per_step), m(b.match_grid_coarsen), m(b.large_closure_max_residual_m), m(b.closure_prior_info),
      m(b.ridge_information), m(b.ridge_fit_tolerance), m(b.unfollowed_closure_min_score), m(b.confirm_second_ratio), m(b.confirm_guess_window_m);
  m(b.search.min_angle_step_rad), m(b.search.max_angle_step_rad), m(b.search.min_score), m(b.search.max_second_ratio),
      m(b.search.peak_separation_m), m(b.search.peak_separation_rad);
  Plicp(m, b.registration);
  Plicp(m, b.closure_registration);
  m(b.max_edge_chi2), m(b.optimizer.max_iterations), m(b.optimizer.min_step_m), m(b.optimizer.min_step_rad),
      m(b.optimizer.kernel_phi), m(b.optimizer.damping);
  dpcr::LocalisationConfig& loc = c.localisation;
  m(loc.relocalise), m(loc.unknown_start), m(loc.localise_only), m(loc.coarsen), m(loc.coarse_angle_step_rad),
      m(loc.angles_per_step), m(loc.window_margin_m), m(loc.cloud_points), m(loc.max_second_ratio), m(loc.min_inlier_ratio),
      m(loc.near_window_m), m(loc.near_window_mps), m(loc.clear_min_score), m(loc.clear_max_ratio),
      m(loc.heading_window_rad), m(loc.heading_window_rad_s);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using Tiny = dpcr::Mapper<dpcr::TinyProfile>;
  static const dpcr::fuzz::TinyMapRun run;
  // Byte 0: an odometry fault (bit 7 on: from scan 4 + bits 0-3 on, the odometry heading jumps by
  // bits 4-6 x 0.15 rad and x 0.1 m, so that registrations fail and the searches run). Then a list
  // of edits of the test configuration: a field index byte, a choice byte (and what the choice
  // consumes); the empty input is the configuration itself.
  const std::uint8_t fault = size > 0 ? data[0] : 0;
  FuzzedDataProvider in(size > 0 ? data + 1 : data, size > 0 ? size - 1 : 0);
  dpcr::MapperConfig config = run.config;
  FieldList list;
  ForEachField(list, config);
  dpcr::fuzz::ValueMutator mutator(in);
  while (in.remaining_bytes() >= 2) {
    const std::size_t index = in.ConsumeIntegral<std::uint8_t>();
    const std::uint8_t choice = in.ConsumeIntegral<std::uint8_t>();
    if (index >= list.fields().size()) continue;
    std::visit([&](auto* field) { mutator(*field, choice); }, list.fields()[index]);
  }
  const dpcr::Status verdict = dpcr::Validate(config, Tiny::Limits());
  static Tiny* mapper = new Tiny();
  FUZZ_CHECK(mapper->Init(config) == verdict);
  if (verdict != dpcr::Status::kOk) return 0;
  // Enough scans for submap line rebuilds, second registrations and a region change at the
  // default periods.
  const std::size_t fault_scan = (fault & 0x80) != 0 ? 4u + (fault & 15u) : SIZE_MAX;
  const float jump = static_cast<float>((fault >> 4) & 7);
  std::size_t odom = 0;
  for (std::size_t i = 0; i < 30 && i < run.run.scans.size(); ++i) {
    const auto& scan = run.run.scans[i];
    while (odom < run.run.odometry.size() && run.run.odometry[odom].stamp_us <= scan.stamp_us) {
      dpcr::OdometrySample sample = run.run.odometry[odom++];
      if (i >= fault_scan) {
        sample.pose.x += 0.1f * jump;
        sample.pose.theta = dpcr::NormalizeAngle(sample.pose.theta + 0.15f * jump);
      }
      mapper->AddOdometry(sample);
    }
    (void)mapper->AddScan(scan);
  }
  const dpcr::Pose2 p = mapper->pose();
  FUZZ_CHECK(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta));
  return 0;
}
