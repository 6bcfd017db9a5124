// Kinematics of the triclinic cell (plugin/core/cell_kinematics.hpp, docs/theory.md §10)
// against independent expectations: Eigen's matrix exponential, closed forms of simple shear,
// LAMMPS's flip rule, the invariance of unwrapped positions and image velocities under a flip,
// and rotations of the frame.
#include "cell_kinematics.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>
#include <random>

using Eigen::Matrix3d;
using Eigen::Matrix3i;
using Eigen::Vector3d;
using Eigen::Vector3i;
using tycore::Vector6d;

namespace {

Matrix3d upper(double a, double b, double c, double xy, double xz, double yz)
{
  return tycore::cell_matrix(a, b, c, xy, xz, yz);
}

Matrix3d random_rotation(std::mt19937& rng)
{
  std::normal_distribution<double> g;
  const Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

double max_abs(const Matrix3d& m) { return m.cwiseAbs().maxCoeff(); }

}    // namespace

// exp(L dt) in closed form equals Eigen's Pade matrix exponential, for equal, close and far
// apart diagonal rates (both branches of the second divided difference)
TEST(CellKinematics, StepDeformationIsTheMatrixExponential)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double spread : {0.0, 1e-9, 1e-5, 0.03, 0.09, 0.11, 0.5, 2.0})
    for (int trial = 0; trial < 20; ++trial) {
      const double base = u(rng);
      const Matrix3d L = upper(base + spread * u(rng), base + spread * u(rng),
                               base + spread * u(rng), u(rng), u(rng), u(rng));
      const double dt = 0.7;
      const Matrix3d expected = (L * dt).exp();
      const Matrix3d F = tycore::step_deformation(L, dt);
      EXPECT_LT(max_abs(F - expected), 2e-15 * max_abs(expected)) << "spread " << spread << "\n"
                                                                   << L;
    }
}

// simple shear (L_xz only): the tilt grows by gamma_dot dt lz exactly, nothing else moves
TEST(CellKinematics, SimpleShearTiltClosedForm)
{
  const Matrix3d h = upper(2.0, 3.0, 5.0, 0.25, -0.5, 0.75);
  Matrix3d L = Matrix3d::Zero();
  L(0, 2) = 0.125;
  const Matrix3d next = tycore::advance_cell(h, L, 0.5);
  Matrix3d expected = h;
  expected(0, 2) += 0.125 * 0.5 * 5.0;
  EXPECT_EQ(next, expected);
}

// an orthogonal cell with a diagonal L: bit for bit the present axis update
// l_i <- l_i exp(-eps_dot_i dt) of fix cell/servo, and no tilt appears
TEST(CellKinematics, OrthogonalUpdateBitIdentical)
{
  const double lengths[3] = {0.0123, 0.0117, 0.0131}, rate[3] = {3.1, -1.7, 0.4}, dt = 2.3e-7;
  Vector6d strain_rate = Vector6d::Zero();
  for (int k = 0; k < 3; ++k) strain_rate(k) = rate[k];
  const Matrix3d next = tycore::advance_cell(upper(lengths[0], lengths[1], lengths[2], 0, 0, 0),
                                             tycore::velocity_gradient(strain_rate), dt);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(next(k, k), lengths[k] * std::exp(-rate[k] * dt));
  EXPECT_EQ(next(0, 1), 0.0);
  EXPECT_EQ(next(0, 2), 0.0);
  EXPECT_EQ(next(1, 2), 0.0);
}

// h_rate for LAMMPS: h_dot h^-1 (as the pair forms it) gives L back; on an orthogonal cell the
// diagonal is bit for bit fix cell/servo's h_rate[k] = -rate[k] * length
TEST(CellKinematics, LammpsHRate)
{
  const Matrix3d h = upper(2.0, 3.0, 5.0, 0.25, -0.5, 0.75);
  const Matrix3d L = upper(0.1, -0.2, 0.05, 0.3, -0.7, 0.4);
  const std::array<double, 6> r = tycore::lammps_h_rate(L, h);
  const Matrix3d h_dot = tycore::cell_matrix_from_lammps(r.data());
  EXPECT_LT(max_abs(h_dot * h.inverse() - L), 1e-15);
  const double rate = 3.7, length = 0.0123;
  Vector6d strain_rate = Vector6d::Zero();
  strain_rate(1) = rate;
  EXPECT_EQ(tycore::lammps_h_rate(tycore::velocity_gradient(strain_rate),
                                  upper(1.0, length, 1.0, 0, 0, 0))[1],
            -rate * length);
}

