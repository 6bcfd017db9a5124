// The Thornton-Yin contact law of the pair style, written once over a lane type V,
// Thornton & Yin (1991), Thornton & Randall (1988). Each piece is read against one section of
// docs/theory.md:
//   carry                  the history onto the turned tangent plane, twisted (§2.3 step 1)
//   halley_start, _again,  the JKR contact radius from the overlap: warm-started Halley
//   closed_form_radius     iteration on the quartic in sqrt(a), else the closed form (§1.4)
//   normal_force           the JKR (or Hertz) normal force (§1.1, §1.6)
//   normal_load            P + 2Pc, dP and the sliding limit mu max(P + 2Pc, 0) (§2.2)
//   peeling                stage A, Savkoor-Briggs peeling (§2.2)
//   tangential_stiffness   k_T = 8 G* a_T, the peeling or the micro-slip radius (§2.2)
//   loading_direction      the loading direction t of a contact without one (§2.3 step 3)
//   slip_direction         THE branch rule: forward or backward slip, or elastic (§2.3 step 3)
//   masing_branch          loading / unloading / reloading, reversal points T*, T** (§2.1)
//   theta                  theta of the micro-slip annulus (§2.1)
//   tangential_increment   dT along t and across it (§2.1, §2.3 step 4), the annulus loss (§2.4)
//   rejoin_loading         back on the virgin loading curve (§2.1)
//   coulomb_cap            stage C, gross sliding at mu (P + 2Pc) (§2.3 step 5)
//   energy_balance         work = dissipation + change of stored energy (§2.4)
//   release_tangential     no tangential force where the sliding limit is 0 (§2.3)
//   tangential_step, step  the step assembled from these
//   snap_on, separates,    the contact's life cycle: first touch, break, its energy (§1.3)
//   break_energy
// The pieces hand their lane masks on in small structs passed by value: a named SlipDirection
// passed by const reference was enough for GCC 12 to leave the law's lane loops scalar
// (tests/test_batch_vectorised.py finds that; the numerical tests cannot, the bits are equal).
// The law has no viscous damping: the pair's damping stays outside the elastic history
// (detail::damped_force, contact_batch.hpp). The history it carries is the table
// TYCORE_HISTORY_FIELDS (contact_types.hpp).
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
#include <utility>

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

// The history of one lane: the fields of TYCORE_HISTORY_FIELDS (contact_types.hpp) with values
// of the lane type; at V = double it is ContactHistory itself
template <class V> using History = HistoryOf<V>;

// the lane mask of the lane type V (bool for V = double)
template <class V> using Mask = decltype(std::declval<V>() > 0.0);

// a in the lanes where m holds, else b, field for field
template <class V, class M>
[[gnu::always_inline]] inline History<V> select_history(M m, const History<V>& a,
                                                         const History<V>& b)
{
  History<V> h;
#define TYCORE_SELECT_FIELD(name, values, carried, from_j, meaning) \
  for (int k = 0; k < values; ++k)                                 \
    history::value(h.name, k) =                                    \
        lane_select(m, history::value(a.name, k), history::value(b.name, k));
  TYCORE_HISTORY_FIELDS(TYCORE_SELECT_FIELD)
#undef TYCORE_SELECT_FIELD
  return h;
}

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

// Stage 1 (docs/theory.md §2.3 step 1): the history's tangent vectors onto the tangent plane of
// n (magnitude kept), twisted about n by the angle whose cosine and sine are (c, s) where
// `twisted` (on the loading branch load_dir = T/|T| is projected once and T follows it; any
// other tangent vector of the history, TYCORE_HISTORY_FIELDS, on its own), and with adhesion
// the JKR radius from the previous one (halley_start).
template <bool Adhesive, class V, class M>
[[gnu::always_inline]] inline void carry(const PairConstants& k, const V n[3], V c, V s,
                                         M twisted, V Rinv, V delta, History<V>& h, Carry<V>& w)
{
  V T[3] = {h.T[0], h.T[1], h.T[2]};
  V dir[3] = {h.load_dir[0], h.load_dir[1], h.load_dir[2]};
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
    h.load_dir[d] = lane_select(dir_follows_T, lane_select(kept, q[d], zero), dir[d]);
  }
  w.T_magnitude = lane_select(dir_follows_T & kept, magnitude, V(-1.0));
