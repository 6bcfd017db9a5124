// The entries of the full affine stiffness with a shear component (docs/theory.md §11.1), one
// contact at a time: what the pair's contact batch tallies on a triclinic cell
// (pair_thornton_yin.cpp) and tycore::AffineStiffnessSums sums (cell_stiffness.hpp). No
// dependencies, so that the batch kernel includes it without Eigen.
#ifndef TYCORE_AFFINE_SHEAR_ENTRIES_HPP
#define TYCORE_AFFINE_SHEAR_ENTRIES_HPP

namespace tycore {

inline constexpr int affine_shear_size = 15;

// one contact's 15 entries of V C with a shear component (J >= 3), in the order of the sums
// (entry k is AffineStiffnessSums::sum[6 + k]), each handed to store(k, value); n the unit branch
// direction (either sign: every entry is even in n), l2 = |branch|^2. Entry (I, J) is
// l^2 [(k_N - k_T) n_i n_j n_k n_l + k_T sym(delta_ik n_j n_l)], sym(delta_ik n_j n_l) the
// quarter sum of delta_ik n_j n_l over the four index pairings, written out for the 15 (I, J)
// (where no delta survives the fourth moment stands alone). Plain arithmetic, so that it
// vectorises in the contact batch's lane loop (pair_thornton_yin.cpp).
template <class Store>
[[gnu::always_inline]] inline void affine_shear_entries(double nx, double ny, double nz,
                                                        double l2, double normal_stiffness,
                                                        double tangential_stiffness, Store&& store)
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
