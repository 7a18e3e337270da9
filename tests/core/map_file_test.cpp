// The map file (core/persistence): round trips, continuing to map after a load, and files that
// are truncated, corrupted, crafted, from another profile or another version: each refused with
// its error, the mapper left as it was.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>

#include "core/persistence/crc32.hpp"
#include "core/persistence/map_reader.hpp"
#include "tests/core/map_file_fixtures.hpp"

namespace {

using dpcr::MapFileError;
using Tiny = dpcr::Mapper<dpcr::TinyProfile>;
using Vacuum = dpcr::Mapper<dpcr::VacuumProfile>;

// The header CRC and the trailer recomputed after an edit: what a crafted file would carry.
void Reseal(std::vector<std::uint8_t>* b) {
  auto& bytes = *b;
  dpcr::PutU32(bytes.data() + 92, dpcr::Crc32Of(bytes.data(), 92));
  const std::size_t end = bytes.size() - dpcr::kMapTrailerBytes;
  dpcr::PutU32(bytes.data() + end, dpcr::Crc32Of(bytes.data(), end));
}

dpcr::MapFileResult Load(Tiny& m, const std::vector<std::uint8_t>& bytes, std::size_t size = SIZE_MAX) {
  dpcr::MemoryMapSource source(dpcr::Span<const std::uint8_t>(bytes.data(), size < bytes.size() ? size : bytes.size()));
  return m.LoadMap(source);
}

// A tiny-profile map of the first `scans` scans of an 8 m room run (two or three regions).
struct TinyMap {
  explicit TinyMap(int scans) : run(8.0f, 400, 180), mapper(dpcr::test::MakeMapper<dpcr::TinyProfile>()) {
    dpcr::test::Feed(*mapper, run, 0, static_cast<std::size_t>(scans));
    bytes = dpcr::test::SaveToBytes(*mapper);
  }
  dpcr::test::SyntheticRun<Tiny> run;
  std::unique_ptr<Tiny> mapper;
  std::vector<std::uint8_t> bytes;
};

// What a refused load must leave alone, cheap enough to compare after every attempt.
struct Summary {
  int regions;
  std::size_t tiles;
  int vertices;
  int edges;
  float anchor_x;
  bool operator==(const Summary& o) const {
    return regions == o.regions && tiles == o.tiles && vertices == o.vertices && edges == o.edges && anchor_x == o.anchor_x;
  }
};
Summary Summarise(const Tiny& m) {
  return Summary{m.region_count(), m.tiles_used(), m.back_end().graph().vertex_count(), m.back_end().graph().edge_count(),
                 m.region_count() > 0 ? m.region_anchor(m.region_count() - 1).x : 0.0f};
}

}  // namespace

TEST_CASE("CRC-32 is zlib's") {
  const char* text = "123456789";
  REQUIRE(dpcr::Crc32Of(reinterpret_cast<const std::uint8_t*>(text), 9) == 0xCBF43926u);
  dpcr::Crc32 split;
  split.Add(reinterpret_cast<const std::uint8_t*>(text), 4);
  split.Add(reinterpret_cast<const std::uint8_t*>(text) + 4, 5);
  REQUIRE(split.value() == 0xCBF43926u);
}

TEST_CASE("Tile runs code every cell pattern and are never longer than needed") {
  std::int16_t cells[dpcr::kTileCells];
  const std::int16_t lo = -3584, hi = 3584;
  for (int i = 0; i < dpcr::kTileCells; ++i) cells[i] = dpcr::kUnknownCell;
  REQUIRE(dpcr::TileRunBytes(cells, lo, hi) == 16);  // 16 runs of 64 unknown cells
  for (int i = 0; i < dpcr::kTileCells; ++i) cells[i] = static_cast<std::int16_t>(i % 3 == 0 ? lo : (i % 3 == 1 ? hi : 7 * i));
  REQUIRE(dpcr::TileRunBytes(cells, lo, hi) < dpcr::kMapRawTileBytes);  // a byte per clamp, 3 per other value
  for (int i = 0; i < dpcr::kTileCells; ++i) cells[i] = static_cast<std::int16_t>(i - 512);
  REQUIRE(dpcr::TileRunBytes(cells, lo, hi) > dpcr::kMapRawTileBytes);  // all different: the writer stores it raw
  // Tokens cover the tile exactly.
  int covered = 0;
  while (covered < dpcr::kTileCells) covered += dpcr::NextTileToken(cells, covered, lo, hi).cells;
  REQUIRE(covered == dpcr::kTileCells);
}