// the six strain-rate components map one-to-one onto L: sym(L) = -eps_dot, D_ij = L_ij/2
TEST(CellKinematics, VelocityGradientFromStrainRate)
{
  Vector6d rate;
  rate << 1.0, -2.0, 3.0, 0.5, -0.25, 4.0;
  const Matrix3d L = tycore::velocity_gradient(rate);
  EXPECT_EQ(L(1, 0), 0.0);
  EXPECT_EQ(L(2, 0), 0.0);
  EXPECT_EQ(L(2, 1), 0.0);
  const Matrix3d D = 0.5 * (L + L.transpose());
  EXPECT_DOUBLE_EQ(D(0, 0), -1.0);
  EXPECT_DOUBLE_EQ(D(0, 1), -0.25);     // = L_xy/2 = -gamma_dot_xy/2
  EXPECT_DOUBLE_EQ(D(0, 2), 0.125);
  EXPECT_DOUBLE_EQ(D(1, 2), -2.0);
  EXPECT_EQ(tycore::strain_rate_of(L), rate);
}

// LAMMPS's rule (fix deform flip yes): yz against ly first with xz shifted by the old xy, then
// xz and xy against lx; exactly half a length does not flip
TEST(CellKinematics, FlipRuleOfLammps)
{
  const Matrix3d h = upper(10.0, 8.0, 6.0, 1.0, 5.5, -4.5);
  const tycore::TiltFlip f = tycore::tilt_flip_of(h);
  EXPECT_EQ(f.yz, 1);    // yz < -ly/2: yz + ly = 3.5, xz + xy = 6.5
  EXPECT_EQ(f.xz, -1);   // 6.5 > lx/2: 6.5 - 10 = -3.5
  EXPECT_EQ(f.xy, 0);
  const Matrix3d next = tycore::flipped_cell(h, f);
  EXPECT_EQ(next, upper(10.0, 8.0, 6.0, 1.0, -3.5, 3.5));
  EXPECT_FALSE(tycore::tilt_flip_of(upper(10.0, 8.0, 6.0, 5.0, -5.0, 4.0)).any());
  EXPECT_EQ(tycore::tilt_flip_of(upper(10.0, 8.0, 6.0, -5.01, 0.0, 0.0)).xy, 1);
}

// a flip is a change of basis of the same lattice of images: every image h n maps to h' n'
// (LAMMPS's image_flip), so unwrapped positions and the affine image velocities L h n are
// unchanged; M is unimodular; unflipping with M^-1 returns h
TEST(CellKinematics, FlipKeepsUnwrappedPositionsAndImageVelocities)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> image(-5, 5);
  int flips = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double lx = 1.0 + 0.5 * u(rng), ly = 1.0 + 0.5 * u(rng), lz = 1.0 + 0.5 * u(rng);
    const Matrix3d h = upper(lx, ly, lz, 0.7 * lx * u(rng), 0.7 * lx * u(rng), 0.9 * ly * u(rng));
    const Matrix3d L = upper(u(rng), u(rng), u(rng), u(rng), u(rng), u(rng));
    const tycore::TiltFlip f = tycore::tilt_flip_of(h);
    flips += f.any();
    const Matrix3d next = tycore::flipped_cell(h, f);
    EXPECT_EQ(f.matrix().determinant(), 1);
    EXPECT_LT(max_abs(next - h * f.matrix().cast<double>()), 1e-15);
    const Matrix3d back = next * f.matrix().cast<double>().inverse();
    EXPECT_LT(max_abs(back - h), 1e-15);
    Matrix3i inverse;    // of [[1, m, n], [0, 1, p], [0, 0, 1]]
    inverse << 1, -f.xy, f.xy * f.yz - f.xz,
               0, 1, -f.yz,
               0, 0, 1;
    EXPECT_EQ(f.matrix() * inverse, Matrix3i(Matrix3i::Identity()));
    for (int k = 0; k < 10; ++k) {
      const Vector3i n(image(rng), image(rng), image(rng));
      const Vector3i n_next = tycore::flipped_image(n, f);
      EXPECT_EQ(n_next, Vector3i(inverse * n));
      EXPECT_LT((next * n_next.cast<double>() - h * n.cast<double>()).norm(), 1e-13);
      EXPECT_LT((tycore::image_velocity(L, next, n_next) - tycore::image_velocity(L, h, n)).norm(),
                1e-13);
    }
    // after the flip the tilts lie within half their lengths
    EXPECT_LE(std::abs(next(1, 2)), 0.5 * ly);
    EXPECT_LE(std::abs(next(0, 2)), 0.5 * lx + 1e-15);
    EXPECT_LE(std::abs(next(0, 1)), 0.5 * lx);
  }
  EXPECT_GT(flips, 100);
}

