// Pieces of the lane operations of the contact law (plugin/core/contact_law.hpp) that every
// SIMD layer of bench/simd_layers.cpp writes the same way, over its own lane types V (double
// lanes) and U (64-bit unsigned lanes): max and clamp by select, the annulus dissipation rate of
// the Mindlin-Deresiewicz law, and the cube root of tycore::simd_cbrt operation for operation
// (plugin/core/simd_math.hpp), so that every layer can agree with the shipping build bit for bit.
// Benchmark only: the product has its one lane type, double (simd_math.hpp).
#ifndef TYBENCH_LANE_COMMON_HPP
#define TYBENCH_LANE_COMMON_HPP

#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"
#include "simd_math.hpp"

#include <cstdint>

namespace tybench {

// lane_max / lane_clamp of simd_math.hpp: a < b ? b : a and v < lo ? lo : (hi < v ? hi : v)
template <class V, class Select> inline V max_by_select(V a, V b, Select select)
{
  return select(a < b, b, a);
}
template <class V, class Select> inline V clamp_by_select(V v, V lo, V hi, Select select)
{
  return select(v < lo, lo, select(hi < v, hi, v));
}

// tycore::detail::divide_by_3 over lanes: floor(b / 3) from 32 x 32 -> 64-bit products
template <class U> inline U divide_by_3(U b)
{
  const U low32(std::uint64_t(0xffffffffu)), m_lo(std::uint64_t(0xAAAAAAABu)),
      m_hi(std::uint64_t(0xAAAAAAAAu));
  const U b_lo = b & low32, b_hi = b >> 32;
  const U p0 = b_lo * m_lo, p1 = b_lo * m_hi, p2 = b_hi * m_lo, p3 = b_hi * m_hi;
  const U middle = (p0 >> 32) + (p1 & low32) + (p2 & low32);
  return (p3 + (p1 >> 32) + (p2 >> 32) + (middle >> 32)) >> 1;
}

// jkr::refine_cube_root over lanes
template <class V> inline V refine_cube_root(V x, V y)
{
  V y3 = y * y * y;
  y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  y3 = y * y * y;
  y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  return y + (x / (y * y) - y) * (1.0 / 3.0);
}

// tycore::simd_cbrt over lanes, given the layer's select, its bit casts double <-> uint64 and
// its floor(bits / 3)
template <class V, class Select, class ToBits, class FromBits, class Third>
inline V cbrt_lanes(V x, Select select, ToBits to_bits, FromBits from_bits, Third third)
{
  constexpr double smallest_normal = 2.2250738585072014e-308, up = 0x1p162, down = 0x1p-54;
  const auto subnormal = x < smallest_normal;
  const auto huge = x >= tycore::jkr::cube_root_huge;
  const V xs = select(subnormal, x * up, select(huge, x * tycore::jkr::cube_root_huge_down, x));
  auto bits = third(to_bits(xs));
  bits = bits + decltype(bits)(tycore::jkr::cube_root_guess_offset);
  V y = from_bits(bits);
  y = refine_cube_root(xs, y);
  y = select(subnormal, y * down, select(huge, y * tycore::jkr::cube_root_huge_up, y));
  constexpr double inf = __builtin_inf();
  return select((x == 0.0) | (x == inf), x, y);
}

// tycore::detail::annulus_dissipation_rate over lanes
template <class V> inline V annulus_rate(V limit, V theta)
{
  return limit * (1.0 - theta) * (1.0 - theta) * (1.0 + 0.5 * theta);
}

}    // namespace tybench

#endif
