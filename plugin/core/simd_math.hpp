// The lane operations of the contact law (contact_law.hpp) for the lane type double, written so
// that GCC vectorises loops that call them (no branches, no libm): select, max, clamp, and the
// cube root of jkr::fast_cbrt, operation for operation. Vector libm (libmvec) has no cube root.
#ifndef TYCORE_SIMD_MATH_HPP
#define TYCORE_SIMD_MATH_HPP

#include "jkr.hpp"

#include <cstdint>
#include <cstring>

namespace tycore {

// c ? a : b, the lane select of the law (contact_law.hpp) for V = double: inlined into a lane
// loop of contact_batch.cpp it becomes a SIMD blend
[[gnu::always_inline]] inline double lane_select(bool c, double a, double b)
{
  return c ? a : b;
}

// std::max and std::clamp by value, with their results (NaN and signed zeros included): the
// std versions return a reference to an argument, which GCC then loads through a pointer
// chosen by a branch and does not vectorise
[[gnu::always_inline]] inline double lane_max(double a, double b)
{
  return a < b ? b : a;
}
[[gnu::always_inline]] inline double lane_clamp(double v, double lo, double hi)
{
  return v < lo ? lo : (hi < v ? hi : v);
}

namespace detail {

  // floor(b / 3) for b < 2^63 from 32 x 32 -> 64-bit products: (b * ceil(2^65/3)) >> 65, the
  // high half of the 128-bit product assembled from its four partial products. A vector
  // division of 64-bit integers does not exist; these products do (pmuludq, vpmullq).
  [[gnu::always_inline]] inline std::uint64_t divide_by_3(std::uint64_t b)
  {
    constexpr std::uint64_t low32 = 0xffffffffu;
    constexpr std::uint64_t m_lo = 0xAAAAAAABu, m_hi = 0xAAAAAAAAu;    // 2^65/3 rounded up
    const std::uint64_t b_lo = b & low32, b_hi = b >> 32;
    const std::uint64_t p0 = b_lo * m_lo, p1 = b_lo * m_hi, p2 = b_hi * m_lo, p3 = b_hi * m_hi;
    const std::uint64_t middle = (p0 >> 32) + (p1 & low32) + (p2 & low32);
    return (p3 + (p1 >> 32) + (p2 >> 32) + (middle >> 32)) >> 1;
  }

}    // namespace detail

// cbrt(x) for x >= 0, bit for bit jkr::fast_cbrt on zero and positive normal numbers (the same
// first guess from the bits, two Halley steps, one Newton step, x >= 2^1020 scaled down as
// there); subnormal x are scaled by 2^162 first (within a few ulps of std::cbrt), +inf gives
// +inf. Not for x < 0 or NaN.
[[gnu::always_inline]] inline double simd_cbrt(double x)
{
  constexpr double smallest_normal = 2.2250738585072014e-308, up = 0x1p162, down = 0x1p-54;
  const bool subnormal = x < smallest_normal;
  const bool huge = x >= jkr::cube_root_huge;
  const double xs = subnormal ? x * up : (huge ? x * jkr::cube_root_huge_down : x);
  std::uint64_t bits;
  std::memcpy(&bits, &xs, sizeof bits);
  bits = detail::divide_by_3(bits) + jkr::cube_root_guess_offset;
  double y;
  std::memcpy(&y, &bits, sizeof y);
  y = jkr::refine_cube_root(xs, y);
  y = subnormal ? y * down : (huge ? y * jkr::cube_root_huge_up : y);
  constexpr double inf = __builtin_inf();
  return ((x == 0.0) | (x == inf)) ? x : y;
}

}    // namespace tycore

#endif