// a long shear with flips: gamma accumulates as int L dt regardless of them, the axial strains
// are the logarithmic edge strains, and the flipped cell times the accumulated flip matrices
// is exp(L t) h0 (round trip: the unflipped cell from the cumulative history)
TEST(CellKinematics, CumulativeStrainAcrossFlips)
{
  const Matrix3d h0 = upper(1.0, 1.1, 0.9, 0.05, -0.1, 0.02);
  const Matrix3d L = upper(-0.01, 0.02, -0.015, 0.7, 1.3, -0.9);
  const double dt = 1e-3;
  const int steps = 3000;
  tycore::CumulativeStrain strain;
  strain.reference_length = h0.diagonal();
  Matrix3d h = h0;
  Matrix3i flips_total = Matrix3i::Identity();
  int flip_count = 0;
  for (int s = 0; s < steps; ++s) {
    h = tycore::advance_cell(h, L, dt);
    strain.advance(L, dt);
    const tycore::TiltFlip f = tycore::tilt_flip_of(h);
    if (f.any()) {
      h = tycore::flipped_cell(h, f);
      flips_total = flips_total * f.matrix();
      ++flip_count;
    }
  }
  EXPECT_GE(flip_count, 5);
  const double t = steps * dt;
  EXPECT_NEAR(strain.shear(0), 0.7 * t, 1e-12);
  EXPECT_NEAR(strain.shear(1), 1.3 * t, 1e-12);
  EXPECT_NEAR(strain.shear(2), -0.9 * t, 1e-12);
  const Vector3d axial = strain.axial(h);
  EXPECT_NEAR(axial(0), 0.01 * t, 1e-12);
  EXPECT_NEAR(axial(1), -0.02 * t, 1e-12);
  const Matrix3d unflipped = h * flips_total.cast<double>().inverse();
  const Matrix3d expected = (L * t).exp() * h0;
  EXPECT_LT(max_abs(unflipped - expected), 1e-12 * max_abs(expected));
  // pure simple shear in xz: the unflipped tilt is xz0 + gamma lz
  Matrix3d Ls = Matrix3d::Zero();
  Ls(0, 2) = 1.3;
  EXPECT_NEAR(((Ls * t).exp() * h0)(0, 2), h0(0, 2) + 1.3 * t * h0(2, 2), 1e-14);
}

TEST(CellKinematics, CumulativeStrainRestartArray)
{
  tycore::CumulativeStrain c;
  c.reference_length = Vector3d(1.5, 2.5, 3.5);
  c.shear = Vector3d(0.1, -0.2, 0.3);
  double a[tycore::CumulativeStrain::size];
  c.to_array(a);
  const tycore::CumulativeStrain d = tycore::CumulativeStrain::from_array(a);
  EXPECT_EQ(d.reference_length, c.reference_length);
  EXPECT_EQ(d.shear, c.shear);
}

// principal values and directions of Q diag Q^T, sorted major first; invariant under an axis
// permutation of the tensor (the values) with the directions permuted alike
TEST(CellKinematics, PrincipalAxesOfARotatedTensor)
{
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Matrix3d Q = random_rotation(rng);
    const Vector3d values(3.0e5, 1.0e5 + 1e3 * trial, 0.5e5);
    const Matrix3d S = Q * values.asDiagonal() * Q.transpose();
    const tycore::PrincipalAxes axes = tycore::principal_axes(S);
    EXPECT_LT((axes.values - values).cwiseAbs().maxCoeff(), 1e-9 * values(0));
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(std::abs(axes.directions.col(k).dot(Q.col(k))), 1.0, 1e-12);
    Eigen::PermutationMatrix<3> P(Vector3i(2, 0, 1));
    const Matrix3d permuted = P * S * P.transpose();
    const tycore::PrincipalAxes paxes = tycore::principal_axes(permuted);
    EXPECT_LT((paxes.values - values).cwiseAbs().maxCoeff(), 1e-9 * values(0));
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(std::abs(paxes.directions.col(k).dot(P * Q.col(k))), 1.0, 1e-12);
  }
}

