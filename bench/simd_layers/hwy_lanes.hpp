// The lane operations of the contact law (plugin/core/contact_law.hpp) for Google Highway 1.0
// (static target: the widest the compiler flags allow, so each instruction set is its own
// build; Highway's run-time dispatch, foreach_target.h + HWY_DYNAMIC_DISPATCH, would compile
// this text once per target in one file). Highway's vectors take no scalars in their operators
// and its masks no & | !, so the law's lane type here is a thin wrapper (V, M, U below). The
// 64-bit lane product of the cube root's bits / 3 is MulEven of the 32-bit halves (pmuludq),
// exact because both factors are below 2^32 there. Include before contact_law.hpp (see
// stdx_lanes.hpp for why std::sqrt / std::abs are declared in std). Benchmark only.
#ifndef TYBENCH_HWY_LANES_HPP
#define TYBENCH_HWY_LANES_HPP

#include "lane_common.hpp"

#include <hwy/highway.h>

namespace tybench::hwy_lanes {
namespace hn = hwy::HWY_NAMESPACE;
using D = hn::ScalableTag<double>;
using DU = hn::RebindToUnsigned<D>;
using DU32 = hn::Repartition<std::uint32_t, D>;

struct M {
  hn::Mask<D> m;
  friend M operator&(M a, M b) { return {hn::And(a.m, b.m)}; }
  friend M operator&(M a, bool b) { return b ? a : M{hn::Not(a.m)} & a; }
  friend M operator|(M a, M b) { return {hn::Or(a.m, b.m)}; }
  friend M operator!(M a) { return {hn::Not(a.m)}; }
};

struct V {
  hn::Vec<D> v;
  V() = default;
  V(double x) : v(hn::Set(D(), x)) {}
  explicit V(hn::Vec<D> x) : v(x) {}
  friend V operator+(V a, V b) { return V(hn::Add(a.v, b.v)); }
  friend V operator-(V a, V b) { return V(hn::Sub(a.v, b.v)); }
  friend V operator*(V a, V b) { return V(hn::Mul(a.v, b.v)); }
  friend V operator/(V a, V b) { return V(hn::Div(a.v, b.v)); }
  friend V operator-(V a) { return V(hn::Neg(a.v)); }
  V& operator-=(V o) { return *this = *this - o; }
  V& operator*=(V o) { return *this = *this * o; }
  friend M operator<(V a, V b) { return {hn::Lt(a.v, b.v)}; }
  friend M operator>(V a, V b) { return {hn::Gt(a.v, b.v)}; }
  friend M operator<=(V a, V b) { return {hn::Le(a.v, b.v)}; }
  friend M operator>=(V a, V b) { return {hn::Ge(a.v, b.v)}; }
  friend M operator==(V a, V b) { return {hn::Eq(a.v, b.v)}; }
  friend M operator!=(V a, V b) { return {hn::Ne(a.v, b.v)}; }
};

struct U {
  hn::Vec<DU> v;
  U(std::uint64_t x) : v(hn::Set(DU(), x)) {}
  explicit U(hn::Vec<DU> x) : v(x) {}
  friend U operator+(U a, U b) { return U(hn::Add(a.v, b.v)); }
  friend U operator&(U a, U b) { return U(hn::And(a.v, b.v)); }
  friend U operator>>(U a, int bits) { return U(hn::ShiftRightSame(a.v, bits)); }
  // the product of the low 32 bits of each lane (both factors < 2^32 in divide_by_3)
  friend U operator*(U a, U b)
  {
    return U(hn::MulEven(hn::BitCast(DU32(), a.v), hn::BitCast(DU32(), b.v)));
  }
};

inline V select(M m, V a, V b) { return V(hn::IfThenElse(m.m, a.v, b.v)); }
}    // namespace tybench::hwy_lanes

namespace std {
inline tybench::hwy_lanes::V sqrt(tybench::hwy_lanes::V x)
{
  return tybench::hwy_lanes::V(tybench::hwy_lanes::hn::Sqrt(x.v));
}
inline tybench::hwy_lanes::V abs(tybench::hwy_lanes::V x)
{
  return tybench::hwy_lanes::V(tybench::hwy_lanes::hn::Abs(x.v));
}
}    // namespace std

namespace tycore {
inline tybench::hwy_lanes::V lane_select(tybench::hwy_lanes::M m, tybench::hwy_lanes::V a,
                                         tybench::hwy_lanes::V b)
{
  return tybench::hwy_lanes::select(m, a, b);
}
inline tybench::hwy_lanes::V lane_max(tybench::hwy_lanes::V a, tybench::hwy_lanes::V b)
{
  return tybench::max_by_select(a, b, tybench::hwy_lanes::select);
}
inline tybench::hwy_lanes::V lane_clamp(tybench::hwy_lanes::V v, tybench::hwy_lanes::V lo,
                                        tybench::hwy_lanes::V hi)
{
  return tybench::clamp_by_select(v, lo, hi, tybench::hwy_lanes::select);
}
inline tybench::hwy_lanes::V simd_cbrt(tybench::hwy_lanes::V x)
{
  using namespace tybench::hwy_lanes;
  return tybench::cbrt_lanes(
      x, tybench::hwy_lanes::select, [](V v) { return U(hn::BitCast(DU(), v.v)); },
      [](U u) { return V(hn::BitCast(D(), u.v)); }, [](U u) { return tybench::divide_by_3(u); });
}
namespace detail {
inline tybench::hwy_lanes::V annulus_dissipation_rate(tybench::hwy_lanes::V limit,
                                                      tybench::hwy_lanes::V theta)
{
  return tybench::annulus_rate(limit, theta);
}
}    // namespace detail
}    // namespace tycore

namespace tybench {
struct HwyLayer {
  using V = hwy_lanes::V;
  static constexpr int width = int(HWY_MAX_BYTES / sizeof(double));
  static constexpr const char* name = "highway";
  static V load(const double* p) { return V(hwy_lanes::hn::Load(hwy_lanes::D(), p)); }
  static void store(V v, double* p) { hwy_lanes::hn::Store(v.v, hwy_lanes::D(), p); }
};
}    // namespace tybench

#endif
