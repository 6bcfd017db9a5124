// The stiffness estimate for other pair styles (docs/theory.md §6.5) against the Hertz law it
// assumes: the tangent dF/d(delta) by finite differences of F(delta), at any E*, R, overlap.
#include "contact_stiffness_estimate.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

double hertz_force(double E_star, double R, double delta)
{
  return 4.0 / 3.0 * E_star * std::sqrt(R) * std::pow(delta, 1.5);
}

}    // namespace

TEST(ContactStiffnessEstimate, IsTheHertzTangentStiffness)
{
  for (double E_star : {3.846e10, 1e6, 2e11})
    for (double R : {5e-5, 1e-3})
      for (double delta : {1e-9, 1e-7, 1e-5 * R}) {
        const double h = 1e-5 * delta;
        const double tangent =
            (hertz_force(E_star, R, delta + h) - hertz_force(E_star, R, delta - h)) / (2.0 * h);
        EXPECT_NEAR(tycore::hertz_normal_stiffness(hertz_force(E_star, R, delta), delta) / tangent,
                    1.0, 1e-9)
            << "E* " << E_star << " R " << R << " delta " << delta;
        // and the Hertz closed form k_N = 2 E* a with a = sqrt(R delta) (docs/theory.md §1.6)
        EXPECT_NEAR(tycore::hertz_normal_stiffness(hertz_force(E_star, R, delta), delta) /
                        (2.0 * E_star * std::sqrt(R * delta)),
                    1.0, 1e-12);
      }
}

TEST(ContactStiffnessEstimate, ContactsWithoutCompressionAddNothing)
{
  EXPECT_EQ(tycore::hertz_normal_stiffness(0.0, 1e-8), 0.0);
  EXPECT_EQ(tycore::hertz_normal_stiffness(-1e-3, 1e-8), 0.0);    // adhesive tension
  EXPECT_EQ(tycore::hertz_normal_stiffness(1e-3, 0.0), 0.0);
  EXPECT_EQ(tycore::hertz_normal_stiffness(1e-3, -1e-9), 0.0);    // beyond touch
}
