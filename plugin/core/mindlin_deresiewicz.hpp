// Thornton's tangential law with adhesion, one contact, one step (docs/theory.md §2):
//   stage A  Savkoor-Briggs peeling: k_T = 8G* a_peel, no micro-slip        (Thornton 1991)
//   stage B  Mindlin-Deresiewicz micro-slip, theta factor for loading, unloading, reloading
//            under varying normal force, with P replaced by P + 2Pc     (Thornton & Randall 1988)
//   stage C  gross sliding at |T| = mu (P + 2Pc)
// With Gamma = 0 (Pc = 0, no peeling) this is exactly Hertz-Mindlin-Deresiewicz.
// The theta bookkeeping is scalar along the loading direction load_dir; the increment normal to it
// meets the no-slip stiffness 8G*a and the Coulomb cap (docs/theory.md §2.3; Thornton & Yin 1991).
#ifndef TYCORE_MINDLIN_DERESIEWICZ_HPP
#define TYCORE_MINDLIN_DERESIEWICZ_HPP

#include "contact_types.hpp"
#include "jkr.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tycore {

// coefficient of T^2 in the Savkoor-Briggs discriminant, E*/(4G*), from Thornton (1991)
// and not re-derived (docs/theory.md §2.2)
inline constexpr double savkoor_briggs_shear_factor = 0.25;

// a_T^3 = 3R*(P + 2Pc)/(4E*): Hertz radius of the effective load (docs/theory.md §2.2)
inline double micro_slip_radius(double R, double E, double effective_load)
{
  return jkr::fast_cbrt(3.0 * R * std::max(effective_load, 0.0) / (4.0 * E));
}

// 4 P Pc + 4 Pc^2 - T^2 E*/(4G*); peeling ends where it vanishes      (docs/theory.md §2.2)
inline double peeling_discriminant(const PairCoefficients& c, double P, double Pc, double T2)
{
  return 4.0 * P * Pc + 4.0 * Pc * Pc - savkoor_briggs_shear_factor * T2 * c.E_star / c.G_star;
}

// 4E*a^3/(3R*) = P + 2Pc + sqrt(discriminant)                         (docs/theory.md §2.2)
inline double peeled_radius(const PairCoefficients& c, double R, double P, double Pc,
                            double discriminant)
{
  return jkr::fast_cbrt(3.0 * R * (P + 2.0 * Pc + std::sqrt(std::max(discriminant, 0.0))) /
                        (4.0 * c.E_star));
}

// T_c = 4 sqrt(Pc (P + Pc) G*/E*): tangential force where peeling ends (docs/theory.md §2.2)
inline double peeling_end_force(const PairCoefficients& c, double P, double Pc)
{
  return std::sqrt(std::max(4.0 * P * Pc + 4.0 * Pc * Pc, 0.0) * c.G_star /
                   (savkoor_briggs_shear_factor * c.E_star));
}

// the pull-off force of the pair, zero in the non-adhesive specialisation
template <bool Adhesive> inline double effective_pull_off(const PairCoefficients& c, double R)
{
  return Adhesive ? jkr::pull_off_force(c.Gamma, R) : 0.0;
}

// Stored tangential energy (docs/theory.md §2.4). Thornton's incremental law is hypo-elastic
// (k_T = 8G* a depends on P, and on T while peeling), so |T|^2/(2 k_T) is not a potential: on a
// no-slip proportional path it misses 1/6 of the work, and it ignores the stiffer peeled radius.
// The energy is therefore carried in the history as (tangential work) - (frictional
// dissipation), with the dissipation computed where slip happens (see tangential_step).
inline double tangential_energy(const ContactHistory& h)
{
  return h.stored_energy;
}

// a new contact (JKR snap-on or Hertz touch): no tangential force, peeling if adhesive
inline void begin_contact(ContactHistory& h, double P_now, bool adhesive)
{
  h = ContactHistory{};
  h.P_prev = P_now;
  h.mode = LOADING;
  h.peeling = adhesive ? 1.0 : 0.0;
}

