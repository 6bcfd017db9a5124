// The Thornton-Yin contact law as the pair style runs it: rotate_history + evaluate_contact
// (thornton_yin.hpp, the reference) fused into scalar stages that a batch of contacts passes
// through together. Same law, same history layout, same decisions; what differs is only the
// arithmetic and its order:
//  * plain doubles instead of Eigen 3-vectors, one |T| per step shared by the loading direction
//    and the Coulomb cap, one projection of T for both vectors on the loading branch,
//    per-material-pair constants (PairConstants) computed once, no libm cube root at theta = 0,
//    the warm-started JKR radius by Halley's method (cubic: two steps, taken without a test
//    between them, where jkr::contact_radius_warm's Newton takes two or three);
//  * the Masing branch decisions as selects (detail::select), not branches: which branch a
//    contact of a vibrating packing takes is close to random from one step to the next;
//  * the step split where a cube root sits on its critical path (StepState): the processor then
//    overlaps the divisions of the cube roots of independent contacts (bench/pair_speed.py:
//    1.2x the unsplit kernel with adhesion; docs/performance.md).
// advance_contact runs the stages for one contact. tests/core/test_contact_kernel.cpp takes
// every step of long random contact paths (peeling, micro-slip reversals, sliding, tension,
// twist, a turning normal) from the same state with this and with the reference and asserts
// the same forces, memory and energies.
#ifndef TYCORE_CONTACT_KERNEL_HPP
#define TYCORE_CONTACT_KERNEL_HPP

#include "contact_types.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace tycore {

namespace detail {
// c ? a : b by bit masks. The compiler turns a plain ?: of doubles into a branch, and the
// branches of the Masing law (which branch a contact of a vibrating packing takes this step)
// are close to random: mispredicted they cost more than these few integer operations
inline double select(bool c, double a, double b)
{
  std::uint64_t ua, ub;
  std::memcpy(&ua, &a, sizeof ua);
  std::memcpy(&ub, &b, sizeof ub);
  const std::uint64_t mask = -static_cast<std::uint64_t>(c);
  const std::uint64_t r = (ua & mask) | (ub & ~mask);
  double out;
  std::memcpy(&out, &r, sizeof out);
  return out;
}
}    // namespace detail

// per material pair, derived once from PairCoefficients (§: sections of docs/theory.md)
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

// Savkoor-Briggs discriminant 4 P Pc + 4 Pc^2 - T^2 E*/(4G*) (peeling_discriminant,
// docs/theory.md §2.2) with the shear factor of the pair computed once
inline double peeling_discriminant(const PairConstants& k, double P, double Pc, double T2)
{
  return 4.0 * P * Pc + 4.0 * Pc * Pc - k.peel_shear * T2;
}

// What one contact carries from one stage of its step to the next. The step is split where a
// cube root sits on its critical path (the stiffness radius a_T, the theta factor), so that the
// pair can run each stage over a batch of contacts and the cube roots of independent contacts
// overlap in the processor instead of waiting for each other (docs/performance.md).
struct StepState {
  double P, contact_radius, Pc, effective_load, dP, sliding_limit;
  double T_old[3], ds[3];
  double stiffness_cubed;    // (stiffness / 8G*)^3 when the radius needs a cube root
  double stiffness;          // k_T = 8 G* a_T (or 8 G* a_peel while peeling)
  double T_magnitude;        // |T| when known from the rotation, else < 0
  double s, ks, mu_dP, T_along, limit;
  double theta_cubed, theta;
  double lost;
  int mode;
  bool frictionless, was_sliding, needs_cbrt, peeled_step, active, slipping;
};