#define TYCORE_CARRY_TANGENT(name, values, carried, from_j, meaning) \
  if constexpr (history::carried == history::tangent) {            \
    keep_magnitude(h.name, n);                                     \
    twist(h.name, n, c, s, twisted);                               \
  }
  TYCORE_HISTORY_FIELDS(TYCORE_CARRY_TANGENT)
#undef TYCORE_CARRY_TANGENT

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

// ---- the facts of the law that its callers share (each defined here once) ----

// a^3 = 3R*L/(4E*): the Hertz contact radius under the load L, cubed (docs/theory.md §1.6)
template <class V>
[[gnu::always_inline]] inline V hertz_radius_cubed(const PairConstants& k, V R, V load)
{
  return k.cube_radius_per_load * R * load;
}

// a_T^3 = 3R*(P + 2Pc)/(4E*): the Hertz radius of the effective load P + 2Pc, cubed, whose
// 8 G* a_T is the micro-slip stiffness k_T (§2.2; zero where P + 2Pc <= 0)
template <class V>
[[gnu::always_inline]] inline V micro_slip_radius_cubed(const PairConstants& k, V R, V effective_load)
{
  return hertz_radius_cubed(k, R, lane_max(effective_load, V(0.0)));
}

// the sliding limit mu max(P + 2Pc, 0) of the effective load P + 2Pc (§2.2 stage C): zero for
// mu = 0 and for a Hertz contact at zero load, where there is no tangential force (§2.3)
template <class V>
[[gnu::always_inline]] inline V sliding_limit(const PairConstants& k, V effective_load)
{
  return k.c.mu * lane_max(effective_load, V(0.0));
}

// ---- the contact's life cycle (docs/theory.md §1.3), contact by contact (both are rare) ----

// Snap-on: the history of a contact created at overlap delta >= 0 (JKR: the radius jumps to
// a(delta), (4/9)^(1/3) a0 at delta = 0, the force to P(a); no work is done): no tangential
// force, peeling if adhesive (begin_contact), the radius the warm start of its first step
inline ContactHistory snap_on(const PairCoefficients& c, double R, double delta, bool adhesive)
{
  const double a =
      adhesive ? jkr::contact_radius(delta, R, c.E_star, c.Gamma) : std::sqrt(R * delta);
  ContactHistory h;
  begin_contact(h, jkr::normal_force(a, R, c.E_star, c.Gamma), adhesive);
  h.radius = a;
  return h;
}

// Break: the contact separates beyond the break overlap, delta < delta_f (JKR under
// displacement control, §1.2; delta_f = 0 without adhesion). delta_f <= 0: only a tensile
// contact can break.
inline bool separates(const PairCoefficients& c, double R, double delta, bool adhesive)
{
  if (!(delta < 0.0)) return false;
  return delta < (adhesive ? jkr::break_overlap(R, c.E_star, c.Gamma) : 0.0);
}

// the elastic energy lost when a contact separates: its stored tangential energy and the JKR
// energy at the break radius a_f (§1.7, §3.2)
inline double break_energy(const PairCoefficients& c, double R, const ContactHistory& h,
                           bool adhesive)
{
  double stored = h.stored_energy;
  if (adhesive) {
    const double a_break = jkr::contact_radius(jkr::break_overlap(R, c.E_star, c.Gamma), R,
                                               c.E_star, c.Gamma);
    stored += jkr::stored_energy(a_break, R, c.E_star, c.Gamma);
  }
  return stored;
}

// ---- one step of the tangential law, piece by piece (docs/theory.md §2) ----

// The normal load as the tangential law sees it (§2.2): the JKR force P, the pull-off force
// Pc = 3 pi Gamma R* (0 without adhesion), the effective load P + 2Pc on which micro-slip and
// sliding act, the change dP of P since the last step and the sliding limit
template <class V> struct NormalLoad {
  V P, Pc, effective, dP, sliding_limit;
};

template <bool Adhesive, class V>
[[gnu::always_inline]] inline NormalLoad<V> normal_load(const PairConstants& k, V R, V P, V P_prev)
{
  NormalLoad<V> load;
  load.P = P;
  load.Pc = Adhesive ? V(jkr::pull_off_force(k.c.Gamma, 1.0)) * R : V(0.0);
  load.effective = P + 2.0 * load.Pc;
  load.dP = P - P_prev;
  load.sliding_limit = sliding_limit(k, load.effective);
  return load;
}

