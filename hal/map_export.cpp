#include "hal/map_export.hpp"

#include <cstdio>

namespace dpcr {
namespace {

// "P5\n<w> <h>\n255\n": at most 3 + 11 + 1 + 11 + 1 + 4 characters.
int PgmHeader(int width, int height, char* out, std::size_t size) {
  return std::snprintf(out, size, "P5\n%d %d\n255\n", width, height);
}

}  // namespace

std::uint8_t PgmValue(std::int16_t cell) {
  if (cell == kUnknownCell) return kPgmUnknown;
  const float p = Probability(cell);
  if (p >= kOccupiedThreshold) return kPgmOccupied;
  if (p <= kFreeThreshold) return kPgmFree;
  return kPgmUnknown;
}

std::size_t PgmSize(int width, int height) {
  char header[64];
  const int n = PgmHeader(width, height, header, sizeof(header));
  return static_cast<std::size_t>(n) + static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

std::size_t EncodePgm(Span<const std::int16_t> cells, int width, int height, Span<std::uint8_t> out) {
  const std::size_t w = static_cast<std::size_t>(width);
  const std::size_t h = static_cast<std::size_t>(height);
  if (width <= 0 || height <= 0 || cells.size() < w * h || out.size() < PgmSize(width, height)) return 0;
  char header[64];
  const std::size_t n = static_cast<std::size_t>(PgmHeader(width, height, header, sizeof(header)));
  for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<std::uint8_t>(header[i]);
  for (std::size_t row = 0; row < h; ++row) {
    const std::int16_t* src = cells.data() + (h - 1 - row) * w;  // top row first
    std::uint8_t* dst = out.data() + n + row * w;
    for (std::size_t x = 0; x < w; ++x) dst[x] = PgmValue(src[x]);
  }
  return n + w * h;
}

std::size_t EncodeMapYaml(const char* image_file, float resolution_m, CellBox box, Span<char> out) {
  const double res = static_cast<double>(resolution_m);
  const int n = std::snprintf(out.data(), out.size(),
                              "image: %s\nmode: trinary\nresolution: %.4f\norigin: [%.4f, %.4f, 0.0]\n"
                              "negate: 0\noccupied_thresh: %.2f\nfree_thresh: %.3f\n",
                              image_file, res, box.min.x * res, box.min.y * res,
                              static_cast<double>(kOccupiedThreshold), static_cast<double>(kFreeThreshold));
  if (n < 0 || static_cast<std::size_t>(n) >= out.size()) return 0;
  return static_cast<std::size_t>(n);
}

}  // namespace dpcr
