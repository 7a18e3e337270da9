// Compile-time capacities, grouped in named board profiles. sizeof(Mapper<Profile>) is the
// RAM bill of a profile; tests/budget/memory_budget_test.cpp prints it and checks it against
// kRamBudgetBytes.
//
// kBudget*Instr: instruction budgets per scan, by stage (mean over the fixed run of
// tests/budget/stage_cost.sh, counted by callgrind on x86-64, ~1.2-1.3x the count measured when
// set): prediction (odometry + de-skew), first registration, second registration, insertion
// (submap + regional map), line extraction (reference builds: obstacle cells, lines; the
// nearest-obstacle searches are paid by the registrations that query them).
#pragma once

#include <cstddef>
#include <cstdint>

namespace dpcr {

// Cells per tile side. 32x32 int16 = 2 KiB: small enough that unobserved space costs little,
// large enough that the per-tile index and bookkeeping stay under 7 % of the cells.
constexpr int kTileSide = 32;
constexpr int kTileCells = kTileSide * kTileSide;

// A robot vacuum in a home of 200 m² or more, on a Cortex-A7/A53 SoC or a Cortex-M7 with 2 MiB for mapping.
struct VacuumProfile {
  static constexpr const char* kName = "vacuum";
  static constexpr std::size_t kRamBudgetBytes = 2u * 1024u * 1024u;
  // LD06/LD19 give ~450 points per revolution; more is decimated, never truncated.
  static constexpr int kMaxBeams = 512;
  // Shared by every regional map: 600 tiles = 1.2 MiB of cells, 240 m² of observed floor at 5 cm
  // if regional maps did not overlap (they do, by the margin).
  static constexpr int kTilePoolTiles = 600;
  // Regions of 4 m over a 200 m² home: ~13 needed, with room for re-mapping and odd layouts.
  static constexpr int kMaxRegions = 30;
  // A regional map's index box in tiles per side (8 x 32 cells x 5 cm = 12.8 m: S = 4 m plus a 4.4 m margin).
  static constexpr int kRegionBoxTiles = 8;
  // Scans kept in the submap ring (the paper's N = 20 is the default, this the most).
  static constexpr int kSubmapMaxScans = 20;
  // Robot-centred submap: 256 x 256 cells = 12.8 m at 5 cm.
  static constexpr int kSubmapSideCells = 256;
  // Line features per grid (submap or regional map).
  static constexpr int kMaxLines = 512;
  // Obstacle cells a registration reference holds (a 12.8 m window of walls and furniture). Four
  // short of 4096: their 80 bytes (two references) hold the back end's closure waiting for
  // confirmation (closure_confirmation.hpp) in a budget that was full to the byte.
  static constexpr int kReferenceCells = 4092;
  // Edges of the back end's pose graph (part of the map file's layout: a change makes saved maps unloadable).
  static constexpr int kMaxGraphEdges = 96;
  // Prediction 225 K measured (71 K before the run declared an LD06's range noise: smoothing a
  // 450-beam scan's returns along its walls, core/geometry/return_smoothing.hpp, ~150 K).
  static constexpr std::uint64_t kBudgetPredictionInstr = 280'000;
  static constexpr std::uint64_t kBudgetFirstRegistrationInstr = 320'000;
  static constexpr std::uint64_t kBudgetSecondRegistrationInstr = 65'000;
  static constexpr std::uint64_t kBudgetInsertionInstr = 1'070'000;
  static constexpr std::uint64_t kBudgetLineExtractionInstr = 172'000;
  // The worst single AddScan call with the back end at work (a slice of a loop-closure search, a
  // map-to-map registration, an optimisation, a step of a lost robot's global search), counted by
  // tests/budget/back_end_cost.sh. Was 19 M (14.4 M measured, a map-to-map job); the worst is now
  // a relocalisation step (one map's coarse grid and a slice of 45 headings over it, 19.2 M; the
  // back end's own worst, a map-to-map job, is 17.2 M; a loop-closure search slice less). ~20-40 ms
  // on a Cortex-A53: a fifth to two fifths of a 10 Hz scan period. Since 2026-12-02 the run
  // declares an LD06's range noise, as dpcr-sim does (noise-aware line fits and trim floor, the
  // returns' smoothing): 21.5 M measured, hence 24 M. That call enters a new region (its map seeded
  // from the submap's scans 10.9 M, the submap recentred 4.1 M, a reference build 3.2 M) in the
  // scan a back-end job runs (3.1 M): seeding and a job in one call, not the smoothing (0.15 M).
  static constexpr std::uint64_t kBudgetWorstScanInstr = 24'000'000;
};

// The public benchmark logs (intel.clf: a 30 m x 30 m lab, ~900 m² with long corridors):
// not a vacuum, used by dpcr-replay on CARMEN logs so that those runs are not pool-limited.
struct BuildingProfile {
  static constexpr const char* kName = "building";
  static constexpr std::size_t kRamBudgetBytes = 8u * 1024u * 1024u;
  static constexpr int kMaxBeams = 512;
  static constexpr int kTilePoolTiles = 3200;
  static constexpr int kMaxRegions = 160;
  static constexpr int kRegionBoxTiles = 8;
  static constexpr int kSubmapMaxScans = 20;
  static constexpr int kSubmapSideCells = 256;
  static constexpr int kMaxLines = 512;
  static constexpr int kReferenceCells = 4096;
  static constexpr int kMaxGraphEdges = 1024;
  static constexpr std::uint64_t kBudgetPredictionInstr = 30'000;
  static constexpr std::uint64_t kBudgetFirstRegistrationInstr = 165'000;
  static constexpr std::uint64_t kBudgetSecondRegistrationInstr = 22'000;
  static constexpr std::uint64_t kBudgetInsertionInstr = 330'000;
  static constexpr std::uint64_t kBudgetLineExtractionInstr = 73'000;
};

// A small profile for tests: full pools are easy to reach.
struct TinyProfile {
  static constexpr const char* kName = "tiny";
  // 352 KiB: the grids and pools below plus the first registration's coarse search grid (80 x 80
  // cells) and the back end's fixed scratch (a region's cloud, the loop-closure search grid).
  static constexpr std::size_t kRamBudgetBytes = 352u * 1024u;
  static constexpr int kMaxBeams = 256;
  static constexpr int kTilePoolTiles = 48;
  static constexpr int kMaxRegions = 4;
  static constexpr int kRegionBoxTiles = 4;
  static constexpr int kSubmapMaxScans = 10;
  static constexpr int kSubmapSideCells = 128;
  static constexpr int kMaxLines = 128;
  static constexpr int kReferenceCells = 2048;
  static constexpr int kMaxGraphEdges = 16;
  static constexpr std::uint64_t kBudgetPredictionInstr = 160'000;  // 128 K, the returns' smoothing included
  // 480 K (was 140 K) and 170 K (was 54 K) below: this run (an 8 m room seen through the 6.4 m
  // submap, 180° turns in one scan at the lane ends) rejects 81 of its 300 first registrations;
  // a rejection now triggers a coarse pose search (every other scan of a streak) and a weak match
  // an early submap reference rebuild (every other scan at most). Measured 436 K and 155 K.
  // Line extraction 170 K -> 200 K: the first registration takes a clean fit of part of a scan
  // (PlicpConfig::accept_partial_overlap), and most of those 81 rejections were the part of the
  // room the submap does not reach: 12-20 are left, and the matches taken are weak ones, each
  // followed by an early rebuild (92 -> 112 of them). Measured 187 K.
  static constexpr std::uint64_t kBudgetFirstRegistrationInstr = 500'000;  // 484 K with the search's scratch off the stack
  static constexpr std::uint64_t kBudgetSecondRegistrationInstr = 40'000;  // 32 K: the hit margin gives more target cells
  static constexpr std::uint64_t kBudgetInsertionInstr = 445'000;
  static constexpr std::uint64_t kBudgetLineExtractionInstr = 200'000;
};

}  // namespace dpcr
