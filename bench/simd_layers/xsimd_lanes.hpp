// The lane operations of the contact law (plugin/core/contact_law.hpp) for xsimd 8
// (xsimd::batch<double>, the widest the compiler target has: each instruction set is its own
// build, -m flags; xsimd's run-time dispatch, xsimd::dispatch, would call such builds). Include
// before contact_law.hpp (see stdx_lanes.hpp for why std::sqrt / std::abs are declared in std).
// xsimd 8.1 has no 32 x 32 -> 64-bit lane product (pmuludq) and multiplies 64-bit lanes one by
// one below AVX-512DQ: the cube root's bits / 3 then leaves the registers. Benchmark only.
#ifndef TYBENCH_XSIMD_LANES_HPP
#define TYBENCH_XSIMD_LANES_HPP

#include "lane_common.hpp"

#include <xsimd/xsimd.hpp>

namespace tybench::xsimd_lanes {
using V = xsimd::batch<double>;
using M = V::batch_bool_type;
using U = xsimd::batch<std::uint64_t>;
inline V select(M m, V a, V b) { return xsimd::select(m, a, b); }
}    // namespace tybench::xsimd_lanes

namespace std {
inline tybench::xsimd_lanes::V sqrt(tybench::xsimd_lanes::V x) { return xsimd::sqrt(x); }
inline tybench::xsimd_lanes::V abs(tybench::xsimd_lanes::V x) { return xsimd::abs(x); }
}    // namespace std

namespace tycore {
// a mask and a bool (halley_again's last round): AVX-512's batch_bool converts to an integer
// as well as from bool, which makes the mask & bool of the law ambiguous
inline tybench::xsimd_lanes::M operator&(tybench::xsimd_lanes::M m, bool b)
{
  return m & tybench::xsimd_lanes::M(b);
}
inline tybench::xsimd_lanes::V lane_select(tybench::xsimd_lanes::M m, tybench::xsimd_lanes::V a,
                                           tybench::xsimd_lanes::V b)
{
  return tybench::xsimd_lanes::select(m, a, b);
}
inline tybench::xsimd_lanes::V lane_max(tybench::xsimd_lanes::V a, tybench::xsimd_lanes::V b)
{
  return tybench::max_by_select(a, b, tybench::xsimd_lanes::select);
}
inline tybench::xsimd_lanes::V lane_clamp(tybench::xsimd_lanes::V v, tybench::xsimd_lanes::V lo,
                                          tybench::xsimd_lanes::V hi)
{
  return tybench::clamp_by_select(v, lo, hi, tybench::xsimd_lanes::select);
}
inline tybench::xsimd_lanes::V simd_cbrt(tybench::xsimd_lanes::V x)
{
  using namespace tybench::xsimd_lanes;
  return tybench::cbrt_lanes(
      x, tybench::xsimd_lanes::select, [](V v) { return xsimd::bitwise_cast<U>(v); },
      [](U u) { return xsimd::bitwise_cast<V>(u); }, [](U u) { return tybench::divide_by_3(u); });
}
namespace detail {
inline tybench::xsimd_lanes::V annulus_dissipation_rate(tybench::xsimd_lanes::V limit,
                                                        tybench::xsimd_lanes::V theta)
{
  return tybench::annulus_rate(limit, theta);
}
}    // namespace detail
}    // namespace tycore

namespace tybench {
struct XsimdLayer {
  using V = xsimd_lanes::V;
  static constexpr int width = int(V::size);
  static constexpr const char* name = "xsimd";
  static V load(const double* p) { return V::load_aligned(p); }
  static void store(V v, double* p) { v.store_aligned(p); }
};
}    // namespace tybench

#endif
