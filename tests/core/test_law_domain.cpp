// Bounds of the law's meaning, tycore::law_domain_fault and zero_load_radius_ratio
// (plugin/core/law_domain.hpp). Expected values from the closed forms of docs/theory.md §1.
#include "law_domain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kR = 1e-4, kRstar = kR / 2.0;

tycore::PairCoefficients glass(double E = 70e9, double mu = 0.3, double Gamma = 0.3)
{
  const double nu = 0.3;
  return {E / (2.0 * (1.0 - nu * nu)), E / (2.0 * (1.0 + nu)) / (2.0 * (2.0 - nu)), mu, Gamma};
}

TEST(LawDomain, ZeroLoadRadiusRatioIsTheJkrClosedForm)
{
  const auto c = glass();
  // a0^3 = 9 pi Gamma R*^2/E*
  EXPECT_NEAR(tycore::zero_load_radius_ratio(c, kRstar),
              std::cbrt(9.0 * kPi * c.Gamma * kRstar * kRstar / c.E_star) / kRstar, 1e-15);
  EXPECT_EQ(tycore::zero_load_radius_ratio(glass(70e9, 0.3, 0.0), kRstar), 0.0);
  // a0 = R* exactly at Gamma = E* R*/(9 pi)
  const auto at_bound = glass(70e9, 0.3, glass().E_star * kRstar / (9.0 * kPi));
  EXPECT_NEAR(tycore::zero_load_radius_ratio(at_bound, kRstar), 1.0, 1e-14);
}

TEST(LawDomain, OrdinaryGlassHasNoFaultOverItsRange)
{
  for (const double Gamma : {0.0, 0.3, 3.0, 1000.0})
    EXPECT_EQ(tycore::law_domain_fault(glass(70e9, 0.3, Gamma), kRstar, kR).quantity, nullptr)
        << Gamma;
}

TEST(LawDomain, OverflowingCoefficientsNameTheQuantity)
{
  // Gamma^2 R*^4 E*^4 (delta R*)^3 > 1e308 in the closed-form JKR root
  const auto stiff = tycore::law_domain_fault(glass(1e100), kRstar, kR);
  ASSERT_NE(stiff.quantity, nullptr);
  EXPECT_STREQ(stiff.quantity, "contact radius a");
  EXPECT_EQ(stiff.delta, kR);
  // E*^2 underflows: delta_f = -cbrt(0/0)
  const auto soft = tycore::law_domain_fault(glass(1e-300, 0.3, 0.0), kRstar, kR);
  ASSERT_NE(soft.quantity, nullptr);
  EXPECT_STREQ(soft.quantity, "break overlap delta_f");
  const auto rough = tycore::law_domain_fault(glass(70e9, 1e300), kRstar, kR);
  ASSERT_NE(rough.quantity, nullptr);
  EXPECT_STREQ(rough.quantity, "tangential energy at sliding");
}

}    // namespace
