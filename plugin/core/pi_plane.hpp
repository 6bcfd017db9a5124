// Principal-space invariants and the Pi-plane (docs/theory.md §7).
//
// Conventions: a principal triple v = (v1, v2, v3) holds values along the box axes x, y, z,
// compression positive (stresses and natural strains alike). Functions that need the order
// of magnitude (b, sin(phi)) sort internally; the Pi-plane coordinates keep the axis labels,
// so that paths through all six sectors plot without folding.
//
// Pi-plane (plane normal to (1,1,1), axis 1 drawn upwards), docs/theory.md §7.2:
//   y = (2 v1 - v2 - v3)/sqrt(6),   x = (v2 - v3)/sqrt(2),
// i.e. the deviator is s = x e_x + y e_y with orthonormal e_x = (0,1,-1)/sqrt(2),
// e_y = (2,-1,-1)/sqrt(6), and the Pi radius sqrt(x^2 + y^2) = |s| (Frobenius norm).
// The Lode angle theta is measured from the axis-1 direction towards +x (axis 2 projects to
// the lower right, axis 3 to the lower left): 0 deg = axisymmetric compression along 1,
// 60 deg = axisymmetric extension along 3 (v1 = v2), 120 deg = compression along 2, ...
// Increasing theta runs clockwise on that drawing.
#ifndef TYCORE_PI_PLANE_HPP
#define TYCORE_PI_PLANE_HPP

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tycore {

namespace piplane {
  inline constexpr double sqrt2 = 1.4142135623730950488;
  inline constexpr double sqrt6 = 2.4494897427831780982;
  inline constexpr double degree = 3.14159265358979323846 / 180.0;    // rad per degree
}    // namespace piplane

// ---------------------------------------------------------------------------------------------
// Stress invariants

struct PrincipalInvariants {
  double I1, I2, I3;
};

inline PrincipalInvariants principal_invariants(const Eigen::Vector3d &sigma)
{
  return {sigma.sum(), sigma(0) * sigma(1) + sigma(1) * sigma(2) + sigma(2) * sigma(0),
          sigma.prod()};
}

// p = I1/3
inline double mean_stress(const Eigen::Vector3d &sigma)
{
  return sigma.sum() / 3.0;
}

inline Eigen::Vector3d deviator(const Eigen::Vector3d &v)
{
  return v - Eigen::Vector3d::Constant(v.mean());
}

// q = sqrt(3 J2) = sqrt(((s1-s2)^2 + (s2-s3)^2 + (s3-s1)^2)/2)
inline double deviatoric_stress(const Eigen::Vector3d &sigma)
{
  return std::sqrt(1.5) * deviator(sigma).norm();
}

inline Eigen::Vector3d sorted_descending(Eigen::Vector3d v)
{
  std::sort(v.data(), v.data() + 3, [](double a, double b) {
    return a > b;
  });
  return v;
}

// b = (s2 - s3)/(s1 - s3) of the sorted values (paper eq. 1); NaN for an isotropic state
inline double b_value(const Eigen::Vector3d &sigma)
{
  const Eigen::Vector3d s = sorted_descending(sigma);
  const double span = s(0) - s(2);
  if (span == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return (s(1) - s(2)) / span;
}

// mobilised friction sin(phi) = (s_max - s_min)/(s_max + s_min)   (paper section 3)
inline double mobilised_sinphi(const Eigen::Vector3d &sigma)
{
  const double s_max = sigma.maxCoeff(), s_min = sigma.minCoeff();
  return (s_max - s_min) / (s_max + s_min);
}

// Lade-Duncan eta = I1^3/I3 - 27   (paper eq. 2)
inline double lade_duncan_eta(const Eigen::Vector3d &sigma)
{
  const PrincipalInvariants inv = principal_invariants(sigma);
  return inv.I1 * inv.I1 * inv.I1 / inv.I3 - 27.0;
}

// Matsuoka-Nakai I1 I2 / I3   (docs/theory.md §7.3)
inline double matsuoka_nakai_ratio(const Eigen::Vector3d &sigma)
{
  const PrincipalInvariants inv = principal_invariants(sigma);
  return inv.I1 * inv.I2 / inv.I3;
}

// ---------------------------------------------------------------------------------------------
// Pi-plane coordinates (docs/theory.md §7.2); the same map serves stresses and strains

inline Eigen::Vector3d pi_unit_x()
{
  return Eigen::Vector3d(0, 1, -1) / piplane::sqrt2;
}
inline Eigen::Vector3d pi_unit_y()
{
  return Eigen::Vector3d(2, -1, -1) / piplane::sqrt6;
}

// (x, y) = ((v2 - v3)/sqrt 2, (2 v1 - v2 - v3)/sqrt 6)
inline Eigen::Vector2d pi_coordinates(const Eigen::Vector3d &v)
{
  return {(v(1) - v(2)) / piplane::sqrt2, (2.0 * v(0) - v(1) - v(2)) / piplane::sqrt6};
}

// traceless principal triple with Pi coordinates xy: s = x e_x + y e_y
inline Eigen::Vector3d deviator_from_pi(const Eigen::Vector2d &xy)
{
  return xy.x() * pi_unit_x() + xy.y() * pi_unit_y();
}

// inverse of pi_coordinates given the mean value (p for stresses, eps_v/3 for strains)
inline Eigen::Vector3d principal_from_pi(const Eigen::Vector2d &xy, double mean)
{
  return Eigen::Vector3d::Constant(mean) + deviator_from_pi(xy);
}

// Lode angle from the axis-1 direction, tan(theta) = x/y, in [0, 360) degrees
// (docs/theory.md §7.2); NaN at the origin, where it is undefined
inline double lode_angle_deg(const Eigen::Vector2d &xy)
{
  if (xy.x() == 0.0 && xy.y() == 0.0) return std::numeric_limits<double>::quiet_NaN();
  const double theta = std::atan2(xy.x(), xy.y()) / piplane::degree;
  return theta < 0.0 ? theta + 360.0 : theta;
}

// point at Pi radius r and Lode angle theta
inline Eigen::Vector2d pi_point(double radius, double lode_deg)
{
  const double theta = lode_deg * piplane::degree;
  return {radius * std::sin(theta), radius * std::cos(theta)};
}

// ---------------------------------------------------------------------------------------------
// Strain measures (docs/theory.md §7.1), natural strains, compression positive

// eps_v = eps1 + eps2 + eps3
inline double volumetric_strain(const Eigen::Vector3d &eps)
{
  return eps.sum();
}

// eps_q = sqrt(2/3 e:e)
inline double deviatoric_strain(const Eigen::Vector3d &eps)
{
  return std::sqrt(2.0 / 3.0) * deviator(eps).norm();
}

// eps1 - eps3 by axis label (paper Fig. 1 "deviator strain")
inline double strain_difference_13(const Eigen::Vector3d &eps)
{
  return eps(0) - eps(2);
}

// ---------------------------------------------------------------------------------------------
// Failure surfaces through a given compression (b = 0) friction angle (docs/theory.md §7.3)

enum class FailureCriterion { LADE_DUNCAN, MATSUOKA_NAKAI };

inline double criterion_value(FailureCriterion criterion, const Eigen::Vector3d &sigma)
{
  return criterion == FailureCriterion::LADE_DUNCAN ? lade_duncan_eta(sigma)
                                                    : matsuoka_nakai_ratio(sigma);
}

// stress state (K, 1 + b(K - 1), 1) with K = sigma1/sigma3   (docs/theory.md §7.3)
inline Eigen::Vector3d state_at_ratio(double stress_ratio, double b)
{
  return {stress_ratio, 1.0 + b * (stress_ratio - 1.0), 1.0};
}

// K = (1 + sin phi)/(1 - sin phi)
inline double stress_ratio_from_sinphi(double sinphi)
{
  return (1.0 + sinphi) / (1.0 - sinphi);
}

// value of the criterion on the surface through (sinphi_tc, b = 0)
inline double criterion_constant(FailureCriterion criterion, double sinphi_tc)
{
  return criterion_value(criterion, state_at_ratio(stress_ratio_from_sinphi(sinphi_tc), 0.0));
}

// sin(phi) at intermediate-stress ratio b on the surface through sinphi_tc: bisection on
// K > 1, along which the criterion grows monotonically (docs/theory.md §7.3)
inline double sinphi_on_surface(FailureCriterion criterion, double sinphi_tc, double b)
{
  if (!(sinphi_tc > 0.0 && sinphi_tc < 1.0))
    throw std::invalid_argument("sinphi_tc = " + std::to_string(sinphi_tc) + " must lie in (0, 1)");
  if (!(b >= 0.0 && b <= 1.0))
    throw std::invalid_argument("b = " + std::to_string(b) + " is outside [0, 1]");
  const double target = criterion_constant(criterion, sinphi_tc);
  auto excess = [&](double K) {
    return criterion_value(criterion, state_at_ratio(K, b)) - target;
  };
  double lo = 1.0, hi = 2.0;
  while (excess(hi) < 0.0) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (excess(mid) < 0.0 ? lo : hi) = mid;
  }
  const double K = 0.5 * (lo + hi);
  return (K - 1.0) / (K + 1.0);
}

}    // namespace tycore

#endif
