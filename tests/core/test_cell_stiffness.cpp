// The full affine stiffness (plugin/core/cell_stiffness.hpp, docs/theory.md §11-12) against
// independent expectations: the elastic energy of one contact, rotation of the frame, and the
// Hertz-Mindlin FCC lattice - its closed form and the finite-difference stress response of the
// frozen lattice built here from Hertz's force law.
#include "cell_stiffness.hpp"
#include "hertz_lattice.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tycore::Matrix6d;
using tycore::Vector6d;

namespace {

// glass of docs/theory.md §1.8: E = 70 GPa, nu = 0.3; like spheres: E* = E/(2(1 - nu^2)),
// G* = G/(2(2 - nu)), Mindlin k_T/k_N = 8 G* a/(2 E* a)
const double kE = 70e9, kNu = 0.3;
const double kContactModulus = kE / (2 * (1 - kNu * kNu));
const double kShearModulus = kE / (2 * (1 + kNu)) / (2 * (2 - kNu));
const double kTangentialRatio = 4 * kShearModulus / kContactModulus;
const double kRadius = 1e-4;

Matrix3d random_rotation(std::mt19937& rng)
{
  std::normal_distribution<double> g;
  const Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

// C_ijkl from the Voigt6 matrix (engineering shears: C_IJ = C_ijkl)
double tensor_entry(const Matrix6d& c, int i, int j, int k, int l)
{
  return c(tycore::voigt_index(i, j), tycore::voigt_index(k, l));
}

Matrix6d rotated(const Matrix6d& c, const Matrix3d& Q)
{
  Matrix6d r;
  for (int I = 0; I < 6; ++I)
    for (int J = 0; J < 6; ++J) {
      const int i = tycore::voigt_pairs[I][0], j = tycore::voigt_pairs[I][1];
      const int k = tycore::voigt_pairs[J][0], l = tycore::voigt_pairs[J][1];
      double sum = 0.0;
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q)
          for (int s = 0; s < 3; ++s)
            for (int t = 0; t < 3; ++t)
              sum += Q(i, p) * Q(j, q) * Q(k, s) * Q(l, t) * tensor_entry(c, p, q, s, t);
      r(I, J) = sum;
    }
  return r;
}

Matrix6d cubic(const tycore::CubicStiffness& c)
{
  Matrix6d m = Matrix6d::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m(i, j) = i == j ? c.c11 : c.c12;
    m(3 + i, 3 + i) = c.c44;
  }
  return m;
}

