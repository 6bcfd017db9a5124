// The full affine stiffness of a periodic cell (docs/theory.md §11): d sigma_I = C_IJ d eps_J in
// Voigt6 (xx yy zz xy xz yz, engineering shears, compression positive; cell_kinematics.hpp),
//   C_ijkl = (1/V) sum_c l^2 [k_N n_i n_j n_k n_l + k_T (sym(delta_ik n_j n_l) - n_i n_j n_k n_l)],
//   sym(delta_ik n_j n_l)
//     = (delta_ik n_j n_l + delta_jk n_i n_l + delta_il n_j n_k + delta_jl n_i n_k)/4,
// from 21 independent sums over the contacts. Its principal block (I, J < 3) is cell_servo.hpp's
// affine_stiffness; one contact's share of either is affine_stiffness_entries.hpp's.
#ifndef TYCORE_CELL_STIFFNESS_HPP
#define TYCORE_CELL_STIFFNESS_HPP

#include "affine_stiffness_entries.hpp"
#include "cell_kinematics.hpp"
#include "cell_servo.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>

namespace tycore {

// per-rank sums of V*C over contacts, summed across ranks element by element (MPI_SUM over
// `size` doubles). The layout (CellTallies::STIFFNESS of plugin/lammps/cell_tally.h): first the
// principal block in LAMMPS virial order (xx, yy, zz, xy, xz, yz of the 3x3 C_ij of
// cell_servo.hpp's affine_stiffness, whose 6 sums an orthogonal cell needs), then the 15
// entries (I, J) with J >= 3, I <= J, row by row: the couplings of the normal components to the
// shears (9) and the shear block (6), which only a cell with shear components needs
struct AffineStiffnessSums {
  static constexpr int size = 21;
  static constexpr int principal_size = 6;
  static constexpr int shear_size = size - principal_size;
  static_assert(shear_size == affine_shear_size, "the 15 entries of affine_shear_entries");
  std::array<double, size> sum{};

  static constexpr int index(int I, int J)
  {
    if (I > J) return index(J, I);
    if (J < 3) return I == J ? I : I + J + 2;    // (0,1) -> 3, (0,2) -> 4, (1,2) -> 5
    if (I < 3) return 6 + 3 * I + (J - 3);       // (0..2, 3..5) -> 6..14
    return 15 + (I - 3) * 3 - (I - 3) * (I - 4) / 2 + (J - I);    // (3,3) 15 ... (5,5) 20
  }

  // sets of the entries (bit index(I, J)): the principal block, all 21; one entry
  static constexpr unsigned principal_entries = 0x3Fu;
  static constexpr unsigned all_entries = 0x1FFFFFu;
  static constexpr unsigned entry(int I, int J) { return 1u << index(I, J); }

  // one contact, branch = x2 - x1 (image-shifted), counted once
  void add_contact(const Eigen::Vector3d &branch, double normal_stiffness,
                   double tangential_stiffness)
  {
    contact_entries(branch, normal_stiffness, tangential_stiffness, [this](int k, double value) {
      sum[k] += value;
    });
  }

  AffineStiffnessSums &operator+=(const AffineStiffnessSums &other)
  {
    for (int k = 0; k < size; ++k) sum[k] += other.sum[k];
    return *this;
  }

  Matrix6d stiffness(double volume) const
  {
    Matrix6d c;
    for (int I = 0; I < 6; ++I)
      for (int J = 0; J < 6; ++J) c(I, J) = sum[index(I, J)] / volume;
    return c;
  }

  // one contact's share of V*C (Voigt6)
  static Matrix6d affine_stiffness_contribution_voigt(const Eigen::Vector3d &branch,
                                                      double normal_stiffness,
                                                      double tangential_stiffness)
  {
    double entries[size];
    contact_entries(branch, normal_stiffness, tangential_stiffness,
                    [&entries](int k, double value) {
                      entries[k] = value;
                    });
    Matrix6d c;
    for (int I = 0; I < 6; ++I)
      for (int J = 0; J < 6; ++J) c(I, J) = entries[index(I, J)];
    return c;
  }

  // one contact's share of the 15 entries with a shear component (J >= 3), in the order of the
  // sums (entries[k] is sum[principal_size + k]); branch = x2 - x1 (either sign). The pair
  // styles' tallies (plugin/lammps/cell_tally.h) add exactly these when a cell has shears
  static void shear_entries(const Eigen::Vector3d &branch, double normal_stiffness,
                            double tangential_stiffness, double entries[shear_size])
  {
    const double l2 = branch.squaredNorm();
    const Eigen::Vector3d n = branch / std::sqrt(l2);
    affine_shear_entries(n(0), n(1), n(2), l2, normal_stiffness, tangential_stiffness,
                         [entries](int k, double value) {
                           entries[k] = value;
                         });
  }

  // one contact's 21 entries, entry k handed to store(k, value) (affine_stiffness_entries.hpp)
  template <class Store>
  static void contact_entries(const Eigen::Vector3d &branch, double normal_stiffness,
                              double tangential_stiffness, Store &&store)
  {
    const double l2 = branch.squaredNorm();
    const Eigen::Vector3d n = branch / std::sqrt(l2);
    affine_principal_entries(n(0), n(1), n(2), l2, normal_stiffness, tangential_stiffness, store);
    affine_shear_entries(n(0), n(1), n(2), l2, normal_stiffness, tangential_stiffness,
                         [&store](int k, double value) {
                           store(principal_size + k, value);
                         });
  }
};

}    // namespace tycore

#endif
