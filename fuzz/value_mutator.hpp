// What the mapper targets do to one value they are given: set it to a bad or a random value, by
// kind (0, negated, NaN, infinities, huge, tiny, scaled, nudged, any; integers also their extremes,
// doubled, halved; bools flipped). `choice` picks the edit, the rest comes from the input.
#pragma once

#include <cstdint>
#include <limits>

#include <fuzzer/FuzzedDataProvider.h>

namespace dpcr::fuzz {

class ValueMutator {
 public:
  explicit ValueMutator(FuzzedDataProvider& in) : in_(in) {}

  void operator()(float& v, std::uint8_t choice) {
    switch (choice % 8) {
      case 0: v = 0.0f; break;
      case 1: v = -v; break;
      case 2: v = std::numeric_limits<float>::quiet_NaN(); break;
      case 3: v = (choice & 8) != 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity(); break;
      case 4: v = (choice & 8) != 0 ? 1e30f : 1e-30f; break;
      case 5: v *= in_.ConsumeFloatingPointInRange<float>(0.0f, 4.0f); break;
      case 6: v += in_.ConsumeFloatingPointInRange<float>(-1.0f, 1.0f); break;
      default: v = in_.ConsumeFloatingPoint<float>(); break;
    }
  }
  // The arithmetic is done in 64 bits and narrowed (wrapping), so that the edit itself never
  // overflows: an int field at its largest, doubled, once stopped this harness instead of the code
  // under test.
  template <class Int>
  void Integer(Int& v, std::uint8_t choice) {
    const long long w = v;
    switch (choice % 8) {
      case 0: v = 0; break;
      case 1: v = Narrow<Int>(-w); break;
      case 2: v = (choice & 8) != 0 ? std::numeric_limits<Int>::min() : std::numeric_limits<Int>::max(); break;
      case 3: v = Narrow<Int>(w * 2); break;
      case 4: v = static_cast<Int>(w / 2); break;
      case 5: v = Narrow<Int>(w + in_.ConsumeIntegralInRange<int>(-3, 3)); break;
      case 6: v = in_.ConsumeIntegralInRange<Int>(-2, 1000); break;
      default: v = in_.ConsumeIntegral<Int>(); break;
    }
  }
  void operator()(int& v, std::uint8_t choice) { Integer(v, choice); }
  void operator()(std::int16_t& v, std::uint8_t choice) { Integer(v, choice); }
  void operator()(std::uint8_t& v, std::uint8_t choice) {  // counts: 0 (off), the largest, any
    v = choice % 3 == 0 ? 0 : choice % 3 == 1 ? std::numeric_limits<std::uint8_t>::max() : in_.ConsumeIntegral<std::uint8_t>();
  }
  void operator()(bool& v, std::uint8_t) { v = !v; }

 private:
  template <class Int>
  static Int Narrow(long long w) {
    return static_cast<Int>(static_cast<unsigned long long>(w));  // modulo 2^bits, no overflow
  }

  FuzzedDataProvider& in_;
};

}  // namespace dpcr::fuzz
