// The hot-loop numerics of the contact law: tycore::jkr::fast_cbrt (plugin/core/jkr.hpp)
// against std::cbrt, and the law's warm-started delta -> a inversion (the Halley iteration of
// contact_law.hpp, scalar entry tycore::normal_contact) against the closed form of
// docs/theory.md §1.4 and an independent bisection.
#include "contact_kernel.hpp"
#include "contact_types.hpp"
#include "jkr.hpp"

#include "glass_pair.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace {

namespace jkr = tycore::jkr;
using namespace glass_pair;    // docs/theory.md §1.8 glass pair

// fast_cbrt: two Halley steps and one Newton step from a 3.3 % guess; stated tolerance 1e-15
// relative (about 4.5 ulps; the measured worst case is ~3 ulps)
constexpr double kCbrtTol = 1e-15;

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

}    // namespace

TEST(FastCbrt, MatchesStdCbrtOverTheWholeNormalRange)
{
  std::mt19937_64 gen(12345);
  std::uniform_real_distribution<double> exponent(-307.0, 307.0);
  double worst = 0.0;
  for (int k = 0; k < 2000000; ++k) {
    const double x = std::pow(10.0, exponent(gen));
    worst = std::max(worst, rel(jkr::fast_cbrt(x), std::cbrt(x)));
  }
  EXPECT_LE(worst, kCbrtTol);
}

// the top of the range, where 2 y^3 in the Halley steps overflowed (NaN at DBL_MAX before the
// argument was scaled down there)
TEST(FastCbrt, MatchesStdCbrtUpToTheLargestDouble)
{
  const double largest = std::numeric_limits<double>::max();
  double worst = 0.0;
  for (double x : {largest, std::nextafter(largest, 0.0), 0x1p1020, std::nextafter(0x1p1020, 0.0),
                   0.5 * largest, 1e307, 1e308})
    worst = std::max(worst, rel(jkr::fast_cbrt(x), std::cbrt(x)));
  std::mt19937_64 gen(99);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  for (int k = 0; k < 100000; ++k) {
    const double x = std::ldexp(mantissa(gen), 1000 + k % 24);
    worst = std::max(worst, rel(jkr::fast_cbrt(x), std::cbrt(x)));
  }
  EXPECT_LE(worst, kCbrtTol);
  // cbrt(DBL_MAX) = 5.64380309412236197e102 (30-digit decimal arithmetic: Python's
  // Decimal(1.7976931348623157e308) ** (Decimal(1) / 3))
  EXPECT_NEAR(jkr::fast_cbrt(largest), 5.64380309412236197e102, 1e-15 * 5.64380309412236197e102);
}

TEST(FastCbrt, MatchesStdCbrtOnUnitIntervalAndExactCubes)
{
  double worst = 0.0;
  for (int k = 1; k <= 1000000; ++k) {    // theta^3 in (0, 1], densely
    const double x = k * 1e-6;
    worst = std::max(worst, rel(jkr::fast_cbrt(x), std::cbrt(x)));
  }
  for (int m = 1; m < 3000; ++m) {    // exact cubes: within the tolerance of the integer
    const double y = m * 0.125;
    worst = std::max(worst, rel(jkr::fast_cbrt(y * y * y), y));
  }
  for (double x : {std::numeric_limits<double>::min(), std::numeric_limits<double>::max(), 1.0,
                   8.0, 0.125, 2.0, 3.0})
    worst = std::max(worst, rel(jkr::fast_cbrt(x), std::cbrt(x)));
  EXPECT_LE(worst, kCbrtTol);
}

TEST(FastCbrt, SpecialArgumentsAsStdCbrt)
{
  EXPECT_EQ(jkr::fast_cbrt(0.0), 0.0);
  EXPECT_EQ(jkr::fast_cbrt(-8.0), -2.0);
  EXPECT_EQ(jkr::fast_cbrt(-0.0), 0.0);
  const double denormal = std::numeric_limits<double>::denorm_min() * 1000.0;
  EXPECT_EQ(jkr::fast_cbrt(denormal), std::cbrt(denormal));
  EXPECT_TRUE(std::isinf(jkr::fast_cbrt(std::numeric_limits<double>::infinity())));
  EXPECT_TRUE(std::isnan(jkr::fast_cbrt(std::numeric_limits<double>::quiet_NaN())));
}

// the law's warm-started Halley iteration in sqrt(a): <= 1e-12 relative to the closed form along
// a quasi-static path, after large jumps, from bad guesses (below the break radius, 0, negative:
// closed form) and on the first step of a contact (guess 0)
TEST(JkrWarmInversion, MatchesClosedFormAlongPathsAndJumps)
{
  for (double Gamma : {0.3, 0.6, 3.0}) {
    const tycore::PairConstants k = tycore::pair_constants(coefficients(0.3, Gamma));
    const auto radius = [&](double delta, double guess) {
      return tycore::normal_contact<true>(k, kRstar, delta, guess).contact_radius;
    };
    const double Pc = 3.0 * kPi * Gamma * kRstar;
    const double a0 = std::cbrt(3.0 * kRstar * Pc / kEstar), du = a0 * a0 / kRstar;
    // quasi-static path, compressive to just above the break and back
    double a = 0.0;
    for (int i = 0; i < 20000; ++i) {
      const double d = du * (2.0 - 2.26 * std::sin(kPi * i / 20000.0));    // down to -0.26 du
      a = radius(d, a);
      const double closed = jkr::contact_radius(d, kRstar, kEstar, Gamma);
      ASSERT_NEAR(a, closed, 1e-12 * closed) << Gamma << " " << i;
    }
    // jumps between any two states, and unusable guesses
    const double ds[] = {-0.27, -0.2, -0.13, 0.0, 0.3, 1.0, 10.0, 1e3, 1e5};
    for (double from : ds)
      for (double to : ds) {
        const double guess = jkr::contact_radius(from * du, kRstar, kEstar, Gamma);
        const double closed = jkr::contact_radius(to * du, kRstar, kEstar, Gamma);
        EXPECT_NEAR(radius(to * du, guess), closed, 1e-12 * closed) << from << " -> " << to;
        for (double bad : {0.0, -1.0, 0.1 * a0, 0.3 * a0, 1e3 * a0})
          EXPECT_NEAR(radius(to * du, bad), closed, 1e-12 * closed) << bad << " -> " << to;
      }
  }
  // Hertz: a = sqrt(R* delta)
  const tycore::PairConstants hertz = tycore::pair_constants(coefficients(0.3, 0.0));
  EXPECT_EQ(tycore::normal_contact<false>(hertz, kRstar, 1e-8, 1e-6).contact_radius,
            std::sqrt(kRstar * 1e-8));
}