// the major direction of R(theta) diag(s1, s3) R(theta)^T in a plane is at theta; pure shear
// (s_ii = s_jj, s_ij > 0) at 45 degrees; it agrees with the eigenvector's angle
TEST(CellKinematics, MajorAngleInPlane)
{
  for (int plane = 0; plane < 3; ++plane) {
    const int i = plane == 2 ? 1 : 0, j = plane == 0 ? 1 : 2;
    for (double theta : {-89.0, -60.0, -10.0, 0.0, 25.0, 44.0, 70.0, 90.0}) {
      const double a = theta * tycore::piplane::degree;
      Matrix3d R = Matrix3d::Identity();
      R(i, i) = std::cos(a), R(i, j) = -std::sin(a), R(j, i) = std::sin(a), R(j, j) = std::cos(a);
      Vector3d d = Vector3d::Constant(2.0);
      d(i) = 5.0, d(j) = 1.0;
      const Matrix3d S = R * d.asDiagonal() * R.transpose();
      EXPECT_NEAR(tycore::major_angle_in_plane_deg(S, i, j), theta, 1e-12) << plane;
      const Vector3d major = tycore::principal_axes(S).directions.col(0);
      EXPECT_NEAR(tycore::direction_angle_deg(major, i, j), theta, 1e-9) << plane;
    }
    Matrix3d shear = Matrix3d::Identity();
    shear(i, j) = shear(j, i) = 0.3;
    EXPECT_NEAR(tycore::major_angle_in_plane_deg(shear, i, j), 45.0, 1e-12);
  }
}

// non-coaxiality: the difference of the major directions of stress and strain rate, wrapped to
// (-90, 90]; zero for coaxial tensors; unchanged by a rotation of both about the plane normal
TEST(CellKinematics, NonCoaxiality)
{
  auto in_plane = [](double theta_deg, double major, double minor) {
    const double a = theta_deg * tycore::piplane::degree;
    Matrix3d R = Matrix3d::Identity();
    R(0, 0) = std::cos(a), R(0, 2) = -std::sin(a), R(2, 0) = std::sin(a), R(2, 2) = std::cos(a);
    return Matrix3d(R * Vector3d(major, 1.0, minor).asDiagonal() * R.transpose());
  };
  EXPECT_NEAR(tycore::non_coaxiality_deg(in_plane(30, 4, 2), in_plane(10, 1e-3, -1e-3), 0, 2),
              20.0, 1e-12);
  EXPECT_NEAR(tycore::non_coaxiality_deg(in_plane(33, 4, 2), in_plane(33, 5e-4, -2e-3), 0, 2),
              0.0, 1e-12);
  EXPECT_NEAR(tycore::non_coaxiality_deg(in_plane(80, 4, 2), in_plane(-20, 1, -1), 0, 2), -80.0,
              1e-12);
  for (double turn : {15.0, 50.0, 120.0})
    EXPECT_NEAR(tycore::non_coaxiality_deg(in_plane(30 + turn, 4, 2),
                                           in_plane(10 + turn, 1, -1), 0, 2),
                20.0, 1e-11);
}

TEST(CellKinematics, RejectsInvalidCells)
{
  EXPECT_THROW(tycore::require_valid_cell(upper(1, 1, -1, 0, 0, 0)), std::invalid_argument);
  EXPECT_THROW(tycore::require_valid_cell(upper(1, 1, 1, NAN, 0, 0)), std::invalid_argument);
  Matrix3d lower = Matrix3d::Identity();
  lower(2, 0) = 0.1;
  EXPECT_THROW(tycore::require_valid_cell(lower), std::invalid_argument);
  EXPECT_NO_THROW(tycore::require_valid_cell(upper(1, 2, 3, 0.4, -0.2, 0.9)));
}
