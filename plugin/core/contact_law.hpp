// The Thornton-Yin contact law of the pair style, written once over a lane type V: Thornton
// & Yin (1991), Thornton (1991), with the Mindlin-Deresiewicz memory of slip_bands.hpp. Each
// piece is read against one section of docs/theory.md:
//   carry                  the history onto the turned tangent plane, twisted (§2.3 step 1)
//   halley_start, _again,  the JKR contact radius from the overlap: warm-started Halley
//   closed_form_radius     iteration on the quartic in sqrt(a), else the closed form (§1.4)
//   normal_force           the JKR (or Hertz) normal force (§1.1, §1.6)
//   normal_load            P + 2Pc and the sliding limit mu max(P + 2Pc, 0) (§2.2)
//   peeling                stage A, Savkoor-Briggs peeling (§2.2)
//   micro_slip_radius      a_T, the Hertz radius of P + 2Pc, of the memory's contact (§2.2)
//   tangential_stiffness   k_T = 8 G* a_T, the peeling or the micro-slip radius (§2.2)
//   memory_axis            the axis t of the memory of a contact without one (§2.3 step 3)
//   memory_of, store_memory  the memory of the history as slip bands and back (§2.3)
//   micro_slip             stage B: the memory advanced along t, the force across t, the
//                          memory turned with the force (§2.3 steps 3-4, slip_bands.hpp)
//   coulomb_limit          stage C, gross sliding at mu (P + 2Pc) (§2.3 step 5)
//   energy_balance         the memory's energy, the dissipation of the step (§2.4)
//   release_tangential     no tangential force where the sliding limit is 0 (§2.3)
//   tangential_step, step  the step assembled from these
//   snap_on, separates,    the contact's life cycle: first touch, break, its energy (§1.3)
//   break_energy
// The pieces hand their lane masks on in small structs passed by value: a named mask struct
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
#include "slip_bands.hpp"

#include <cmath>
#include <utility>

namespace tycore {

// per material pair, derived once from PairCoefficients (§: sections of docs/theory.md)
struct PairConstants {
  PairCoefficients c;
  double newton_c;          // 2 sqrt(pi Gamma/E*): delta = u^4/R* - newton_c u, u = sqrt(a)
  double adhesive_force;    // 4 sqrt(pi Gamma E*): P = 4E*a^3/(3R*) - adhesive_force a^(3/2)
  double peel_shear;        // E*/(4 G*): the coefficient of T^2 in the peeling discriminant (§2.2)
  double cube_radius_per_load;    // 3/(4E*): a^3 = 3R*P/(4E*) for a Hertz load P (§2.2)
  double slip_slope;              // kappa = mu E*/(4 G*): the springs' limit |u| <= kappa w (§2.3)
};

inline PairConstants pair_constants(const PairCoefficients &c)
{
  PairConstants k;
  k.c = c;
  k.newton_c = 2.0 * std::sqrt(jkr::pi * c.Gamma / c.E_star);
  k.adhesive_force = 4.0 * std::sqrt(jkr::pi * c.Gamma * c.E_star);
  k.peel_shear = savkoor_briggs_shear_factor * c.E_star / c.G_star;
  k.cube_radius_per_load = 3.0 / (4.0 * c.E_star);
  k.slip_slope = c.mu * c.E_star / (4.0 * c.G_star);
  return k;
}

// Savkoor-Briggs discriminant 4 P Pc + 4 Pc^2 - T^2 E*/(4G*) (peeling_discriminant,
// docs/theory.md §2.2) with the shear factor of the pair computed once
template <class V>
[[gnu::always_inline]] inline V peeling_discriminant(const PairConstants &k, V P, V Pc, V T2)
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
  [[gnu::always_inline]] inline History<V> select_history(M m, const History<V> &a,
                                                          const History<V> &b)
  {
    History<V> h;
#define TYCORE_SELECT_FIELD(name, values, carried, from_j, meaning) \
  for (int k = 0; k < values; ++k)                                  \
    history::value(h.name, k) =                                     \
        lane_select(m, history::value(a.name, k), history::value(b.name, k));
    TYCORE_HISTORY_FIELDS(TYCORE_SELECT_FIELD)
#undef TYCORE_SELECT_FIELD
    return h;
  }

