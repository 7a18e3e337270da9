// A BlobStore in memory for firmware tests: writes replace a blob at Commit (or at once).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "hal/ports.hpp"

namespace dpcr::test {

struct MemoryStore : BlobStore {
  IoStatus Write(const char* name, const std::uint8_t* data, std::size_t size) override {
    blobs[name].assign(data, data + size);
    return IoStatus::kOk;
  }
  IoStatus Begin(const char* name) override {
    pending_name = name;
    pending.clear();
    open = true;
    return IoStatus::kOk;
  }
  IoStatus Append(const std::uint8_t* data, std::size_t size) override {
    if (!open) return IoStatus::kIoError;
    pending.insert(pending.end(), data, data + size);
    return IoStatus::kOk;
  }
  IoStatus Commit() override {
    if (!open) return IoStatus::kIoError;
    blobs[pending_name] = pending;
    open = false;
    return IoStatus::kOk;
  }
  void Abort() override { open = false; }
  ByteRead ReadAt(const char* name, std::uint64_t offset, std::uint8_t* buffer, std::size_t capacity) override {
    ByteRead r;
    const auto it = blobs.find(name);
    if (it == blobs.end()) {
      r.status = IoStatus::kNotFound;
      return r;
    }
    const std::vector<std::uint8_t>& b = it->second;
    for (std::size_t i = 0; i < capacity && offset + i < b.size(); ++i) buffer[r.size++] = b[static_cast<std::size_t>(offset + i)];
    return r;
  }

  std::map<std::string, std::vector<std::uint8_t>> blobs;
  std::string pending_name;
  std::vector<std::uint8_t> pending;
  bool open = false;
};

}  // namespace dpcr::test
