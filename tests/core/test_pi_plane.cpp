#include "pi_plane.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using Eigen::Vector2d;
using Eigen::Vector3d;
using tycore::FailureCriterion;

// sigma = (3, 2, 1) by hand: p = 2; s = (1, 0, -1), J2 = 1, q = sqrt 3; b = (2-1)/(3-1) = 0.5;
// sin(phi) = 2/4; x = 1/sqrt 2, y = 3/sqrt 6, tan(theta) = 1/sqrt 3 -> 30 deg;
// I1 = 6, I2 = 11, I3 = 6 -> eta = 216/6 - 27 = 9, I1 I2/I3 = 11
TEST(PiPlaneInvariants, HandComputedState321)
{
  const Vector3d sigma(3, 2, 1);
  EXPECT_DOUBLE_EQ(tycore::mean_stress(sigma), 2.0);
  EXPECT_NEAR(tycore::deviatoric_stress(sigma), std::sqrt(3.0), 1e-15);
  EXPECT_DOUBLE_EQ(tycore::b_value(sigma), 0.5);
  EXPECT_DOUBLE_EQ(tycore::mobilised_sinphi(sigma), 0.5);
  const Vector2d xy = tycore::pi_coordinates(sigma);
  EXPECT_NEAR(xy.x(), 1 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(xy.y(), 3 / std::sqrt(6.0), 1e-15);
  EXPECT_NEAR(tycore::lode_angle_deg(xy), 30.0, 1e-12);
  EXPECT_NEAR(tycore::lade_duncan_eta(sigma), 9.0, 1e-13);
  EXPECT_NEAR(tycore::matsuoka_nakai_ratio(sigma), 11.0, 1e-13);
}

// b and sin(phi) sort the values; the Pi coordinates keep the axis labels
TEST(PiPlaneInvariants, OrderFreeMeasuresIgnoreAxisLabels)
{
  const Vector3d sigma(1, 3, 2);
  EXPECT_DOUBLE_EQ(tycore::b_value(sigma), 0.5);
  EXPECT_DOUBLE_EQ(tycore::mobilised_sinphi(sigma), 0.5);
  EXPECT_NEAR(tycore::lade_duncan_eta(sigma), 9.0, 1e-13);
  // (1,3,2): x = 1/sqrt 2, y = (2-3-2)/sqrt 6 = -3/sqrt 6 -> 150 deg (sector of axis 2)
  EXPECT_NEAR(tycore::lode_angle_deg(tycore::pi_coordinates(sigma)), 150.0, 1e-12);
}

// the six axisymmetric states land on the six multiples of 60 deg of docs/theory.md §7.2
TEST(PiPlaneInvariants, LodeAngleOfAxisymmetricStatesInAllSectors)
{
  struct Case { Vector3d sigma; double lode; };
  const Case cases[] = {{{2, 1, 1}, 0},   {{2, 2, 1}, 60},  {{1, 2, 1}, 120},
                        {{1, 2, 2}, 180}, {{1, 1, 2}, 240}, {{2, 1, 2}, 300}};
  for (const Case& c : cases)
    EXPECT_NEAR(tycore::lode_angle_deg(tycore::pi_coordinates(c.sigma)), c.lode, 1e-12)
        << c.sigma.transpose();
}

// for sigma1 >= sigma2 >= sigma3, tan(theta) = sqrt(3) b/(2 - b)   (docs/theory.md §7.2)
TEST(PiPlaneInvariants, LodeAngleFollowsBValue)
{
  for (double b = 0.0; b <= 1.0; b += 0.05) {
    const Vector3d sigma(5.0, 2.0 + 3.0 * b, 2.0);
    const double expected = std::atan2(std::sqrt(3.0) * b, 2.0 - b) * 180.0 / M_PI;
    EXPECT_NEAR(tycore::lode_angle_deg(tycore::pi_coordinates(sigma)), expected, 1e-12);
    EXPECT_NEAR(tycore::b_value(sigma), b, 1e-14);
  }
}

// Pi radius is the Frobenius norm of the deviator: r = sqrt(2 J2) = sqrt(2/3) q
TEST(PiPlaneInvariants, PiRadiusIsDeviatorNorm)
{
  const Vector3d sigma(7.0, -2.0, 3.5);
  EXPECT_NEAR(tycore::pi_coordinates(sigma).norm(),
              std::sqrt(2.0 / 3.0) * tycore::deviatoric_stress(sigma), 1e-13);
}

// pi_coordinates followed by the inverse map with the mean restores the triple
TEST(PiPlaneInvariants, InverseMapRoundTrip)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  for (int k = 0; k < 100; ++k) {
    const Vector3d v(u(rng), u(rng), u(rng));
    const Vector3d back = tycore::principal_from_pi(tycore::pi_coordinates(v), v.mean());
    EXPECT_LT((back - v).norm(), 1e-14 * v.norm());
  }
}

// the Pi basis is orthonormal and normal to the hydrostatic axis
TEST(PiPlaneInvariants, PiBasisOrthonormalAndTraceless)
{
  const Vector3d ex = tycore::pi_unit_x(), ey = tycore::pi_unit_y();
  EXPECT_NEAR(ex.norm(), 1.0, 1e-15);
  EXPECT_NEAR(ey.norm(), 1.0, 1e-15);
  EXPECT_NEAR(ex.dot(ey), 0.0, 1e-15);
  EXPECT_NEAR(ex.sum(), 0.0, 1e-15);
  EXPECT_NEAR(ey.sum(), 0.0, 1e-15);
}

// undefined cases are reported as NaN, not as a plausible number
TEST(PiPlaneInvariants, IsotropicStateHasNoBOrLode)
{
  EXPECT_TRUE(std::isnan(tycore::b_value(Vector3d(4, 4, 4))));
  EXPECT_TRUE(std::isnan(tycore::lode_angle_deg(tycore::pi_coordinates(Vector3d(4, 4, 4)))));
}