  // What the carry stage hands to the law stage: the state of the JKR Halley iteration (a < 0: no
  // radius yet; pending 1: it goes on)
  template <class V> struct Carry {
    V u, f1, f2, step, a, pending;
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
    for (int d = 0; d < 3; ++d)
      x[d] = lane_select(none, x[d], lane_select(flat, zero, p[d] * scale));
  }

  // one Halley step on f(u) = u^4/R* - c u - delta, c = 2 sqrt(pi Gamma/E*) (docs/theory.md §1.4)
  template <class V, class M>
  [[gnu::always_inline]] inline void halley_step(V &u, V &f1, V &f2, V &step, M &slope_positive,
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
  [[gnu::always_inline]] inline void halley_start(const PairConstants &k, V Rinv, V delta, V radius,
                                                  Carry<V> &w)
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

  // Stage 1 (docs/theory.md §2.3 step 1): the history's tangent vectors (T, the memory's axis
  // load_dir, and any other of TYCORE_HISTORY_FIELDS) each onto the tangent plane of n with its
  // magnitude kept, twisted about n by the angle whose cosine and sine are (c, s) where
  // `twisted`; with adhesion the JKR radius from the previous one (halley_start).
  template <bool Adhesive, class V, class M>
  [[gnu::always_inline]] inline void carry(const PairConstants &k, const V n[3], V c, V s,
                                           M twisted, V Rinv, V delta, History<V> &h, Carry<V> &w)
  {
#define TYCORE_CARRY_TANGENT(name, values, carried, from_j, meaning) \
  if constexpr (history::carried != history::kept) {                 \
    keep_magnitude(h.name, n);                                       \
    twist(h.name, n, c, s, twisted);                                 \
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
                                                  Carry<V> &w)
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
  [[gnu::always_inline]] inline void closed_form_radius(const PairCoefficients &c, double R,
                                                        double delta, Carry<double> &w)
  {
    w.a = jkr::contact_radius(delta, R, c.E_star, c.Gamma);
    w.u = std::sqrt(w.a);
  }

  // The normal force (§1.1) at overlap delta, P > 0 repulsive, and the contact radius `a`: JKR at
  // the radius of the iteration (w.a, w.u = sqrt(a)), or Hertz
  template <bool Adhesive, class V>
  [[gnu::always_inline]] inline V normal_force(const PairConstants &k, V R, V Rinv, V delta,
                                               const Carry<V> &w, V &a)
  {
    const PairCoefficients &c = k.c;
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
  [[gnu::always_inline]] inline V hertz_radius_cubed(const PairConstants &k, V R, V load)
  {
    return k.cube_radius_per_load * R * load;
  }

  // a_T^3 = 3R*(P + 2Pc)/(4E*): the Hertz radius of the effective load P + 2Pc, cubed, whose
  // 8 G* a_T is the micro-slip stiffness k_T (§2.2; zero where P + 2Pc <= 0)
  template <class V>
  [[gnu::always_inline]] inline V micro_slip_radius_cubed(const PairConstants &k, V R,
                                                          V effective_load)
  {
    return hertz_radius_cubed(k, R, lane_max(effective_load, V(0.0)));
  }

  // the sliding limit mu max(P + 2Pc, 0) of the effective load P + 2Pc (§2.2 stage C): zero for
  // mu = 0 and for a Hertz contact at zero load, where there is no tangential force (§2.3)
  template <class V>
  [[gnu::always_inline]] inline V sliding_limit(const PairConstants &k, V effective_load)
  {
    return k.c.mu * lane_max(effective_load, V(0.0));
  }

  // ---- the contact's life cycle (docs/theory.md §1.3), contact by contact (both are rare) ----

  // Snap-on: the history of a contact created at overlap delta >= 0 (JKR: the radius jumps to
  // a(delta), (4/9)^(1/3) a0 at delta = 0, the force to P(a); no work is done): no tangential
  // force, peeling if adhesive (begin_contact), the radius the warm start of its first step
  inline ContactHistory snap_on(const PairCoefficients &c, double R, double delta, bool adhesive)
  {
    const double a = adhesive ? jkr::contact_radius(delta, R, c.E_star, c.Gamma)
                              : std::sqrt(R * delta);
    ContactHistory h;
    begin_contact(h, adhesive);
    h.radius = a;
    return h;
  }

  // Break: the contact separates beyond the break overlap, delta < delta_f (JKR under
  // displacement control, §1.2; delta_f = 0 without adhesion). delta_f <= 0: only a tensile
  // contact can break.
  inline bool separates(const PairCoefficients &c, double R, double delta, bool adhesive)
  {
    if (!(delta < 0.0)) return false;
    return delta < (adhesive ? jkr::break_overlap(R, c.E_star, c.Gamma) : 0.0);
  }

  // the elastic energy lost when a contact separates: its stored tangential energy and the JKR
  // energy at the break radius a_f (§1.7, §3.2)
  inline double break_energy(const PairCoefficients &c, double R, const ContactHistory &h,
                             bool adhesive)
  {
    double stored = h.stored_energy;
    if (adhesive) {
      const double a_break =
          jkr::contact_radius(jkr::break_overlap(R, c.E_star, c.Gamma), R, c.E_star, c.Gamma);
      stored += jkr::stored_energy(a_break, R, c.E_star, c.Gamma);
    }
    return stored;
  }

  // ---- one step of the tangential law, piece by piece (docs/theory.md §2) ----

  // The normal load as the tangential law sees it (§2.2): the JKR force P, the pull-off force
  // Pc = 3 pi Gamma R* (0 without adhesion), the effective load P + 2Pc on which micro-slip and
  // sliding act, and the sliding limit mu max(P + 2Pc, 0)
  template <class V> struct NormalLoad {
    V P, Pc, effective, sliding_limit;
  };

  template <bool Adhesive, class V>
  [[gnu::always_inline]] inline NormalLoad<V> normal_load(const PairConstants &k, V R, V P)
  {
    NormalLoad<V> load;
    load.P = P;
    load.Pc = Adhesive ? V(jkr::pull_off_force(k.c.Gamma, 1.0)) * R : V(0.0);
    load.effective = P + 2.0 * load.Pc;
    load.sliding_limit = sliding_limit(k, load.effective);
    return load;
  }

  // Stage A, Savkoor-Briggs peeling (§2.2): a contact still peeling (its flag set; adhesive
  // contacts start so) peels on this step while the discriminant 4PPc + 4Pc^2 - T^2 E*/(4G*) of
  // its force T is positive; where the discriminant is no longer positive, peeling is over.
  template <class V> struct Peeling {
    Mask<V> peeled;    // this step is a peeling step
    V discriminant;    // of the force before the step
    V flag;            // the peeling flag after the step
  };

  template <bool Adhesive, class V>
  [[gnu::always_inline]] inline Peeling<V> peeling(const PairConstants &k,
                                                   const NormalLoad<V> &load, V T2, V flag)
  {
    const V zero = V(0.0);
    Peeling<V> p;
    p.discriminant = peeling_discriminant(k, load.P, load.Pc, T2);
    const auto was_peeling = Adhesive ? flag != 0.0 : zero != zero;
    p.peeled = was_peeling & (p.discriminant > 0.0);
    p.flag = lane_select(was_peeling & !p.peeled, zero, flag);
    return p;
  }

  // The micro-slip radius a_T (§2.2): the Hertz radius of the effective load P + 2Pc
  // (micro_slip_radius_cubed); without adhesion the contact radius a itself (§2.1). The memory's
  // springs live on the effective Hertz contact of radius a_T and overlap a_T^2/R* (§2.3).
  template <bool Adhesive, class V>
  [[gnu::always_inline]] inline V micro_slip_radius(const PairConstants &k, V R, V a,
                                                    const NormalLoad<V> &load)
  {
    if (!Adhesive) return a;
    return simd_cbrt(micro_slip_radius_cubed(k, R, load.effective));
  }

  // The tangential stiffness k_T = 8 G* a_T of the step (§2.2): a_T of the peeling contact,
  // 4E*a_T^3/(3R*) = P + 2Pc + sqrt(discriminant), or after peeling the micro-slip radius
  template <bool Adhesive, class V>
  [[gnu::always_inline]] inline V tangential_stiffness(const PairConstants &k, V R, V a_T,
                                                       const NormalLoad<V> &load, Peeling<V> p)
  {
    if (!Adhesive) return 8.0 * k.c.G_star * a_T;
    const V peeling_cubed = hertz_radius_cubed(k, R, load.effective + std::sqrt(p.discriminant));
    return 8.0 * k.c.G_star * lane_select(p.peeled, simd_cbrt(peeling_cubed), a_T);
  }

  // The memory's axis t (§2.3 step 3): kept once chosen; a contact without one (not while
  // peeling) takes it along its force T, or else along the increment ds. `active`: the contact
  // has an axis after the step.
  template <class V> struct MemoryAxis {
    V t[3];
    Mask<V> active;
  };

  template <class V>
  [[gnu::always_inline]] inline MemoryAxis<V> memory_axis(const V old_t[3], const V T_old[3],
                                                          const V ds[3], Mask<V> peeled)
  {
    MemoryAxis<V> axis;
    const V T2 = dot3(T_old, T_old), s2 = dot3(ds, ds);
    const auto has_axis = dot3(old_t, old_t) != 0.0;
    const auto fresh = !has_axis & !peeled & ((T2 > 0.0) | (s2 > 0.0));
    const V inv_T = 1.0 / std::sqrt(T2), inv_s = 1.0 / std::sqrt(s2);
    for (int i = 0; i < 3; ++i) {
      const V along_T_or_ds = lane_select(T2 > 0.0, T_old[i] * inv_T, ds[i] * inv_s);
      axis.t[i] = lane_select(fresh, along_T_or_ds, old_t[i]);
    }
    axis.active = has_axis | fresh;
    return axis;
  }

  // The memory of the history h as a profile of bands, and back (the history's band fields,
  // TYCORE_HISTORY_FIELDS)
  template <class V> [[gnu::always_inline]] inline bands::Profile<V> memory_of(const History<V> &h)
  {
    bands::Profile<V> p;
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j)
      p.outer[j] = h.band_outer[j], p.inner[j] = h.band_inner[j], p.depth[j] = h.band_depth[j];
    return p;
  }

  template <class V>
  [[gnu::always_inline]] inline void store_memory(History<V> &h, const bands::Profile<V> &p)
  {
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j)
      h.band_outer[j] = p.outer[j], h.band_inner[j] = p.inner[j], h.band_depth[j] = p.depth[j];
  }

  // Stage B, micro-slip (§2.3 steps 3-4): the memory along the axis t takes the step to the
  // effective overlap with the increment s = ds.t (slip_bands.hpp: exact Mindlin-Deresiewicz for
  // any history along t); the increment across t meets the no-slip stiffness k_T, and the force
  // then turns the memory with it: its slopes are raised by the ratio the turn added, at most to
  // the limit (§2.3 step 4). Returns the new T; t becomes its direction (sense kept).
  template <class V>
  [[gnu::always_inline]] inline void micro_slip(bands::Profile<V> &p, V t[3], V overlap,
                                                const V ds[3], V k_T, V limit, double kappa, V T[3])
  {
    const V inv_t = 1.0 / std::sqrt(dot3(t, t));    // unit (carried step after step, it drifts)
    const auto has_axis = inv_t < 1e300;
    for (int d = 0; d < 3; ++d) t[d] = lane_select(has_axis, t[d] * inv_t, t[d]);
    const V s = dot3(ds, t);
    bands::advance(p, overlap, s, kappa);
    const auto weights = bands::band_weights(p, overlap);
    const V along = limit * bands::force_ratio(p, weights);
    V across[3], Tv[3];
    for (int d = 0; d < 3; ++d) across[d] = k_T * (ds[d] - s * t[d]);
    for (int d = 0; d < 3; ++d) Tv[d] = along * t[d] + across[d];
    const V magnitude = std::sqrt(along * along + dot3(across, across));
    const V sense = lane_select(along < 0.0, V(-1.0), V(1.0));
    const V raised = sense * (magnitude - std::abs(along)) / limit;
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j) {
      p.outer[j] = lane_clamp(p.outer[j] + raised, V(-1.0), V(1.0));
      p.inner[j] = lane_clamp(p.inner[j] + raised, V(-1.0), V(1.0));
    }
    const V turned = limit * bands::force_ratio(p, weights);
    const V inv = sense / magnitude;
    const auto turns = magnitude > 0.0;
    for (int d = 0; d < 3; ++d) {
      t[d] = lane_select(turns, Tv[d] * inv, t[d]);
      T[d] = turned * t[d];
    }
  }