// Stage 1a: history onto the new tangent plane of n, twisted by `twist` (rotate_history)
inline void carry_history(const double n[3], double twist, ContactHistory& h, StepState& st)
{
  using namespace detail;
  double* T = h.T;
  double* dir = h.load_dir;
  double tw_c = 1.0, tw_s = 0.0;
  if (twist != 0.0) twist_cos_sin(twist, tw_c, tw_s);
  const double T2_before = dot(T, T);
  const bool dir_follows_T = h.mode == LOADING && T2_before > 0.0 && dot(dir, dir) > 0.0;
  st.T_magnitude = -1.0;
  if (dir_follows_T) {    // load_dir = T/|T| on the loading branch: project once
    const double along = dot(T, n);
    double p[3] = {T[0] - along * n[0], T[1] - along * n[1], T[2] - along * n[2]};
    const double in_plane2 = dot(p, p);
    if (in_plane2 > 0.0) {
      const double inv = 1.0 / std::sqrt(in_plane2);
      dir[0] = p[0] * inv;
      dir[1] = p[1] * inv;
      dir[2] = p[2] * inv;
      if (twist != 0.0) twist_vector(dir, n, tw_c, tw_s);
      st.T_magnitude = std::sqrt(T2_before);
      T[0] = st.T_magnitude * dir[0];
      T[1] = st.T_magnitude * dir[1];
      T[2] = st.T_magnitude * dir[2];
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
}

// Stage 1b: normal force at overlap delta (jkr::contact_radius_warm, jkr::normal_force);
// Rinv = 1/R, which the caller may have from the division that gave R
template <bool Adhesive>
inline void normal_force_step(const PairConstants& k, double R, double Rinv, double delta, ContactHistory& h,
                              StepState& st)
{
  const PairCoefficients& c = k.c;
  if (Adhesive) {
    double a = -1.0, u = 0.0;
    if (h.radius > 0.0) {    // Halley on f(u) = u^4/R - c u - delta from the previous radius (§1.4b)
      u = std::sqrt(h.radius);
      // the first two steps without a convergence test between them: one step suffices on
      // some steps and not on others, and that branch mispredicts more often than not in a
      // vibrating packing (cachegrind --branch-sim), costing more than the second step
      bool slope_positive = true;
      double f1 = 0.0, f2 = 0.0, step = 0.0;
      const auto halley_step = [&]() {
        const double u2 = u * u;
        const double f = u2 * u2 * Rinv - k.newton_c * u - delta;
        f1 = 4.0 * u2 * u * Rinv - k.newton_c;
        slope_positive = slope_positive && f1 > 0.0;
        f2 = 12.0 * u2 * Rinv;
        step = 2.0 * f * f1 / (2.0 * f1 * f1 - f * f2);
        u -= step;
      };
      halley_step();
      halley_step();
      for (int it = 2; slope_positive; ++it) {
        // error of the new iterate ~ |f2^2/(4 f1^2) - f3/(6 f1)| step^3, f3 = 24 u/R; 4x margin
        const double step3 = std::abs(step * step * step);
        if (4.0 * std::abs(0.25 * f2 * f2 - 4.0 * u * Rinv * f1) * step3 <= 1e-14 * u * f1 * f1) {
          a = u * u;
          break;
        }
        if (it == 6) break;
        halley_step();
      }
    }
    if (a < 0.0) {
      a = jkr::contact_radius(delta, R, c.E_star, c.Gamma);
      u = std::sqrt(a);
    }
    st.contact_radius = a;
    st.P = 4.0 * c.E_star * (a * a * a) * Rinv * (1.0 / 3.0) - k.adhesive_force * (a * u);
  } else {
    const double a = std::sqrt(R * std::max(delta, 0.0));
    st.contact_radius = a;
    st.P = (4.0 / 3.0) * c.E_star * a * std::max(delta, 0.0);    // 4E*a^3/(3R*), a^2 = R* delta
  }
  h.radius = st.contact_radius;
}

// Whether a contact whose force is evaluated without a step of its history (the setup pass of
// a run: unchanged positions, history kept) slides under the coefficients in force now: its
// kept |T| at the Coulomb limit mu max(P + 2Pc, 0) (docs/theory.md §2), or a limit of zero (a
// frictionless contact, or a Hertz contact at zero load), which a step of the law also flags
// as sliding. The flag kept in the history belongs to the last step and to the mu of that
// step: after a change of mu (a new pair_coeff, fix adapt) it would be stale.
inline bool slides_without_step(const PairConstants& k, double R, double P, const ContactHistory& h)
{
  const double Pc = jkr::pull_off_force(k.c.Gamma, R);
  const double limit = k.c.mu * std::max(P + 2.0 * Pc, 0.0);
  if (limit <= 0.0) return true;
  const double T2 = h.T[0] * h.T[0] + h.T[1] * h.T[1] + h.T[2] * h.T[2];
  return T2 >= limit * limit * (1.0 - 1e-12);
}

// Stage 1c: start of the tangential law (tangential_step): the frictionless case completely,
// otherwise what the stiffness radius needs
template <bool Adhesive>
inline void begin_tangential(const PairConstants& k, double R, const double ds[3],
                             ContactHistory& h, StepState& st)
{
  const PairCoefficients& c = k.c;
  double* T = h.T;
  double* dir = h.load_dir;
  const double P = st.P;
  for (int d = 0; d < 3; ++d) {
    st.T_old[d] = T[d];
    st.ds[d] = ds[d];
  }
  st.Pc = Adhesive ? jkr::pull_off_force(c.Gamma, R) : 0.0;
  st.effective_load = P + 2.0 * st.Pc;
  st.dP = P - h.P_prev;
  st.sliding_limit = c.mu * std::max(st.effective_load, 0.0);
  st.was_sliding = h.sliding != 0.0;
  h.sliding = 0.0;
  st.lost = st.theta_cubed = st.theta = 0.0;
  st.needs_cbrt = st.peeled_step = st.slipping = false;
  st.active = true;
  st.frictionless = st.sliding_limit <= 0.0;
  if (st.frictionless) {    // frictionless, or a Hertz contact at zero load
    T[0] = T[1] = T[2] = 0.0;
    dir[0] = dir[1] = dir[2] = 0.0;
    h.mode = LOADING;
    h.T_star = h.T_star2 = 0.0;
    h.sliding = 1.0;
    h.peeling = 0.0;
    h.P_prev = P;
    return;
  }
  if (Adhesive && h.peeling != 0.0) {    // stage A: Savkoor-Briggs peeling  (docs/theory.md §2.2)
    const double before = peeling_discriminant(k, P, st.Pc, detail::dot(T, T));
    if (before > 0.0) {    // 4E*a^3/(3R*) = P + 2Pc + sqrt(discriminant)
      st.stiffness_cubed = k.cube_radius_per_load * R * (P + 2.0 * st.Pc + std::sqrt(before));
      st.needs_cbrt = st.peeled_step = true;
      return;
    }
    h.peeling = 0.0;
  }
  if (Adhesive) {    // stage B radius: a_T^3 = 3R*(P + 2Pc)/(4E*)
    st.stiffness_cubed = k.cube_radius_per_load * R * std::max(st.effective_load, 0.0);
    st.needs_cbrt = true;
  } else {
    st.stiffness = 8.0 * c.G_star * st.contact_radius;
  }
}

// Stage 2: the stiffness radius's cube root (adhesive contacts)
inline void stiffness_of(const PairConstants& k, StepState& st)
{
  if (st.needs_cbrt) st.stiffness = 8.0 * k.c.G_star * jkr::fast_cbrt(st.stiffness_cubed);
}

// Stage 3: the peeled step, or the micro-slip branch decision up to theta^3 (micro_slip_step)
inline void slip_decision(const PairConstants& k, ContactHistory& h, StepState& st)
{
  using namespace detail;
  if (st.frictionless) return;
  const PairCoefficients& c = k.c;
  double* T = h.T;
  double* dir = h.load_dir;
  const double* ds = st.ds;
  if (st.peeled_step) {
    T[0] += st.stiffness * ds[0];
    T[1] += st.stiffness * ds[1];
    T[2] += st.stiffness * ds[2];
    st.T_magnitude = -1.0;
    if (peeling_discriminant(k, st.P, st.Pc, dot(T, T)) <= 0.0) h.peeling = 0.0;
    return;
  }
  bool at_limit = st.was_sliding && h.mode == LOADING;
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
        st.active = false;
        return;
      }
    }
    h.mode = LOADING;
    at_limit = false;
  }
  st.limit = c.mu * st.effective_load;
  st.s = dot(ds, dir);
  st.ks = st.stiffness * st.s;
  st.mu_dP = c.mu * st.dP;
  const double T_projected = dot(T, dir);
  st.T_along = select(st.T_magnitude >= 0.0, st.T_magnitude, T_projected);
  const double ks = st.ks, mu_dP = st.mu_dP;
  // the Masing branch of this increment, without branches (detail::select)
  const int mode_before = static_cast<int>(h.mode);
  const bool unloading = mode_before == UNLOADING;
  const bool forward = ks > mu_dP, backward = ks < -mu_dP;
  const bool to_unloading = !unloading & !forward & backward;
  const bool to_reloading = unloading & !backward & forward;
  const int mode = to_unloading ? UNLOADING : (to_reloading ? RELOADING : mode_before);
  // reversal points follow the normal load                              (docs/theory.md §2.1)
  h.T_star = select(to_unloading, st.T_along, h.T_star) + mu_dP;
  h.T_star2 = select(to_reloading, st.T_along, h.T_star2) - mu_dP;
  st.mode = mode;
  st.slipping = forward | backward;
  // theta^3 of Thornton & Randall (1988), P -> P + 2Pc                    (docs/theory.md §2.1)
  // loading 1 - (T + mu dP)/L, unloading 1 - (T* - T + 2 mu dP)/2L,
  // reloading 1 - (T - T** + 2 mu dP)/2L
  const double branch_term =
      select(mode == UNLOADING, h.T_star - st.T_along,
             select(mode == RELOADING, st.T_along - h.T_star2, 2.0 * st.T_along));
  const double t3 = 1.0 - (branch_term + 2.0 * mu_dP) / (2.0 * st.limit);
  const bool on_slip_branch = st.slipping & !((mode == LOADING) & at_limit);
  st.theta_cubed = select(on_slip_branch, std::clamp(t3, 0.0, 1.0), 0.0);
}

