// Closed form for a simple cubic lattice of equal Hertzian spheres (no adhesion, Gamma = 0)
// under principal strains: the reference answer for the isotropic-compression servo test
// (docs/theory.md §9).
//
// Derivation. Spheres of radius R sit on a simple cubic lattice with spacing s_i along axis i;
// they touch at s_i = 2R. The natural strain from the touching lattice, compression positive,
// is eps_i = ln(2R/s_i), so s_i = 2R exp(-eps_i) and the overlap of the contacts along axis i
// is delta_i = 2R - s_i = 2R x_i with x_i = 1 - exp(-eps_i). Hertz (docs/theory.md §1.6) with
// R* = R/2 gives P_i = (4/3) E* sqrt(R/2) delta_i^(3/2) = (4/3) E* 2 R^2 x_i^(3/2).
// A lattice cell (volume V = s1 s2 s3) holds one grain and one contact along each axis, with
// branch vector s_i e_i, so the Love-Weber stress sigma_ij = (1/V) sum_c f_i l_j is diagonal:
//     sigma_i = P_i s_i / V = P_i / (s_j s_k) = (2/3) E* x_i^(3/2) exp(eps_j + eps_k),
// independent of R. Isotropically (all eps_i = eps, x = 1 - exp(-eps)):
//     p(eps) = (2/3) E* (1 - exp(-eps))^(3/2) exp(2 eps) = (2/3) E* x^(3/2) / (1 - x)^2,
// so p ~ (2/3) E* eps^(3/2) at small strain. The affine stiffness of cell_servo.hpp
// (k_N = 2 E* a, a = sqrt(R* delta) = R sqrt(x_i)) is diagonal as well:
//     C_ii = k_N s_i^2 / V = E* sqrt(x_i) exp(eps_j + eps_k - eps_i).
// E* is the contact modulus of the pair, 1/E* = 2 (1 - nu^2)/E for like spheres.
#ifndef TYCORE_HERTZ_LATTICE_HPP
#define TYCORE_HERTZ_LATTICE_HPP

#include "pi_plane.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tycore {

// x_i = delta_i/(2R) = 1 - exp(-eps_i); negative (no contact) for eps_i < 0
inline double hertz_lattice_relative_overlap(double natural_strain)
{
  return -std::expm1(-natural_strain);
}

// principal stresses sigma_i = (2/3) E* x_i^(3/2) exp(eps_j + eps_k); zero without contact
inline Eigen::Vector3d hertz_lattice_stress(const Eigen::Vector3d& strain, double contact_modulus)
{
  Eigen::Vector3d sigma;
  for (int i = 0; i < 3; ++i) {
    const double x = std::max(0.0, hertz_lattice_relative_overlap(strain(i)));
    const double lateral = strain((i + 1) % 3) + strain((i + 2) % 3);
    sigma(i) = 2.0 / 3.0 * contact_modulus * x * std::sqrt(x) * std::exp(lateral);
  }
  return sigma;
}

// C_ii = E* sqrt(x_i) exp(eps_j + eps_k - eps_i), C_ij = 0
inline Eigen::Matrix3d hertz_lattice_affine_stiffness(const Eigen::Vector3d& strain,
                                                      double contact_modulus)
{
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const double x = std::max(0.0, hertz_lattice_relative_overlap(strain(i)));
    const double lateral = strain((i + 1) % 3) + strain((i + 2) % 3);
    c(i, i) = contact_modulus * std::sqrt(x) * std::exp(lateral - strain(i));
  }
  return c;
}

// p(eps) = (2/3) E* (1 - exp(-eps))^(3/2) exp(2 eps)
inline double hertz_lattice_mean_stress(double natural_strain, double contact_modulus)
{
  return hertz_lattice_stress(Eigen::Vector3d::Constant(natural_strain), contact_modulus)(0);
}

// isotropic natural strain at mean stress p: with y = sqrt(x), the root in (0, 1) of
// f(y) = (2/3) y^3 - (p/E*) (1 - y^2)^2, increasing there from -p/E* to 2/3; Newton from the
// small-strain guess y = (3p/2E*)^(1/3), kept inside a shrinking bisection bracket
inline double hertz_lattice_strain(double mean_stress, double contact_modulus)
{
  if (!(mean_stress > 0.0) || !(contact_modulus > 0.0))
    throw std::invalid_argument("Hertz lattice needs positive p and E* (got p = "
                                + std::to_string(mean_stress) + ", E* = "
                                + std::to_string(contact_modulus) + ")");
  const double ratio = mean_stress / contact_modulus;
  auto f = [ratio](double y) { return 2.0 / 3.0 * y * y * y - ratio * std::pow(1 - y * y, 2); };
  auto df = [ratio](double y) { return 2.0 * y * y + 4.0 * ratio * y * (1 - y * y); };
  double lo = 0.0, hi = 1.0;
  double y = std::min(std::cbrt(1.5 * ratio), 0.5);
  for (int i = 0; i < 100; ++i) {
    const double value = f(y);
    (value < 0.0 ? lo : hi) = y;
    double next = y - value / df(y);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - y) <= 1e-16 * y) {
      y = next;
      break;
    }
    y = next;
  }
  return -std::log1p(-y * y);
}

// ---------------------------------------------------------------------------------------------
// Face-centred cubic lattice of equal Hertz-Mindlin spheres under isotropic pressure
// (docs/theory.md §12). Nearest neighbours at d = 2R(1 - x) along the 12 directions
// (+-1, +-1, 0)/sqrt2 and permutations, 6 contacts and V_p = d^3/sqrt2 per grain, all in
// equilibrium under an affine strain (a Bravais lattice). With k_N = 2 E* a, a = R sqrt(x),
// k_T = kappa k_N (Mindlin: kappa = 4 G*/E* = 2(1 - nu)/(2 - nu) for like spheres):
//     p = (4 sqrt2/3) E* x^(3/2)/(1 - x)^2 = 2 sqrt2 p_simple-cubic(x),
//     C11 = K0 (1 + kappa), C12 = K0 (1 - kappa)/2, C44 = K0 (1 + kappa)/2,
//     K0 = sqrt2 E* sqrt(x)/(1 - x)   (cubic axes, Voigt engineering shears).

struct CubicStiffness {
  double c11, c12, c44;
};

inline double fcc_lattice_pressure(double relative_overlap, double contact_modulus)
{
  const double x = relative_overlap;
  return 4.0 * piplane::sqrt2 / 3.0 * contact_modulus * x * std::sqrt(x) / ((1 - x) * (1 - x));
}

// x at pressure p: the simple-cubic root at p/(2 sqrt2), since the two laws differ by that factor
inline double fcc_lattice_relative_overlap(double pressure, double contact_modulus)
{
  return hertz_lattice_relative_overlap(
      hertz_lattice_strain(pressure / (2.0 * piplane::sqrt2), contact_modulus));
}

inline CubicStiffness fcc_lattice_affine_stiffness(double relative_overlap,
                                                   double contact_modulus,
                                                   double tangential_ratio)
{
  const double x = relative_overlap, kappa = tangential_ratio;
  const double k0 = piplane::sqrt2 * contact_modulus * std::sqrt(x) / (1 - x);
  return {k0 * (1 + kappa), 0.5 * k0 * (1 - kappa), 0.5 * k0 * (1 + kappa)};
}

}    // namespace tycore

#endif
