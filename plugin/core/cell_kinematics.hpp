// Kinematics of a triclinic periodic cell (docs/theory.md §10): the LAMMPS cell matrix h, the
// upper-triangular velocity gradient L and its six strain-rate components, the exact update of
// h over a step, tilt flips at half a box length, the cumulative strain, principal values and
// directions and the non-coaxiality angle. Plain data in, plain data out; no LAMMPS.
//
// Conventions
//   h = [[lx, xy, xz], [0, ly, yz], [0, 0, lz]]: its columns are the cell's edge vectors
//     a = (lx, 0, 0), b = (xy, ly, 0), c = (xz, yz, lz) (LAMMPS's h[6] = lx ly lz yz xz xy).
//   Six-component vectors are in LAMMPS's virial order xx, yy, zz, xy, xz, yz (Voigt6), shears
//     as engineering strains (gamma_ij = 2 eps_ij), so that sigma : d eps = sum_I sigma_I deps_I.
//   Stresses and strains are compression positive, as in cell_servo.hpp: the compression-
//     positive strain rate is eps_dot = -(L_xx, L_yy, L_zz, L_xy, L_xz, L_yz), i.e. minus the
//     rate of deformation D = sym(L) in Voigt form (D_ij = L_ij/2 for i < j).
//   The shear of a simple-shear test is reported in the tilt sense: gamma_ij = int L_ij dt
//     (> 0 when the edge along j tilts towards +i), tau_ij = -sigma_ij (the Cauchy shear stress),
//     so that tau/sigma_n > 0 while gamma grows.
#ifndef TYCORE_CELL_KINEMATICS_HPP
#define TYCORE_CELL_KINEMATICS_HPP

#include "pi_plane.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tycore {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// the (row, column) of each Voigt6 component
inline constexpr std::array<std::array<int, 2>, 6> voigt_pairs{
    {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};
inline constexpr std::array<const char *, 6> voigt_names{"xx", "yy", "zz", "xy", "xz", "yz"};

// Voigt6 index of the tensor component (i, j), i.e. of (j, i)
inline int voigt_index(int i, int j)
{
  if (i == j) return i;
  return i + j + 2;    // (0,1) -> 3, (0,2) -> 4, (1,2) -> 5
}

// ---------------------------------------------------------------------------------------------
// Symmetric tensors <-> Voigt6

inline Eigen::Matrix3d tensor_from_stress(const Vector6d &s)
{
  Eigen::Matrix3d t;
  // clang-format off
  t << s(0), s(3), s(4),
       s(3), s(1), s(5),
       s(4), s(5), s(2);
  // clang-format on
  return t;
}

inline Vector6d stress_from_tensor(const Eigen::Matrix3d &t)
{
  Vector6d s;
  for (int I = 0; I < 6; ++I) s(I) = t(voigt_pairs[I][0], voigt_pairs[I][1]);
  return s;
}

// strains carry engineering shears: the tensor's off-diagonal entries are gamma/2
inline Eigen::Matrix3d tensor_from_strain(const Vector6d &e)
{
  Vector6d s = e;
  s.tail<3>() *= 0.5;
  return tensor_from_stress(s);
}

inline Vector6d strain_from_tensor(const Eigen::Matrix3d &t)
{
  Vector6d e = stress_from_tensor(t);
  e.tail<3>() *= 2.0;
  return e;
}

// ---------------------------------------------------------------------------------------------
// Cell matrix and velocity gradient

inline Eigen::Matrix3d cell_matrix(double lx, double ly, double lz, double xy, double xz, double yz)
{
  Eigen::Matrix3d h;
  // clang-format off
  h << lx, xy, xz,
       0.0, ly, yz,
       0.0, 0.0, lz;
  // clang-format on
  return h;
}

// LAMMPS's domain->h: lx ly lz yz xz xy
inline Eigen::Matrix3d cell_matrix_from_lammps(const double h[6])
{
  return cell_matrix(h[0], h[1], h[2], h[5], h[4], h[3]);
}

inline void require_valid_cell(const Eigen::Matrix3d &h)
{
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!std::isfinite(h(i, j)))
        throw std::invalid_argument("cell matrix entry (" + std::to_string(i) + ", " +
                                    std::to_string(j) + ") is not finite");
  if (h(1, 0) != 0.0 || h(2, 0) != 0.0 || h(2, 1) != 0.0)
    throw std::invalid_argument("cell matrix must be upper triangular (LAMMPS's restricted "
                                "triclinic box)");
  for (int i = 0; i < 3; ++i)
    if (!(h(i, i) > 0.0))
      throw std::invalid_argument(std::string("cell edge l") + "xyz"[i] + " must be positive");
}