// Stage A, Savkoor-Briggs peeling (§2.2): a contact still peeling (its flag set; adhesive
// contacts start so) peels on this step while the discriminant 4PPc + 4Pc^2 - T^2 E*/(4G*) of
// its force T is positive; where the discriminant is no longer positive, peeling is over.
template <class V> struct Peeling {
  Mask<V> peeled;     // this step is a peeling step
  V discriminant;     // of the force before the step
  V flag;             // the peeling flag after the step
};

template <bool Adhesive, class V>
[[gnu::always_inline]] inline Peeling<V> peeling(const PairConstants& k, const NormalLoad<V>& load,
                                                 V T2, V flag)
{
  const V zero = V(0.0);
  Peeling<V> p;
  p.discriminant = peeling_discriminant(k, load.P, load.Pc, T2);
  const auto was_peeling = Adhesive ? flag != 0.0 : zero != zero;
  p.peeled = was_peeling & (p.discriminant > 0.0);
  p.flag = lane_select(was_peeling & !p.peeled, zero, flag);
  return p;
}

// The tangential stiffness k_T = 8 G* a_T of the step (§2.2): a_T of the peeling contact,
// 4E*a_T^3/(3R*) = P + 2Pc + sqrt(discriminant), or after peeling the Hertz radius of the
// effective load (micro_slip_radius_cubed); without adhesion the contact radius a (§2.1)
template <bool Adhesive, class V>
[[gnu::always_inline]] inline V tangential_stiffness(const PairConstants& k, V R, V a,
                                                     const NormalLoad<V>& load, Peeling<V> p)
{
  if (!Adhesive) return 8.0 * k.c.G_star * a;
  const V peeling_cubed = hertz_radius_cubed(k, R, load.effective + std::sqrt(p.discriminant));
  const V micro_slip_cubed = micro_slip_radius_cubed(k, R, load.effective);
  const V cubed = lane_select(p.peeled, peeling_cubed, micro_slip_cubed);
  return 8.0 * k.c.G_star * simd_cbrt(cubed);
}

// The loading direction t of §2.3 step 3 for a contact that has none yet (not while peeling):
// along T where there is a force, else along the increment; such a contact starts on the
// loading branch. An inactive step (no direction, no force, no increment) changes nothing.
template <class V> struct LoadingDirection {
  V t[3];             // the unit loading direction (load_dir)
  V mode;             // the branch the step starts on
  Mask<V> fresh;      // t was chosen this step
  Mask<V> active;
};

template <class V>
[[gnu::always_inline]] inline LoadingDirection<V> loading_direction(const History<V>& old, V T2_old,
                                                                    const V ds[3], Mask<V> peeled)
{
  LoadingDirection<V> d;
  const auto needs_dir = dot3(old.load_dir, old.load_dir) == 0.0;
  const V s2 = dot3(ds, ds);
  const V inv_T = 1.0 / std::sqrt(T2_old), inv_s = 1.0 / std::sqrt(s2);
  d.active = !needs_dir | (T2_old > 0.0) | (s2 > 0.0);
  d.fresh = needs_dir & d.active & !peeled;
  for (int i = 0; i < 3; ++i) {
    const V along_T_or_ds = lane_select(T2_old > 0.0, old.T[i] * inv_T, ds[i] * inv_s);
    d.t[i] = lane_select(d.fresh, along_T_or_ds, old.load_dir[i]);
  }
  d.mode = lane_select(d.fresh, V(double(LOADING)), old.mode);
  return d;
}

// The branch rule of §2.3 step 3: with k s the elastic increment along t and mu dP the shift
// of the slip thresholds by the normal load, slip forward where k s > mu dP, backward where
// k s < -mu dP, elastic in between. Where both hold (dP < 0: the thresholds cross) the
// increment counts as forward slip (masing_branch keeps the branch; a known deviation from
// Mindlin & Deresiewicz, §2.3).
template <class V> struct SlipDirection {
  Mask<V> forward, backward;
};

template <class V>
[[gnu::always_inline]] inline SlipDirection<V> slip_direction(V ks, V mu_dP)
{
  return SlipDirection<V>{ks > mu_dP, ks < -mu_dP};
}