double relative_difference(const Matrix6d& a, const Matrix6d& b)
{
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// ---- the frozen FCC lattice, from Hertz's law (docs/theory.md §1.6) ----

struct Lattice {
  std::vector<Vector3d> branches;   // one per contact (6 per grain), at rest
  double volume;                    // per grain
  double normal_stiffness, tangential_stiffness;
};

// grain at the origin, its 6 contacts (one of each +- pair) at d = 2R(1 - x), rotated by Q
Lattice fcc_lattice(double x, const Matrix3d& Q)
{
  const double d = 2 * kRadius * (1 - x);
  Lattice lat;
  const double s = d / std::sqrt(2.0);
  for (const Vector3d& v : {Vector3d(1, 1, 0), Vector3d(1, -1, 0), Vector3d(1, 0, 1),
                            Vector3d(1, 0, -1), Vector3d(0, 1, 1), Vector3d(0, 1, -1)})
    lat.branches.push_back(Q * (s * v));
  lat.volume = d * d * d / std::sqrt(2.0);
  const double a = kRadius * std::sqrt(x);    // sqrt(R* delta), R* = R/2, delta = 2R x
  lat.normal_stiffness = 2 * kContactModulus * a;
  lat.tangential_stiffness = 8 * kShearModulus * a;
  return lat;
}

// compression-positive Love-Weber stress (1/V) sum f (x) l of the lattice strained affinely by
// the compression-positive strain e (l = (1 - e) l0), grains not rotating: Hertz normal force
// on the overlap, a linear tangential spring k_T of the rest state on the tangential relative
// displacement; symmetric part
Matrix3d lattice_stress(const Lattice& lat, const Matrix3d& e)
{
  const Matrix3d F = Matrix3d::Identity() - e;
  Matrix3d sigma = Matrix3d::Zero();
  for (const Vector3d& l0 : lat.branches) {
    const Vector3d l = F * l0;
    const Vector3d n = l.normalized();
    const double overlap = 2 * kRadius - l.norm();
    const double normal_force =
        4.0 / 3.0 * kContactModulus * std::sqrt(kRadius / 2) * std::pow(overlap, 1.5);
    const Vector3d slip = (Matrix3d::Identity() - n * n.transpose()) * (l - l0);
    const Vector3d f = normal_force * n - lat.tangential_stiffness * slip;
    sigma += f * l.transpose();
  }
  sigma /= lat.volume * F.determinant();
  return 0.5 * (sigma + sigma.transpose());
}

// the geometric (initial-stress) part of d sigma/d e at rest, derived in docs/theory.md §12:
// -(1/V) sum F l [(e n) n^T + n (e n)^T - (n.e n) n n^T] + sigma tr e
Matrix3d geometric_response(const Lattice& lat, const Matrix3d& e)
{
  const Matrix3d sigma = lattice_stress(lat, Matrix3d::Zero());
  Matrix3d g = sigma * e.trace();
  for (const Vector3d& l0 : lat.branches) {
    const Vector3d n = l0.normalized();
    const double overlap = 2 * kRadius - l0.norm();
    const double normal_force =
        4.0 / 3.0 * kContactModulus * std::sqrt(kRadius / 2) * std::pow(overlap, 1.5);
    const Vector3d en = e * n;
    g -= normal_force * l0.norm() / lat.volume
         * (en * n.transpose() + n * en.transpose() - n.dot(en) * n * n.transpose());
  }
  return g;
}

Matrix6d lattice_affine_stiffness(const Lattice& lat)
{
  tycore::AffineStiffnessSums sums;
  for (const Vector3d& l : lat.branches)
    sums.add_contact(l, lat.normal_stiffness, lat.tangential_stiffness);
  return sums.stiffness(lat.volume);
}

}    // namespace

// one contact: e : C : e = l^2 [k_N (n.e n)^2 + k_T (|e n|^2 - (n.e n)^2)] / V, the energy of
// its normal and tangential springs under the affine displacement e l, for random e and l
TEST(CellStiffness, EnergyOfOneContact)
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Vector3d l(u(rng), u(rng), u(rng));
    const double kn = 1.0 + u(rng) * 0.5, kt = 0.7 + 0.3 * u(rng);
    Vector6d e;
    for (int k = 0; k < 6; ++k) e(k) = u(rng);
    tycore::AffineStiffnessSums sums;
    sums.add_contact(l, kn, kt);
    const Matrix6d c = sums.stiffness(2.0);
    const Matrix3d et = tycore::tensor_from_strain(e);
    const Vector3d n = l.normalized();
    const double normal = n.dot(et * n);
    const double expected =
        l.squaredNorm() * (kn * normal * normal + kt * ((et * n).squaredNorm() - normal * normal))
        / 2.0;
    EXPECT_NEAR(e.dot(c * e), expected, 1e-13 * std::abs(expected) + 1e-15);
    EXPECT_LT((c - c.transpose()).cwiseAbs().maxCoeff(), 1e-15);
  }
}

// C is a fourth-order tensor: the contacts rotated by Q give Q Q Q Q C
TEST(CellStiffness, RotationOfTheFrame)
{
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vector3d> branches;
  for (int k = 0; k < 40; ++k) branches.emplace_back(u(rng), u(rng), u(rng));
  const Matrix3d Q = random_rotation(rng);
  tycore::AffineStiffnessSums sums, sums_rotated;
  for (const Vector3d& l : branches) {
    sums.add_contact(l, 2.0, 0.8);
    sums_rotated.add_contact(Q * l, 2.0, 0.8);
  }
  EXPECT_LT(relative_difference(sums_rotated.stiffness(1.0), rotated(sums.stiffness(1.0), Q)),
            1e-13);
}

