#include "tools/bench/figure.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdint>

namespace dpcr_bench {
namespace {

constexpr int kScale = 3;

struct Image {
  int w, h;
  std::vector<std::uint8_t> rgb;
  Image(int width, int height) : w(width), h(height), rgb(static_cast<std::size_t>(width * height * 3), 255) {}
  void Set(int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    const std::size_t i = static_cast<std::size_t>(((h - 1 - y) * w + x) * 3);  // y up
    rgb[i] = r, rgb[i + 1] = g, rgb[i + 2] = b;
  }
};

}  // namespace

bool WriteRegistrationFigure(const std::string& path, const dpcr::TiledGrid& grid,
                             const dpcr::RegistrationReference& ref, const std::vector<dpcr::Point2>& scan,
                             dpcr::Pose2 initial, dpcr::Pose2 improved, dpcr::Pose2 classic) {
  const dpcr::CellBox box = grid.box();
  const float res = grid.resolution_m();
  Image img(box.width() * kScale, box.height() * kScale);
  const auto px = [&](dpcr::Point2 p, int* x, int* y) {
    *x = static_cast<int>((p.x / res - static_cast<float>(box.min.x)) * kScale);
    *y = static_cast<int>((p.y / res - static_cast<float>(box.min.y)) * kScale);
  };
  for (int cy = 0; cy < box.height(); ++cy) {
    for (int cx = 0; cx < box.width(); ++cx) {
      const std::int16_t v = grid.Get(dpcr::CellIndex{box.min.x + cx, box.min.y + cy});
      const std::uint8_t grey = v == dpcr::kUnknownCell ? 210 : (v > 0 ? 90 : 255);
      for (int k = 0; k < kScale * kScale; ++k) img.Set(cx * kScale + k % kScale, cy * kScale + k / kScale, grey, grey, grey);
    }
  }
  for (std::uint16_t i = 0; i < ref.cell_count(); ++i) {  // clutter cells (no line): blue
    if (ref.cell(i).line != dpcr::kNoLine) continue;
    int x, y;
    px(ref.ObstaclePoint(i), &x, &y);
    for (int k = 0; k < 4; ++k) img.Set(x + k % 2, y + k / 2, 40, 90, 230);
  }
  for (std::uint16_t i = 0; i < ref.line_count(); ++i) {  // line features: red
    const dpcr::LineFeature& l = ref.line(i);
    const float len = std::hypot(l.b.x - l.a.x, l.b.y - l.a.y);
    const int n = static_cast<int>(len / res * kScale) + 1;
    for (int k = 0; k <= n; ++k) {
      const float t = static_cast<float>(k) / static_cast<float>(n);
      int x, y;
      px(dpcr::Point2{l.a.x + t * (l.b.x - l.a.x), l.a.y + t * (l.b.y - l.a.y)}, &x, &y);
      img.Set(x, y, 220, 30, 30);
      img.Set(x + 1, y, 220, 30, 30);
    }
  }
  const auto draw_scan = [&](dpcr::Pose2 pose, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    for (const dpcr::Point2& p : scan) {
      int x, y;
      px(pose.Apply(p), &x, &y);
      for (int k = 0; k < 4; ++k) img.Set(x + k % 2, y + k / 2, r, g, b);
    }
  };
  draw_scan(initial, 255, 150, 0);  // orange: initial guess
  draw_scan(classic, 200, 0, 200);  // magenta: classic result
  draw_scan(improved, 0, 170, 0);   // green: improved result
  return stbi_write_png(path.c_str(), img.w, img.h, 3, img.rgb.data(), img.w * 3) != 0;
}

}  // namespace dpcr_bench
