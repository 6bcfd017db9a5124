// One contact's share of the affine stiffness V C (docs/theory.md §6.1, §11.1), the one
// definition of the formula: the principal block that the pair's contact batch computes for
// every contact (contact_batch.hpp), the entries with a shear component that it tallies on a
// triclinic cell (pair_thornton_yin.cpp), and tycore::AffineStiffnessSums (cell_stiffness.hpp),
// which the estimate for other pair styles sums (compute_cell_tally.cpp). No dependencies, so
// that the batch kernel includes it without Eigen; plain arithmetic, so that it vectorises in
// the batch's lane loops.
#ifndef TYCORE_AFFINE_STIFFNESS_ENTRIES_HPP
#define TYCORE_AFFINE_STIFFNESS_ENTRIES_HPP

namespace tycore {

// one contact's 6 entries of V C of the principal block (I, J < 3) in LAMMPS's virial order
// xx yy zz xy xz yz (entry m is AffineStiffnessSums::sum[m]), each handed to store(m, value):
// l^2 [k_N n_a^2 n_b^2 + k_T (delta_ab n_a^2 - n_a^2 n_b^2)]; n the unit branch direction
// (either sign), l2 = |branch|^2
template <class Store>
[[gnu::always_inline]] inline void
affine_principal_entries(double nx, double ny, double nz, double l2, double normal_stiffness,
                         double tangential_stiffness, Store &&store)
{
  const double n2[3] = {nx * nx, ny * ny, nz * nz};
  constexpr int a_of[6] = {0, 1, 2, 0, 0, 1}, b_of[6] = {0, 1, 2, 1, 2, 2};
#pragma GCC unroll 6
  for (int m = 0; m < 6; ++m) {
    const double nn = n2[a_of[m]] * n2[b_of[m]];
    store(m,
          l2 * (normal_stiffness * nn + tangential_stiffness * ((m < 3 ? n2[a_of[m]] : 0.0) - nn)));
  }
}

inline constexpr int affine_shear_size = 15;

// one contact's 15 entries of V C with a shear component (J >= 3), in the order of the sums
// (entry k is AffineStiffnessSums::sum[6 + k]), each handed to store(k, value); n the unit branch
// direction (either sign: every entry is even in n), l2 = |branch|^2. Entry (I, J) is
// l^2 [(k_N - k_T) n_i n_j n_k n_l + k_T sym(delta_ik n_j n_l)], sym(delta_ik n_j n_l) the
// quarter sum of delta_ik n_j n_l over the four index pairings, written out for the 15 (I, J)
// (where no delta survives the fourth moment stands alone). Plain arithmetic, so that it
// vectorises in the contact batch's lane loop (pair_thornton_yin.cpp).
template <class Store>
[[gnu::always_inline]] inline void affine_shear_entries(double nx, double ny, double nz, double l2,
                                                        double normal_stiffness,
                                                        double tangential_stiffness, Store &&store)
{
  const double w = (normal_stiffness - tangential_stiffness) * l2;
  const double h = 0.5 * tangential_stiffness * l2, q = 0.25 * tangential_stiffness * l2;
  const double xx = nx * nx, yy = ny * ny, zz = nz * nz, xy = nx * ny, xz = nx * nz, yz = ny * nz;
  // normal xx, yy, zz with the shears xy, xz, yz
  store(0, w * xx * xy + h * xy);
  store(1, w * xx * xz + h * xz);
  store(2, w * xx * yz);
  store(3, w * yy * xy + h * xy);
  store(4, w * yy * xz);
  store(5, w * yy * yz + h * yz);
  store(6, w * zz * xy);
  store(7, w * zz * xz + h * xz);
  store(8, w * zz * yz + h * yz);
  // the shear block xy-xy, xy-xz, xy-yz, xz-xz, xz-yz, yz-yz
  store(9, w * xy * xy + q * (xx + yy));
  store(10, w * xx * yz + q * yz);
  store(11, w * yy * xz + q * xz);
  store(12, w * xz * xz + q * (xx + zz));
  store(13, w * zz * xy + q * xy);
  store(14, w * yz * yz + q * (yy + zz));
}

}    // namespace tycore

#endif