// Stage 4: theta = cbrt(theta^3), without the libm call fast_cbrt makes at 0; theta = 1 off
// the slip branches, where finish_step's increment reduces to the elastic k s
inline void theta_of(StepState& st)
{
  st.theta = !st.slipping ? 1.0 : (st.theta_cubed > 0.0 ? jkr::fast_cbrt(st.theta_cubed) : 0.0);
}

// Stage 5: the micro-slip increment, branch changes, Coulomb cap and energy balance
inline void finish_step(ContactHistory& h, StepState& st, double& dissipation)
{
  using namespace detail;
  double* T = h.T;
  double* dir = h.load_dir;
  const double* ds = st.ds;
  if (st.frictionless) {
    const double released = h.stored_energy + 0.5 * dot(st.T_old, ds);
    h.stored_energy = 0.0;
    dissipation += std::max(released, 0.0);
    return;
  }
  if (!st.peeled_step && st.active) {
    // dT_par = theta k s + (-1)^k mu dP (1 - theta); = k s, no annulus loss, at theta = 1
    const double theta = st.theta;
    const double sign = select(st.mode == UNLOADING, -1.0, 1.0);
    const double dT_par = theta * st.ks + sign * st.mu_dP * (1.0 - theta);
    st.lost += detail::annulus_dissipation_rate(st.limit, theta) * std::abs(st.s);
    // T += dT_par dir + k (ds - s dir)
    const double along = dT_par - st.stiffness * st.s;
    T[0] += along * dir[0] + st.stiffness * ds[0];
    T[1] += along * dir[1] + st.stiffness * ds[1];
    T[2] += along * dir[2] + st.stiffness * ds[2];
    // back on the virgin curve: unloading past -T* (direction reversed), reloading past T*
    const int mode = st.mode;
    const double T_after = dot(T, dir);
    const bool reversed = (mode == UNLOADING) & (T_after <= -h.T_star);
    const bool rejoined = (mode == RELOADING) & (T_after >= h.T_star);
    const double flip = select(reversed, -1.0, 1.0);
    dir[0] *= flip, dir[1] *= flip, dir[2] *= flip;
    h.mode = (reversed | rejoined) ? LOADING : mode;
  }

  // one |T| for the loading direction and the Coulomb cap (stage C)
  const double sliding_limit = st.sliding_limit;
  const double magnitude = std::sqrt(dot(T, T));
  const bool loading_dir = !st.peeled_step && h.mode == LOADING && magnitude > 0.0;
  const bool capped = magnitude >= sliding_limit * (1.0 - detail::limit_tolerance);
  if (loading_dir || capped) {
    const double inv = 1.0 / magnitude;
    dir[0] = T[0] * inv, dir[1] = T[1] * inv, dir[2] = T[2] * inv;
  }
  if (capped) {    // gross sliding at |T| = mu (P + 2Pc)
    if (magnitude > sliding_limit * (1.0 + detail::limit_tolerance)) {
      st.lost += sliding_limit * (magnitude - sliding_limit) / st.stiffness;
      const double scale = sliding_limit / magnitude;
      T[0] *= scale, T[1] *= scale, T[2] *= scale;
    }
    h.mode = LOADING;
    h.T_star = h.T_star2 = 0.0;
    h.sliding = 1.0;
    h.peeling = 0.0;
  }
  h.P_prev = st.P;
  const double available =
      h.stored_energy + 0.5 * ((st.T_old[0] + T[0]) * ds[0] + (st.T_old[1] + T[1]) * ds[1] +
                               (st.T_old[2] + T[2]) * ds[2]);
  const double lost = std::clamp(st.lost, 0.0, std::max(available, 0.0));
  h.stored_energy = std::max(available - lost, 0.0);
  dissipation += lost;
}

// One contact, one step, after a previous step or begin_contact: the stored vectors are carried
// onto the tangent plane of n and twisted by `twist` (rotate_history), then the normal force at
// overlap delta and the tangential law for the increment ds (evaluate_contact with
// RESULT_FORCES). Adds the frictional dissipation of the step to `dissipation`.
template <bool Adhesive>
inline KernelResult advance_contact(const PairConstants& k, double R, double delta,
                                    const double n[3], double twist, const double ds[3],
                                    ContactHistory& h, double& dissipation)
{
  StepState st;
  carry_history(n, twist, h, st);
  normal_force_step<Adhesive>(k, R, 1.0 / R, delta, h, st);
  begin_tangential<Adhesive>(k, R, ds, h, st);
  stiffness_of(k, st);
  slip_decision(k, h, st);
  theta_of(st);
  finish_step(h, st, dissipation);
  return KernelResult{st.P, st.contact_radius};
}

}    // namespace tycore

#endif