namespace detail {

inline double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// cos and sin of a per-step twist: below 1e-3 rad the Taylor polynomials, whose remainders
// t^6/720 and t^7/5040 are < 1.5e-21, replace the libm calls exactly to round-off
inline void twist_cos_sin(double twist, double& c, double& s)
{
  if (std::abs(twist) < 1e-3) {
    const double t2 = twist * twist;
    c = 1.0 - t2 * (0.5 - t2 * (1.0 / 24.0));
    s = twist * (1.0 - t2 * (1.0 / 6.0 - t2 * (1.0 / 120.0)));
  } else {
    c = std::cos(twist);
    s = std::sin(twist);
  }
}

// x -> cos(t) x + sin(t) n x x: rotation about the contact normal
inline void twist_vector(double* x, const double* n, double c, double s)
{
  const double x0 = x[0], x1 = x[1], x2 = x[2];
  x[0] = c * x0 + s * (n[1] * x2 - n[2] * x1);
  x[1] = c * x1 + s * (n[2] * x0 - n[0] * x2);
  x[2] = c * x2 + s * (n[0] * x1 - n[1] * x0);
}

// x onto the tangent plane of the unit normal n, its magnitude kept (zero stays zero, a vector
// along n becomes zero)
inline void project_keep_magnitude(double* x, const double* n)
{
  const double magnitude2 = dot(x, x);
  if (magnitude2 == 0.0) return;
  const double along = dot(x, n);
  x[0] -= along * n[0];
  x[1] -= along * n[1];
  x[2] -= along * n[2];
  const double in_plane2 = dot(x, x);
  if (in_plane2 == 0.0) {
    x[0] = x[1] = x[2] = 0.0;
    return;
  }
  const double scale = std::sqrt(magnitude2 / in_plane2);
  x[0] *= scale;
  x[1] *= scale;
  x[2] *= scale;
}

}    // namespace detail

// carry the stored vectors with the contact: onto the new tangent plane (magnitude kept), then
// about the normal by the mean spin of the two spheres, twist = (w_i + w_j).n dt / 2
inline void rotate_history(ContactHistory& h, const Eigen::Vector3d& n, double twist)
{
  double c = 1.0, s = 0.0;
  if (twist != 0.0) detail::twist_cos_sin(twist, c, s);
  for (double* v : {h.T, h.load_dir}) {
    detail::project_keep_magnitude(v, n.data());
    if (twist != 0.0) detail::twist_vector(v, n.data(), c, s);
  }
}

