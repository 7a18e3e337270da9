// Four points of a span at a time, as lanes of Float4 (core/base/float4.hpp), for loops that
// compute the same thing for every point of a scan (ray insertion).
#pragma once

#include <cstddef>

#include "core/base/float4.hpp"
#include "core/base/span.hpp"
#include "core/geometry/pose2.hpp"

namespace dpcr {

struct Points4 {
  Float4 x;
  Float4 y;
};

// Points [i, i + 4) of a non-empty span, the last one repeated past its end.
inline Points4 LoadPoints4(Span<const Point2> points, std::size_t i) {
  const std::size_t last = points.size() - 1;
  const Point2& a = points[i];
  const Point2& b = points[i + 1 <= last ? i + 1 : last];
  const Point2& c = points[i + 2 <= last ? i + 2 : last];
  const Point2& d = points[i + 3 <= last ? i + 3 : last];
  return Points4{Float4{a.x, b.x, c.x, d.x}, Float4{a.y, b.y, c.y, d.y}};
}

// How many of the four lanes from `i` hold points of a span of `size` (i < size).
inline int LanesAt(std::size_t i, std::size_t size) { return size - i < 4 ? static_cast<int>(size - i) : 4; }

}  // namespace dpcr
