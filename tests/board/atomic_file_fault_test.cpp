// Saving maps through the atomic file store on a simulated file system that fails or loses power
// at any step: every write, fsync, close, rename and directory fsync of a save fails (EIO), or
// writes short, or is where the power goes. After each, and after each power loss, the map file
// holds the old map or the new one, and a save that said it succeeded survives a power loss.
#include <catch2/catch.hpp>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <map>
#include <string>
#include <vector>

#include "board/atomic_file.hpp"
#include "board/map_store.hpp"
#include "tests/core/map_file_fixtures.hpp"

namespace {

using Tiny = dpcr::Mapper<dpcr::TinyProfile>;

// Files and directory entries with what a power loss keeps: file contents as of their last
// fsync, directory entries as of the directory's last fsync. One directory.
class SimulatedFs final : public dpcr::board::FileOps {
 public:
  enum class Fault { kNone, kFail, kShortWrite, kPowerLoss };

  int Open(const char* path, int flags, mode_t) override {
    if (!Proceed()) return -1;
    if ((flags & O_DIRECTORY) != 0) return NewFd(-1);
    const auto it = names_.find(path);
    if ((flags & O_CREAT) == 0) {
      if (it == names_.end()) return Error(ENOENT);
      return NewFd(it->second);
    }
    if (it != names_.end()) {
      if ((flags & O_TRUNC) != 0) inodes_[static_cast<std::size_t>(it->second)].data.clear();
      return NewFd(it->second);
    }
    inodes_.push_back(Inode{});
    names_[path] = static_cast<int>(inodes_.size() - 1);
    return NewFd(static_cast<int>(inodes_.size() - 1));
  }
  ssize_t Write(int fd, const void* data, std::size_t size) override {
    const bool short_write = fault_at_ == op_ && fault_ == Fault::kShortWrite;
    if (!Proceed()) return -1;
    const std::size_t n = short_write && size > 1 ? size / 2 : size;
    auto& d = inodes_[static_cast<std::size_t>(fds_.at(fd))].data;
    d.insert(d.end(), static_cast<const std::uint8_t*>(data), static_cast<const std::uint8_t*>(data) + n);
    return static_cast<ssize_t>(n);
  }
  ssize_t PRead(int fd, void* data, std::size_t size, off_t offset) override {
    if (!Proceed()) return -1;
    const auto& d = inodes_[static_cast<std::size_t>(fds_.at(fd))].data;
    std::size_t n = 0;
    for (; n < size && static_cast<std::size_t>(offset) + n < d.size(); ++n) {
      static_cast<std::uint8_t*>(data)[n] = d[static_cast<std::size_t>(offset) + n];
    }
    return static_cast<ssize_t>(n);
  }
  int Fsync(int fd) override {
    if (!Proceed()) return -1;
    const int inode = fds_.at(fd);
    if (inode < 0) {
      durable_names_ = names_;
    } else {
      inodes_[static_cast<std::size_t>(inode)].synced = inodes_[static_cast<std::size_t>(inode)].data;
    }
    return 0;
  }
  int Close(int fd) override {
    if (!Proceed()) return -1;
    fds_.erase(fd);
    return 0;
  }
  int Rename(const char* from, const char* to) override {
    if (!Proceed()) return -1;
    const auto it = names_.find(from);
    if (it == names_.end()) return Error(ENOENT);
    names_[to] = it->second;
    names_.erase(from);
    return 0;
  }
  int Unlink(const char* path) override {
    if (!Proceed()) return -1;
    return names_.erase(path) == 1 ? 0 : Error(ENOENT);
  }

  // The next operations: number `at` (from now) gets `fault`.
  void Arm(int at, Fault fault) {
    op_ = 0;
    fault_at_ = at;
    fault_ = fault;
  }
  int operations() const { return op_; }
  // Power back: what was durable, no faults.
  void PowerCycle() {
    names_ = durable_names_;
    for (Inode& i : inodes_) i.data = i.synced;
    fds_.clear();
    powered_ = true;
    fault_ = Fault::kNone;
  }
  void Disarm() { fault_ = Fault::kNone; }

 private:
  struct Inode {
    std::vector<std::uint8_t> data;
    std::vector<std::uint8_t> synced;
  };
  // False (errno set) when this operation fails or the power is gone.
  bool Proceed() {
    const int k = op_++;
    if (!powered_) return Error(EIO) == 0;
    if (k == fault_at_ && fault_ == Fault::kPowerLoss) {
      powered_ = false;
      return Error(EIO) == 0;
    }
    if (k == fault_at_ && fault_ == Fault::kFail) return Error(EIO) == 0;
    return true;
  }
  static int Error(int e) {
    errno = e;
    return -1;
  }
  int NewFd(int inode) {
    fds_[next_fd_] = inode;
    return next_fd_++;
  }