namespace detail {

// relative tolerance (a few ulps) for "|T| is at the sliding limit"
inline constexpr double limit_tolerance = 4.0 * std::numeric_limits<double>::epsilon();

// theta^3 of Thornton & Randall (1988) with P -> P + 2Pc, clamped to [0, 1] (docs/theory.md §2.1)
inline double theta_cubed(int mode, double T_along, const ContactHistory& h, double mu,
                          double effective_load, double dP)
{
  const double limit = mu * effective_load;
  double t3;
  switch (mode) {
    case UNLOADING: t3 = 1.0 - (h.T_star - T_along + 2.0 * mu * dP) / (2.0 * limit); break;
    case RELOADING: t3 = 1.0 - (T_along - h.T_star2 + 2.0 * mu * dP) / (2.0 * limit); break;
    default: t3 = 1.0 - (T_along + mu * dP) / limit;
  }
  return std::clamp(t3, 0.0, 1.0);
}

// Mindlin-Deresiewicz annulus dissipation per unit tangential displacement on a branch with
// stiffness factor theta at constant P: mu Peff (1 - theta)^2 (1 + theta/2). It is the Masing /
// Iwan-consistent rate (virgin curve f: f - x f'; Masing branch g = 2f(u/2): (g - u g')/2, both
// equal to the expression above), zero without micro-slip, mu Peff at gross sliding, >= 0, and
// it reproduces the Mindlin-Deresiewicz loop loss and the stored energy 1.2 (mu P)^2/(2 k_T) of
// the fully mobilised (Hertzian-traction) contact (docs/theory.md §2.4).
inline double annulus_dissipation_rate(double limit, double theta)
{
  return limit * (1.0 - theta) * (1.0 - theta) * (1.0 + 0.5 * theta);
}

// One micro-slip step (docs/theory.md §2.1/§2.3 with P -> Peff = P + 2Pc); returns the annulus
// dissipation. Vector form (Thornton & Yin 1991 generalised as in docs/theory.md §2.3):
//  * component s = ds.t of the increment along the loading direction t: scalar MD law
//      dT_par = 8G*a theta s + (-1)^k mu dP (1 - theta)
//  * component ds_perp normal to t: 8G*a ds_perp. Annulus tractions sit on the friction circle
//    |q| = mu p, and a perpendicular increment only turns them (|q| changes to second order), so
//    it meets the no-slip stiffness; slip in that direction comes from the Coulomb cap in
//    tangential_step (return to the circle |T| = mu Peff).
//  * branch choice without a jump: forward slip (k = 0, 2) iff 8G*a s > mu dP, reverse slip
//    (k = 1) iff 8G*a s < -mu dP, otherwise elastic (theta = 1; Thornton's "|dT| < mu dP" rule).
//    At the two thresholds the slip formula equals the elastic increment for every theta, so dT
//    is continuous in ds and dP (a reversal only moves T*/T** memory, not the force).
//  * at the sliding limit (previous step slid, loading branch) theta = 0 exactly instead of
//    cbrt of a round-off-sized theta^3.
//  stiffness = 8G* a_T(effective_load), computed once by the caller.
inline double micro_slip_step(const PairCoefficients& c, double stiffness, double effective_load,
                              double dP, const Eigen::Vector3d& ds, ContactHistory& h,
                              bool at_limit)
{
  Eigen::Map<Eigen::Vector3d> T(h.T), dir(h.load_dir);
  if (dir.squaredNorm() == 0.0) {
    if (T.squaredNorm() > 0.0) dir = T.normalized();
    else if (ds.squaredNorm() > 0.0) dir = ds.normalized();
    else return 0.0;
    h.mode = LOADING;
    at_limit = false;
  }
  const double limit = c.mu * effective_load;
  const double s = ds.dot(dir);
  const Eigen::Vector3d ds_perp = ds - s * dir;
  const double ks = stiffness * s, mu_dP = c.mu * dP;
  const double T_along = T.dot(dir);
  int mode = static_cast<int>(h.mode);
  bool slipping = false;
  if (mode != UNLOADING) {    // forward branch: loading or reloading
    if (ks > mu_dP) slipping = true;
    else if (ks < -mu_dP) {
      mode = UNLOADING;
      h.T_star = T_along;
      slipping = true;
    }
  } else {
    if (ks < -mu_dP) slipping = true;
    else if (ks > mu_dP) {
      mode = RELOADING;
      h.T_star2 = T_along;
      slipping = true;
    }
  }
  h.T_star += mu_dP;    // reversal points follow the normal load          (docs/theory.md §2.1)
  h.T_star2 -= mu_dP;

  double dT_par = ks, dissipation = 0.0;
  if (slipping) {
    const double t3 = (mode == LOADING && at_limit)
                          ? 0.0
                          : theta_cubed(mode, T_along, h, c.mu, effective_load, dP);
    const double theta = jkr::fast_cbrt(t3);
    const double sign = (mode == UNLOADING) ? -1.0 : 1.0;
    dT_par = theta * ks + sign * mu_dP * (1.0 - theta);
    dissipation = annulus_dissipation_rate(limit, theta) * std::abs(s);
  }
  T += dT_par * dir + stiffness * ds_perp;

  const double T_after = T.dot(dir);
  if (mode == UNLOADING && T_after <= -h.T_star) {    // back on the virgin curve, reversed
    mode = LOADING;
    dir = -dir;
  } else if (mode == RELOADING && T_after >= h.T_star) {
    mode = LOADING;
  }
  if (mode == LOADING && T.squaredNorm() > 0.0) dir = T.normalized();
  h.mode = mode;
  return dissipation;
}

// Coulomb cap |T| <= limit (docs/theory.md §2.3): returns the dissipation limit x slip, the
// slip being the removed force / k. Within a few ulps of the limit T is kept as is (no work).
inline bool cap_at_limit(Eigen::Map<Eigen::Vector3d>& T, double limit, double stiffness,
                         double& dissipation)
{
  const double magnitude = T.norm();
  if (magnitude < limit * (1.0 - limit_tolerance)) return false;
  if (magnitude > limit * (1.0 + limit_tolerance)) {
    dissipation += limit * (magnitude - limit) / stiffness;
    T *= limit / magnitude;
  }
  return true;
}

}    // namespace detail

