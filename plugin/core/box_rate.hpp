// Does a box's rate explain its change? A pair style that adds the affine contact velocity
// L (x_i - x_j) reads L = h_rate h^-1 from LAMMPS's domain->h_rate (docs/theory.md §5.1, §10.1);
// a fix that changes the box without setting h_rate (LAMMPS 2021's fix deform 'volume', a
// barostat) silently removes part of that velocity. The check compares the change of the box
// over a step with what h_rate predicts. Plain C++, no LAMMPS (tests/core/test_box_rate.cpp).
//
// Boxes and rates are in LAMMPS's layout h[6] = lx ly lz yz xz xy, compared as matrices. A tilt
// flip (fix deform 'flip yes', fix cell/servo) replaces the box h by h M, M unit upper-triangular
// with integer flip counts (docs/theory.md §10.3): the same lattice of images. Its jumps are no
// change of the box: the box and the rate are compared in the basis of the box before the flip,
// h M^-1 and h_rate M^-1 (a flip leaves L = h_rate h^-1 unchanged, so h_rate goes to h_rate M
// with the box).
#ifndef TYCORE_BOX_RATE_HPP
#define TYCORE_BOX_RATE_HPP

#include "cell_kinematics.hpp"

#include <Eigen/Core>
#include <Eigen/LU>

#include <cmath>

namespace tycore {

// a component (index into the LAMMPS layout) whose change from h0 to h1 over dt the rate
// h_rate does not explain (-1: none), its change and what the rate gives (flips taken out)
struct BoxChange {
  int component = -1;
  double change = 0.0, from_rate = 0.0;
};

// The first component whose change h_rate does not explain. h_rate explains a change if it was
// held over the step (fix deform erate: h1 = h0 + h_rate dt), or if the velocity gradient was,
// L = h_rate h1^-1 with h at the end of the step (fix cell/servo: h1 = exp(L dt) h0) or
// L = h_rate h0^-1 at its start (fix deform trate): exact at any rate. Changes below 1e-12 of
// the edge a component is measured against are round-off.
inline BoxChange unexplained_box_change(const double h0[6], const double h1[6],
                                        const double h_rate[6], double dt)
{
  const Eigen::Matrix3d H0 = cell_matrix_from_lammps(h0), H1 = cell_matrix_from_lammps(h1);
  const Eigen::Matrix3d R = cell_matrix_from_lammps(h_rate);
  // the flip counts: H0^-1 H1 is M up to one step's change
  Eigen::Matrix3d M = (H0.inverse() * H1).array().round().matrix();
  M.diagonal().setOnes();
  M(1, 0) = M(2, 0) = M(2, 1) = 0.0;
  const Eigen::Matrix3d Minv = M.inverse();
  const Eigen::Matrix3d box = H1 * Minv, rate = R * Minv;
  // the three readings of the rate: h0 + h_rate dt; h0 from h1 at the end-of-step L; h1 from
  // h0 at the start-of-step L
  const Eigen::Matrix3d held = H0 + rate * dt;
  const Eigen::Matrix3d end_before = advance_cell(box, -(rate * box.inverse()), dt);
  const Eigen::Matrix3d start_after = advance_cell(H0, rate * H0.inverse(), dt);
  // (row, column) of h[k] and the edge its change is measured against
  constexpr int row[6] = {0, 1, 2, 1, 0, 0}, column[6] = {0, 1, 2, 2, 2, 1};
  constexpr int edge[6] = {0, 1, 2, 1, 0, 0};
  for (int k = 0; k < 6; ++k) {
    const int i = row[k], j = column[k];
    const double change = box(i, j) - H0(i, j), from_rate = rate(i, j) * dt;
    const double tolerance = 1e-3 * (std::fabs(change) + std::fabs(from_rate));
    const bool explained = std::fabs(box(i, j) - held(i, j)) <= tolerance ||
        std::fabs(H0(i, j) - end_before(i, j)) <= tolerance ||
        std::fabs(box(i, j) - start_after(i, j)) <= tolerance;
    // (a tilt is measured against the edge it shears, not against its own size, which may be 0)
    if (!explained && 1e3 * tolerance > 1e-12 * std::fabs(box(edge[k], edge[k])))
      return {k, change, from_rate};
  }
  return {};
}

}    // namespace tycore

#endif