TEST_CASE("A saved map loads into a fresh mapper with the same maps, anchors and graph") {
  const TinyMap saved(400);
  REQUIRE(saved.mapper->region_count() >= 2);
  REQUIRE(saved.bytes.size() == saved.mapper->map_file_bytes());
  auto fresh = dpcr::test::MakeMapper<dpcr::TinyProfile>();
  const dpcr::MapFileResult r = Load(*fresh, saved.bytes);
  REQUIRE(r.ok());
  REQUIRE(fresh->region_count() == saved.mapper->region_count());
  REQUIRE(fresh->tiles_used() == saved.mapper->tiles_used());
  for (int i = 0; i < fresh->region_count(); ++i) {
    REQUIRE(fresh->region_anchor(i).x == saved.mapper->region_anchor(i).x);
    REQUIRE(fresh->region_anchor(i).y == saved.mapper->region_anchor(i).y);
    REQUIRE(fresh->region_anchor(i).theta == saved.mapper->region_anchor(i).theta);
  }
  REQUIRE(dpcr::test::Fingerprint(*fresh) == dpcr::test::Fingerprint(*saved.mapper));
  // Saved again: the same bytes.
  REQUIRE(dpcr::test::SaveToBytes(*fresh) == saved.bytes);
}

TEST_CASE("A vacuum map round-trips, written in chunks no larger than the writer's buffer") {
  const dpcr::test::SyntheticRun<Vacuum> run(8.0f, 400, 450);
  auto m = dpcr::test::MakeMapper<dpcr::VacuumProfile>();
  dpcr::test::Feed(*m, run);
  dpcr::test::VectorSink sink;
  REQUIRE(m->SaveMap(sink).ok());
  REQUIRE(sink.largest_chunk <= dpcr::kMapWriteChunkBytes);
  REQUIRE(sink.bytes.size() == m->map_file_bytes());
  auto fresh = dpcr::test::MakeMapper<dpcr::VacuumProfile>();
  dpcr::MemoryMapSource source(dpcr::Span<const std::uint8_t>(sink.bytes.data(), sink.bytes.size()));
  REQUIRE(fresh->LoadMap(source).ok());
  REQUIRE(dpcr::test::Fingerprint(*fresh) == dpcr::test::Fingerprint(*m));
  // Observed tiles only, most of them as runs: far below the tiles' raw size.
  REQUIRE(sink.bytes.size() < m->tiles_used() * dpcr::kMapRawTileBytes / 2);
}

TEST_CASE("A mapper never Init'ed loads a map under its default configuration, if the profile takes it") {
  const TinyMap saved(200);
  auto vacuum_map = dpcr::test::MakeMapper<dpcr::VacuumProfile>(dpcr::MapperConfig{});
  const dpcr::test::SyntheticRun<Vacuum> run(8.0f, 200, 450);
  dpcr::test::Feed(*vacuum_map, run);
  const auto bytes = dpcr::test::SaveToBytes(*vacuum_map);
  auto vacuum = std::make_unique<Vacuum>();
  dpcr::MemoryMapSource source(dpcr::Span<const std::uint8_t>(bytes.data(), bytes.size()));
  REQUIRE(vacuum->LoadMap(source).ok());
  REQUIRE(dpcr::test::Fingerprint(*vacuum) == dpcr::test::Fingerprint(*vacuum_map));
  // The defaults ask for more submap scans than the tiny profile holds: refused, not asserted.
  auto tiny = std::make_unique<Tiny>();
  REQUIRE(Load(*tiny, saved.bytes).error == MapFileError::kConfigMismatch);
}

TEST_CASE("An empty mapper saves a file that loads as an empty map") {
  auto m = dpcr::test::MakeMapper<dpcr::TinyProfile>();
  const auto bytes = dpcr::test::SaveToBytes(*m);
  REQUIRE(bytes.size() == dpcr::kMapHeaderBytes + dpcr::kMapTrailerBytes);
  const TinyMap other(100);
  REQUIRE(Load(*other.mapper, bytes).ok());
  REQUIRE(other.mapper->region_count() == 0);
}