// The Masing branch of the increment and its reversal points (§2.1): backward slip off the
// loading or reloading branch starts unloading from T* = T, forward slip off the unloading
// branch starts reloading from T** = T; both reversal points follow the normal load,
// T* <- T* + mu dP, T** <- T** - mu dP.
template <class V> struct MasingBranch {
  V mode, T_star, T_star2;
  Mask<V> slipping, unloading;
};

template <class V>
[[gnu::always_inline]] inline MasingBranch<V> masing_branch(V mode_start, V T_along, V T_star,
                                                            V T_star2, V mu_dP,
                                                            SlipDirection<V> slip)
{
  MasingBranch<V> b;
  const auto was_unloading = mode_start == double(UNLOADING);
  const auto to_unloading = !was_unloading & !slip.forward & slip.backward;
  const auto to_reloading = was_unloading & !slip.backward & slip.forward;
  b.mode = lane_select(to_unloading, V(double(UNLOADING)),
                       lane_select(to_reloading, V(double(RELOADING)), mode_start));
  b.T_star = lane_select(to_unloading, T_along, T_star) + mu_dP;
  b.T_star2 = lane_select(to_reloading, T_along, T_star2) - mu_dP;
  b.slipping = slip.forward | slip.backward;
  b.unloading = b.mode == double(UNLOADING);
  return b;
}

// theta of Thornton & Randall (1988) with P -> P + 2Pc (§2.1, §2.2): theta^3 = loading
// 1 - (T + mu dP)/L, unloading 1 - (T* - T + 2 mu dP)/2L, reloading 1 - (T - T** + 2 mu dP)/2L,
// L = mu (P + 2Pc), clamped to [0, 1]; 1 without slip; 0 at the sliding limit (slid last step
// on the loading branch)
template <class V>
[[gnu::always_inline]] inline V theta(MasingBranch<V> b, V T_along, V mu_dP, V limit,
                                      Mask<V> at_limit)
{
  const V zero = V(0.0), one = V(1.0);
  const V branch_term = lane_select(
      b.unloading, b.T_star - T_along,
      lane_select(b.mode == double(RELOADING), T_along - b.T_star2, 2.0 * T_along));
  const V theta_cubed_formula = 1.0 - (branch_term + 2.0 * mu_dP) / (2.0 * limit);
  const auto on_slip_branch = b.slipping & !((b.mode == double(LOADING)) & at_limit);
  const V theta_cubed =
      lane_select(on_slip_branch, lane_clamp(theta_cubed_formula, zero, one), zero);
  const V root = simd_cbrt(theta_cubed);
  return lane_select(!b.slipping, one, lane_select(theta_cubed > 0.0, root, zero));
}

// T after the increment ds (§2.1, §2.3 step 4): along t, dT = theta k s + (-1)^k mu dP
// (1 - theta) (k = 1 on the unloading branch); across t the no-slip k ds_perp (together k ds
// at theta = 1); while peeling the elastic k ds (§2.2); unchanged in an inactive step. The
// annulus dissipation of the micro-slip, mu (P + 2Pc) (1 - theta)^2 (1 + theta/2) |s| (§2.4),
// goes to `lost`.
template <class V>
[[gnu::always_inline]] inline void tangential_increment(const V T_old[3], const V ds[3],
                                                        const V t[3], V k_T, V s, V theta,
                                                        V mu_dP, V limit, Mask<V> unloading,
                                                        Mask<V> peeled, Mask<V> micro, V T[3],
                                                        V& lost)
{
  const V ks = k_T * s;
  const V sign = lane_select(unloading, V(-1.0), V(1.0));
  const V dT_along = theta * ks + sign * mu_dP * (1.0 - theta);
  lost = lane_select(micro, detail::annulus_dissipation_rate(limit, theta) * std::abs(s), V(0.0));
  const V along = dT_along - ks;
  for (int d = 0; d < 3; ++d) {
    const V slipped = T_old[d] + (along * t[d] + k_T * ds[d]);
    const V elastic = T_old[d] + k_T * ds[d];
    T[d] = lane_select(peeled, elastic, lane_select(micro, slipped, T_old[d]));
  }
}

