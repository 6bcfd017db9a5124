// Thornton's tangential law with adhesion, one contact, one step (physics.md §2):
//   stage A  Savkoor-Briggs peeling: k_T = 8G* a_peel, no micro-slip        (Thornton 1991)
//   stage B  Mindlin-Deresiewicz micro-slip, theta factor for loading, unloading, reloading
//            under varying normal force, with P replaced by P + 2Pc     (Thornton & Randall 1988)
//   stage C  gross sliding at |T| = mu (P + 2Pc)
// With Gamma = 0 (Pc = 0, no peeling) this is exactly Hertz-Mindlin-Deresiewicz.
// The theta bookkeeping is scalar along the loading direction load_dir (physics.md §2.3 note i).
#ifndef TYCORE_MINDLIN_DERESIEWICZ_HPP
#define TYCORE_MINDLIN_DERESIEWICZ_HPP

#include "contact_types.hpp"
#include "jkr.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace tycore {

// coefficient of T^2 in the Savkoor-Briggs discriminant, E*/(4G*) [U in physics.md §2.2]
inline constexpr double savkoor_briggs_shear_factor = 0.25;

// a_T^3 = 3R*(P + 2Pc)/(4E*): Hertz radius of the effective load (physics.md §2.2 stage B)
inline double micro_slip_radius(double R, double E, double effective_load)
{
  return std::cbrt(3.0 * R * std::max(effective_load, 0.0) / (4.0 * E));
}

// 4 P Pc + 4 Pc^2 - T^2 E*/(4G*); peeling ends where it vanishes          (physics.md §2.2)
inline double peeling_discriminant(const PairCoefficients& c, double P, double Pc, double T2)
{
  return 4.0 * P * Pc + 4.0 * Pc * Pc - savkoor_briggs_shear_factor * T2 * c.E_star / c.G_star;
}

// 4E*a^3/(3R*) = P + 2Pc + sqrt(discriminant)                             (physics.md §2.2)
inline double peeled_radius(const PairCoefficients& c, double R, double P, double Pc,
                            double discriminant)
{
  return std::cbrt(3.0 * R * (P + 2.0 * Pc + std::sqrt(std::max(discriminant, 0.0))) /
                   (4.0 * c.E_star));
}

// T_c = 4 sqrt(Pc (P + Pc) G*/E*): tangential force at the end of peeling (physics.md §2.2)
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

// elastic tangential energy |T|^2/(2 k_T), k_T = 8G* a_T(P + 2Pc)
inline double tangential_energy(const PairCoefficients& c, double R, double P,
                                const ContactHistory& h)
{
  const double T2 = h.T[0] * h.T[0] + h.T[1] * h.T[1] + h.T[2] * h.T[2];
  if (T2 == 0.0) return 0.0;
  const double Pc = jkr::pull_off_force(c.Gamma, R);
  const double k_T = 8.0 * c.G_star * micro_slip_radius(R, c.E_star, P + 2.0 * Pc);
  return k_T > 0.0 ? 0.5 * T2 / k_T : 0.0;
}

// a new contact (JKR snap-on or Hertz touch): no tangential force, peeling if adhesive
inline void begin_contact(ContactHistory& h, double P_now, bool adhesive)
{
  h = ContactHistory{};
  h.P_prev = P_now;
  h.mode = LOADING;
  h.peeling = adhesive ? 1.0 : 0.0;
}

// carry the stored vectors with the contact: onto the new tangent plane (magnitude kept), then
// about the normal by the mean spin of the two spheres, twist = (w_i + w_j).n dt / 2
inline void rotate_history(ContactHistory& h, const Eigen::Vector3d& n, double twist)
{
  const double c = std::cos(twist), s = std::sin(twist);
  for (double* v : {h.T, h.load_dir}) {
    Eigen::Map<Eigen::Vector3d> x(v);
    const double magnitude = x.norm();
    if (magnitude == 0.0) continue;
    x -= x.dot(n) * n;
    const double in_plane = x.norm();
    if (in_plane == 0.0) {
      x.setZero();
      continue;
    }
    x *= magnitude / in_plane;
    if (twist != 0.0) x = (c * x + s * n.cross(x)).eval();
  }
}