// L from the compression-positive strain rate (Voigt6, engineering shears): the upper-
// triangular velocity gradient whose symmetric part is -eps_dot; the spin is that of simple
// shear (L_ji = 0 for j > i), the only one an upper-triangular cell can follow
inline Eigen::Matrix3d velocity_gradient(const Vector6d &strain_rate)
{
  return -cell_matrix(strain_rate(0), strain_rate(1), strain_rate(2), strain_rate(3),
                      strain_rate(4), strain_rate(5));
}

inline Vector6d strain_rate_of(const Eigen::Matrix3d &velocity_gradient)
{
  return -strain_from_tensor(0.5 * (velocity_gradient + velocity_gradient.transpose()));
}

namespace detail {

  // sinh(x)/x
  inline double sinhc(double x)
  {
    return std::abs(x) < 1e-4 ? 1.0 + x * x / 6.0 : std::sinh(x) / x;
  }

  // first divided difference of exp: (e^a - e^b)/(a - b), without cancellation
  inline double exp_divided_difference(double a, double b)
  {
    return std::exp(0.5 * (a + b)) * sinhc(0.5 * (a - b));
  }

  // second divided difference of exp at a, b, c. Close points: e^m sum_k h_k(d)/(k+2)! with
  // d = (a, b, c) - m and h_k the complete homogeneous symmetric polynomial (h_1(d) = 0);
  // otherwise the recursive quotient over the widest pair
  inline double exp_second_divided_difference(double a, double b, double c)
  {
    if (std::abs(a - b) > std::abs(a - c)) std::swap(b, c);
    if (std::abs(b - c) > std::abs(a - c)) std::swap(a, b);
    // now |a - c| is the widest separation
    if (std::abs(a - c) > 0.1)
      return (exp_divided_difference(a, b) - exp_divided_difference(b, c)) / (a - c);
    const double m = (a + b + c) / 3.0;
    const double d[3] = {a - m, b - m, c - m};
    // h_k(d0, d1, d2) = sum_l d2^l h_{k-l}(d0, d1), h_k(d0, d1) = sum_i d0^i d1^(k-i)
    constexpr int order = 12;
    double h2[order + 1];    // h_k(d0, d1)
    for (int k = 0; k <= order; ++k) {
      double sum = 0.0, p0 = 1.0;
      for (int i = 0; i <= k; ++i, p0 *= d[0]) sum += p0 * std::pow(d[1], k - i);
      h2[k] = sum;
    }
    double total = 0.0, factorial = 2.0;
    for (int k = 0; k <= order; ++k) {
      double hk = 0.0, p2 = 1.0;
      for (int l = 0; l <= k; ++l, p2 *= d[2]) hk += p2 * h2[k - l];
      total += hk / factorial;
      factorial *= k + 3;
    }
    return std::exp(m) * total;
  }

}    // namespace detail

// exp(L dt) of an upper-triangular L, exactly: diagonal e^{a_i} (a = L_ii dt), first
// superdiagonal L_ij dt f[a_i, a_j], corner L_02 dt f[a_0, a_2] + L_01 L_12 dt^2 f[a_0, a_1, a_2]
// with the divided differences f of exp (docs/theory.md §10.2)
inline Eigen::Matrix3d step_deformation(const Eigen::Matrix3d &L, double dt)
{
  const double a = L(0, 0) * dt, b = L(1, 1) * dt, c = L(2, 2) * dt;
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
  F(0, 0) = std::exp(a), F(1, 1) = std::exp(b), F(2, 2) = std::exp(c);
  F(0, 1) = L(0, 1) * dt * detail::exp_divided_difference(a, b);
  F(1, 2) = L(1, 2) * dt * detail::exp_divided_difference(b, c);
  F(0, 2) = L(0, 2) * dt * detail::exp_divided_difference(a, c) +
      L(0, 1) * L(1, 2) * dt * dt * detail::exp_second_divided_difference(a, b, c);
  return F;
}

