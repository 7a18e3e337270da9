#include "core/persistence/crc32.hpp"

namespace dpcr {
namespace {

struct Crc32Table {
  std::uint32_t entry[256];
};

constexpr Crc32Table MakeTable() {
  Crc32Table t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t.entry[i] = c;
  }
  return t;
}

constexpr Crc32Table kTable = MakeTable();

}  // namespace

void Crc32::Add(const std::uint8_t* data, std::size_t size) {
  std::uint32_t c = state_;
  for (std::size_t i = 0; i < size; ++i) c = kTable.entry[(c ^ data[i]) & 0xFFu] ^ (c >> 8);
  state_ = c;
}

}  // namespace dpcr
