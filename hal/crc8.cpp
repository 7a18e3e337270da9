#include "hal/crc8.hpp"

namespace dpcr {
namespace {

constexpr std::uint8_t kPolynomial = 0x4D;

struct Crc8Table {
  std::uint8_t entry[256] = {};
  constexpr Crc8Table() {
    for (int i = 0; i < 256; ++i) {
      auto c = static_cast<std::uint8_t>(i);
      for (int bit = 0; bit < 8; ++bit) {
        c = (c & 0x80u) != 0 ? static_cast<std::uint8_t>((c << 1) ^ kPolynomial)
                             : static_cast<std::uint8_t>(c << 1);
      }
      entry[i] = c;
    }
  }
};

constexpr Crc8Table kTable{};

}  // namespace

std::uint8_t Crc8Ld(const std::uint8_t* data, std::size_t size, std::uint8_t crc) {
  for (std::size_t i = 0; i < size; ++i) crc = kTable.entry[crc ^ data[i]];
  return crc;
}

std::uint8_t Crc8LdTableEntry(std::uint8_t index) { return kTable.entry[index]; }

}  // namespace dpcr