TEST_CASE("Mapping goes on after a load in the saved frame, new regions joining the same graph") {
  const dpcr::test::SyntheticRun<Vacuum> run(12.0f, 400, 450);
  auto first = dpcr::test::MakeMapper<dpcr::VacuumProfile>();
  dpcr::test::Feed(*first, run, 0, 150);  // the first session sees the start of the room
  const int saved_regions = first->region_count();
  const std::vector<std::uint8_t> bytes = dpcr::test::SaveToBytes(*first);
  auto m = dpcr::test::MakeMapper<dpcr::VacuumProfile>();
  dpcr::MemoryMapSource source(dpcr::Span<const std::uint8_t>(bytes.data(), bytes.size()));
  REQUIRE(m->LoadMap(source).ok());
  // A second session from the same start (the known start pose: the saved frame's origin) goes further.
  dpcr::test::Feed(*m, run);
  const dpcr::Pose2 start = run.Sample(0.095f, 0.25f, 12.0f).pose;
  const dpcr::Pose2 expected = dpcr::Between(start, run.Sample(39.995f, 0.25f, 12.0f).pose);
  CHECK(m->pose().x == Approx(expected.x).margin(0.1));
  CHECK(m->pose().y == Approx(expected.y).margin(0.1));
  CHECK(m->status() == dpcr::MapperStatus::kTracking);
  // No farther from the truth than one session over the whole run gets (8 cm on this run,
  // quantisation; the two take different paths through the same drift, 4 cm apart at the end).
  auto whole = dpcr::test::MakeMapper<dpcr::VacuumProfile>();
  dpcr::test::Feed(*whole, run);
  const float loaded_error = std::hypot(m->pose().x - expected.x, m->pose().y - expected.y);
  const float whole_error = std::hypot(whole->pose().x - expected.x, whole->pose().y - expected.y);
  INFO("after a load " << loaded_error << " m off, one session " << whole_error << " m off");
  CHECK(loaded_error <= whole_error + 0.01f);
  REQUIRE(m->region_count() > saved_regions);
  // Every map, saved or new, is a vertex of one graph, linked to it by an edge.
  const dpcr::PoseGraph& g = m->back_end().graph();
  REQUIRE(g.vertex_count() == m->region_count());
  for (int v = 1; v < g.vertex_count(); ++v) {
    bool linked = false;
    for (int e = 0; e < g.edge_count(); ++e) linked = linked || g.edge(e).from == v || g.edge(e).to == v;
    CHECK(linked);
  }
  // The saved maps were found again and took the second session's scans (no duplicate regions).
  const dpcr::MapFileContent before = first->map_file_content(), after = m->map_file_content();
  for (std::size_t i = 0; i < static_cast<std::size_t>(saved_regions); ++i) {
    CHECK(after.regions[i].key == before.regions[i].key);
    CHECK(after.regions[i].scans_inserted > before.regions[i].scans_inserted);
  }
}

TEST_CASE("A load at a start pose away from the saved origin places the robot there") {
  const TinyMap saved(150);
  auto m = dpcr::test::MakeMapper<dpcr::TinyProfile>();
  dpcr::MemoryMapSource source(dpcr::Span<const std::uint8_t>(saved.bytes.data(), saved.bytes.size()));
  const dpcr::Pose2 start{1.0f, 0.5f, 0.3f};
  REQUIRE(m->LoadMap(source, start).ok());
  REQUIRE(m->pose().x == Approx(1.0f));
  REQUIRE(m->pose().theta == Approx(0.3f));
  dpcr::MemoryMapSource again(dpcr::Span<const std::uint8_t>(saved.bytes.data(), saved.bytes.size()));
  REQUIRE(m->LoadMap(again, dpcr::Pose2{NAN, 0.0f, 0.0f}).error == MapFileError::kBadStartPose);
}

TEST_CASE("A map truncated at every byte offset is refused and the mapper keeps its map") {
  const TinyMap saved(400);
  const TinyMap other(120);  // the mapper's current state: another map
  const Summary before = Summarise(*other.mapper);
  const std::uint32_t fingerprint = dpcr::test::Fingerprint(*other.mapper);
  std::size_t refused = 0;
  for (std::size_t size = 0; size < saved.bytes.size(); ++size) {
    const dpcr::MapFileResult r = Load(*other.mapper, saved.bytes, size);
    if (r.ok() || r.status == dpcr::Status::kOk) FAIL("truncated at " << size << " accepted");
    if (!(Summarise(*other.mapper) == before)) FAIL("truncated at " << size << " changed the mapper");
    ++refused;
  }
  REQUIRE(refused == saved.bytes.size());
  REQUIRE(dpcr::test::Fingerprint(*other.mapper) == fingerprint);
  std::printf("map file: %zu bytes (tiny profile, %d regions, %zu tiles), every truncation refused\n",
              saved.bytes.size(), saved.mapper->region_count(), saved.mapper->tiles_used());
}

