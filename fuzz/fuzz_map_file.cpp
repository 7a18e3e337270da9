// A map file (docs/map-file-format.md) -> the checked reader, as dpcr-map and Mapper::LoadMap
// use it. No crash; a file the mapper accepts saves to a file that loads again and saves to the
// same bytes, and the loaded mapper maps on (a few scans).
// Input: byte 0 is a flag (bit 0: recompute the header CRC and the trailer CRC-32 after the
// mutation, so that the fuzzer reaches the records behind the checksums), the rest the file.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/mapper.hpp"
#include "core/persistence/crc32.hpp"
#include "core/persistence/map_reader.hpp"
#include "fuzz/fuzz_check.hpp"
#include "fuzz/tiny_map_run.hpp"

namespace {

using Tiny = dpcr::Mapper<dpcr::TinyProfile>;

class VectorSink final : public dpcr::MapByteSink {
 public:
  dpcr::Status Write(const std::uint8_t* data, std::size_t size) override {
    bytes.insert(bytes.end(), data, data + size);
    return dpcr::Status::kOk;
  }
  std::vector<std::uint8_t> bytes;
};

std::vector<std::uint8_t> Save(const Tiny& m) {
  VectorSink sink;
  FUZZ_CHECK(m.SaveMap(sink).ok());
  FUZZ_CHECK(sink.bytes.size() == m.map_file_bytes());
  return sink.bytes;
}

dpcr::MapFileResult Load(Tiny& m, const std::vector<std::uint8_t>& bytes) {
  dpcr::MemoryMapSource source(dpcr::Span<const std::uint8_t>(bytes.data(), bytes.size()));
  return m.LoadMap(source);
}

// As dpcr-map check: the header, then every record, for any profile.
void CheckAsTool(const std::vector<std::uint8_t>& bytes) {
  dpcr::MemoryMapSource source(dpcr::Span<const std::uint8_t>(bytes.data(), bytes.size()));
  dpcr::MapFileHeader header;
  if (!dpcr::ReadMapFileHeader(source, &header).ok()) return;
  std::vector<dpcr::Point2> keys(header.region_count);
  dpcr::MapFileSummary summary;
  (void)dpcr::CheckMapFile(source, nullptr, dpcr::Span<dpcr::Point2>(keys.data(), keys.size()), &header, &summary);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::vector<std::uint8_t> file(data + 1, data + size);
  if ((data[0] & 1) != 0 && file.size() >= dpcr::kMapHeaderBytes + dpcr::kMapTrailerBytes) {
    dpcr::PutU32(file.data() + 92, dpcr::Crc32Of(file.data(), 92));
    const std::size_t end = file.size() - dpcr::kMapTrailerBytes;
    dpcr::PutU32(file.data() + end, dpcr::Crc32Of(file.data(), end));
  }
  CheckAsTool(file);

  static const dpcr::fuzz::TinyMapRun run;
  static Tiny* mapper = new Tiny();
  FUZZ_CHECK(mapper->Init(run.config) == dpcr::Status::kOk);
  if (!Load(*mapper, file).ok()) {
    FUZZ_CHECK(mapper->region_count() == 0);  // a refused file leaves the (empty) mapper as it was
    return 0;
  }
  const std::vector<std::uint8_t> saved = Save(*mapper);
  static Tiny* again = new Tiny();
  FUZZ_CHECK(again->Init(run.config) == dpcr::Status::kOk);
  FUZZ_CHECK(Load(*again, saved).ok());
  FUZZ_CHECK(again->region_count() == mapper->region_count());
  FUZZ_CHECK(Save(*again) == saved);
  // Mapping goes on in the loaded map.
  run.Feed(*mapper, 0, 3);
  return 0;
}