// axisymmetric compression strain e = a(2,-1,-1) + v: eps_q = 2a = (2/3)(eps1 - eps3),
// eps1 - eps3 = 3a, eps_v = 3v   (docs/theory.md §7.1)
TEST(PiPlaneStrains, AxisymmetricCompressionMeasures)
{
  const double a = 1e-3, v = -2e-4;
  const Vector3d eps = a * Vector3d(2, -1, -1) + Vector3d::Constant(v);
  EXPECT_NEAR(tycore::deviatoric_strain(eps), 2 * a, 1e-17);
  EXPECT_NEAR(tycore::strain_difference_13(eps), 3 * a, 1e-17);
  EXPECT_NEAR(tycore::volumetric_strain(eps), 3 * v, 1e-18);
  // eps_q = (sqrt 2/3) sqrt((e1-e2)^2 + (e2-e3)^2 + (e3-e1)^2) for any state
  const Vector3d g(3e-3, -1e-3, 5e-4);
  const double pairs = std::pow(g(0) - g(1), 2) + std::pow(g(1) - g(2), 2)
                       + std::pow(g(2) - g(0), 2);
  EXPECT_NEAR(tycore::deviatoric_strain(g), std::sqrt(2.0) / 3.0 * std::sqrt(pairs), 1e-17);
}

// docs/theory.md §7.3 table, and the closed forms eta = (K+2)^3/K - 27, MN = 9 + 8 tan^2(phi)
TEST(PiPlaneFailure, CriterionConstantsOfCompressionFrictionAngle)
{
  const double sinphi[] = {0.30, 0.35, 0.40, 0.45, 0.50, 0.55, 0.60};
  const double eta[] = {3.900, 5.627, 7.873, 10.803, 14.667, 19.853, 27.000};
  const double mn[] = {9.791, 10.117, 10.524, 11.031, 11.667, 12.470, 13.500};
  for (int i = 0; i < 7; ++i) {
    const double ld = tycore::criterion_constant(FailureCriterion::LADE_DUNCAN, sinphi[i]);
    const double m = tycore::criterion_constant(FailureCriterion::MATSUOKA_NAKAI, sinphi[i]);
    EXPECT_NEAR(ld, eta[i], 6e-4) << sinphi[i];
    EXPECT_NEAR(m, mn[i], 6e-4) << sinphi[i];
    const double K = (1 + sinphi[i]) / (1 - sinphi[i]);
    const double tan2 = sinphi[i] * sinphi[i] / (1 - sinphi[i] * sinphi[i]);
    EXPECT_NEAR(ld, std::pow(K + 2, 3) / K - 27, 1e-12);
    EXPECT_NEAR(m, 9 + 8 * tan2, 1e-12);
  }
}

// docs/theory.md §7.3: predicted sin(phi)(b) on LD and MN surfaces through sinphi_TC, 4 decimals
TEST(PiPlaneFailure, SinphiAlongBOnLadeDuncanAndMatsuokaNakai)
{
  const double b[] = {0.0, 0.2, 0.4, 0.5, 0.6, 0.8, 1.0};
  struct Row { FailureCriterion criterion; double tc; double values[7]; };
  const Row rows[] = {
      {FailureCriterion::LADE_DUNCAN, 0.35, {.3500, .3913, .4128, .4153, .4132, .3992, .3778}},
      {FailureCriterion::MATSUOKA_NAKAI, 0.35, {.3500, .3872, .3986, .3961, .3902, .3720, .3500}},
      {FailureCriterion::LADE_DUNCAN, 0.45, {.4500, .5054, .5318, .5346, .5323, .5174, .4946}},
      {FailureCriterion::MATSUOKA_NAKAI, 0.45, {.4500, .4975, .5073, .5029, .4952, .4742, .4500}},
      {FailureCriterion::LADE_DUNCAN, 0.50, {.5000, .5624, .5904, .5933, .5910, .5763, .5538}},
      {FailureCriterion::MATSUOKA_NAKAI, 0.50, {.5000, .5520, .5600, .5547, .5463, .5245, .5000}},
  };
  for (const Row& r : rows)
    for (int j = 0; j < 7; ++j)
      EXPECT_NEAR(tycore::sinphi_on_surface(r.criterion, r.tc, b[j]), r.values[j], 6e-5)
          << "sinphi_TC " << r.tc << " b " << b[j];
}

// the state found on the surface really carries the surface's constant and the asked b
TEST(PiPlaneFailure, SurfaceStateSatisfiesCriterionAndB)
{
  const double s = tycore::sinphi_on_surface(FailureCriterion::LADE_DUNCAN, 0.4, 0.3);
  const Vector3d sigma = tycore::state_at_ratio(tycore::stress_ratio_from_sinphi(s), 0.3);
  EXPECT_NEAR(tycore::lade_duncan_eta(sigma),
              tycore::criterion_constant(FailureCriterion::LADE_DUNCAN, 0.4), 1e-11);
  EXPECT_NEAR(tycore::b_value(sigma), 0.3, 1e-13);
  EXPECT_NEAR(tycore::mobilised_sinphi(sigma), s, 1e-14);
}

// b outside [0, 1] is a named error
TEST(PiPlaneFailure, BadBIsRejected)
{
  EXPECT_THROW(tycore::sinphi_on_surface(FailureCriterion::LADE_DUNCAN, 0.4, 1.2),
               std::invalid_argument);
  EXPECT_THROW(tycore::sinphi_on_surface(FailureCriterion::LADE_DUNCAN, 1.0, 0.2),
               std::invalid_argument);
}
