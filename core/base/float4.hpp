// Four floats at once with the compiler's vector types (SSE2 on x86-64, NEON where it is exact,
// plain scalar code elsewhere: the compiler lowers what the target lacks). Each lane gets the same
// IEEE operation as the scalar code it replaces (+, -, *, /, sqrt: correctly rounded), so the
// same floats and, through FloorToInt4, the same integers.
#pragma once

#include <cmath>
#include <cstdint>

namespace dpcr {

using Float4 = float __attribute__((vector_size(16)));
using Int4 = std::int32_t __attribute__((vector_size(16)));

// FloorToInt (core/grid/cell.hpp) lane by lane: the truncation, one less where the value is
// negative and not whole (a vector comparison is -1 where it holds).
inline Int4 FloorToInt4(Float4 v) {
  const Int4 t = __builtin_convertvector(v, Int4);
  return t + (v < __builtin_convertvector(t, Float4));
}

// std::sqrt lane by lane (for lanes >= 0).
inline Float4 Sqrt4(Float4 v) {
#if defined(__SSE__)
  return __builtin_ia32_sqrtps(v);
#else
  return Float4{std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2]), std::sqrt(v[3])};
#endif
}

}  // namespace dpcr