// Back on the virgin loading curve (§2.1): unloading past -T* (the loading direction
// reverses) or reloading past T*; the branch after the step
template <class V>
[[gnu::always_inline]] inline V rejoin_loading(const V T[3], V t[3], MasingBranch<V> b,
                                               Mask<V> micro, V mode_start)
{
  const V T_along = dot3(T, t);
  const auto reversed = micro & b.unloading & (T_along <= -b.T_star);
  const auto rejoined = micro & (b.mode == double(RELOADING)) & (T_along >= b.T_star);
  const V flip = lane_select(reversed, V(-1.0), V(1.0));
  t[0] *= flip, t[1] *= flip, t[2] *= flip;
  const V mode = lane_select(reversed | rejoined, V(double(LOADING)), b.mode);
  return lane_select(micro, mode, mode_start);
}

// Stage C, the Coulomb cap (§2.3 step 5): |T| <= mu (P + 2Pc); within a few ulps of the limit
// T is kept as is (no work), beyond it T is scaled back onto the limit and the excess force
// over k_T is slid, with the dissipation limit x slip added to `lost`. On the loading branch
// and at the cap the loading direction becomes T/|T|. Returns where the contact is at the cap.
template <class V>
[[gnu::always_inline]] inline Mask<V> coulomb_cap(V T[3], V t[3], V limit, V k_T, Mask<V> peeled,
                                                  V mode, V& lost)
{
  const V magnitude = std::sqrt(dot3(T, T));
  const auto loading_dir = !peeled & (mode == double(LOADING)) & (magnitude > 0.0);
  const auto capped = magnitude >= limit * (1.0 - detail::limit_tolerance);
  const auto over = capped & (magnitude > limit * (1.0 + detail::limit_tolerance));
  const V inv = 1.0 / magnitude, scale = limit / magnitude;
  lost = lane_select(over, lost + limit * (magnitude - limit) / k_T, lost);
  for (int d = 0; d < 3; ++d) {
    t[d] = lane_select(loading_dir | capped, T[d] * inv, t[d]);
    T[d] = lane_select(over, T[d] * scale, T[d]);
  }
  return capped;
}

// The energy balance of the step (§2.4): the work of the mean force over ds plus the stored
// energy goes to dissipation (`lost`, held to [0, what is available]) and the new stored
// energy (>= 0); returns the dissipation
template <class V>
[[gnu::always_inline]] inline V energy_balance(V stored_old, const V T_old[3], const V T[3],
                                               const V ds[3], V lost, V& stored)
{
  const V zero = V(0.0);
  const V available =
      stored_old + 0.5 * ((T_old[0] + T[0]) * ds[0] + (T_old[1] + T[1]) * ds[1] +
                          (T_old[2] + T[2]) * ds[2]);
  const V dissipation = lane_clamp(lost, zero, lane_max(available, zero));
  stored = lane_max(available - dissipation, zero);
  return dissipation;
}

// Where the sliding limit is 0 (§2.3): no tangential force; T, its direction and memory are
// cleared, the contact slides, and the stored tangential energy with the work of this step,
// `released`, is dissipated (returned, >= 0). h keeps its normal part (radius, P_prev).
template <class V>
[[gnu::always_inline]] inline V release_tangential(History<V>& h, V released)
{
  const V zero = V(0.0);
  for (int d = 0; d < 3; ++d) h.T[d] = h.load_dir[d] = zero;
  h.T_star = h.T_star2 = h.peeling = h.stored_energy = zero;
  h.mode = V(double(LOADING));
  h.sliding = V(1.0);
  return lane_max(released, zero);
}