  // Stage C (§2.3 step 5): the contact slides where its force is at the limit mu (P + 2Pc)
  // (within a few ulps): its memory is one band at the limit along T, the axis T/|T|. A
  // peeling force beyond the limit is brought back onto it. Returns where it slides.
  template <class V>
  [[gnu::always_inline]] inline Mask<V> coulomb_limit(bands::Profile<V> &p, V T[3], V t[3], V limit,
                                                      V overlap)
  {
    const V magnitude = std::sqrt(dot3(T, T));
    const auto at_limit = magnitude >= limit * (1.0 - detail::limit_tolerance);
    const auto over = magnitude > limit * (1.0 + detail::limit_tolerance);
    const V inv = 1.0 / magnitude, scale = limit / magnitude;
    bands::Profile<V> slides;
    bands::sliding(slides, overlap, V(1.0));
    for (int d = 0; d < 3; ++d) {
      t[d] = lane_select(at_limit, T[d] * inv, t[d]);
      T[d] = lane_select(over, T[d] * scale, T[d]);
    }
    p = bands::select(at_limit, slides, p);
    return at_limit;
  }

  // The energy of the step (§2.4): the stored tangential energy after it (the elastic energy of
  // the memory's tractions, 4 G* kappa^2 int phi^2 dx, where the memory holds the force; the
  // stored energy and the work of the step while peeling) and the dissipation, the work of the
  // mean force over ds less the change of stored energy (>= 0)
  template <class V>
  [[gnu::always_inline]] inline V energy_balance(V stored_old, const V T_old[3], const V T[3],
                                                 const V ds[3], Mask<V> by_memory, V memory_energy,
                                                 V &stored)
  {
    const V work =
        0.5 * ((T_old[0] + T[0]) * ds[0] + (T_old[1] + T[1]) * ds[1] + (T_old[2] + T[2]) * ds[2]);
    const V available = stored_old + work;
    stored = lane_select(by_memory, memory_energy, lane_max(available, V(0.0)));
    return lane_max(available - stored, V(0.0));
  }

