// The box-rate check (plugin/core/box_rate.hpp, docs/theory.md §5.1, §10.3) against boxes moved
// here by the exact cell update h <- exp(L dt) h (cell_kinematics.hpp): a rate that was held
// explains the change at any rate, with or without a tilt flip in the step; a component changed
// without a rate, or a rate left in the basis of the box before a flip, does not.
#include "box_rate.hpp"

#include <gtest/gtest.h>

#include <array>

using Eigen::Matrix3d;

namespace {

// LAMMPS's layout lx ly lz yz xz xy of an upper-triangular matrix
std::array<double, 6> lammps(const Matrix3d& h)
{
  return {h(0, 0), h(1, 1), h(2, 2), h(1, 2), h(0, 2), h(0, 1)};
}

Matrix3d gradient(double xx, double yy, double zz, double xy, double xz, double yz)
{
  Matrix3d L;
  L << xx, xy, xz, 0.0, yy, yz, 0.0, 0.0, zz;
  return L;
}

}    // namespace

// fix cell/servo's step: h1 = exp(L dt) h0 and h_rate = L h1, at up to 1 % strain per step
TEST(BoxRate, AnExactStepOfTheCellIsExplained)
{
  const Matrix3d h0 = tycore::cell_matrix(1e-3, 1.2e-3, 0.9e-3, 1e-4, -2e-4, 3e-4);
  const double dt = 1e-3;
  for (const double scale : {1e-6, 1e-3, 1.0, 10.0}) {
    const Matrix3d L = scale * gradient(1.0, -0.5, 0.3, 0.7, -0.4, 0.2);
    const Matrix3d h1 = tycore::advance_cell(h0, L, dt);
    const auto a = lammps(h0), b = lammps(h1), rate = tycore::lammps_h_rate(L, h1);
    EXPECT_EQ(tycore::unexplained_box_change(a.data(), b.data(), rate.data(), dt).component, -1)
        << scale;
  }
}

// a tilt that passes half its edge in the step is flipped (h1 M): with h_rate = L h1 M, as the
// fix sets it after the flip, the change is explained; with the rate of the unflipped box, which
// under L_xx != 0 is another L for the pair, it is not
TEST(BoxRate, AFlipIsNoChangeOfTheBoxButAStaleRateIs)
{
  const Matrix3d h0 = tycore::cell_matrix(1e-3, 1e-3, 1e-3, 0.0, 0.4999999e-3, 0.0);
  const double dt = 1e-7;
  const Matrix3d L = gradient(0.9, 0.0, 0.0, 0.0, 0.9, 0.0);
  Matrix3d h1 = tycore::advance_cell(h0, L, dt);
  h1 = tycore::advance_cell(h1, L, 10 * dt);    // (the tilt passes half of lx)
  const Matrix3d before = h1;
  h1 = tycore::advance_cell(before, L, dt);
  const tycore::TiltFlip flip = tycore::tilt_flip_of(h1);
  ASSERT_EQ(flip.xz, -1);
  const Matrix3d flipped = tycore::flipped_cell(h1, flip);
  const auto a = lammps(before), b = lammps(flipped);
  const auto fresh = tycore::lammps_h_rate(L, flipped), stale = tycore::lammps_h_rate(L, h1);
  EXPECT_EQ(tycore::unexplained_box_change(a.data(), b.data(), fresh.data(), dt).component, -1);
  const tycore::BoxChange c = tycore::unexplained_box_change(a.data(), b.data(), stale.data(), dt);
  EXPECT_EQ(c.component, 4);    // xz
  // the change is that of the unflipped tilt, one step's, not the box length of the flip
  EXPECT_NEAR(c.change, h1(0, 2) - before(0, 2), 1e-12 * before(0, 0));
}

// fix deform 'volume' in LAMMPS 2021: y and z change, their rate is 0
TEST(BoxRate, AChangeWithoutItsRateIsFound)
{
  const Matrix3d h0 = tycore::cell_matrix(1e-2, 1e-2, 1e-2, 0.0, 0.0, 0.0);
  Matrix3d h1 = h0;
  h1(0, 0) *= 1.0 + 1e-4;
  h1(1, 1) /= std::sqrt(1.0 + 1e-4);
  h1(2, 2) /= std::sqrt(1.0 + 1e-4);
  std::array<double, 6> rate{};
  rate[0] = (h1(0, 0) - h0(0, 0)) / 1e-3;
  const auto a = lammps(h0), b = lammps(h1);
  const tycore::BoxChange c = tycore::unexplained_box_change(a.data(), b.data(), rate.data(), 1e-3);
  EXPECT_EQ(c.component, 1);
  EXPECT_EQ(c.from_rate, 0.0);
  EXPECT_NEAR(c.change, h1(1, 1) - h0(1, 1), 1e-20);
}
