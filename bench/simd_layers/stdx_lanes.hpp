// The lane operations of the contact law (plugin/core/contact_law.hpp) for
// std::experimental::native_simd<double> (Parallelism TS 2, GCC >= 11 <experimental/simd>):
// its width is the compiler target's (2 with SSE2 or NEON, 4 with AVX2, 8 with AVX-512), so
// each instruction set is its own build (-m flags), with no run-time dispatch of its own.
// Include before contact_law.hpp: the law finds these overloads by ordinary lookup from its
// definition (tycore::lane_select ..., tycore::detail::annulus_dissipation_rate) and by the
// qualified std::sqrt / std::abs it calls, which is why those two are declared in std here (an
// extension of namespace std that the standard does not sanction; a product switch would give
// the law a lane_sqrt / lane_abs of its own). Benchmark only.
#ifndef TYBENCH_STDX_LANES_HPP
#define TYBENCH_STDX_LANES_HPP

#include "lane_common.hpp"

#include <experimental/simd>

namespace tybench::stdx_lanes {
namespace stdx = std::experimental;
using V = stdx::native_simd<double>;
using M = V::mask_type;
using U = stdx::rebind_simd_t<std::uint64_t, V>;
inline V select(M m, V a, V b)
{
  stdx::where(m, b) = a;
  return b;
}
}    // namespace tybench::stdx_lanes

namespace std {
inline tybench::stdx_lanes::V sqrt(tybench::stdx_lanes::V x) { return experimental::sqrt(x); }
inline tybench::stdx_lanes::V abs(tybench::stdx_lanes::V x) { return experimental::abs(x); }
}    // namespace std

namespace tycore {
// a mask and a bool (halley_again's last round): simd_mask's broadcast from bool is explicit
inline tybench::stdx_lanes::M operator&(tybench::stdx_lanes::M m, bool b)
{
  return m & tybench::stdx_lanes::M(b);
}
inline tybench::stdx_lanes::V lane_select(tybench::stdx_lanes::M m, tybench::stdx_lanes::V a,
                                          tybench::stdx_lanes::V b)
{
  return tybench::stdx_lanes::select(m, a, b);
}
inline tybench::stdx_lanes::V lane_max(tybench::stdx_lanes::V a, tybench::stdx_lanes::V b)
{
  return tybench::max_by_select(a, b, tybench::stdx_lanes::select);
}
inline tybench::stdx_lanes::V lane_clamp(tybench::stdx_lanes::V v, tybench::stdx_lanes::V lo,
                                         tybench::stdx_lanes::V hi)
{
  return tybench::clamp_by_select(v, lo, hi, tybench::stdx_lanes::select);
}
inline tybench::stdx_lanes::V simd_cbrt(tybench::stdx_lanes::V x)
{
  using namespace tybench::stdx_lanes;
  return tybench::cbrt_lanes(
      x, tybench::stdx_lanes::select, [](V v) { return __builtin_bit_cast(U, v); },
      [](U u) { return __builtin_bit_cast(V, u); }, [](U u) { return tybench::divide_by_3(u); });
}
namespace detail {
inline tybench::stdx_lanes::V annulus_dissipation_rate(tybench::stdx_lanes::V limit,
                                                       tybench::stdx_lanes::V theta)
{
  return tybench::annulus_rate(limit, theta);
}
}    // namespace detail
}    // namespace tycore

namespace tybench {
struct StdxLayer {
  using V = stdx_lanes::V;
  static constexpr int width = int(V::size());
  static constexpr const char* name = "stdx";
  static V load(const double* p) { return V(p, stdx_lanes::stdx::vector_aligned); }
  static void store(V v, double* p) { v.copy_to(p, stdx_lanes::stdx::vector_aligned); }
};
}    // namespace tybench

#endif