// The tangential law of one step (§2.2, §2.3 steps 3-5, §2.4) from the history `old` (after
// carry) for the increment ds: the new T, its direction and memory, the peeling and sliding
// flags and the stored energy into h; the stiffness k_T and the dissipation into out.
template <bool Adhesive, class V>
[[gnu::always_inline]] inline void tangential_step(const PairConstants& k, V R, const V ds[3],
                                                   const Carry<V>& w, const NormalLoad<V>& load,
                                                   const History<V>& old, History<V>& h,
                                                   Outputs<V>& out)
{
  const V T2_old = dot3(old.T, old.T);
  const Peeling<V> peel = peeling<Adhesive>(k, load, T2_old, old.peeling);
  const V k_T = tangential_stiffness<Adhesive>(k, R, out.a, load, peel);
  LoadingDirection<V> dir = loading_direction(old, T2_old, ds, peel.peeled);
  const auto at_limit = (old.sliding != 0.0) & (old.mode == double(LOADING)) & !dir.fresh;
  // the Masing branch of the increment s along t
  const V limit = k.c.mu * load.effective;
  const V s = dot3(ds, dir.t);
  const V mu_dP = k.c.mu * load.dP;
  const V T_along = lane_select(w.T_magnitude >= 0.0, w.T_magnitude, dot3(old.T, dir.t));
  const SlipDirection<V> slip = slip_direction(k_T * s, mu_dP);
  const MasingBranch<V> branch =
      masing_branch(dir.mode, T_along, old.T_star, old.T_star2, mu_dP, slip);
  const V th = theta(branch, T_along, mu_dP, limit, at_limit);
  // the increment, the end of peeling, back on the loading curve
  const auto micro = !peel.peeled & dir.active;
  V T[3], lost;
  tangential_increment(old.T, ds, dir.t, k_T, s, th, mu_dP, limit, branch.unloading, peel.peeled,
                       micro, T, lost);
  V peeling_flag = peel.flag;
  if (Adhesive) {    // peeling ends where the discriminant vanishes
    const V discriminant_after = peeling_discriminant(k, load.P, load.Pc, dot3(T, T));
    const auto peeling_ends = peel.peeled & (discriminant_after <= 0.0);
    peeling_flag = lane_select(peeling_ends, V(0.0), peeling_flag);
  }
  const V mode = rejoin_loading(T, dir.t, branch, micro, dir.mode);
  const auto capped = coulomb_cap(T, dir.t, load.sliding_limit, k_T, peel.peeled, mode, lost);
  V stored;
  out.dissipation = energy_balance(old.stored_energy, old.T, T, ds, lost, stored);
  out.stiffness = lane_select(peel.peeled, V(-1.0), k_T);

  // the new history; gross sliding clears the memory of the branches
  const V zero = V(0.0);
  for (int d = 0; d < 3; ++d) h.T[d] = T[d], h.load_dir[d] = dir.t[d];
  h.T_star = lane_select(capped, zero, lane_select(micro, branch.T_star, old.T_star));
  h.T_star2 = lane_select(capped, zero, lane_select(micro, branch.T_star2, old.T_star2));
  h.mode = lane_select(capped, V(double(LOADING)), mode);
  h.peeling = lane_select(capped, zero, peeling_flag);
  h.sliding = lane_select(capped, V(1.0), zero);
  h.stored_energy = stored;
}

// Stage 2, one step of the law: the normal force at the radius found (§1.1), then the
// tangential law for the increment ds (tangential_step), or where the sliding limit is 0 its
// outcome release_tangential; h becomes the new history. Frictionless: the material pair has
// mu = 0, so the outcome is known without the tangential law (§2.3): the same values, bit for
// bit, as the full law gives for mu = 0.
template <bool Adhesive, bool Frictionless, class V>
[[gnu::always_inline]] inline Outputs<V> step(const PairConstants& k, V R, V Rinv, V delta,
                                              const V ds[3], const Carry<V>& w, History<V>& h)
{
  const History<V> old = h;
  Outputs<V> out;
  out.P = normal_force<Adhesive>(k, R, Rinv, delta, w, out.a);
  h.radius = out.a;
  h.P_prev = out.P;
  // the stored tangential energy and this step's work, where there is no tangential force
  const V released = old.stored_energy + 0.5 * dot3(old.T, ds);
  History<V> released_h = h;
  const V released_dissipation = release_tangential(released_h, released);
  if (Frictionless) {
    h = released_h;
    out.dissipation = released_dissipation;
    out.stiffness = V(-1.0);
    return out;
  }
  const NormalLoad<V> load = normal_load<Adhesive>(k, R, out.P, old.P_prev);
  tangential_step<Adhesive>(k, R, ds, w, load, old, h, out);
  const auto frictionless = load.sliding_limit <= 0.0;
  h = select_history(frictionless, released_h, h);
  out.dissipation = lane_select(frictionless, released_dissipation, out.dissipation);
  out.stiffness = lane_select(frictionless, V(-1.0), out.stiffness);
  return out;
}

}    // namespace law


}    // namespace tycore

#endif