namespace detail {

// theta^3 of Thornton & Randall (1988) with P -> P + 2Pc                  (physics.md §2.1)
inline double theta_cubed(int mode, double T_along, const ContactHistory& h, double mu,
                          double effective_load, double dP)
{
  const double limit = mu * effective_load;
  switch (mode) {
    case UNLOADING: return 1.0 - (h.T_star - T_along + 2.0 * mu * dP) / (2.0 * limit);
    case RELOADING: return 1.0 - (T_along - h.T_star2 + 2.0 * mu * dP) / (2.0 * limit);
    default: return 1.0 - (T_along + mu * dP) / limit;
  }
}

// dT = 8G* a theta ds + (-1)^k mu dP (1 - theta) load_dir                 (physics.md §2.1)
inline void micro_slip_step(const PairCoefficients& c, double R, double effective_load, double dP,
                            const Eigen::Vector3d& ds, ContactHistory& h)
{
  Eigen::Map<Eigen::Vector3d> T(h.T), dir(h.load_dir);
  if (dir.squaredNorm() == 0.0) {
    if (T.squaredNorm() > 0.0) dir = T.normalized();
    else if (ds.squaredNorm() > 0.0) dir = ds.normalized();
    else return;
    h.mode = LOADING;
  }
  const double stiffness = 8.0 * c.G_star * micro_slip_radius(R, c.E_star, effective_load);
  const double along = ds.dot(dir);
  int mode = static_cast<int>(h.mode);
  const double T_along = T.dot(dir);
  if (mode == LOADING && along < 0.0) {
    mode = UNLOADING;
    h.T_star = T_along;
  } else if (mode == UNLOADING && along > 0.0) {
    mode = RELOADING;
    h.T_star2 = T_along;
  } else if (mode == RELOADING && along < 0.0) {
    mode = UNLOADING;
    h.T_star = T_along;
  }
  h.T_star += c.mu * dP;    // reversal points follow the normal load      (physics.md §2.1)
  h.T_star2 -= c.mu * dP;

  const Eigen::Vector3d elastic = stiffness * ds;
  double theta = 1.0;
  if (!(dP > 0.0 && elastic.norm() < c.mu * dP))    // else no new micro-slip: theta = 1
    theta = std::cbrt(std::clamp(theta_cubed(mode, T_along, h, c.mu, effective_load, dP), 0.0, 1.0));
  const double sign = (mode == UNLOADING) ? -1.0 : 1.0;
  T += theta * elastic + sign * c.mu * dP * (1.0 - theta) * dir;

  const double T_after = T.dot(dir);
  if (mode == UNLOADING && T_after <= -h.T_star) {    // back on the virgin curve, reversed
    mode = LOADING;
    dir = -dir;
  } else if (mode == RELOADING && T_after >= h.T_star) {
    mode = LOADING;
  }
  if (mode == LOADING && T.squaredNorm() > 0.0) dir = T.normalized();
  h.mode = mode;
}

}    // namespace detail

// One step of the tangential law at the current normal force P for the tangential displacement
// increment ds of j relative to i at the contact. Updates h (T, memory, P_prev); adds the
// energy dissipated this step (tangential work minus change of tangential energy).
template <bool Adhesive>
inline void tangential_step(const PairCoefficients& c, double R, double P, const Eigen::Vector3d& ds,
                            ContactHistory& h, double& dissipation)
{
  Eigen::Map<Eigen::Vector3d> T(h.T);
  const Eigen::Vector3d T_old = T;
  const double energy_old = tangential_energy(c, R, h.P_prev, h);
  const double Pc = effective_pull_off<Adhesive>(c, R);
  const double effective_load = P + 2.0 * Pc;
  const double dP = P - h.P_prev;
  const double sliding_limit = c.mu * std::max(effective_load, 0.0);
  h.sliding = 0.0;

  if (sliding_limit <= 0.0) {    // frictionless, or a Hertz contact at zero load
    T.setZero();
    Eigen::Map<Eigen::Vector3d>(h.load_dir).setZero();
    h.mode = LOADING;
    h.sliding = 1.0;
    h.peeling = 0.0;
  } else {
    if (Adhesive && h.peeling != 0.0) {    // stage A: Savkoor-Briggs peeling
      const double before = peeling_discriminant(c, P, Pc, T.squaredNorm());
      if (before > 0.0) {
        T += 8.0 * c.G_star * peeled_radius(c, R, P, Pc, before) * ds;
        if (peeling_discriminant(c, P, Pc, T.squaredNorm()) <= 0.0) h.peeling = 0.0;
      } else {
        h.peeling = 0.0;
        detail::micro_slip_step(c, R, effective_load, dP, ds, h);
      }
    } else {                                // stage B: micro-slip
      detail::micro_slip_step(c, R, effective_load, dP, ds, h);
    }
    const double magnitude = T.norm();
    if (magnitude >= sliding_limit) {       // stage C: gross sliding, fresh reversal memory
      T *= sliding_limit / magnitude;
      Eigen::Map<Eigen::Vector3d>(h.load_dir) = T / sliding_limit;
      h.mode = LOADING;
      h.T_star = h.T_star2 = 0.0;
      h.sliding = 1.0;
      h.peeling = 0.0;
    }
  }
  h.P_prev = P;
  dissipation += 0.5 * (T_old + T).dot(ds) - (tangential_energy(c, R, P, h) - energy_old);
}

}    // namespace tycore

#endif
