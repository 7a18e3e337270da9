// Map files (core/persistence) at any path, for the host apps: saved and read through the
// board's storage port (board/map_store.hpp over the atomic file store, as dpcr-firmware does).
// Errors are std::runtime_error with one line: "PATH: what went wrong".
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "board/atomic_file.hpp"
#include "board/map_store.hpp"

namespace dpcr::output {

// The store of the file's directory and the file's name in it.
struct MapFilePlace {
  explicit MapFilePlace(const std::string& path)
      : store(DirectoryOf(path)), name(path.substr(path.rfind('/') == std::string::npos ? 0 : path.rfind('/') + 1)) {}
  static std::string DirectoryOf(const std::string& path) {
    const std::size_t slash = path.rfind('/');
    return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  }
  dpcr::board::AtomicFileStore store;
  std::string name;
};

// Creates the directory a map is to be saved in (before a run, not after it).
inline void PrepareMapFileDir(const std::string& path) {
  const std::string dir = MapFilePlace::DirectoryOf(path);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir + ": " + ec.message());
}

template <class MapperType>
void SaveMapFile(const MapperType& mapper, const std::string& path) {
  MapFilePlace place(path);
  std::string error;
  if (!dpcr::board::SaveMapBlob(mapper, place.store, place.name.c_str(), &error)) {
    throw std::runtime_error(place.store.last_error().empty() ? path + ": " + error : place.store.last_error());
  }
}

// Loads the map at `path` with the robot at `start` in its frame; the mapper is unchanged when
// this throws.
template <class MapperType>
void LoadMapFile(MapperType& mapper, const std::string& path, const dpcr::Pose2& start) {
  MapFilePlace place(path);
  const dpcr::board::MapLoad load = dpcr::board::LoadMapBlob(mapper, place.store, place.name.c_str(), start);
  if (load.io == dpcr::IoStatus::kNotFound) throw std::runtime_error(path + ": no such file");
  if (load.io != dpcr::IoStatus::kOk) throw std::runtime_error(place.store.last_error());
  if (!load.file.ok()) throw std::runtime_error(dpcr::board::DescribeMapLoad(path.c_str(), load));
}

}  // namespace dpcr::output
