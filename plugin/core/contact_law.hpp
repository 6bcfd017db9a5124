// The Thornton-Yin contact law of the pair style, written once over a lane type V: JKR normal
// force (the warm-started Halley iteration on the quartic in sqrt(a), docs/theory.md §1.4),
// the history carried onto the new tangent plane and twisted, Savkoor-Briggs peeling (§2.2),
// Mindlin-Deresiewicz micro-slip with its loading / unloading / reloading memory under a
// varying normal load (§2.1, §2.3), the Coulomb cap (gross sliding), the frictionless
// shortcut and the energy balance (§2.4). Thornton & Yin (1991); Thornton & Randall (1988).
//
// Every branch of the law is a lane select (lane_select): each lane computes every branch and
// keeps its own. One text, two instantiations in the plugin:
//  * V = double called contact after contact: the scalar entry advance_contact
//    (contact_kernel.hpp) and the scalar build of advance_batch (contact_batch.hpp);
//  * V = double inside the lane loops of contact_batch.cpp, which the compiler turns into SIMD
//    code once per instruction set (SSE2, AVX2, AVX-512 on x86-64; the baseline elsewhere).
// The instantiations do the same arithmetic in the same order (no fused multiply-add, the same
// cube root bit for bit: simd_cbrt), so they agree to the last bit; tests/core/
// test_contact_batch.cpp compares every instantiation on every branch of the law (and
// tests/test_scalar_law_build.py the build without the SIMD ones), and the closed-form tests of
// the law (test_mindlin_deresiewicz.cpp, test_thornton_yin.cpp) drive the scalar entry. There
// is no other copy of the law: the closed-form pieces it calls are in jkr.hpp and
// mindlin_deresiewicz.hpp.
// A lane type needs: + - * / and comparisons with doubles, masks combined by & | !,
// lane_select, lane_max, lane_clamp, std::sqrt, std::abs and simd_cbrt (simd_math.hpp).
#ifndef TYCORE_CONTACT_LAW_HPP
#define TYCORE_CONTACT_LAW_HPP

#include "contact_types.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"
#include "simd_math.hpp"

#include <cmath>

