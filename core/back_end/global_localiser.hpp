// Global localisation against the regional maps (a robot kidnapped, lost, or started somewhere
// unknown in a saved map): where does one scan's cloud lie among all the maps? Coarse to fine:
// the back end's correlative search (branch and bound, correlative_search.hpp) runs over each
// map's region square and every heading on a 20 cm match grid, a few headings per call so that a
// scan's work stays bounded, and keeps the best few poses far apart in the world frame; each is
// then searched again on the loop-closure search's 10 cm grid. The best must be strong and unique
// (no separate pose of another or the same map scoring nearly as well: twin rooms), and PLICP
// against the map's lines verifies it.
//
// No storage of its own: the match grid borrows the regional reference's table
// (RegistrationReference::LendTable, as the loop-closure search does); the frozen cloud and the
// candidates live in the back end's cloud buffer and the rotation scratch is the back end's (both
// idle while the robot is lost: the front end runs no back-end job then). Twelve bytes of search
// state persist between calls.
#pragma once

#include <cstdint>

#include "core/back_end/back_end.hpp"
#include "core/back_end/correlative_search.hpp"
#include "core/back_end/localisation_config.hpp"
#include "core/base/span.hpp"
#include "core/base/status.hpp"
#include "core/front_end/regional_map.hpp"
#include "core/geometry/pose2.hpp"
#include "core/registration/plicp.hpp"
#include "core/registration/registration_reference.hpp"

namespace dpcr {

// The answer of a search round.
struct GlobalFix {
  int map = -1;
  Pose2 in_map;   // the cloud's frame (the robot at the frozen scan) in the map's frame
  float score = 0.0f;         // the best pose's score on the 10 cm grid (0..1)
  float second_score = 0.0f;  // the best separate pose's
  float inlier_ratio = 0.0f;  // PLICP's
};

class GlobalLocaliser {
 public:
  // Candidates kept from the coarse search (the best poses, pairwise separated in the world).
  static constexpr int kCandidates = 6;
  // Back-end cloud entries they take (three points each), at its end.
  static constexpr std::size_t kCandidateEntries = 3 * kCandidates;
  // Entries just before them: a local round's centre and window (two points) and the held fix
  // (two points), kept while the frozen cloud of the next round fills the front.
  static constexpr std::size_t kStateEntries = 4;
  // A local round's window is searched in squares of at most this half-width (each gives its own
  // candidates, so that a look-alike inside the window competes with the best pose).
  static constexpr float kLocalTileHalfM = 0.5f;
  // Squares a map's square is cut into in a global round limited to a window of headings.
  static constexpr int kTilesPerMap = 4;
  // Points of the frozen cloud the coarse search scores (an even thinning of it): its cost is
  // proportional, and the fine search and PLICP use the whole cloud.
  static constexpr std::size_t kCoarsePoints = 32;

  // Storage (BackEndStorage, passed to each call, not kept: RAM): the match grid and the
  // regional reference whose table it borrows, the cloud buffer (the frozen cloud, the
  // candidates), the rotation scratch and the correspondences.
  // Starts a round with the robot-frame points `hits` (thinned into the frozen cloud).
  void Begin(const BackEndStorage& s, Span<const Point2> hits, const LocalisationConfig& config);
  // A local round: the same search over map `map` alone, translations within `window_m` of
  // `centre` (the robot's believed pose at the frozen scan, in the map's frame), every heading
  // (LocalisationConfig::near_window_m: a robot without a heading sensor lost nearby).
  void BeginLocal(const BackEndStorage& s, Span<const Point2> hits, const LocalisationConfig& config, int map,
                  const Pose2& centre, float window_m);
  // Only headings within `half_window_rad` of `world_heading` (the robot's, in the world frame, at
  // the frozen scan) are searched in this round; 0 or pi and more: every heading. Called after
  // Begin / BeginLocal (which search every heading).
  void LimitHeadings(float world_heading, float half_window_rad);
  // Whether the current (or last) round is a local one.
  bool local() const { return local_tiles_ > 0; }
  void Cancel() { phase_ = kIdle; }
  // A fix held until another round agrees with it (LocalisationConfig::clear_min_score): any pose
  // (the front end's: the submap frame in the world), in the cloud buffer's state entries.
  void Hold(const BackEndStorage& s, const Pose2& pose);
  bool Held(const BackEndStorage& s, Pose2* pose) const;
  void Drop() { held_ = false; }
  bool holding() const { return held_; }
  // Someone else built the reference whose table the match grid borrows: rebuild it before use.
  void ForgetGrid() { grid_map_ = -1; }
  bool active() const { return phase_ != kIdle; }