// the sums of two ranks add up to those of all contacts; the 21 indices are distinct
TEST(CellStiffness, SumsAcrossRanks)
{
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  tycore::AffineStiffnessSums all, rank0, rank1;
  for (int k = 0; k < 30; ++k) {
    const Vector3d l(u(rng), u(rng), u(rng));
    all.add_contact(l, 3.0, 1.0);
    (k % 2 ? rank1 : rank0).add_contact(l, 3.0, 1.0);
  }
  rank0 += rank1;
  EXPECT_LT(relative_difference(rank0.stiffness(1.0), all.stiffness(1.0)), 1e-14);
  std::vector<int> seen(tycore::AffineStiffnessSums::size, 0);
  for (int I = 0; I < 6; ++I)
    for (int J = I; J < 6; ++J) ++seen[tycore::AffineStiffnessSums::index(I, J)];
  for (int s : seen) EXPECT_EQ(s, 1);
}

// the FCC lattice under pressure: the stress of the lattice built from Hertz's law is p of the
// closed form (and the inverse), and C from the 21 sums is the closed-form cubic C11, C12, C44
TEST(CellStiffness, FccLatticeClosedForm)
{
  for (double p : {1e4, 1e6, 1e8}) {
    const double x = tycore::fcc_lattice_relative_overlap(p, kContactModulus);
    EXPECT_NEAR(tycore::fcc_lattice_pressure(x, kContactModulus), p, 1e-12 * p);
    const Lattice lat = fcc_lattice(x, Matrix3d::Identity());
    const Matrix3d sigma = lattice_stress(lat, Matrix3d::Zero());
    EXPECT_LT((sigma - p * Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-9 * p) << sigma;
    const tycore::CubicStiffness closed =
        tycore::fcc_lattice_affine_stiffness(x, kContactModulus, kTangentialRatio);
    EXPECT_LT(relative_difference(lattice_affine_stiffness(lat), cubic(closed)), 1e-13);
    // the small-strain shear modulus C44 and its leading order in p:
    // (1 + kappa)/sqrt2 E* x^(1/2), x ~ (3p/(4 sqrt2 E*))^(2/3)
    const double leading = (1 + kTangentialRatio) / std::sqrt(2.0) * kContactModulus
                           * std::cbrt(3 * p / (4 * std::sqrt(2.0) * kContactModulus));
    EXPECT_NEAR(closed.c44 / leading, 1.0, 3 * x);
  }
}

// Lattice oracle: the 6x6 stiffness from the contact sums plus the geometric part equals the
// central finite-difference stress response of the frozen lattice (grains not rotating) to 1e-6
// relative, in the cubic frame and in a rotated one; without the geometric part it would not
TEST(CellStiffness, FccLatticeFiniteDifference)
{
  std::mt19937 rng(17);
  const double p = 1e6, step = 1e-7;
  const double x = tycore::fcc_lattice_relative_overlap(p, kContactModulus);
  for (const Matrix3d& Q : {Matrix3d(Matrix3d::Identity()), random_rotation(rng)}) {
    const Lattice lat = fcc_lattice(x, Q);
    const Matrix6d c = lattice_affine_stiffness(lat);
    Matrix6d fd, geometric;
    for (int J = 0; J < 6; ++J) {
      const Matrix3d e = tycore::tensor_from_strain(step * Vector6d::Unit(J));
      const Matrix3d dsigma = lattice_stress(lat, e) - lattice_stress(lat, -e);
      fd.col(J) = tycore::stress_from_tensor(dsigma / (2 * step));
      geometric.col(J) = tycore::stress_from_tensor(geometric_response(lat, e) / step);
    }
    // the measured differences, quoted in docs/theory.md §12
    std::printf("FCC lattice, p = %g Pa: |FD - (C + geometric)| = %.2g, |FD - C| = %.2g of |C|\n",
                p, relative_difference(fd, c + geometric), relative_difference(fd, c));
    EXPECT_LT(relative_difference(fd, c + geometric), 1e-6) << fd << "\n\n" << c + geometric;
    EXPECT_GT(relative_difference(fd, c), 1e-5);    // the geometric part is resolved
    EXPECT_LT(relative_difference(c, rotated(cubic(tycore::fcc_lattice_affine_stiffness(
                                                   x, kContactModulus, kTangentialRatio)),
                                               Q)),
              1e-13);
  }
}