TEST_CASE("A map with any one byte flipped is refused and the mapper keeps its map") {
  const TinyMap saved(400);
  const TinyMap other(120);
  const Summary before = Summarise(*other.mapper);
  const std::uint32_t fingerprint = dpcr::test::Fingerprint(*other.mapper);
  std::vector<std::uint8_t> bytes = saved.bytes;
  for (const std::uint8_t flip : {std::uint8_t{0xFF}, std::uint8_t{0x01}, std::uint8_t{0x80}}) {
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      bytes[i] ^= flip;
      const dpcr::MapFileResult r = Load(*other.mapper, bytes);
      bytes[i] ^= flip;
      if (r.ok()) FAIL("byte " << i << " ^ " << int{flip} << " accepted");
      if (!(Summarise(*other.mapper) == before)) FAIL("byte " << i << " changed the mapper");
    }
  }
  REQUIRE(dpcr::test::Fingerprint(*other.mapper) == fingerprint);
  REQUIRE(Load(*other.mapper, bytes).ok());  // the unflipped file still loads
}

TEST_CASE("Crafted files with valid checksums cannot crash the loader") {
  // Every byte changed and the CRCs recomputed: the structure checks alone stand between the
  // file and the mapper. Either refused (mapper unchanged) or loaded into a mapper that maps on.
  const TinyMap saved(400);
  auto m = dpcr::test::MakeMapper<dpcr::TinyProfile>();
  std::vector<std::uint8_t> bytes = saved.bytes;
  std::size_t accepted = 0, refused = 0;
  for (const std::uint8_t flip : {std::uint8_t{0xFF}, std::uint8_t{0x10}}) {
    for (std::size_t i = 0; i + dpcr::kMapTrailerBytes < bytes.size(); ++i) {
      if (i >= 92 && i < 96) continue;  // the header CRC itself
      const std::uint8_t keep = bytes[i];
      bytes[i] = static_cast<std::uint8_t>(keep ^ flip);
      Reseal(&bytes);
      const Summary before = Summarise(*m);
      const dpcr::MapFileResult r = Load(*m, bytes);
      if (r.ok()) {
        ++accepted;
        if (accepted % 64 == 1) dpcr::test::Feed(*m, saved.run, 0, 3);  // maps on without a crash
      } else {
        ++refused;
        if (!(Summarise(*m) == before)) FAIL("byte " << i << " refused but the mapper changed");
      }
      bytes[i] = keep;
    }
  }
  Reseal(&bytes);
  REQUIRE(bytes == saved.bytes);
  CHECK(refused > 0);
  std::printf("crafted files: %zu refused, %zu accepted (cell values, anchors within range)\n", refused, accepted);
}

TEST_CASE("Each kind of bad file gets its own error") {
  const TinyMap saved(400);
  auto m = dpcr::test::MakeMapper<dpcr::TinyProfile>();
  auto expect = [&](std::vector<std::uint8_t> bytes, MapFileError error, bool reseal) {
    if (reseal) Reseal(&bytes);
    const dpcr::MapFileResult r = Load(*m, bytes);
    CHECK(r.error == error);
    CHECK(r.status != dpcr::Status::kOk);
    CHECK(std::string(dpcr::Describe(r.error)).size() > 5);
  };
  auto edit = [&](std::size_t at, std::uint8_t value) {
    std::vector<std::uint8_t> b = saved.bytes;
    b[at] = value;
    return b;
  };
  expect(edit(0, 'X'), MapFileError::kBadMagic, false);
  expect(edit(8, 2), MapFileError::kUnsupportedVersion, true);
  expect(edit(30, 0xAA), MapFileError::kBadHeader, false);  // header CRC
  expect(edit(12, 'x'), MapFileError::kWrongProfile, true);  // "tiny" -> "xiny"
  expect(edit(300, static_cast<std::uint8_t>(saved.bytes[300] ^ 1)), MapFileError::kBadChecksum, false);
  std::vector<std::uint8_t> longer = saved.bytes;
  longer.push_back(0);
  expect(longer, MapFileError::kTrailingData, false);
  // Region 0's anchor x (offset 96 + 8) NaN; its key out of range.
  std::vector<std::uint8_t> b = saved.bytes;
  dpcr::PutF32(b.data() + 104, NAN);
  expect(b, MapFileError::kBadRegion, true);
  b = saved.bytes;
  dpcr::PutU32(b.data() + 96, 0x7FFFFFFF);
  expect(b, MapFileError::kBadRegion, true);
  // Region 0's first tile (offset 96 + 28): outside the 4-tile box, an unknown encoding.
  expect(edit(124, 9), MapFileError::kBadTile, true);
  expect(edit(126, 7), MapFileError::kBadTile, true);
  // The last edge's `from`: a vertex that does not exist.
  b = saved.bytes;
  const std::size_t last_edge = b.size() - dpcr::kMapTrailerBytes - dpcr::kMapEdgeBytes;
  dpcr::PutU16(b.data() + last_edge, 999);
  expect(b, MapFileError::kBadGraph, true);
  b = saved.bytes;
  dpcr::PutF32(b.data() + last_edge + 20, -1.0f);  // information(0, 0)
  expect(b, MapFileError::kBadGraph, true);
}

