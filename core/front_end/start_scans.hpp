// Scans of the run's first seconds, kept to place the start in the finished first map.
//
// The start pose is the world frame's only truth, and the first map's walls are fitted to the
// first scans' noisy returns: the whole map ends up turned about the start by a fraction of a
// degree (XV-11, apartment: -0.5 to +0.5 degrees), and that turn, times the distance from the
// start, is most of a run's error against the truth. The map keeps turning a little as it matures,
// so a fit of the heading during the first seconds (start_heading.hpp) misses part of it
// (docs/back-end.md, "The start placed in the finished map").
// Over a few seconds a gyro knows the robot's turn since the start to a few hundredths of a degree.
// So a few scans of the first seconds are kept with their heading less the gyro's turn since the
// start; at the end of the run each is registered again against the finished first map, and its
// heading there less the gyro's turn is the start's heading in that map, less the gyro's bias times
// the time. A least-squares line over the kept scans gives the start's heading at t = 0. Without a
// gyro, wheel ticks that carry only an IMU's heading serve as one (the front end decides at the end).
//
// Storage: kTiles tiles borrowed from the regional maps' tile pool (no RAM of its own, the pool's
// size and the map file unchanged). Each kept scan has kWordsPerScan int16 words: a header (its
// time since the start in ms, its point count, its heading less the gyro's turn in 1e-7 rad) and up
// to kMaxPoints points in the first map's frame in millimetres, thinned evenly. The object itself
// holds 24 bytes: the first tile's id, the start's stamp, the gyro's turn. The front end gives
// the tiles back when the pool runs out (the maps come first) and after the refinement.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/base/span.hpp"
#include "core/config.hpp"
#include "core/geometry/pose2.hpp"
#include "core/grid/tile_pool.hpp"

namespace dpcr {

// What FrontEnd::RefineStart did (metrics.json "start_scans").
struct StartRefinement {
  bool refined = false;    // the start was turned by offset_rad
  int kept = 0;            // start scans kept
  int registered = 0;      // of those, registered again against the finished map
  float offset_rad = 0.0f;  // the start's heading in the finished map less its recorded one
  float bias_rad_s = 0.0f;  // the gyro's bias, fitted with it
  float offset_se_rad = NAN;  // the offset's standard error
  // Without wheels measuring the translation: the start scan searched for in the finished first
  // map (StartScansConfig::locate). `shift` is the pose found in the recorded start's
  // frame (its heading is the search's, not applied); `moved`: the start moved by its x, y.
  bool located = false;
  bool moved = false;
  Pose2 shift;
};

class StartScans {
 public:
  static constexpr int kTiles = 8;
  static constexpr int kMaxKept = 32;
  static constexpr int kWordsPerScan = kTiles * kTileCells / kMaxKept;
  static constexpr int kHeaderWords = 4;
  static constexpr int kMaxPoints = (kWordsPerScan - kHeaderWords) / 2;
  // They take at most a sixteenth of the pool: a smaller pool (the tiny test profile) keeps none.
  static constexpr std::size_t kMinPoolTiles = 16 * kTiles;
  static_assert(kTiles - 1 <= static_cast<int>(sizeof(Tile::updated) / sizeof(Tile::updated[0])), "the other tiles' ids fit in the first's update bits");
  static_assert(kMaxPoints >= 100, "a kept scan needs about a hundred points for a heading to 0.1 degree");

  // One kept scan's header.
  struct Kept {
    float t_s = 0.0f;                   // since the start scan
    float heading_less_turn_rad = 0.0f;  // its heading in the first map then, less the gyro's turn since the start
    int points = 0;
  };

  // Gives back any tiles held (to `pool`, the one they came from) and keeps nothing. Every call
  // below that reads or writes the kept scans takes the pool their tiles came from: the class
  // holds their ids only (the vacuum profile has no byte to spare).
  void Reset(TilePool* pool);
  // The run's start scan, with the heading sensor's yaw at it: borrows the tiles (false, keeping
  // nothing, when the pool cannot spare them or is too small). Keep the start scan itself next.
  // `wheel_turns`: the yaw is the wheel odometry's (ticks that may carry only an IMU's heading;
  // the front end decides at the end whether they do).
  bool Begin(TilePool* pool, std::int64_t stamp_us, float yaw_rad, bool wheel_turns);
  // Every later scan, with the same sensor's yaw (have_yaw false: none). The turn since the start
  // is unwrapped scan by scan. Without a yaw, or past the window, keeping stops (what is kept stays).
  void Track(std::int64_t stamp_us, bool have_yaw, float yaw_rad, const StartScansConfig& config);
  void Stop() { keeping_ = false; }
  // Whether this scan is to be kept: keeping, room left, config.every_s since the last one kept.
  bool Due(const TilePool& pool, std::int64_t stamp_us, const StartScansConfig& config) const;
  // Keeps the scan: `in_map` its pose in the first map, `hits` its points in the robot frame.
  void Keep(TilePool* pool, std::int64_t stamp_us, const Pose2& in_map, Span<const Point2> hits);
  // Everything kept dropped and the tiles given back (the start scan's stamp stays).
  void Release(TilePool* pool);

  bool keeping() const { return keeping_; }
  bool wheel_turns() const { return wheel_turns_; }
  bool holds_tiles() const { return first_tile_ != kNoTile; }
  std::int64_t start_stamp_us() const { return start_us_; }
  int size() const { return n_; }
  Kept kept(const TilePool& pool, int i) const;
  // Kept scan i's points in the first map's frame, written to `out` (at most out.size()).
  std::size_t Points(const TilePool& pool, int i, Span<Point2> out) const;

 private:
  // The tile holding kept scan `scan`: the first one's id is here, the others' in the first tile's
  // update bits (a borrowed tile has no scans to mark).
  TileId TileOf(const TilePool& pool, int scan) const;
  std::int16_t* Words(TilePool* pool, int scan);
  const std::int16_t* Words(const TilePool& pool, int scan) const;

  std::int64_t start_us_ = 0;
  float last_yaw_ = 0.0f;
  float turn_ = 0.0f;  // the gyro's, unwrapped, since the start
  TileId first_tile_ = kNoTile;
  std::uint8_t n_ = 0;
  bool keeping_ = false;
  bool wheel_turns_ = false;
};

// The start's heading in the finished map less its recorded one, from the kept scans registered
// again: registered_turn[i] is kept(i)'s heading change by that registration (NaN: refused).
// Least squares r(t) = offset - bias t, r = heading then + registered turn - gyro turn - start
// heading.
struct StartOffsetFit {
  int scans = 0;               // registered scans fitted
  float offset_rad = 0.0f;
  float bias_rad_s = 0.0f;
  float offset_se_rad = NAN;   // the offset's standard error, from the residuals about the line
};
// False when fewer than config.min_scans were registered or the offset or bias is past the
// config's bounds (`fit` holds what was fitted).
bool FitStartOffset(const StartScans& scans, const TilePool& pool, const float* registered_turn, float start_heading_rad,
                    const StartScansConfig& config, StartOffsetFit* fit);

}  // namespace dpcr
