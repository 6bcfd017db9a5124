// JKR adhesive elastic normal contact as used by Thornton & Yin (1991): docs/theory.md §1.
// R = R*, E = E*, Gamma = interface energy of each surface; delta > 0 compressive, P > 0 repulsive.
// Every function is exact in the Hertz limit Gamma = 0.
#ifndef TYCORE_JKR_HPP
#define TYCORE_JKR_HPP

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace tycore::jkr {

inline constexpr double pi = 3.14159265358979323846;

// cbrt(x) from the first guess y: two Halley steps, one Newton step (fast_cbrt, simd_cbrt)
[[gnu::always_inline]] inline double refine_cube_root(double x, double y)
{
  double y3 = y * y * y;
  y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  y3 = y * y * y;
  y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  return y + (x / (y * y) - y) * (1.0 / 3.0);
}

// first guess of cbrt(x): bits(x)/3 + this, i.e. 2/3 of the exponent bias (0x2AA0...) put
// back, lowered slightly so that the guess errs by less than 3.3 % either way
inline constexpr std::uint64_t cube_root_guess_offset = 0x2A9F76253119D328ULL;

// cube root of x without a libm call, for the hot contact loop. Normal positive x: bit-trick
// first guess (relative error < 3.3 %), two Halley steps (error ~ e^3 each: < 4e-5, then below
// 1e-13) and one Newton step (quadratic: to round-off). Agrees with std::cbrt to a few ulps
// (tests/core/test_fast_numerics.cpp: FastCbrt, <= 1e-15 relative). Zero, negative,
// subnormal, inf and NaN arguments go to std::cbrt. From x = 2^1020 on, 2 y^3 and 2x of the
// Halley steps would overflow (NaN at DBL_MAX): x is scaled by 2^-162 first and the root
// back by 2^54 (both exact).
inline constexpr double cube_root_huge = 0x1p1020, cube_root_huge_down = 0x1p-162,
                        cube_root_huge_up = 0x1p54;

inline double fast_cbrt(double x)
{
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const std::uint64_t biased_exponent = bits >> 52;    // includes the sign bit
  if (biased_exponent == 0 || biased_exponent >= 0x7ff) return std::cbrt(x);
  const bool huge = x >= cube_root_huge;
  const double xs = huge ? x * cube_root_huge_down : x;
  std::memcpy(&bits, &xs, sizeof bits);
  bits = bits / 3 + cube_root_guess_offset;
  double y;
  std::memcpy(&y, &bits, sizeof y);
  y = refine_cube_root(xs, y);
  return huge ? y * cube_root_huge_up : y;
}

// Pc = 3 pi Gamma R*                                                 (docs/theory.md §0)
inline double pull_off_force(double Gamma, double R)
{
  return 3.0 * pi * Gamma * R;
}

// a0^3 = 9 pi Gamma R*^2 / E*                                        (docs/theory.md §1.1)
inline double zero_load_radius(double Gamma, double R, double E)
{
  return std::cbrt(9.0 * pi * Gamma * R * R / E);
}

// P = 4E*a^3/(3R*) - 4 sqrt(pi Gamma E* a^3)                         (docs/theory.md §1.1)
inline double normal_force(double a, double R, double E, double Gamma)
{
  const double a3 = a * a * a;
  return 4.0 * E * a3 / (3.0 * R) - 4.0 * std::sqrt(pi * Gamma * E * a3);
}

// separation under displacement control, delta_f = -(27 pi^2 Gamma^2 R*/(16 E*^2))^(1/3) (§1.2)
inline double break_overlap(double R, double E, double Gamma)
{
  return -std::cbrt(27.0 * pi * pi * Gamma * Gamma * R / (16.0 * E * E));
}

// stable-branch a(delta), closed form of the quartic in sqrt(a) (docs/theory.md §1.4; Parteli et
// al. 2014). Valid for delta >= delta_f; arguments of the roots clamped at 0 against round-off.
inline double contact_radius(double delta, double R, double E, double Gamma)
{
  if (Gamma == 0.0) return std::sqrt(R * std::max(delta, 0.0));
  const double D = delta * R;
  const double t0 = Gamma * Gamma * R * R * R * R * E;
  const double t1 = 27.0 * pi * pi * t0;
  const double t2 = 8.0 * D * D * D * E * E * E;
  const double t3 = 4.0 * D * D * E;
  const double t4 = std::cbrt(
      t1 + t2 + 3.0 * std::sqrt(3.0) * pi * std::sqrt(std::max(t0 * (t1 + 2.0 * t2), 0.0)));
  const double t5 = t3 / t4 + t4 / E;
  const double t6 = std::sqrt(std::max(2.0 * D + t5, 0.0));
  const double inner = 4.0 * D - t5 + 6.0 * std::sqrt(6.0) * pi * Gamma * R * R / (E * t6);
  return (t6 + std::sqrt(std::max(inner, 0.0))) / std::sqrt(6.0);
}

// k_N = dP/d(delta) = 2E*a * 3(2 - s)/(6 - s), s = (a0/a)^(3/2)      (docs/theory.md §1.5)
// (branch-free: the batch's lane loops inline it)
[[gnu::always_inline]] inline double normal_stiffness(double a, double R, double E, double Gamma)
{
  const double s = std::sqrt(9.0 * pi * Gamma * R * R / (E * a * a * a));
  const double adhesive = 2.0 * E * a * 3.0 * (2.0 - s) / (6.0 - s);
  return Gamma == 0.0 ? 2.0 * E * a : adhesive;
}

// U(a) = integral of P d(delta) from first touch (a_touch = (4/9)^(1/3) a0, delta = 0):
// 8E*a^5/(15R*^2) - (8/(3R*)) sqrt(pi Gamma E*) a^(7/2) + 2 pi Gamma a^2 - U(a_touch)   (§1.7)
inline double stored_energy(double a, double R, double E, double Gamma)
{
  const auto U = [&](double x) {
    const double x2 = x * x;
    return 8.0 * E * (x2 * x2 * x) / (15.0 * R * R) -
        8.0 / (3.0 * R) * std::sqrt(pi * Gamma * E) * (x2 * x * std::sqrt(x)) +
        2.0 * pi * Gamma * x2;
  };
  if (Gamma == 0.0) return U(a);
  return U(a) - U(std::cbrt(4.0 / 9.0) * zero_load_radius(Gamma, R, E));
}

}    // namespace tycore::jkr

#endif