// One step of the tangential law at the current normal force P for the tangential displacement
// increment ds of j relative to i at the contact. Updates h (T, memory, P_prev, stored energy);
// adds the energy dissipated by friction this step. Energy definition (documented choice):
//   dissipation = annulus micro-slip loss (detail::annulus_dissipation_rate x |ds along t|)
//               + gross sliding loss (mu Peff x slip at the Coulomb cap), never negative;
//   stored energy += tangential work 0.5 (T_old + T_new).ds - dissipation.
// Elastic steps (theta = 1, peeling below T_c) therefore dissipate exactly nothing.
// hertz_radius: the contact radius a(delta), if the caller has it (< 0: not given). Without
// adhesion (Pc = 0) it is the micro-slip radius (a_T^3 = 3R*P/(4E*) = a^3, docs/theory.md
// §1.6), so the cube root is skipped; the two differ by round-off only.
template <bool Adhesive>
inline void tangential_step(const PairCoefficients& c, double R, double P, const Eigen::Vector3d& ds,
                            ContactHistory& h, double& dissipation, double hertz_radius = -1.0)
{
  Eigen::Map<Eigen::Vector3d> T(h.T);
  const Eigen::Vector3d T_old = T;
  const double Pc = effective_pull_off<Adhesive>(c, R);
  const double effective_load = P + 2.0 * Pc;
  const double dP = P - h.P_prev;
  const double sliding_limit = c.mu * std::max(effective_load, 0.0);
  const bool was_sliding = h.sliding != 0.0;
  h.sliding = 0.0;
  double lost = 0.0;

  if (sliding_limit <= 0.0) {    // frictionless, or a Hertz contact at zero load
    T.setZero();
    Eigen::Map<Eigen::Vector3d>(h.load_dir).setZero();
    h.mode = LOADING;
    h.T_star = h.T_star2 = 0.0;
    h.sliding = 1.0;
    h.peeling = 0.0;
    h.P_prev = P;
    const double released = h.stored_energy + 0.5 * T_old.dot(ds);    // stored energy is lost
    h.stored_energy = 0.0;
    dissipation += std::max(released, 0.0);
    return;
  }

  double stiffness = 0.0;    // k_T of this step: peeled or micro-slip radius
  bool peeled_step = false;
  if (Adhesive && h.peeling != 0.0) {    // stage A: Savkoor-Briggs peeling, elastic
    const double before = peeling_discriminant(c, P, Pc, T.squaredNorm());
    if (before > 0.0) {
      stiffness = 8.0 * c.G_star * peeled_radius(c, R, P, Pc, before);
      T += stiffness * ds;
      peeled_step = true;
      if (peeling_discriminant(c, P, Pc, T.squaredNorm()) <= 0.0) h.peeling = 0.0;
    } else {
      h.peeling = 0.0;
    }
  }
  if (!peeled_step) {    // stage B: micro-slip (with Pc = 0 exactly Hertz-Mindlin-Deresiewicz)
    stiffness = 8.0 * c.G_star *
        ((Pc == 0.0 && hertz_radius >= 0.0) ? hertz_radius
                                             : micro_slip_radius(R, c.E_star, effective_load));
    lost += detail::micro_slip_step(c, stiffness, effective_load, dP, ds, h,
                                    was_sliding && h.mode == LOADING);
  }
  if (detail::cap_at_limit(T, sliding_limit, stiffness, lost)) {    // stage C: gross sliding
    Eigen::Map<Eigen::Vector3d>(h.load_dir) = T.normalized();
    h.mode = LOADING;
    h.T_star = h.T_star2 = 0.0;
    h.sliding = 1.0;
    h.peeling = 0.0;
  }
  h.P_prev = P;
  // energy balance: work = dissipation + change of stored energy, dissipation >= 0. With P
  // varying, the hypo-elastic law (T kept while k_T(P) changes) is not conservative and can give
  // back more work than was put in; the stored energy is then held at 0 (that excess, small in
  // practice, is the only part of the tangential work left out of the balance).
  const double available = h.stored_energy + 0.5 * (T_old + T).dot(ds);
  lost = std::clamp(lost, 0.0, std::max(available, 0.0));
  h.stored_energy = std::max(available - lost, 0.0);
  dissipation += lost;
}

}    // namespace tycore

#endif
