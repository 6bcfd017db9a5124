#include "cell_servo.hpp"
#include "hertz_lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

// glass spheres of docs/theory.md §1.8: E = 70 GPa, nu = 0.3, like pair: E* = E/(2(1 - nu^2))
const double kContactModulus = 70e9 / (2 * (1 - 0.09));
const double kRadius = 1e-4;

// the lattice from its physical ingredients: spacing s_i, Hertz force with R* = R/2,
// Love-Weber sigma_i = P_i s_i / (s1 s2 s3)
double hertz_force(double overlap)
{
  return overlap > 0 ? 4.0 / 3.0 * kContactModulus * std::sqrt(kRadius / 2) * std::pow(overlap, 1.5)
                     : 0.0;
}

Vector3d lattice_stress_from_spacing(const Vector3d& s)
{
  Vector3d sigma;
  for (int i = 0; i < 3; ++i) sigma(i) = hertz_force(2 * kRadius - s(i)) * s(i) / s.prod();
  return sigma;
}

}    // namespace

// inverse and forward closed forms agree from 1 Pa to 1 GPa
TEST(HertzLattice, InverseRoundTrip)
{
  for (double p = 1.0; p <= 1e9; p *= 3.7) {
    const double eps = tycore::hertz_lattice_strain(p, kContactModulus);
    EXPECT_NEAR(tycore::hertz_lattice_mean_stress(eps, kContactModulus), p, 1e-12 * p) << p;
  }
}

// independent solve: bisection on the lattice spacing of the physical lattice (R = 0.1 mm)
// for sigma = P(2R - s)/s^2 = p, then eps = ln(2R/s); s ~ 2R carries 16 digits, so eps ~ 1e-5
// is resolved to ~1e-11 relative
TEST(HertzLattice, StrainAgreesWithBisectionOnSpacing)
{
  for (double p : {1e3, 1e5, 1e7}) {
    double lo = kRadius, hi = 2 * kRadius;   // stress falls as the spacing grows
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (lattice_stress_from_spacing(Vector3d::Constant(mid))(0) > p ? lo : hi) = mid;
    }
    const double eps = std::log(2 * kRadius / (0.5 * (lo + hi)));
    EXPECT_NEAR(tycore::hertz_lattice_strain(p, kContactModulus), eps, 1e-9 * eps) << p;
  }
}

// small strains: p -> (2/3) E* eps^(3/2) with a relative correction O(eps)
TEST(HertzLattice, SmallStrainLimit)
{
  for (double eps : {1e-6, 1e-5, 1e-4}) {
    const double ratio = tycore::hertz_lattice_mean_stress(eps, kContactModulus)
                         / (2.0 / 3.0 * kContactModulus * std::pow(eps, 1.5));
    EXPECT_NEAR(ratio, 1.0, 2 * eps);
  }
}

// anisotropic strains: closed form equals the physical lattice with s_i = 2R exp(-eps_i),
// including axes that have lost contact (zero stress)
TEST(HertzLattice, PrincipalStressesMatchPhysicalLattice)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1e-4, 3e-3);
  for (int k = 0; k < 50; ++k) {
    const Vector3d eps(u(rng), u(rng), u(rng));
    const Vector3d spacing = 2 * kRadius * (-eps.array()).exp();
    const Vector3d expected = lattice_stress_from_spacing(spacing);
    const Vector3d sigma = tycore::hertz_lattice_stress(eps, kContactModulus);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(sigma(i), expected(i), 1e-12 * expected.norm());
  }
}

// C_ii equals the finite-difference d sigma_i/d eps_i at fixed lateral strains; the
// off-diagonal d sigma_i/d eps_j = sigma_i is the area change the contact-based affine
// estimate leaves out (C_ij = 0), smaller than C_ii by the factor sigma/C ~ strain
TEST(HertzLattice, AffineStiffnessIsAxialTangent)
{
  const Vector3d eps(2e-3, 1.5e-3, 1e-3);
  const Matrix3d C = tycore::hertz_lattice_affine_stiffness(eps, kContactModulus);
  const Vector3d sigma = tycore::hertz_lattice_stress(eps, kContactModulus);
  const double h = 1e-9;
  for (int j = 0; j < 3; ++j) {
    const Vector3d dh = h * Vector3d::Unit(j);
    const Vector3d tangent = (tycore::hertz_lattice_stress(eps + dh, kContactModulus)
                              - tycore::hertz_lattice_stress(eps - dh, kContactModulus)) / (2 * h);
    for (int i = 0; i < 3; ++i) {
      const double expected = i == j ? C(i, i) : sigma(i);
      EXPECT_NEAR(tangent(i), expected, 1e-6 * C(i, i)) << i << j;
    }
  }
  EXPECT_EQ(C(0, 1), 0.0);
}

// the fix's contact sum (cell_servo.hpp) over the lattice's three contacts per cell, with
// Hertz k_N = 2 E* sqrt(R* delta), gives the closed-form lattice stiffness
TEST(HertzLattice, ContactSumReproducesLatticeStiffness)
{
  const Vector3d eps(2e-3, 1.5e-3, 1e-3);
  const Vector3d spacing = 2 * kRadius * (-eps.array()).exp();
  Matrix3d sum = Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const double overlap = 2 * kRadius - spacing(i);
    const double k_normal = 2 * kContactModulus * std::sqrt(kRadius / 2 * overlap);
    sum += tycore::affine_stiffness_contribution(spacing(i) * Vector3d::Unit(i), k_normal);
  }
  const Matrix3d C = tycore::hertz_lattice_affine_stiffness(eps, kContactModulus);
  EXPECT_LT((sum / spacing.prod() - C).norm(), 1e-12 * C.norm());
}

// non-positive p or E* is a named error
TEST(HertzLattice, BadInputIsRejected)
{
  EXPECT_THROW(tycore::hertz_lattice_strain(0.0, kContactModulus), std::invalid_argument);
  EXPECT_THROW(tycore::hertz_lattice_strain(1e5, -1.0), std::invalid_argument);
}