  // One bounded step of the round over `maps`. kNotEnoughData: the round goes on; kOk: `fix` is
  // verified (the round is over); kRejected: the round ended with no strong, unique, verified
  // pose (`fix` says what was best). `reference`: the regional reference's settings (its
  // obstacle threshold marks walls).
  Status Step(const BackEndStorage& s, Span<const RegionalMap> maps, float region_width_m,
              const ReferenceConfig& reference, const LocalisationConfig& config, const BackEndConfig& back_end,
              GlobalFix* fix);

 private:
  enum Phase : std::uint8_t { kIdle, kCoarse, kFine, kVerify };
  struct Candidate {
    Pose2 in_map;
    float coarse = 0.0f, fine = 0.0f;
    int map = -1;
  };
  void EnsureGrid(const BackEndStorage& s, const RegionalMap& map, int index, int coarsen, std::int16_t threshold);
  void CoarseStep(const BackEndStorage& s, Span<const RegionalMap> maps, float region_width_m, std::int16_t threshold,
                  const LocalisationConfig& config, const BackEndConfig& back_end);
  // The coarse phase's search settings; one slice of headings (centred on base_heading + the
  // slice's place in the turn) over translations within window_m of `at` in map `map`, its best
  // pose offered as a candidate (not when on the window's border and `border_rejects`), and the
  // cursor moved on (next slice, or next map or square after the last).
  static CorrelativeSearchConfig CoarseSearch(const LocalisationConfig& config, const BackEndConfig& back_end);
  void SearchSlice(const BackEndStorage& s, Span<const RegionalMap> maps, int map, Point2 at, float base_heading, float window_m,
                   bool border_rejects, const LocalisationConfig& config, const BackEndConfig& back_end);
  // Searches a map takes: slices of headings; under LimitHeadings one (a local round's square)
  // or kTilesPerMap squares of the map (a global round).
  int SlicesPerMap(const LocalisationConfig& config) const;
  // A slice's half width of headings: kSliceAngles steps, or the LimitHeadings window when narrower.
  float SliceHalfWidth(const LocalisationConfig& config) const;
  void EndCoarse();
  void LocalCoarseStep(const BackEndStorage& s, Span<const RegionalMap> maps, float region_width_m, std::int16_t threshold,
                       const LocalisationConfig& config, const BackEndConfig& back_end);
  // State entry i (0, 1: the local centre and window; 2, 3: the held fix).
  static Point2* State(const BackEndStorage& s, int i) {
    return s.cloud.data() + s.cloud.size() - kCandidateEntries - kStateEntries + static_cast<std::size_t>(i);
  }
  void FineStep(const BackEndStorage& s, Span<const RegionalMap> maps, std::int16_t threshold,
                const LocalisationConfig& config, const BackEndConfig& back_end);
  void Offer(const BackEndStorage& s, Span<const RegionalMap> maps, const Candidate& c, const CorrelativeSearchConfig& search);
  Status Verify(const BackEndStorage& s, Span<const RegionalMap> maps, const ReferenceConfig& reference,
                const LocalisationConfig& config, const BackEndConfig& back_end, GlobalFix* fix);
  Span<const Point2> Cloud(const BackEndStorage& s) const { return Span<const Point2>(s.cloud.data(), cloud_size_); }
  // Its first points, an even thinning to at most kCoarsePoints (Begin stores it interleaved).
  Span<const Point2> CoarseCloud(const BackEndStorage& s) const;
  // Candidate i in the cloud buffer's last entries: (x, y), (theta, coarse), (fine, map).
  static Candidate Load(const BackEndStorage& s, int i);
  static void Store(const BackEndStorage& s, int i, const Candidate& c);

  std::uint16_t cloud_size_ = 0;
  std::int16_t grid_map_ = -1;  // the map the match grid holds at the current phase's resolution
  std::uint8_t cursor_ = 0;     // coarse: the map being searched; fine: the candidate
  std::uint8_t slice_ = 0;      // coarse: the map's next slice of headings
  std::uint8_t candidates_ = 0;
  Phase phase_ = kIdle;
  std::int16_t local_map_ = -1;
  std::uint8_t local_tiles_ = 0;  // a local round's squares per side (0: a global round)
  float heading_ = 0.0f;          // LimitHeadings: the world heading searched around
  float heading_window_ = 0.0f;   // and the half window (0: every heading)
  bool held_ = false;
};

}  // namespace dpcr