  std::vector<Inode> inodes_;
  std::map<std::string, int> names_;
  std::map<std::string, int> durable_names_;
  std::map<int, int> fds_;
  int next_fd_ = 3;
  int op_ = 0;
  int fault_at_ = -1;
  Fault fault_ = Fault::kNone;
  bool powered_ = true;
};

struct Maps {
  Maps() : run(8.0f, 400, 180), old_map(dpcr::test::MakeMapper<dpcr::TinyProfile>()), new_map(dpcr::test::MakeMapper<dpcr::TinyProfile>()) {
    dpcr::test::Feed(*old_map, run, 0, 120);
    dpcr::test::Feed(*new_map, run);
    old_print = dpcr::test::Fingerprint(*old_map);
    new_print = dpcr::test::Fingerprint(*new_map);
  }
  dpcr::test::SyntheticRun<Tiny> run;
  std::unique_ptr<Tiny> old_map;
  std::unique_ptr<Tiny> new_map;
  std::uint32_t old_print = 0;
  std::uint32_t new_print = 0;
};

// The map in the file system's "/maps/map.dpcr": its fingerprint, 0 when it cannot be loaded.
std::uint32_t StoredMap(SimulatedFs& fs) {
  dpcr::board::AtomicFileStore store("/maps", fs);
  auto m = dpcr::test::MakeMapper<dpcr::TinyProfile>();
  const dpcr::board::MapLoad load = dpcr::board::LoadMapBlob(*m, store, "map.dpcr");
  return load.loaded() ? dpcr::test::Fingerprint(*m) : 0;
}

const char* Name(SimulatedFs::Fault f) {
  switch (f) {
    case SimulatedFs::Fault::kFail: return "fails";
    case SimulatedFs::Fault::kShortWrite: return "writes short";
    case SimulatedFs::Fault::kPowerLoss: return "loses power";
    case SimulatedFs::Fault::kNone: break;
  }
  return "none";
}

}  // namespace

TEST_CASE("A map save that fails, writes short or loses power at any step leaves the old or the new map") {
  const Maps maps;
  REQUIRE(maps.old_print != maps.new_print);
  SimulatedFs with_old;
  {
    dpcr::board::AtomicFileStore store("/maps", with_old);
    std::string error;
    REQUIRE(dpcr::board::SaveMapBlob(*maps.old_map, store, "map.dpcr", &error));
  }
  REQUIRE(StoredMap(with_old) == maps.old_print);
  // How many operations a clean save takes.
  int steps = 0;
  {
    SimulatedFs fs = with_old;
    fs.Arm(-1, SimulatedFs::Fault::kNone);
    dpcr::board::AtomicFileStore store("/maps", fs);
    std::string error;
    REQUIRE(dpcr::board::SaveMapBlob(*maps.new_map, store, "map.dpcr", &error));
    steps = fs.operations();
    fs.PowerCycle();
    REQUIRE(StoredMap(fs) == maps.new_print);  // a clean save survives a power loss
  }
  REQUIRE(steps > 10);
  int scenarios = 0;
  for (const auto fault : {SimulatedFs::Fault::kFail, SimulatedFs::Fault::kShortWrite, SimulatedFs::Fault::kPowerLoss}) {
    for (int at = 0; at < steps; ++at) {
      SimulatedFs fs = with_old;
      fs.Arm(at, fault);
      bool saved = false;
      std::string error;
      {
        dpcr::board::AtomicFileStore store("/maps", fs);
        saved = dpcr::board::SaveMapBlob(*maps.new_map, store, "map.dpcr", &error);
      }
      INFO("operation " << at << " of " << steps << " " << Name(fault) << "; save said: " << (saved ? "ok" : error));
      fs.Disarm();
      if (fault != SimulatedFs::Fault::kPowerLoss) {
        const std::uint32_t now = StoredMap(fs);
        CHECK((now == maps.old_print || now == maps.new_print));
        if (saved) CHECK(now == maps.new_print);
        if (fault == SimulatedFs::Fault::kShortWrite) CHECK(saved);  // a short write is not an error
      }
      // And the power goes (again) now: what is left on the disk.
      fs.PowerCycle();
      const std::uint32_t after = StoredMap(fs);
      CHECK((after == maps.old_print || after == maps.new_print));
      if (saved) CHECK(after == maps.new_print);
      ++scenarios;
    }
  }
  std::printf("atomic map save: %d operations, %d fault scenarios, old or new map every time\n", steps, scenarios);
}

TEST_CASE("A failed save says which file and step failed, and leaves no temp file behind") {
  const Maps maps;
  SimulatedFs fs;
  dpcr::board::AtomicFileStore store("/maps", fs);
  std::string error;
  REQUIRE(dpcr::board::SaveMapBlob(*maps.old_map, store, "map.dpcr", &error));
  fs.Arm(5, SimulatedFs::Fault::kFail);  // a write in the middle of the map
  REQUIRE_FALSE(dpcr::board::SaveMapBlob(*maps.new_map, store, "map.dpcr", &error));
  CHECK(error.find("map.dpcr") != std::string::npos);
  CHECK(store.last_error().find("/maps/map.dpcr.tmp: write") != std::string::npos);
  fs.Disarm();
  std::uint8_t b[4];
  CHECK(store.ReadAt("map.dpcr.tmp", 0, b, sizeof(b)).status == dpcr::IoStatus::kNotFound);
  CHECK(StoredMap(fs) == maps.old_print);
}