namespace tycore {

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

// Savkoor-Briggs discriminant 4 P Pc + 4 Pc^2 - T^2 E*/(4G*) (peeling_discriminant,
// docs/theory.md §2.2) with the shear factor of the pair computed once
template <class V>
[[gnu::always_inline]] inline V peeling_discriminant(const PairConstants& k, V P, V Pc, V T2)
{
  return 4.0 * P * Pc + 4.0 * Pc * Pc - k.peel_shear * T2;
}

namespace law {

// ContactHistory of one lane (contact_types.hpp), field for field
template <class V> struct History {
  V T[3], dir[3], T_star, T_star2, P_prev, mode, peeling, sliding, stored_energy, radius;
};

// What the carry stage hands to the law stage: |T| where the rotation gave it (else -1) and the
// state of the JKR Halley iteration (a < 0: no radius yet; pending 1: it goes on)
template <class V> struct Carry {
  V T_magnitude, u, f1, f2, step, a, pending;
};

// What the law stage gives besides the new history
template <class V> struct Outputs {
  V P;              // normal force, > 0 repulsive
  V a;              // JKR contact radius a(delta)
  V dissipation;    // frictional dissipation of the step
  V stiffness;      // k_T the law used this step, -1 where it used none (frictionless, peeled)
};

template <class V> [[gnu::always_inline]] inline V dot3(const V a[3], const V b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// x -> cos(t) x + sin(t) n x x (rotation about the contact normal), kept as is where not twisted
template <class V, class M>
[[gnu::always_inline]] inline void twist(V x[3], const V n[3], V c, V s, M twisted)
{
  const V x0 = x[0], x1 = x[1], x2 = x[2];
  const V y0 = c * x0 + s * (n[1] * x2 - n[2] * x1);
  const V y1 = c * x1 + s * (n[2] * x0 - n[0] * x2);
  const V y2 = c * x2 + s * (n[0] * x1 - n[1] * x0);
  x[0] = lane_select(twisted, y0, x0);
  x[1] = lane_select(twisted, y1, x1);
  x[2] = lane_select(twisted, y2, x2);
}

// x onto the tangent plane of the unit normal n, its magnitude kept (zero stays zero, a vector
// along n becomes zero)
template <class V> [[gnu::always_inline]] inline void keep_magnitude(V x[3], const V n[3])
{
  const V magnitude2 = dot3(x, x);
  const V along = dot3(x, n);
  const V p[3] = {x[0] - along * n[0], x[1] - along * n[1], x[2] - along * n[2]};
  const V in_plane2 = dot3(p, p);
  const V scale = std::sqrt(magnitude2 / in_plane2);
  const V zero = V(0.0);
  const auto flat = in_plane2 == 0.0, none = magnitude2 == 0.0;
  for (int d = 0; d < 3; ++d) x[d] = lane_select(none, x[d], lane_select(flat, zero, p[d] * scale));
}

// one Halley step on f(u) = u^4/R* - c u - delta, c = 2 sqrt(pi Gamma/E*)    (docs/theory.md §1.4)
template <class V, class M>
[[gnu::always_inline]] inline void halley_step(V& u, V& f1, V& f2, V& step, M& slope_positive,
                                               V Rinv, double newton_c, V delta)
{
  const V u2 = u * u;
  const V f = u2 * u2 * Rinv - newton_c * u - delta;
  f1 = 4.0 * u2 * u * Rinv - newton_c;
  slope_positive = slope_positive & (f1 > 0.0);
  f2 = 12.0 * u2 * Rinv;
  step = 2.0 * f * f1 / (2.0 * f1 * f1 - f * f2);
  u -= step;
}

// converged after `step`: the error of the new iterate ~ |f2^2/(4 f1^2) - f3/(6 f1)| step^3,
// f3 = 24 u/R*, with a 4x margin below 1e-14 u
template <class V>
[[gnu::always_inline]] inline auto halley_converged(V u, V f1, V f2, V step, V Rinv)
{
  const V step3 = std::abs(step * step * step);
  return 4.0 * std::abs(0.25 * f2 * f2 - 4.0 * u * Rinv * f1) * step3 <= 1e-14 * u * f1 * f1;
}

// The JKR radius from the previous one (`radius`; <= 0: none): two Halley steps without a test
// between them (one suffices on some steps, and that branch mispredicts more often than not in
// a vibrating packing), the first test, and the next step where it fails (iteration 3). w.a < 0
// where no radius is found yet (pending 1: the iteration goes on, halley_again).
template <class V>
[[gnu::always_inline]] inline void halley_start(const PairConstants& k, V Rinv, V delta, V radius,
                                                Carry<V>& w)
{
  const V zero = V(0.0);
  const auto has_guess = radius > 0.0;
  V u = std::sqrt(lane_select(has_guess, radius, V(1.0)));
  V f1 = zero, f2 = zero, step = zero;
  auto slope_positive = zero == zero;    // all lanes true
  halley_step(u, f1, f2, step, slope_positive, Rinv, k.newton_c, delta);
  halley_step(u, f1, f2, step, slope_positive, Rinv, k.newton_c, delta);
  const auto go_on = has_guess & slope_positive;
  const auto converged = go_on & halley_converged(u, f1, f2, step, Rinv);
  w.a = lane_select(converged, u * u, V(-1.0));
  V u_next = u, f1_next = f1, f2_next = f2, step_next = step;
  auto slope_next = slope_positive;
  halley_step(u_next, f1_next, f2_next, step_next, slope_next, Rinv, k.newton_c, delta);
  const auto stepped = go_on & !converged;
  w.u = lane_select(stepped, u_next, u);
  w.f1 = lane_select(stepped, f1_next, f1);
  w.f2 = lane_select(stepped, f2_next, f2);
  w.step = lane_select(stepped, step_next, step);
  w.pending = lane_select(stepped & slope_next, V(1.0), zero);
}

// Stage 1: the stored vectors onto the tangent plane of n (magnitude kept), twisted about n by
// the angle whose cosine and sine are (c, s) where `twisted` (on the loading branch
// load_dir = T/|T| is projected once and T follows it), and with adhesion the JKR radius from
// the previous one (halley_start).
template <bool Adhesive, class V, class M>
[[gnu::always_inline]] inline void carry(const PairConstants& k, const V n[3], V c, V s,
                                         M twisted, V Rinv, V delta, History<V>& h, Carry<V>& w)
{
  V T[3] = {h.T[0], h.T[1], h.T[2]};
  V dir[3] = {h.dir[0], h.dir[1], h.dir[2]};
  const V T2_before = dot3(T, T);
  const auto dir_follows_T = (h.mode == double(LOADING)) & (T2_before > 0.0) & (dot3(dir, dir) > 0.0);
  // loading branch: load_dir = T/|T|, projected once
  const V along = dot3(T, n);
  V q[3] = {T[0] - along * n[0], T[1] - along * n[1], T[2] - along * n[2]};
  const V in_plane2 = dot3(q, q);
  const V inv = 1.0 / std::sqrt(in_plane2);
  q[0] *= inv, q[1] *= inv, q[2] *= inv;
  twist(q, n, c, s, twisted);
  const V magnitude = std::sqrt(T2_before);
  const auto kept = in_plane2 > 0.0;
  // otherwise each vector on its own
  keep_magnitude(T, n);
  twist(T, n, c, s, twisted);
  keep_magnitude(dir, n);
  twist(dir, n, c, s, twisted);
  const V zero = V(0.0);
  for (int d = 0; d < 3; ++d) {
    h.T[d] = lane_select(dir_follows_T, lane_select(kept, magnitude * q[d], zero), T[d]);
    h.dir[d] = lane_select(dir_follows_T, lane_select(kept, q[d], zero), dir[d]);
  }
  w.T_magnitude = lane_select(dir_follows_T & kept, magnitude, V(-1.0));

  if (Adhesive) halley_start(k, Rinv, delta, h.radius, w);
}

// A later round of the Halley iteration (rounds 3 .. 6 after carry's) where it is pending:
// the test of the last iterate, then a step unless converged or at the last round (6); the
// closed form (jkr::contact_radius) where it has not converged by then
template <class V>
[[gnu::always_inline]] inline void halley_again(V Rinv, V delta, double newton_c, bool last,
                                                Carry<V>& w)
{
  const auto pending = w.pending != 0.0;
  const auto converged = pending & halley_converged(w.u, w.f1, w.f2, w.step, Rinv);
  w.a = lane_select(converged, w.u * w.u, w.a);
  V u = w.u, f1 = w.f1, f2 = w.f2, step = w.step;
  auto slope_positive = V(0.0) == V(0.0);    // all lanes true
  halley_step(u, f1, f2, step, slope_positive, Rinv, newton_c, delta);
  const auto stepped = pending & !converged & !last;
  w.u = lane_select(stepped, u, w.u);
  w.f1 = lane_select(stepped, f1, w.f1);
  w.f2 = lane_select(stepped, f2, w.f2);
  w.step = lane_select(stepped, step, w.step);
  w.pending = lane_select(stepped & slope_positive, V(1.0), V(0.0));
}

// where the iteration found no radius (no warm start, or no convergence within its rounds: the
// first step of a contact, a large jump): the closed form (jkr::contact_radius, §1.4)
[[gnu::always_inline]] inline void closed_form_radius(const PairCoefficients& c, double R,
                                                      double delta, Carry<double>& w)
{
  w.a = jkr::contact_radius(delta, R, c.E_star, c.Gamma);
  w.u = std::sqrt(w.a);
}

// The normal force (§1.1) at overlap delta, P > 0 repulsive, and the contact radius `a`: JKR at
// the radius of the iteration (w.a, w.u = sqrt(a)), or Hertz
template <bool Adhesive, class V>
[[gnu::always_inline]] inline V normal_force(const PairConstants& k, V R, V Rinv, V delta,
                                             const Carry<V>& w, V& a)
{
  const PairCoefficients& c = k.c;
  if (Adhesive) {
    a = w.a;
    return 4.0 * c.E_star * (a * a * a) * Rinv * (1.0 / 3.0) - k.adhesive_force * (a * w.u);
  }
  const V compression = lane_max(delta, V(0.0));
  a = std::sqrt(R * compression);
  return (4.0 / 3.0) * c.E_star * a * compression;
}

// a_T^3 = 3R*(P + 2Pc)/(4E*): the Hertz radius of the effective load P + 2Pc, cubed, whose
// 8 G* a_T is the micro-slip stiffness k_T (§2.2; zero where P + 2Pc <= 0)
template <class V>
[[gnu::always_inline]] inline V micro_slip_radius_cubed(const PairConstants& k, V R, V effective_load)
{
  return k.cube_radius_per_load * R * lane_max(effective_load, V(0.0));
}

// Stage 2: the normal force at the radius found and the tangential law for the increment ds
// (peeling, micro-slip, Coulomb cap, energy balance); h becomes the new history. Frictionless:
// the material pair has mu = 0, so the outcome is known without the tangential law: T and its
// memory cleared, sliding, the stored energy released (docs/theory.md §2.3); the same values,
// bit for bit, as the full law gives for mu = 0.
template <bool Adhesive, bool Frictionless, class V>
[[gnu::always_inline]] inline Outputs<V> step(const PairConstants& k, V R, V Rinv, V delta,
                                              const V ds[3], const Carry<V>& w, History<V>& h)
{
  const PairCoefficients& c = k.c;
  const V zero = V(0.0), one = V(1.0);
  const V T_old[3] = {h.T[0], h.T[1], h.T[2]};
  const V dir_old[3] = {h.dir[0], h.dir[1], h.dir[2]};
  const V mode_old = h.mode, peeling_old = h.peeling;
  const V T_star_old = h.T_star, T_star2_old = h.T_star2, stored_old = h.stored_energy;
  const V P_prev = h.P_prev;
  const auto was_sliding = h.sliding != 0.0;

  Outputs<V> out;
  V a;
  const V P = normal_force<Adhesive>(k, R, Rinv, delta, w, a);
  out.P = P;
  out.a = a;
  h.radius = a;
  h.P_prev = P;
  // frictionless, or a Hertz contact at zero load: T and its memory go, stored energy lost
  const V released = stored_old + 0.5 * dot3(T_old, ds);

  if (Frictionless) {
    for (int d = 0; d < 3; ++d) h.T[d] = h.dir[d] = zero;
    h.T_star = h.T_star2 = h.peeling = h.stored_energy = zero;
    h.mode = V(double(LOADING));
    h.sliding = one;
    out.dissipation = 0.0 + lane_max(released, zero);
    out.stiffness = V(-1.0);
    return out;
  }

  const V Pc = Adhesive ? V(jkr::pull_off_force(c.Gamma, 1.0)) * R : zero;
  const V effective_load = P + 2.0 * Pc;
  const V dP = P - P_prev;
  const V sliding_limit = c.mu * lane_max(effective_load, zero);
  const auto frictionless = sliding_limit <= 0.0;
  const V T2_old = dot3(T_old, T_old);
  // stage A, Savkoor-Briggs peeling (§2.2): k_T = 8G* a_peel, elastic
  const V before = peeling_discriminant(k, P, Pc, T2_old);
  const auto tried_peeling = Adhesive ? peeling_old != 0.0 : zero != zero;
  const auto peeled = tried_peeling & (before > 0.0);
  V peeling = lane_select(tried_peeling & !peeled, zero, peeling_old);
  V stiffness;
  if (Adhesive) {    // k_T = 8G* a_T, a_T^3 peeled (4E*a^3/(3R*) = P + 2Pc + sqrt(disc)) or 3R*(P + 2Pc)/(4E*)
    const V cubed = lane_select(peeled,
                                k.cube_radius_per_load * R * (P + 2.0 * Pc + std::sqrt(before)),
                                micro_slip_radius_cubed(k, R, effective_load));
    stiffness = 8.0 * c.G_star * simd_cbrt(cubed);
  } else {
    stiffness = 8.0 * c.G_star * a;
  }

  // stage B, micro-slip (§2.1, §2.3): the loading direction where there is none yet
  auto at_limit = was_sliding & (mode_old == double(LOADING));
  const auto needs_dir = dot3(dir_old, dir_old) == 0.0;
  const V s2 = dot3(ds, ds);
  const V inv_T = 1.0 / std::sqrt(T2_old), inv_s = 1.0 / std::sqrt(s2);
  const auto active = !needs_dir | (T2_old > 0.0) | (s2 > 0.0);
  const auto new_dir = needs_dir & active & !peeled;
  V dir[3];
  for (int d = 0; d < 3; ++d) {
    const V fresh = lane_select(T2_old > 0.0, T_old[d] * inv_T, ds[d] * inv_s);
    dir[d] = lane_select(new_dir, fresh, dir_old[d]);
  }
  const V mode_start = lane_select(new_dir, V(double(LOADING)), mode_old);
  at_limit = at_limit & !new_dir;
  // the Masing branch of this increment: forward slip iff k s > mu dP, reverse iff k s < -mu dP,
  // elastic otherwise; the reversal points follow the normal load
  const V limit = c.mu * effective_load;
  const V s = dot3(ds, dir);
  const V ks = stiffness * s;
  const V mu_dP = c.mu * dP;
  const V T_along = lane_select(w.T_magnitude >= 0.0, w.T_magnitude, dot3(T_old, dir));
  const auto was_unloading = mode_start == double(UNLOADING);
  const auto forward = ks > mu_dP, backward = ks < -mu_dP;
  const auto to_unloading = !was_unloading & !forward & backward;
  const auto to_reloading = was_unloading & !backward & forward;
  const V mode = lane_select(to_unloading, V(double(UNLOADING)),
                             lane_select(to_reloading, V(double(RELOADING)), mode_start));
  const V T_star = lane_select(to_unloading, T_along, T_star_old) + mu_dP;
  const V T_star2 = lane_select(to_reloading, T_along, T_star2_old) - mu_dP;
  const auto slipping = forward | backward;
  const auto on_unloading = mode == double(UNLOADING);
  // theta^3 of Thornton & Randall (1988), P -> P + 2Pc: loading 1 - (T + mu dP)/L, unloading
  // 1 - (T* - T + 2 mu dP)/2L, reloading 1 - (T - T** + 2 mu dP)/2L
  const V branch_term =
      lane_select(on_unloading, T_star - T_along,
                  lane_select(mode == double(RELOADING), T_along - T_star2, 2.0 * T_along));
  const V t3 = 1.0 - (branch_term + 2.0 * mu_dP) / (2.0 * limit);
  // at the sliding limit (slid last step, loading branch) theta = 0 exactly
  const auto on_slip_branch = slipping & !((mode == double(LOADING)) & at_limit);
  const V theta_cubed = lane_select(on_slip_branch, lane_clamp(t3, zero, one), zero);
  const V root = simd_cbrt(theta_cubed);
  const V theta = lane_select(!slipping, one, lane_select(theta_cubed > 0.0, root, zero));

  // the micro-slip increment dT_par = theta k s + (-1)^k mu dP (1 - theta) along dir, k ds_perp
  // across it (= k ds at theta = 1), or the peeled elastic one
  const auto micro = (!peeled) & active;
  const V sign = lane_select(on_unloading, V(-1.0), one);
  const V dT_par = theta * ks + sign * mu_dP * (1.0 - theta);
  const V annulus = 0.0 + detail::annulus_dissipation_rate(limit, theta) * std::abs(s);
  V lost = lane_select(micro, annulus, zero);
  const V along = dT_par - stiffness * s;
  V T[3];
  for (int d = 0; d < 3; ++d) {
    const V slipped = T_old[d] + (along * dir[d] + stiffness * ds[d]);
    const V elastic = T_old[d] + stiffness * ds[d];
    T[d] = lane_select(peeled, elastic, lane_select(micro, slipped, T_old[d]));
  }
  if (Adhesive) {    // peeling ends where the discriminant vanishes
    const auto peeling_ends = peeled & (peeling_discriminant(k, P, Pc, dot3(T, T)) <= 0.0);
    peeling = lane_select(peeling_ends, zero, peeling);
  }
  // back on the virgin curve: unloading past -T* (direction reversed), reloading past T*
  const V T_after = dot3(T, dir);
  const auto reversed = micro & on_unloading & (T_after <= -T_star);
  const auto rejoined = micro & (mode == double(RELOADING)) & (T_after >= T_star);
  const V flip = lane_select(reversed, V(-1.0), one);
  dir[0] *= flip, dir[1] *= flip, dir[2] *= flip;
  const V mode_after = lane_select(micro, lane_select(reversed | rejoined, V(double(LOADING)), mode),
                                   mode_start);

  // stage C: one |T| for the loading direction and the Coulomb cap |T| <= mu (P + 2Pc); within
  // a few ulps of the limit T is kept as is (no work)
  const V magnitude = std::sqrt(dot3(T, T));
  const auto loading_dir = !peeled & (mode_after == double(LOADING)) & (magnitude > 0.0);
  const auto capped = magnitude >= sliding_limit * (1.0 - detail::limit_tolerance);
  const auto over = capped & (magnitude > sliding_limit * (1.0 + detail::limit_tolerance));
  const V inv = 1.0 / magnitude, scale = sliding_limit / magnitude;
  const V slid = lost + sliding_limit * (magnitude - sliding_limit) / stiffness;
  lost = lane_select(over, slid, lost);
  for (int d = 0; d < 3; ++d) {
    dir[d] = lane_select(loading_dir | capped, T[d] * inv, dir[d]);
    T[d] = lane_select(over, T[d] * scale, T[d]);
  }
  // energy balance (§2.4): work = dissipation + change of stored energy, dissipation >= 0
  const V available =
      stored_old + 0.5 * ((T_old[0] + T[0]) * ds[0] + (T_old[1] + T[1]) * ds[1] +
                          (T_old[2] + T[2]) * ds[2]);
  const V kept_lost = lane_clamp(lost, zero, lane_max(available, zero));
  const V stored = lane_max(available - kept_lost, zero);

  // the new history: frictionless lanes lose T, memory and stored energy; sliding lanes memory
  for (int d = 0; d < 3; ++d) {
    h.T[d] = lane_select(frictionless, zero, T[d]);
    h.dir[d] = lane_select(frictionless, zero, dir[d]);
  }
  const auto memory_cleared = frictionless | capped;
  h.T_star = lane_select(memory_cleared, zero, lane_select(micro, T_star, T_star_old));
  h.T_star2 = lane_select(memory_cleared, zero, lane_select(micro, T_star2, T_star2_old));
  h.mode = lane_select(memory_cleared, V(double(LOADING)), mode_after);
  h.peeling = lane_select(memory_cleared, zero, peeling);
  h.sliding = lane_select(memory_cleared, one, zero);
  h.stored_energy = lane_select(frictionless, zero, stored);
  out.dissipation = lane_select(frictionless, 0.0 + lane_max(released, zero), 0.0 + kept_lost);
  out.stiffness = lane_select(frictionless | peeled, V(-1.0), stiffness);
  return out;
}

}    // namespace law

}    // namespace tycore

#endif
