#include "core/back_end/global_localiser.hpp"

#include <cmath>

namespace dpcr {
namespace {

// Two poses are separate peaks when they differ by more than the loop-closure search's separation.
bool Separated(const Pose2& a, const Pose2& b, const CorrelativeSearchConfig& search) {
  return std::hypot(a.x - b.x, a.y - b.y) >= search.peak_separation_m ||
         std::fabs(NormalizeAngle(a.theta - b.theta)) >= search.peak_separation_rad;
}

// Headings per coarse search: each search gives one candidate, so a map is cut into slices
// (about pi each at 0.07 rad: two per map) and its wrong headings can compete with its right one.
constexpr int kSliceAngles = 45;

}  // namespace

int GlobalLocaliser::SlicesPerMap(const LocalisationConfig& c) const {
  // Under LimitHeadings a global round's map is searched in kTilesPerMap squares instead (each
  // gives its own candidate, so that a look-alike at the same heading competes with the best).
  if (heading_window_ > 0.0f) return local_tiles_ > 0 ? 1 : kTilesPerMap;
  return static_cast<int>(std::ceil(2.0f * kPi / (static_cast<float>(kSliceAngles) * c.coarse_angle_step_rad)));
}

float GlobalLocaliser::SliceHalfWidth(const LocalisationConfig& c) const {
  const float full = 0.5f * static_cast<float>(kSliceAngles) * c.coarse_angle_step_rad;
  return heading_window_ > 0.0f && heading_window_ < full ? heading_window_ : full;
}

void GlobalLocaliser::LimitHeadings(float world_heading, float half_window_rad) {
  heading_ = world_heading;
  heading_window_ = half_window_rad > 0.0f && half_window_rad < kPi ? half_window_rad : 0.0f;
}

GlobalLocaliser::Candidate GlobalLocaliser::Load(const BackEndStorage& s, int i) {
  const Point2* p = s.cloud.data() + s.cloud.size() - kCandidateEntries + 3 * static_cast<std::size_t>(i);
  Candidate c;
  c.in_map = Pose2{p[0].x, p[0].y, p[1].x};
  c.coarse = p[1].y;
  c.fine = p[2].x;
  c.map = static_cast<int>(p[2].y);
  return c;
}

void GlobalLocaliser::Store(const BackEndStorage& s, int i, const Candidate& c) {
  Point2* p = s.cloud.data() + s.cloud.size() - kCandidateEntries + 3 * static_cast<std::size_t>(i);
  p[0] = Point2{c.in_map.x, c.in_map.y};
  p[1] = Point2{c.in_map.theta, c.coarse};
  p[2] = Point2{c.fine, static_cast<float>(c.map)};
}

void GlobalLocaliser::Hold(const BackEndStorage& s, const Pose2& pose) {
  if (s.cloud.size() < kCandidateEntries + kStateEntries) return;
  State(s, 2)[0] = Point2{pose.x, pose.y};
  State(s, 3)[0] = Point2{pose.theta, 0.0f};
  held_ = true;
}

bool GlobalLocaliser::Held(const BackEndStorage& s, Pose2* pose) const {
  if (!held_) return false;
  *pose = Pose2{State(s, 2)->x, State(s, 2)->y, State(s, 3)->x};
  return true;
}

void GlobalLocaliser::BeginLocal(const BackEndStorage& s, Span<const Point2> hits, const LocalisationConfig& config,
                                 int map, const Pose2& centre, float window_m) {
  Begin(s, hits, config);
  if (s.cloud.size() < kCandidateEntries + kStateEntries || map < 0 || !(window_m > 0.0f)) return;
  State(s, 0)[0] = Point2{centre.x, centre.y};
  State(s, 1)[0] = Point2{centre.theta, window_m};
  const float tiles = std::ceil(window_m / kLocalTileHalfM);
  local_tiles_ = static_cast<std::uint8_t>(tiles < 1.0f ? 1.0f : (tiles > 15.0f ? 15.0f : tiles));
  local_map_ = static_cast<std::int16_t>(map);
}

void GlobalLocaliser::Begin(const BackEndStorage& s, Span<const Point2> hits, const LocalisationConfig& config) {
  const std::size_t reserved = kCandidateEntries + kStateEntries;
  const std::size_t room = s.cloud.size() > reserved ? s.cloud.size() - reserved : 0;
  const std::size_t capacity = static_cast<std::size_t>(config.cloud_points) < room ? static_cast<std::size_t>(config.cloud_points) : room;
  std::size_t n = 0;
  if (capacity > 0 && !hits.empty()) {
    // The hits thinned evenly to at most `capacity`, stored interleaved: every k-th first, so that
    // the cloud's first CoarseSize() points are an even thinning too (the coarse search's).
    const std::size_t stride = (hits.size() + capacity - 1) / capacity;
    const std::size_t count = (hits.size() + stride - 1) / stride;
    const std::size_t k = (count + kCoarsePoints - 1) / kCoarsePoints;
    for (std::size_t phase = 0; phase < k; ++phase) {
      for (std::size_t j = phase; j < count; j += k) s.cloud[n++] = hits[j * stride];
    }
  }
  cloud_size_ = static_cast<std::uint16_t>(n);
  grid_map_ = -1;
  local_tiles_ = 0;
  local_map_ = -1;
  heading_window_ = 0.0f;
  cursor_ = slice_ = candidates_ = 0;
  phase_ = kCoarse;
}

Span<const Point2> GlobalLocaliser::CoarseCloud(const BackEndStorage& s) const {
  const std::size_t k = (cloud_size_ + kCoarsePoints - 1) / kCoarsePoints;
  return Span<const Point2>(s.cloud.data(), k == 0 ? 0 : (cloud_size_ + k - 1) / k);
}

void GlobalLocaliser::EnsureGrid(const BackEndStorage& s, const RegionalMap& map, int index, int coarsen,
                                 std::int16_t threshold) {
  if (grid_map_ == index) return;
  // The regional reference's table, as for a loop closure: nothing else builds that reference
  // while the robot is lost.
  s.match_grid->Attach(s.reference->LendTable());
  s.match_grid->Build(*map.grid, map.grid->box(), coarsen, threshold);
  grid_map_ = static_cast<std::int16_t>(index);
}

void GlobalLocaliser::Offer(const BackEndStorage& s, Span<const RegionalMap> maps, const Candidate& c,
                            const CorrelativeSearchConfig& search) {
  // Compared in the world frame: neighbouring maps overlap, and the same pose found in two of
  // them is one peak, not two.
  const Pose2 world = maps[static_cast<std::size_t>(c.map)].anchor * c.in_map;
  int worst = -1;
  for (int i = 0; i < candidates_; ++i) {
    const Candidate k = Load(s, i);
    if (!Separated(world, maps[static_cast<std::size_t>(k.map)].anchor * k.in_map, search)) {
      if (c.coarse > k.coarse) Store(s, i, c);
      return;
    }
    if (worst < 0 || k.coarse < Load(s, worst).coarse) worst = i;
  }
  if (candidates_ < kCandidates) {
    Store(s, candidates_++, c);
  } else if (c.coarse > Load(s, worst).coarse) {
    Store(s, worst, c);
  }
}

CorrelativeSearchConfig GlobalLocaliser::CoarseSearch(const LocalisationConfig& config, const BackEndConfig& back_end) {
  CorrelativeSearchConfig search = back_end.search;
  search.min_angle_step_rad = search.max_angle_step_rad = config.coarse_angle_step_rad;
  // Only each slice's best pose is kept (the fine phase judges ambiguity): prune every block
  // that cannot beat it, not the near-best ones the loop-closure search keeps.
  search.max_second_ratio = 1.0f;
  return search;
}

void GlobalLocaliser::SearchSlice(const BackEndStorage& s, Span<const RegionalMap> maps, int map, Point2 at,
                                  float base_heading, float window_m, bool border_rejects, const LocalisationConfig& config,
                                  const BackEndConfig& back_end) {
  // The slice's headings around its centre, its translations within window_m of `at`; under
  // LimitHeadings the one slice is the window about the robot's heading in the map's frame.
  const bool limited = heading_window_ > 0.0f;
  const float half_slice = SliceHalfWidth(config);
  const float centre = limited ? heading_ - maps[static_cast<std::size_t>(map)].anchor.theta
                               : base_heading - kPi + (2.0f * static_cast<float>(slice_) + 1.0f) * half_slice;
  if (limited && local_tiles_ == 0) {
    // Square slice_ of the 2 x 2 the map's square is cut into, overlapping by a match cell (a
    // peak on their border is one candidate: Offer keeps the better of two close poses).
    const float half = 0.5f * window_m;
    at = Point2{at.x + (slice_ % 2 == 0 ? -half : half), at.y + (slice_ / 2 == 0 ? -half : half)};
    window_m = half + s.match_grid->resolution_m();
  }
  const CorrelativeSearchConfig search = CoarseSearch(config, back_end);
  const CorrelativeSearchResult r = CorrelativeSearch(*s.match_grid, CoarseCloud(s), Pose2{at.x, at.y, NormalizeAngle(centre)},
                                                      window_m, half_slice, search, s.rotated);
  if (r.verdict != Status::kNotEnoughData && !(border_rejects && r.on_border)) {
    Candidate c;
    c.in_map = r.pose;
    c.coarse = r.score;
    c.map = map;
    Offer(s, maps, c, search);
  }
  if (++slice_ >= SlicesPerMap(config)) {
    slice_ = 0;
    ++cursor_;
  }
}

void GlobalLocaliser::EndCoarse() {
  phase_ = kFine;
  cursor_ = 0;
  grid_map_ = -1;  // the fine phase builds at its own resolution
}

void GlobalLocaliser::LocalCoarseStep(const BackEndStorage& s, Span<const RegionalMap> maps, float region_width_m,
                                      std::int16_t threshold, const LocalisationConfig& config, const BackEndConfig& back_end) {
  const int n = local_tiles_, squares = n * n;
  const Point2 c = *State(s, 0), cw = *State(s, 1);
  const float half = cw.y / static_cast<float>(n);
  // The work of a global step (angles_per_step headings over a map's square and margin), counted in
  // squares: a square's slice costs its share of that area.
  const float global_half = 0.5f * region_width_m + config.window_margin_m;
  const bool young = local_map_ < 0 || static_cast<std::size_t>(local_map_) >= maps.size() ||
                     maps[static_cast<std::size_t>(local_map_)].scans_inserted < static_cast<std::uint32_t>(back_end.min_scans);
  // Squares overlap by a match cell.
  const float overlap = young ? 0.0f : maps[static_cast<std::size_t>(local_map_)].grid->resolution_m() * static_cast<float>(config.coarsen);
  const float cost = ((half + overlap) * (half + overlap)) / (global_half * global_half);
  const float budget = static_cast<float>(config.angles_per_step) / static_cast<float>(kSliceAngles);
  for (float done = 0.0f; phase_ == kCoarse; done += cost) {
    if (young || cursor_ >= squares) {
      EndCoarse();
      return;
    }
    if (done >= budget) return;
    EnsureGrid(s, maps[static_cast<std::size_t>(local_map_)], local_map_, config.coarsen, threshold);
    const int ix = static_cast<int>(cursor_) % n, iy = static_cast<int>(cursor_) / n;
    const float ox = static_cast<float>(2 * ix + 1 - n) * half, oy = static_cast<float>(2 * iy + 1 - n) * half;
    // A best pose on a square's border (or on a slice's: the two slices overlap) is the slope of a
    // peak found inside another square, or of one outside the window: not a candidate.
    SearchSlice(s, maps, local_map_, Point2{c.x + ox, c.y + oy}, cw.x, half + overlap, true, config, back_end);
  }
}

void GlobalLocaliser::CoarseStep(const BackEndStorage& s, Span<const RegionalMap> maps, float region_width_m,
                                 std::int16_t threshold, const LocalisationConfig& config, const BackEndConfig& back_end) {
  if (local_tiles_ > 0) {
    LocalCoarseStep(s, maps, region_width_m, threshold, config, back_end);
    return;
  }
  const float window_m = 0.5f * region_width_m + config.window_margin_m;
  // Up to angles_per_step headings: whole slices, map after map; maps too young to hold a room
  // are skipped.
  for (int done = 0; done < config.angles_per_step && phase_ == kCoarse;) {
    if (cursor_ >= maps.size()) {
      EndCoarse();
      return;
    }
    const RegionalMap& map = maps[cursor_];
    if (map.scans_inserted < static_cast<std::uint32_t>(back_end.min_scans)) {
      ++cursor_;
      continue;
    }
    EnsureGrid(s, map, static_cast<int>(cursor_), config.coarsen, threshold);
    // Translations over the map's region square and margin (the anchor is the square's centre).
    SearchSlice(s, maps, static_cast<int>(cursor_), Point2{0.0f, 0.0f}, 0.0f, window_m, false, config, back_end);
    // A slice limited to a window of headings costs its share.
    done += heading_window_ > 0.0f ? 1 + static_cast<int>(2.0f * heading_window_ / config.coarse_angle_step_rad) : kSliceAngles;
  }
}

void GlobalLocaliser::FineStep(const BackEndStorage& s, Span<const RegionalMap> maps, std::int16_t threshold,
                               const LocalisationConfig& config, const BackEndConfig& back_end) {
  // Each candidate again on the 10 cm grid, within a coarse cell and step of it; several per call
  // while they share the map the grid holds (one grid build per call).
  bool built = false;
  while (cursor_ < candidates_) {
    Candidate c = Load(s, cursor_);
    if (grid_map_ != c.map) {
      if (built) return;
      EnsureGrid(s, maps[static_cast<std::size_t>(c.map)], c.map, back_end.match_grid_coarsen, threshold);
      built = true;
    }
    const float window_m = s.match_grid->resolution_m() * static_cast<float>(config.coarsen) / static_cast<float>(back_end.match_grid_coarsen);
    const CorrelativeSearchResult r =
        CorrelativeSearch(*s.match_grid, Cloud(s), c.in_map, window_m, config.coarse_angle_step_rad, back_end.search, s.rotated);
    c.fine = r.verdict != Status::kNotEnoughData ? r.score : 0.0f;
    if (r.verdict != Status::kNotEnoughData) c.in_map = r.pose;
    Store(s, cursor_++, c);
  }
  phase_ = kVerify;
}

Status GlobalLocaliser::Step(const BackEndStorage& s, Span<const RegionalMap> maps, float region_width_m,
                             const ReferenceConfig& reference, const LocalisationConfig& config,
                             const BackEndConfig& back_end, GlobalFix* fix) {
  switch (phase_) {
    case kIdle:
      return Status::kRejected;
    case kCoarse:
      CoarseStep(s, maps, region_width_m, reference.obstacle_threshold, config, back_end);
      return Status::kNotEnoughData;
    case kFine:
      FineStep(s, maps, reference.obstacle_threshold, config, back_end);
      return Status::kNotEnoughData;
    case kVerify:
      break;
  }
  return Verify(s, maps, reference, config, back_end, fix);
}

Status GlobalLocaliser::Verify(const BackEndStorage& s, Span<const RegionalMap> maps, const ReferenceConfig& reference,
                               const LocalisationConfig& config, const BackEndConfig& back_end, GlobalFix* fix) {
  phase_ = kIdle;
  *fix = GlobalFix{};
  int best = -1;
  for (int i = 0; i < candidates_; ++i) {
    if (best < 0 || Load(s, i).fine > Load(s, best).fine) best = i;
  }
  if (best < 0) return Status::kRejected;
  const Candidate b = Load(s, best);
  const Pose2 best_world = maps[static_cast<std::size_t>(b.map)].anchor * b.in_map;
  float second = 0.0f;
  for (int i = 0; i < candidates_; ++i) {
    const Candidate k = Load(s, i);
    if (i != best && k.fine > second && Separated(maps[static_cast<std::size_t>(k.map)].anchor * k.in_map, best_world, back_end.search)) {
      second = k.fine;
    }
  }
  fix->map = b.map;
  fix->in_map = b.in_map;
  fix->score = b.fine;
  fix->second_score = second;
  // Weak, or ambiguous (twin rooms, a bare corridor).
  if (b.fine < back_end.search.min_score || second >= config.max_second_ratio * b.fine) return Status::kRejected;
  // Verified by PLICP against the map's lines (the reference build takes the table back).
  const RegionalMap& map = maps[static_cast<std::size_t>(b.map)];
  ReferenceBuildStats stats;
  (void)s.reference->Build(*map.grid, map.grid->box(), reference, &stats);
  grid_map_ = -1;
  PlicpConfig plicp = back_end.closure_registration;
  plicp.min_inlier_ratio = config.min_inlier_ratio;
  const RegistrationResult r = RegisterImproved(*s.reference, Cloud(s), b.in_map, nullptr, plicp, s.correspondences);
  fix->inlier_ratio = r.inlier_ratio;
  if (r.verdict != Status::kOk) return Status::kRejected;
  fix->in_map = r.pose;
  return Status::kOk;
}

}  // namespace dpcr