TEST_CASE("A map from another profile or grid is refused with the mapper unchanged") {
  const TinyMap saved(200);
  auto vacuum = dpcr::test::MakeMapper<dpcr::VacuumProfile>();
  dpcr::MemoryMapSource source(dpcr::Span<const std::uint8_t>(saved.bytes.data(), saved.bytes.size()));
  const dpcr::MapFileResult r = vacuum->LoadMap(source);
  REQUIRE(r.error == MapFileError::kWrongProfile);
  REQUIRE(r.status == dpcr::Status::kRejected);
  REQUIRE(vacuum->region_count() == 0);
  dpcr::MapperConfig coarser = dpcr::test::TestConfig<dpcr::TinyProfile>();
  coarser.grid.resolution_m = 0.1f;
  auto m = dpcr::test::MakeMapper<dpcr::TinyProfile>(coarser);
  REQUIRE(m != nullptr);
  REQUIRE(Load(*m, saved.bytes).error == MapFileError::kConfigMismatch);
}

namespace {

// Serves the map, but different bytes from the `change_on`-th pass on.
class ChangingSource final : public dpcr::MapByteSource {
 public:
  ChangingSource(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int change_on)
      : a_(a), b_(b), change_on_(change_on) {}
  std::size_t Read(std::uint8_t* buffer, std::size_t capacity) override {
    const std::vector<std::uint8_t>& v = passes_ >= change_on_ ? b_ : a_;
    std::size_t n = v.size() - offset_ < capacity ? v.size() - offset_ : capacity;
    std::memcpy(buffer, v.data() + offset_, n);
    offset_ += n;
    return n;
  }
  bool Rewind() override {
    ++passes_;
    offset_ = 0;
    return !fail_rewind;
  }
  bool fail_rewind = false;

 private:
  const std::vector<std::uint8_t>& a_;
  const std::vector<std::uint8_t>& b_;
  int change_on_;
  int passes_ = 0;
  std::size_t offset_ = 0;
};

class FailingSink final : public dpcr::MapByteSink {
 public:
  explicit FailingSink(std::size_t budget) : budget_(budget) {}
  dpcr::Status Write(const std::uint8_t*, std::size_t size) override {
    if (size > budget_) return dpcr::Status::kCapacityExceeded;
    budget_ -= size;
    return dpcr::Status::kOk;
  }

 private:
  std::size_t budget_;
};

}  // namespace

TEST_CASE("A source that cannot rewind, or changes under the load, is handled") {
  const TinyMap saved(400);
  std::vector<std::uint8_t> corrupt = saved.bytes;
  corrupt[corrupt.size() / 2] ^= 0x40;
  auto m = dpcr::test::MakeMapper<dpcr::TinyProfile>();
  ChangingSource stuck(saved.bytes, saved.bytes, 99);
  stuck.fail_rewind = true;
  REQUIRE(m->LoadMap(stuck).error == MapFileError::kUnreadable);
  // Changed after the checks (pass 3): noticed, the mapper emptied rather than half loaded.
  const TinyMap other(120);
  ChangingSource late(saved.bytes, corrupt, 3);
  REQUIRE(other.mapper->LoadMap(late).error == MapFileError::kChangedDuringLoad);
  REQUIRE(other.mapper->region_count() == 0);
  REQUIRE(other.mapper->back_end().graph().vertex_count() == 0);
  // Changed before: refused by the checks, the mapper unchanged.
  const TinyMap third(120);
  const Summary before = Summarise(*third.mapper);
  ChangingSource early(saved.bytes, corrupt, 2);
  REQUIRE(!third.mapper->LoadMap(early).ok());
  REQUIRE(Summarise(*third.mapper) == before);
}

TEST_CASE("A sink that fails stops the save with its status") {
  const TinyMap saved(200);
  for (std::size_t budget : {std::size_t{0}, std::size_t{100}, saved.bytes.size() - 1}) {
    FailingSink sink(budget);
    const dpcr::MapFileResult r = saved.mapper->SaveMap(sink);
    CHECK(r.error == MapFileError::kWriteFailed);
    CHECK(r.status == dpcr::Status::kCapacityExceeded);
  }
  FailingSink enough(saved.bytes.size());
  REQUIRE(saved.mapper->SaveMap(enough).ok());
}