  // Where the sliding limit is 0 (§2.3): no tangential force; T, its direction and memory are
  // cleared, the contact slides, and the stored tangential energy with the work of this step,
  // `released`, is dissipated (returned, >= 0). h keeps its normal part (radius).
  template <class V> [[gnu::always_inline]] inline V release_tangential(History<V> &h, V released)
  {
    const V zero = V(0.0);
    for (int d = 0; d < 3; ++d) h.T[d] = h.load_dir[d] = zero;
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j)
      h.band_outer[j] = h.band_inner[j] = h.band_depth[j] = zero;
    h.peeling = h.stored_energy = zero;
    h.sliding = V(1.0);
    return lane_max(released, zero);
  }

  // The tangential law of one step (§2.2, §2.3 steps 3-5, §2.4) from the history `old` (after
  // carry) for the increment ds: the new T, the memory's axis and bands, the peeling and sliding
  // flags and the stored energy into h; the stiffness k_T and the dissipation into out.
  template <bool Adhesive, class V>
  [[gnu::always_inline]] inline void
  tangential_step(const PairConstants &k, V R, const V ds[3], const NormalLoad<V> &load,
                  const History<V> &old, History<V> &h, Outputs<V> &out)
  {
    const V zero = V(0.0);
    const V limit = load.sliding_limit;
    const Peeling<V> peel = peeling<Adhesive>(k, load, dot3(old.T, old.T), old.peeling);
    const V a_T = micro_slip_radius<Adhesive>(k, R, out.a, load);
    const V k_T = tangential_stiffness<Adhesive>(k, R, a_T, load, peel);
    const V overlap = a_T * a_T / R;    // of the effective Hertz contact (§2.3)
    MemoryAxis<V> axis = memory_axis(old.load_dir, old.T, ds, peel.peeled);
    bands::Profile<V> memory = memory_of(old);
    // stage A: the peeling contact is elastic; stage B: the memory where it holds the force
    V T_micro[3];
    bands::Profile<V> slipped = memory;
    micro_slip(slipped, axis.t, overlap, ds, k_T, limit, k.slip_slope, T_micro);
    V T[3];
    for (int d = 0; d < 3; ++d) T[d] = lane_select(peel.peeled, old.T[d] + k_T * ds[d], T_micro[d]);
    memory = bands::select(peel.peeled, memory, slipped);
    // peeling ends where the discriminant vanishes: the memory of Mindlin & Deresiewicz's first
    // loading to the force reached (§2.2), along T
    V peeling_flag = peel.flag;
    auto by_memory = !peel.peeled;
    if (Adhesive) {
      const V T_size = std::sqrt(dot3(T, T));
      const V left = peeling_discriminant(k, load.P, load.Pc, T_size * T_size);
      const auto ends = peel.peeled & (left <= 0.0);
      peeling_flag = lane_select(ends, zero, peeling_flag);
      bands::Profile<V> first;
      bands::first_loading(first, overlap, lane_clamp(T_size / limit, zero, V(1.0)));
      memory = bands::select(ends, first, memory);
      const V inv = 1.0 / T_size;
      const auto along_T = ends & (T_size > 0.0);
      for (int d = 0; d < 3; ++d) axis.t[d] = lane_select(along_T, T[d] * inv, axis.t[d]);
      by_memory = by_memory | ends;
    }
    const auto slides = coulomb_limit(memory, T, axis.t, limit, overlap);
    by_memory = by_memory | slides;
    const V memory_energy =
        4.0 * k.c.G_star * k.slip_slope * k.slip_slope * bands::energy_factor(memory, overlap, R);
    V stored;
    out.dissipation =
        energy_balance(old.stored_energy, old.T, T, ds, by_memory, memory_energy, stored);
    out.stiffness = lane_select(peel.peeled, V(-1.0), k_T);

    // the new history; a contact without an axis keeps none
    for (int d = 0; d < 3; ++d)
      h.T[d] = T[d], h.load_dir[d] = lane_select(axis.active | slides, axis.t[d], zero);
    store_memory(h, memory);
    h.peeling = lane_select(slides, zero, peeling_flag);
    h.sliding = lane_select(slides, V(1.0), zero);
    h.stored_energy = stored;
  }

  // Stage 2, one step of the law: the normal force at the radius found (§1.1), then the
  // tangential law for the increment ds (tangential_step), or where the sliding limit is 0 its
  // outcome release_tangential; h becomes the new history. Frictionless: the material pair has
  // mu = 0, so the outcome is known without the tangential law (§2.3): the same values, bit for
  // bit, as the full law gives for mu = 0.
  template <bool Adhesive, bool Frictionless, class V>
  [[gnu::always_inline]] inline Outputs<V> step(const PairConstants &k, V R, V Rinv, V delta,
                                                const V ds[3], const Carry<V> &w, History<V> &h)
  {
    const History<V> old = h;
    Outputs<V> out;
    out.P = normal_force<Adhesive>(k, R, Rinv, delta, w, out.a);
    h.radius = out.a;
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
    const NormalLoad<V> load = normal_load<Adhesive>(k, R, out.P);
    tangential_step<Adhesive>(k, R, ds, load, old, h, out);
    const auto frictionless = load.sliding_limit <= 0.0;
    h = select_history(frictionless, released_h, h);
    out.dissipation = lane_select(frictionless, released_dissipation, out.dissipation);
    out.stiffness = lane_select(frictionless, V(-1.0), out.stiffness);
    return out;
  }

}    // namespace law

}    // namespace tycore

#endif