// h <- exp(L dt) h over one step at constant L. On an orthogonal cell with a diagonal L this is
// l_i exp(L_ii dt) exactly as cell_servo's axis update l_i exp(-eps_dot_i dt)
inline Eigen::Matrix3d advance_cell(const Eigen::Matrix3d &h, const Eigen::Matrix3d &L, double dt)
{
  const Eigen::Matrix3d F = step_deformation(L, dt);
  Eigen::Matrix3d next = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) {
    next(i, i) = h(i, i) * F(i, i);
    for (int j = i + 1; j < 3; ++j) {
      double sum = 0.0;
      for (int k = i; k <= j; ++k) sum += F(i, k) * h(k, j);
      next(i, j) = sum;
    }
  }
  return next;
}

// LAMMPS's domain->h_rate (lx ly lz yz xz xy) of the cell h moving with L: h_dot = L h. The
// pair reads L back as h_dot h^-1 (docs/theory.md §5.1); on an orthogonal cell the diagonal is
// fix cell/servo's h_rate[k] = -eps_dot_k l_k
inline std::array<double, 6> lammps_h_rate(const Eigen::Matrix3d &L, const Eigen::Matrix3d &h)
{
  std::array<double, 6> rate;
  for (int i = 0; i < 3; ++i) rate[i] = L(i, i) * h(i, i);
  rate[3] = L(1, 1) * h(1, 2) + L(1, 2) * h(2, 2);
  rate[4] = L(0, 0) * h(0, 2) + L(0, 1) * h(1, 2) + L(0, 2) * h(2, 2);
  rate[5] = L(0, 0) * h(0, 1) + L(0, 1) * h(1, 1);
  return rate;
}

// mean-field velocity difference between a point and its periodic image shifted by the
// integer image offset n: L (h n) (docs/theory.md §10.1)
inline Eigen::Vector3d image_velocity(const Eigen::Matrix3d &L, const Eigen::Matrix3d &h,
                                      const Eigen::Vector3i &image)
{
  return L * (h * image.cast<double>());
}

// ---------------------------------------------------------------------------------------------
// Tilt flips (docs/theory.md §10.3), as LAMMPS's fix deform with 'flip yes': a tilt beyond half
// its box length is replaced by an equivalent one. With m = xy, n = xz, p = yz flip counts the
// edges become a' = a, b' = b + m a, c' = c + p b + n a, i.e. h' = h M with the unimodular
// M = [[1, m, n], [0, 1, p], [0, 0, 1]]; the image offsets of the atoms change to M^-1 image
// (LAMMPS's Domain::image_flip) so that every unwrapped position h image + x is unchanged.

struct TiltFlip {
  int xy = 0, xz = 0, yz = 0;    // LAMMPS's flipxy, flipxz, flipyz

  bool any() const { return xy != 0 || xz != 0 || yz != 0; }
  Eigen::Matrix3i matrix() const
  {
    Eigen::Matrix3i M;
    // clang-format off
    M << 1, xy, xz,
         0, 1, yz,
         0, 0, 1;
    // clang-format on
    return M;
  }
};

// the flip LAMMPS's fix deform makes of h: yz against ly first (shifting xz by the old xy),
// then xz and xy against lx; a tilt exactly at half its length stays
inline TiltFlip tilt_flip_of(const Eigen::Matrix3d &h)
{
  TiltFlip f;
  const double lx = h(0, 0), ly = h(1, 1);
  double xz = h(0, 2);
  const double xy = h(0, 1), yz = h(1, 2);
  if (yz < -0.5 * ly)
    f.yz = 1, xz += xy;
  else if (yz > 0.5 * ly)
    f.yz = -1, xz -= xy;
  if (xz < -0.5 * lx)
    f.xz = 1;
  else if (xz > 0.5 * lx)
    f.xz = -1;
  if (xy < -0.5 * lx)
    f.xy = 1;
  else if (xy > 0.5 * lx)
    f.xy = -1;
  return f;
}

inline Eigen::Matrix3d flipped_cell(const Eigen::Matrix3d &h, const TiltFlip &f)
{
  Eigen::Matrix3d next = h;
  next(1, 2) += f.yz * h(1, 1);
  next(0, 2) += f.yz * h(0, 1) + f.xz * h(0, 0);
  next(0, 1) += f.xy * h(0, 0);
  return next;
}

// image offsets after the flip: c' = c, b' = b - p c, a' = a - m b' - n c
inline Eigen::Vector3i flipped_image(const Eigen::Vector3i &image, const TiltFlip &f)
{
  Eigen::Vector3i next = image;
  next(1) -= f.yz * image(2);
  next(0) -= f.xy * next(1) + f.xz * image(2);
  return next;
}

