// The Thornton-Yin contact law fused into one scalar routine for the pair style's hot loop:
// rotate_history + evaluate_contact (thornton_yin.hpp) in a single pass over one contact.
// Same law, same history layout, same branch decisions; what differs is only the arithmetic:
//  * plain doubles instead of Eigen 3-vectors (callgrind: Eigen's SSE2 packets, shuffles and
//    cross products were 14 % of the pair's instructions on 3-vectors),
//  * one |T| per step shared by the loading direction and the Coulomb cap, and on the loading
//    branch (load_dir = T/|T|) one projection of T onto the new tangent plane for both vectors,
//  * per-material-pair constants (PairConstants) computed once, the JKR force from u = sqrt(a)
//    of the warm-started Newton without another square root, no libm cube root at theta = 0.
// tests/core/test_contact_kernel.cpp runs both on long random contact paths (peeling,
// micro-slip reversals, sliding, tension, separation) and asserts agreement to round-off.
#ifndef TYCORE_CONTACT_KERNEL_HPP
#define TYCORE_CONTACT_KERNEL_HPP

#include "contact_types.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"

#include <algorithm>
#include <cmath>

namespace tycore {

// per material pair, derived once from PairCoefficients
struct PairConstants {
  PairCoefficients c;
  double newton_c;          // 2 sqrt(pi Gamma/E*): delta = u^4/R* - newton_c u, u = sqrt(a)  (§1.4b)
  double adhesive_force;    // 4 sqrt(pi Gamma E*): P = 4E*a^3/(3R*) - adhesive_force a^(3/2)  (§1.1)
  double peel_shear;        // E*/(4 G*): coefficient of T^2 in the Savkoor-Briggs discriminant (§2.2)
  double cube_radius_per_load;    // 3/(4E*): a^3 = 3R*P/(4E*) for a Hertz load P     (§2.2)
};

inline PairConstants pair_constants(const PairCoefficients& c)
{
  PairConstants k;
  k.c = c;
  k.newton_c = 2.0 * std::sqrt(jkr::pi * c.Gamma / c.E_star);
  k.adhesive_force = 4.0 * std::sqrt(jkr::pi * c.Gamma * c.E_star);
  k.peel_shear = savkoor_briggs_shear_factor * c.E_star / c.G_star;
  k.cube_radius_per_load = 3.0 / (4.0 * c.E_star);
  return k;
}

struct KernelResult {
  double P;                 // normal force, positive repulsive
  double contact_radius;    // JKR radius a(delta)
};

namespace kernel_detail {

inline double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// x -> cos(t) x + sin(t) n x x (rotate_history's twist; the same Taylor polynomials)
inline void twist_vector(double* x, const double* n, double c, double s)
{
  const double x0 = x[0], x1 = x[1], x2 = x[2];
  x[0] = c * x0 + s * (n[1] * x2 - n[2] * x1);
  x[1] = c * x1 + s * (n[2] * x0 - n[0] * x2);
  x[2] = c * x2 + s * (n[0] * x1 - n[1] * x0);
}

// onto the tangent plane with its magnitude kept (rotate_history for one vector)
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

// theta = cbrt(theta^3), without the libm call fast_cbrt makes at 0
inline double theta_of(double theta_cubed) { return theta_cubed > 0.0 ? jkr::fast_cbrt(theta_cubed) : 0.0; }

}    // namespace kernel_detail

// One contact, one step, after a previous step or begin_contact: the stored vectors are carried
// onto the tangent plane of n and twisted by `twist` (rotate_history), then the normal force at
// overlap delta and the tangential law for the increment ds (evaluate_contact with
// RESULT_FORCES). Adds the frictional dissipation of the step to `dissipation`.
template <bool Adhesive>
inline KernelResult advance_contact(const PairConstants& k, double R, double delta,
                                    const double n[3], double twist, const double ds[3],
                                    ContactHistory& h, double& dissipation)
{
  using namespace kernel_detail;
  const PairCoefficients& c = k.c;
  double* T = h.T;
  double* dir = h.load_dir;

  // ---- history onto the new tangent plane (rotate_history) ----
  double tw_c = 1.0, tw_s = 0.0;
  if (twist != 0.0) {
    if (std::abs(twist) < 1e-3) {
      const double t2 = twist * twist;
      tw_c = 1.0 - t2 * (0.5 - t2 * (1.0 / 24.0));
      tw_s = twist * (1.0 - t2 * (1.0 / 6.0 - t2 * (1.0 / 120.0)));
    } else {
      tw_c = std::cos(twist);
      tw_s = std::sin(twist);
    }
  }
  const double T2_before = dot(T, T);
  const bool dir_follows_T = h.mode == LOADING && T2_before > 0.0 && dot(dir, dir) > 0.0;
  double T_magnitude = -1.0;    // |T| after the rotation when known, else < 0
  if (dir_follows_T) {          // load_dir = T/|T| on the loading branch: project once
    const double along = dot(T, n);
    double p[3] = {T[0] - along * n[0], T[1] - along * n[1], T[2] - along * n[2]};
    const double in_plane2 = dot(p, p);
    if (in_plane2 > 0.0) {
      const double inv = 1.0 / std::sqrt(in_plane2);
      dir[0] = p[0] * inv;
      dir[1] = p[1] * inv;
      dir[2] = p[2] * inv;
      if (twist != 0.0) twist_vector(dir, n, tw_c, tw_s);
      T_magnitude = std::sqrt(T2_before);
      T[0] = T_magnitude * dir[0];
      T[1] = T_magnitude * dir[1];
      T[2] = T_magnitude * dir[2];
    } else {
      T[0] = T[1] = T[2] = 0.0;
      dir[0] = dir[1] = dir[2] = 0.0;
    }
  } else {
    for (double* x : {T, dir}) {
      project_keep_magnitude(x, n);
      if (twist != 0.0) twist_vector(x, n, tw_c, tw_s);
    }
  }

  // ---- normal force (evaluate_contact; jkr::contact_radius_warm, jkr::normal_force) ----
  KernelResult out;
  const double Rinv = 1.0 / R;
  if (Adhesive) {
    double a = -1.0, u = 0.0;
    if (h.radius > 0.0) {    // Newton on u^4/R - c u - delta from the previous radius
      u = std::sqrt(h.radius);
      for (int it = 0; it < 8; ++it) {
        const double u2 = u * u;
        const double slope = 4.0 * u2 * u * Rinv - k.newton_c;
        if (!(slope > 0.0)) break;
        const double step = (u2 * u2 * Rinv - k.newton_c * u - delta) / slope;
        u -= step;
        if (24.0 * u2 * step * step <= 1e-14 * u * R * slope) {
          a = u * u;
          break;
        }
      }
    }
    if (a < 0.0) {
      a = jkr::contact_radius(delta, R, c.E_star, c.Gamma);
      u = std::sqrt(a);
    }
    out.contact_radius = a;
    out.P = 4.0 * c.E_star * (a * a * a) * Rinv * (1.0 / 3.0) - k.adhesive_force * (a * u);
  } else {
    const double a = std::sqrt(R * std::max(delta, 0.0));
    out.contact_radius = a;
    out.P = 4.0 * c.E_star * (a * a * a) / (3.0 * R);
  }
  h.radius = out.contact_radius;
  const double P = out.P;

  // ---- tangential law (tangential_step) ----
  const double T_old[3] = {T[0], T[1], T[2]};
  const double Pc = Adhesive ? jkr::pull_off_force(c.Gamma, R) : 0.0;
  const double effective_load = P + 2.0 * Pc;
  const double dP = P - h.P_prev;
  const double sliding_limit = c.mu * std::max(effective_load, 0.0);
  const bool was_sliding = h.sliding != 0.0;
  h.sliding = 0.0;
  double lost = 0.0;

  if (sliding_limit <= 0.0) {    // frictionless, or a Hertz contact at zero load
    T[0] = T[1] = T[2] = 0.0;
    dir[0] = dir[1] = dir[2] = 0.0;
    h.mode = LOADING;
    h.T_star = h.T_star2 = 0.0;
    h.sliding = 1.0;
    h.peeling = 0.0;
    h.P_prev = P;
    const double released = h.stored_energy + 0.5 * dot(T_old, ds);
    h.stored_energy = 0.0;
    dissipation += std::max(released, 0.0);
    return out;
  }

  double stiffness = 0.0;
  bool peeled_step = false;
  if (Adhesive && h.peeling != 0.0) {    // stage A: Savkoor-Briggs peeling      (physics.md §2.2)
    const double base = 4.0 * P * Pc + 4.0 * Pc * Pc;
    const double before = base - k.peel_shear * dot(T, T);
    if (before > 0.0) {
      stiffness = 8.0 * c.G_star *
          jkr::fast_cbrt(k.cube_radius_per_load * R * (P + 2.0 * Pc + std::sqrt(before)));
      T[0] += stiffness * ds[0];
      T[1] += stiffness * ds[1];
      T[2] += stiffness * ds[2];
      peeled_step = true;
      T_magnitude = -1.0;
      if (base - k.peel_shear * dot(T, T) <= 0.0) h.peeling = 0.0;
    } else {
      h.peeling = 0.0;
    }
  }

  if (!peeled_step) {    // stage B: micro-slip (micro_slip_step)
    stiffness = 8.0 * c.G_star *
        (Adhesive ? jkr::fast_cbrt(k.cube_radius_per_load * R * std::max(effective_load, 0.0))
                  : out.contact_radius);
    bool at_limit = was_sliding && h.mode == LOADING;
    bool active = true;
    if (dot(dir, dir) == 0.0) {
      const double T2 = dot(T, T);
      if (T2 > 0.0) {
        const double inv = 1.0 / std::sqrt(T2);
        dir[0] = T[0] * inv, dir[1] = T[1] * inv, dir[2] = T[2] * inv;
      } else {
        const double s2 = dot(ds, ds);
        if (s2 > 0.0) {
          const double inv = 1.0 / std::sqrt(s2);
          dir[0] = ds[0] * inv, dir[1] = ds[1] * inv, dir[2] = ds[2] * inv;
        } else {
          active = false;
        }
      }
      if (active) {
        h.mode = LOADING;
        at_limit = false;
      }
    }
    if (active) {
      const double limit = c.mu * effective_load;
      const double s = dot(ds, dir);
      const double ks = stiffness * s, mu_dP = c.mu * dP;
      const double T_along = T_magnitude >= 0.0 ? T_magnitude : dot(T, dir);
      int mode = static_cast<int>(h.mode);
      bool slipping = false;
      if (mode != UNLOADING) {
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
      h.T_star += mu_dP;    // reversal points follow the normal load              (physics.md §2.1)
      h.T_star2 -= mu_dP;

      double dT_par = ks;
      if (slipping) {
        double t3 = 0.0;    // theta^3 of Thornton & Randall (1988), P -> P + 2Pc  (physics.md §2.1)
        if (!(mode == LOADING && at_limit)) {
          switch (mode) {
            case UNLOADING: t3 = 1.0 - (h.T_star - T_along + 2.0 * mu_dP) / (2.0 * limit); break;
            case RELOADING: t3 = 1.0 - (T_along - h.T_star2 + 2.0 * mu_dP) / (2.0 * limit); break;
            default: t3 = 1.0 - (T_along + mu_dP) / limit;
          }
          t3 = std::clamp(t3, 0.0, 1.0);
        }
        const double theta = theta_of(t3);
        const double sign = (mode == UNLOADING) ? -1.0 : 1.0;
        dT_par = theta * ks + sign * mu_dP * (1.0 - theta);
        lost += detail::annulus_dissipation_rate(limit, theta) * std::abs(s);
      }
      // T += dT_par dir + k (ds - s dir)
      const double along = dT_par - stiffness * s;
      T[0] += along * dir[0] + stiffness * ds[0];
      T[1] += along * dir[1] + stiffness * ds[1];
      T[2] += along * dir[2] + stiffness * ds[2];

      if (mode == UNLOADING || mode == RELOADING) {
        const double T_after = dot(T, dir);
        if (mode == UNLOADING && T_after <= -h.T_star) {    // back on the virgin curve, reversed
          mode = LOADING;
          dir[0] = -dir[0], dir[1] = -dir[1], dir[2] = -dir[2];
        } else if (mode == RELOADING && T_after >= h.T_star) {
          mode = LOADING;
        }
      }
      h.mode = mode;
    }
  }

  // one |T| for the loading direction and the Coulomb cap (stage C)
  const double T2 = dot(T, T);
  const double magnitude = std::sqrt(T2);
  const bool loading_dir = !peeled_step && h.mode == LOADING && T2 > 0.0;
  const bool capped = magnitude >= sliding_limit * (1.0 - detail::limit_tolerance);
  if (loading_dir || capped) {
    const double inv = 1.0 / magnitude;
    if (loading_dir || magnitude > 0.0) {
      dir[0] = T[0] * inv, dir[1] = T[1] * inv, dir[2] = T[2] * inv;
    }
  }
  if (capped) {    // gross sliding at |T| = mu (P + 2Pc)
    if (magnitude > sliding_limit * (1.0 + detail::limit_tolerance)) {
      lost += sliding_limit * (magnitude - sliding_limit) / stiffness;
      const double scale = sliding_limit / magnitude;
      T[0] *= scale, T[1] *= scale, T[2] *= scale;
    }
    h.mode = LOADING;
    h.T_star = h.T_star2 = 0.0;
    h.sliding = 1.0;
    h.peeling = 0.0;
  }
  h.P_prev = P;
  const double available =
      h.stored_energy + 0.5 * ((T_old[0] + T[0]) * ds[0] + (T_old[1] + T[1]) * ds[1] +
                               (T_old[2] + T[2]) * ds[2]);
  lost = std::clamp(lost, 0.0, std::max(available, 0.0));
  h.stored_energy = std::max(available - lost, 0.0);
  dissipation += lost;
  return out;
}

}    // namespace tycore

#endif
