// Map files through the storage port (hal/ports.hpp BlobStore; on Linux the atomic file store):
// a save streams the core's chunks into one atomic blob write, so the map is never copied whole in
// RAM and a power cut leaves the old map or the new one; a load reads the blob (at most the
// largest map the profile can write) and hands it to Mapper::LoadMap, which checks it whole
// before the mapper changes. Errors are one line: "NAME: what went wrong".
#pragma once

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "core/persistence/map_file_format.hpp"
#include "core/persistence/map_stream.hpp"
#include "hal/ports.hpp"

namespace dpcr::board {

// The store's streaming write as the core's sink.
class BlobMapSink final : public MapByteSink {
 public:
  explicit BlobMapSink(BlobStore& store) : store_(store) {}
  Status Write(const std::uint8_t* data, std::size_t size) override {
    return store_.Append(data, size) == IoStatus::kOk ? Status::kOk : Status::kInvalidArgument;
  }

 private:
  BlobStore& store_;
};

// Reads blob `name` into `out`, at most `max_bytes` + 1 bytes (one more than any valid map, so
// that an oversized file is refused by the loader, not silently cut). kNotFound: no such blob.
IoStatus ReadBlob(BlobStore& store, const char* name, std::uint64_t max_bytes, std::vector<std::uint8_t>* out);

template <class MapperType>
bool SaveMapBlob(const MapperType& mapper, BlobStore& store, const char* name, std::string* error) {
  if (store.Begin(name) != IoStatus::kOk) {
    *error = std::string(name) + ": " + std::strerror(errno);
    return false;
  }
  BlobMapSink sink(store);
  const MapFileResult r = mapper.SaveMap(sink);
  if (!r.ok()) {
    const int saved = errno;
    store.Abort();
    *error = std::string(name) + ": " + std::strerror(saved);
    return false;
  }
  if (store.Commit() != IoStatus::kOk) {
    *error = std::string(name) + ": " + std::strerror(errno);
    return false;
  }
  return true;
}

// What a load found: the blob absent (kNotFound, nothing changed), unreadable, refused (the
// mapper as it was), or loaded.
struct MapLoad {
  IoStatus io = IoStatus::kOk;
  MapFileResult file;
  std::size_t bytes = 0;
  bool loaded() const { return io == IoStatus::kOk && file.ok(); }
};

inline std::string DescribeMapLoad(const char* name, const MapLoad& load) {
  if (load.io == IoStatus::kNotFound) return std::string(name) + ": no such map";
  if (load.io != IoStatus::kOk) return std::string(name) + ": cannot be read";
  return std::string(name) + ": " + Describe(load.file.error) + " (at byte " + std::to_string(load.file.offset) + ")";
}

template <class MapperType>
MapLoad LoadMapBlob(MapperType& mapper, BlobStore& store, const char* name, const Pose2& start = Pose2::Identity()) {
  MapLoad load;
  std::vector<std::uint8_t> bytes;
  load.io = ReadBlob(store, name, MaxMapFileBytes(mapper.map_file_limits()), &bytes);
  if (load.io != IoStatus::kOk) return load;
  load.bytes = bytes.size();
  MemoryMapSource source(Span<const std::uint8_t>(bytes.data(), bytes.size()));
  load.file = mapper.LoadMap(source, start);
  return load;
}

}  // namespace dpcr::board