// ---------------------------------------------------------------------------------------------
// Cumulative strain (docs/theory.md §10.4): the axial natural strains from the edge lengths as
// today (eps_i = -ln(l_i/l_i0); an upper-triangular L changes l_i by exp(L_ii dt) whatever the
// tilts, and a flip leaves l_i alone), and the engineering shears gamma_ij = int L_ij dt
// accumulated step by step, since a flip changes the tilt but not the strain

struct CumulativeStrain {
  Eigen::Vector3d reference_length = Eigen::Vector3d::Ones();    // l_i0
  Eigen::Vector3d shear = Eigen::Vector3d::Zero();               // gamma_xy, gamma_xz, gamma_yz

  static constexpr int size = 6;
  void to_array(double *a) const
  {
    for (int i = 0; i < 3; ++i) a[i] = reference_length(i), a[3 + i] = shear(i);
  }
  static CumulativeStrain from_array(const double *a)
  {
    CumulativeStrain c;
    for (int i = 0; i < 3; ++i) c.reference_length(i) = a[i], c.shear(i) = a[3 + i];
    return c;
  }

  // the step of L over dt; the trapezoidal and exact integrals agree since L is constant
  void advance(const Eigen::Matrix3d &L, double dt)
  {
    shear(0) += L(0, 1) * dt;
    shear(1) += L(0, 2) * dt;
    shear(2) += L(1, 2) * dt;
  }

  Eigen::Vector3d axial(const Eigen::Matrix3d &h) const
  {
    Eigen::Vector3d eps;
    for (int i = 0; i < 3; ++i) eps(i) = -std::log(h(i, i) / reference_length(i));
    return eps;
  }

  // compression-positive Voigt6 strain: axial natural strains, shears -gamma (engineering)
  Vector6d voigt(const Eigen::Matrix3d &h) const
  {
    Vector6d e;
    e.head<3>() = axial(h);
    e.tail<3>() = -shear;
    return e;
  }
};

// ---------------------------------------------------------------------------------------------
// Principal values and directions (docs/theory.md §10.5)

struct PrincipalAxes {
  Eigen::Vector3d values;        // descending: major, intermediate, minor
  Eigen::Matrix3d directions;    // column k: unit vector of values(k), sign fixed by a
                                 // non-negative largest component
};

inline PrincipalAxes principal_axes(const Eigen::Matrix3d &symmetric)
{
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(symmetric);
  PrincipalAxes axes;
  for (int k = 0; k < 3; ++k) {
    axes.values(k) = solver.eigenvalues()(2 - k);
    Eigen::Vector3d v = solver.eigenvectors().col(2 - k);
    Eigen::Index largest;
    v.cwiseAbs().maxCoeff(&largest);
    if (v(largest) < 0.0) v = -v;
    axes.directions.col(k) = v;
  }
  return axes;
}

// an angle of a direction (an axis: theta and theta + 180 degrees are the same) in (-90, 90]
inline double axis_angle_deg(double angle_deg)
{
  double a = std::fmod(angle_deg, 180.0);
  if (a <= -90.0) a += 180.0;
  if (a > 90.0) a -= 180.0;
  return a;
}

// angle from axis i towards axis j of the projection of direction v onto the (i, j) plane
inline double direction_angle_deg(const Eigen::Vector3d &v, int i, int j)
{
  return axis_angle_deg(std::atan2(v(j), v(i)) / piplane::degree);
}

// angle from axis i towards axis j of the major principal direction of the in-plane part
// [[s_ii, s_ij], [s_ij, s_jj]]: tan 2 theta = 2 s_ij/(s_ii - s_jj)
inline double major_angle_in_plane_deg(const Eigen::Matrix3d &symmetric, int i, int j)
{
  const double theta = 0.5 * std::atan2(2.0 * symmetric(i, j), symmetric(i, i) - symmetric(j, j));
  return axis_angle_deg(theta / piplane::degree);
}

// non-coaxiality in the (i, j) plane: the angle from the major principal direction of the
// strain rate to that of the stress, in (-90, 90] (both compression positive)
inline double non_coaxiality_deg(const Eigen::Matrix3d &stress, const Eigen::Matrix3d &strain_rate,
                                 int i, int j)
{
  return axis_angle_deg(major_angle_in_plane_deg(stress, i, j) -
                        major_angle_in_plane_deg(strain_rate, i, j));
}

}    // namespace tycore

#endif
