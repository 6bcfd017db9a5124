// The vector builds of tycore::advance_batch (contact_batch.hpp): the law of contact_kernel.hpp
// over the lanes of a ContactBatch, one loop per stage, each loop body branch-free so that GCC
// turns it into SIMD code (every `c ? x : y` a lane select, every stage computed for all lanes
// and the lane's own result kept). The same body is compiled three times, for SSE2 (every
// x86-64), AVX2 and AVX-512; advance_batch picks one at run time (best_isa).
//
// What does not vectorise runs lane by lane where it is rare: first touch and separation
// (detail::touch_or_break), cos/sin of a twist above 1e-3 rad, the JKR closed form where the
// warm-started Halley iteration does not converge (first steps, large jumps).
//
// The loops have a fixed trip count (batch_lanes) and no branches, local arrays only of
// constant index, bools combined by & and | (not && and ||, which GCC keeps as control flow),
// so that GCC's auto-vectoriser takes them whole (check: -fopt-info-vec). Compiled with
// -fno-trapping-math (the loops compute divisions whose lanes are then not selected; without
// it GCC keeps such code in branches), -ffp-contract=off (no fused multiply-add: the scalar
// kernel's roundings, so that both builds agree to the bit), -fno-tree-pre and
// -fno-thread-jumps (both otherwise rewrite comparisons of selected values into selects of
// masks that GCC 12 does not vectorise); CMakeLists.txt sets them for this file alone. With
// them every lane loop here vectorises in all three builds; the loops that stay scalar are
// the rare-case ones named above.
#include "contact_batch.hpp"

#include "contact_kernel.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"
#include "simd_math.hpp"

#include <algorithm>
#include <cmath>

namespace tycore {

namespace {

constexpr int L = batch_lanes;
constexpr double loading = LOADING, unloading = UNLOADING, reloading = RELOADING;

// the per-lane state one loop of the step hands to the next
struct Carry {
  alignas(64) double tw_c[L], tw_s[L];    // cos and sin of the twist
  alignas(64) double T_magnitude[L];      // |T| from the rotation, else -1 (StepState)
  alignas(64) double u[L];                // sqrt(a) of the Halley iteration
  alignas(64) double f1[L], f2[L], step[L];    // its last f', f'' and step
  alignas(64) double a[L];                // JKR radius, -1 until found
  alignas(64) double pending[L];          // 1: the Halley iteration goes on
};

using detail::lane_outputs;

// x -> cos(t) x + sin(t) n x x (detail::twist_vector), kept as is where the twist is 0
[[gnu::always_inline]] inline void twist_lane(double x[3], const double n[3], double c, double s,
                                              bool twisted)
{
  const double x0 = x[0], x1 = x[1], x2 = x[2];
  const double y0 = c * x0 + s * (n[1] * x2 - n[2] * x1);
  const double y1 = c * x1 + s * (n[2] * x0 - n[0] * x2);
  const double y2 = c * x2 + s * (n[0] * x1 - n[1] * x0);
  x[0] = twisted ? y0 : x0;
  x[1] = twisted ? y1 : x1;
  x[2] = twisted ? y2 : x2;
}

[[gnu::always_inline]] inline double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// x onto the tangent plane, magnitude kept (detail::project_keep_magnitude)
[[gnu::always_inline]] inline void keep_magnitude_lane(double x[3], const double n[3])
{
  const double magnitude2 = dot3(x, x);
  const double along = dot3(x, n);
  double p[3] = {x[0] - along * n[0], x[1] - along * n[1], x[2] - along * n[2]};
  const double in_plane2 = dot3(p, p);
  const double scale = std::sqrt(magnitude2 / in_plane2);
  const double y[3] = {in_plane2 == 0.0 ? 0.0 : p[0] * scale, in_plane2 == 0.0 ? 0.0 : p[1] * scale,
                       in_plane2 == 0.0 ? 0.0 : p[2] * scale};
  x[0] = magnitude2 == 0.0 ? x[0] : y[0];
  x[1] = magnitude2 == 0.0 ? x[1] : y[1];
  x[2] = magnitude2 == 0.0 ? x[2] : y[2];
}

// one Halley step on f(u) = u^4/R - c u - delta (normal_force_step's halley_step, §1.4)
[[gnu::always_inline]] inline void halley_lane(double& u, double& f1, double& f2, double& step,
                                               bool& slope_positive, double Rinv, double newton_c,
                                               double delta)
{
  const double u2 = u * u;
  const double f = u2 * u2 * Rinv - newton_c * u - delta;
  f1 = 4.0 * u2 * u * Rinv - newton_c;
  slope_positive = slope_positive & (f1 > 0.0);
  f2 = 12.0 * u2 * Rinv;
  step = 2.0 * f * f1 / (2.0 * f1 * f1 - f * f2);
  u -= step;
}

// normal_force_step's convergence test of the iterate after `step`
[[gnu::always_inline]] inline bool halley_converged(double u, double f1, double f2, double step,
                                                    double Rinv)
{
  const double step3 = std::abs(step * step * step);
  return 4.0 * std::abs(0.25 * f2 * f2 - 4.0 * u * Rinv * f1) * step3 <= 1e-14 * u * f1 * f1;
}

// Stage 1 of every lane: the history onto the new tangent plane (carry_history) and, with
// adhesion, the first two Halley steps and the first convergence test (normal_force_step).
// (Every loop body below reads its inputs before any select and takes the constants by value:
// a load under a condition may fault, and GCC would keep it in a branch.)
template <bool Adhesive>
[[gnu::always_inline]] inline void carry_stage(ContactBatch& b, const PairConstants k, double dt,
                                               Carry& w)
{

  for (int i = 0; i < L; ++i) {
    const double n[3] = {b.n[0][i], b.n[1][i], b.n[2][i]};
    const bool twisted = 0.5 * dt * b.spin_n[i] != 0.0;    // twist != 0, as carry_history
    const double c = w.tw_c[i], s = w.tw_s[i];
    double T[3] = {b.T[0][i], b.T[1][i], b.T[2][i]};
    double dir[3] = {b.dir[0][i], b.dir[1][i], b.dir[2][i]};
    const double mode = b.mode[i], radius = b.radius[i], Rinv = b.Rinv[i], delta = b.delta[i];
    const double T2_before = dot3(T, T);
    const bool dir_follows_T = (mode == loading) & (T2_before > 0.0) & (dot3(dir, dir) > 0.0);
    // loading branch: load_dir = T/|T|, project once
    const double along = dot3(T, n);
    double q[3] = {T[0] - along * n[0], T[1] - along * n[1], T[2] - along * n[2]};
    const double in_plane2 = dot3(q, q);
    const double inv = 1.0 / std::sqrt(in_plane2);
    q[0] *= inv, q[1] *= inv, q[2] *= inv;
    twist_lane(q, n, c, s, twisted);
    const double magnitude = std::sqrt(T2_before);
    const bool kept = in_plane2 > 0.0;
    // otherwise each vector on its own
    keep_magnitude_lane(T, n);
    twist_lane(T, n, c, s, twisted);
    keep_magnitude_lane(dir, n);
    twist_lane(dir, n, c, s, twisted);
#pragma GCC unroll 3
    for (int d = 0; d < 3; ++d) {
      b.T[d][i] = dir_follows_T ? (kept ? magnitude * q[d] : 0.0) : T[d];
      b.dir[d][i] = dir_follows_T ? (kept ? q[d] : 0.0) : dir[d];
    }
    w.T_magnitude[i] = dir_follows_T & kept ? magnitude : -1.0;

    if (Adhesive) {    // Halley from the previous radius; a < 0: not (yet) found
      const bool has_guess = radius > 0.0;
      double u = std::sqrt(has_guess ? radius : 1.0);
      double f1 = 0.0, f2 = 0.0, step = 0.0;
      bool slope_positive = true;
      halley_lane(u, f1, f2, step, slope_positive, Rinv, k.newton_c, delta);
      halley_lane(u, f1, f2, step, slope_positive, Rinv, k.newton_c, delta);
      const bool go_on = has_guess & slope_positive;
      const bool converged = go_on & halley_converged(u, f1, f2, step, Rinv);
      w.a[i] = converged ? u * u : -1.0;
      // not converged: the next step now (the scalar loop's it = 2)
      double u_next = u, f1_next = f1, f2_next = f2, step_next = step;
      bool slope_next = slope_positive;
      halley_lane(u_next, f1_next, f2_next, step_next, slope_next, Rinv, k.newton_c, delta);
      const bool stepped = go_on & !converged;
      w.u[i] = stepped ? u_next : u;
      w.f1[i] = stepped ? f1_next : f1;
      w.f2[i] = stepped ? f2_next : f2;
      w.step[i] = stepped ? step_next : step;
      w.pending[i] = stepped & slope_next ? 1.0 : 0.0;
    }
  }
}

// the rest of the Halley iteration where a lane needs it: tests at it = 3 .. 6 of the scalar
// loop, a step after each failed test but the last
[[gnu::always_inline]] inline void halley_rest(ContactBatch& b, int n, const double newton_c, Carry& w)
{
  for (int it = 3; it <= 6; ++it) {
    bool any = false;
    for (int i = 0; i < n; ++i) any |= w.pending[i] != 0.0;
    if (!any) return;
    const bool last = it == 6;

    for (int i = 0; i < L; ++i) {
      const bool pending = w.pending[i] != 0.0;
      const double u0 = w.u[i], f10 = w.f1[i], f20 = w.f2[i], step0 = w.step[i], a0 = w.a[i];
      const double Rinv = b.Rinv[i], delta = b.delta[i];
      const bool converged = pending & halley_converged(u0, f10, f20, step0, Rinv);
      w.a[i] = converged ? u0 * u0 : a0;
      double u = u0, f1 = f10, f2 = f20, step = step0;
      bool slope_positive = true;
      halley_lane(u, f1, f2, step, slope_positive, Rinv, newton_c, delta);
      const bool stepped = pending & !converged & !last;
      w.u[i] = stepped ? u : u0;
      w.f1[i] = stepped ? f1 : f10;
      w.f2[i] = stepped ? f2 : f20;
      w.step[i] = stepped ? step : step0;
      w.pending[i] = stepped & slope_positive ? 1.0 : 0.0;
    }
  }
}

// Stage 2 of every lane: the normal force and the tangential law (begin_tangential,
// stiffness_of, slip_decision, theta_of, finish_step), then lane_outputs. Frictionless: the
// batch's material pair has mu = 0, so every lane's sliding limit mu (P + 2Pc) is 0 and the
// law's outcome is known without the tangential law: T and its memory cleared, sliding, the
// stored energy released (docs/theory.md §2.3); the same values, bit for bit, as the full
// stage gives for mu = 0.
template <bool Adhesive, bool Damped, bool Tally, bool Frictionless>
[[gnu::always_inline]] inline void law_stage(ContactBatch& b, const PairConstants k,
                                             const BatchParameters p, const Carry& w)
{
  const PairCoefficients c = k.c;
  const double dt = p.dt;

  for (int i = 0; i < L; ++i) {
    const bool gone = b.broken[i] != 0.0;
    const double R = b.R[i], Rinv = b.Rinv[i], delta = b.delta[i];
    const double ds[3] = {-b.vt[0][i] * dt, -b.vt[1][i] * dt, -b.vt[2][i] * dt};
    const double T_old[3] = {b.T[0][i], b.T[1][i], b.T[2][i]};
    const double dir_old[3] = {b.dir[0][i], b.dir[1][i], b.dir[2][i]};
    const double P_prev = b.P_prev[i], mode_old = b.mode[i], peeling_old = b.peeling[i];
    const double T_star_old = b.T_star[i], T_star2_old = b.T_star2[i];
    const double stored_old = b.stored_energy[i];
    const bool was_sliding = b.sliding[i] != 0.0;
    const double T_magnitude = w.T_magnitude[i], a_found = w.a[i], u = w.u[i];

    // normal force (normal_force_step)
    double a, P;
    if (Adhesive) {
      a = a_found;
      P = 4.0 * c.E_star * (a * a * a) * Rinv * (1.0 / 3.0) - k.adhesive_force * (a * u);
    } else {
      const double compression = lane_max(delta, 0.0);
      a = std::sqrt(R * compression);
      P = (4.0 / 3.0) * c.E_star * a * compression;
    }

    if (Frictionless) {
      const double released = stored_old + 0.5 * dot3(T_old, ds);
#pragma GCC unroll 3
      for (int d = 0; d < 3; ++d) b.T[d][i] = b.dir[d][i] = 0.0;
      b.T_star[i] = b.T_star2[i] = 0.0;
      b.mode[i] = loading;
      b.peeling[i] = 0.0;
      b.sliding[i] = gone ? 0.0 : 1.0;
      b.P_prev[i] = gone ? 0.0 : P;
      b.stored_energy[i] = 0.0;
      b.radius[i] = gone ? 0.0 : a;
      b.P[i] = gone ? 0.0 : P;
      b.contact_radius[i] = gone ? 0.0 : a;
      b.dissipation[i] = gone ? 0.0 : 0.0 + lane_max(released, 0.0);
      lane_outputs<Adhesive, Damped, Tally>(b, i, c, p, -1.0);
      continue;
    }

    // begin_tangential
    const double Pc = Adhesive ? jkr::pull_off_force(c.Gamma, R) : 0.0;
    const double effective_load = P + 2.0 * Pc;
    const double dP = P - P_prev;
    const double sliding_limit = c.mu * lane_max(effective_load, 0.0);
    const bool frictionless = sliding_limit <= 0.0;
    const double T2_old = dot3(T_old, T_old);
    // stage A, Savkoor-Briggs peeling (docs/theory.md §2.2)
    const double before = peeling_discriminant(k, P, Pc, T2_old);
    const bool tried_peeling = Adhesive & (peeling_old != 0.0);
    const bool peeled = tried_peeling & (before > 0.0);
    double peeling = tried_peeling & !peeled ? 0.0 : peeling_old;
    double stiffness;
    if (Adhesive) {    // stiffness_of: k_T = 8G* a_T, a_T^3 peeled or from P + 2Pc
      const double cubed = peeled
          ? k.cube_radius_per_load * R * (P + 2.0 * Pc + std::sqrt(before))
          : k.cube_radius_per_load * R * lane_max(effective_load, 0.0);
      stiffness = 8.0 * c.G_star * simd_cbrt(cubed);
    } else {
      stiffness = 8.0 * c.G_star * a;
    }

    // slip_decision: the loading direction where there is none yet
    bool at_limit = was_sliding & (mode_old == loading);
    const bool needs_dir = dot3(dir_old, dir_old) == 0.0;
    const double s2 = dot3(ds, ds);
    const double inv_T = 1.0 / std::sqrt(T2_old), inv_s = 1.0 / std::sqrt(s2);
    const bool active = !needs_dir | (T2_old > 0.0) | (s2 > 0.0);
    const bool new_dir = needs_dir & active & !peeled;
    double dir[3];
#pragma GCC unroll 3
    for (int d = 0; d < 3; ++d) {
      const double fresh = T2_old > 0.0 ? T_old[d] * inv_T : ds[d] * inv_s;
      dir[d] = new_dir ? fresh : dir_old[d];
    }
    const double mode_start = new_dir ? loading : mode_old;
    at_limit = at_limit & !new_dir;
    // the Masing branch of this increment (docs/theory.md §2.1)
    const double limit = c.mu * effective_load;
    const double s = dot3(ds, dir);
    const double ks = stiffness * s;
    const double mu_dP = c.mu * dP;
    const double T_projected = dot3(T_old, dir);
    const double T_along = T_magnitude >= 0.0 ? T_magnitude : T_projected;
    const bool was_unloading = mode_start == unloading;
    const bool forward = ks > mu_dP, backward = ks < -mu_dP;
    const bool to_unloading = !was_unloading & !forward & backward;
    const bool to_reloading = was_unloading & !backward & forward;
    const double mode = to_unloading ? unloading : (to_reloading ? reloading : mode_start);
    const double T_star = (to_unloading ? T_along : T_star_old) + mu_dP;
    const double T_star2 = (to_reloading ? T_along : T_star2_old) - mu_dP;
    const bool slipping = forward | backward;
    const double branch_term =
        mode == unloading ? T_star - T_along
                          : (mode == reloading ? T_along - T_star2 : 2.0 * T_along);
    const double t3 = 1.0 - (branch_term + 2.0 * mu_dP) / (2.0 * limit);
    const bool on_slip_branch = slipping & !((mode == loading) & at_limit);
    const double theta_cubed = on_slip_branch ? lane_clamp(t3, 0.0, 1.0) : 0.0;
    // theta_of
    const double root = simd_cbrt(theta_cubed);
    const double theta = !slipping ? 1.0 : (theta_cubed > 0.0 ? root : 0.0);

    // finish_step: the micro-slip increment, or the peeled elastic one
    const bool micro = !peeled & active;
    const double sign = mode == unloading ? -1.0 : 1.0;
    const double dT_par = theta * ks + sign * mu_dP * (1.0 - theta);
    const double annulus = 0.0 + detail::annulus_dissipation_rate(limit, theta) * std::abs(s);
    double lost = micro ? annulus : 0.0;
    const double along = dT_par - stiffness * s;
    double T[3];
#pragma GCC unroll 3
    for (int d = 0; d < 3; ++d) {
      const double slipped = T_old[d] + (along * dir[d] + stiffness * ds[d]);
      const double elastic = T_old[d] + stiffness * ds[d];
      T[d] = peeled ? elastic : (micro ? slipped : T_old[d]);
    }
    if (Adhesive) {
      const bool peeling_ends = peeled & (peeling_discriminant(k, P, Pc, dot3(T, T)) <= 0.0);
      peeling = peeling_ends ? 0.0 : peeling;
    }
    // back on the virgin curve: unloading past -T* (direction reversed), reloading past T*
    const double T_after = dot3(T, dir);
    const bool reversed = micro & (mode == unloading) & (T_after <= -T_star);
    const bool rejoined = micro & (mode == reloading) & (T_after >= T_star);
    const double flip = reversed ? -1.0 : 1.0;
    dir[0] *= flip, dir[1] *= flip, dir[2] *= flip;
    const double mode_after = micro ? ((reversed | rejoined) ? loading : mode) : mode_start;
    // one |T| for the loading direction and the Coulomb cap (stage C)
    const double magnitude = std::sqrt(dot3(T, T));
    const bool loading_dir = !peeled & (mode_after == loading) & (magnitude > 0.0);
    const bool capped = magnitude >= sliding_limit * (1.0 - detail::limit_tolerance);
    const bool over = capped & (magnitude > sliding_limit * (1.0 + detail::limit_tolerance));
    const double inv = 1.0 / magnitude, scale = sliding_limit / magnitude;
    const double slid = lost + sliding_limit * (magnitude - sliding_limit) / stiffness;
    lost = over ? slid : lost;
#pragma GCC unroll 3
    for (int d = 0; d < 3; ++d) {
      dir[d] = (loading_dir | capped) ? T[d] * inv : dir[d];
      T[d] = over ? T[d] * scale : T[d];
    }
    const double available =
        stored_old + 0.5 * ((T_old[0] + T[0]) * ds[0] + (T_old[1] + T[1]) * ds[1] +
                            (T_old[2] + T[2]) * ds[2]);
    const double kept_lost = lane_clamp(lost, 0.0, lane_max(available, 0.0));
    const double stored = lane_max(available - kept_lost, 0.0);
    // frictionless, or a Hertz contact at zero load: T and its memory go, stored energy lost
    const double released = stored_old + 0.5 * dot3(T_old, ds);

    // the new history (a broken lane: cleared) and the law's outputs
    const bool reset = frictionless | gone;
#pragma GCC unroll 3
    for (int d = 0; d < 3; ++d) {
      b.T[d][i] = reset ? 0.0 : T[d];
      b.dir[d][i] = reset ? 0.0 : dir[d];
    }
    const bool memory_cleared = frictionless | capped;
    b.T_star[i] = gone | memory_cleared ? 0.0 : (micro ? T_star : T_star_old);
    b.T_star2[i] = gone | memory_cleared ? 0.0 : (micro ? T_star2 : T_star2_old);
    b.mode[i] = gone | memory_cleared ? loading : mode_after;
    b.peeling[i] = gone | memory_cleared ? 0.0 : peeling;
    b.sliding[i] = gone ? 0.0 : (memory_cleared ? 1.0 : 0.0);
    b.P_prev[i] = gone ? 0.0 : P;
    b.stored_energy[i] = reset ? 0.0 : stored;
    b.radius[i] = gone ? 0.0 : a;
    b.P[i] = gone ? 0.0 : P;
    b.contact_radius[i] = gone ? 0.0 : a;
    const double friction_loss = frictionless ? 0.0 + lane_max(released, 0.0) : 0.0 + kept_lost;
    b.dissipation[i] = gone ? 0.0 : friction_loss;
    lane_outputs<Adhesive, Damped, Tally>(b, i, c, p, (frictionless | peeled) ? -1.0 : stiffness);
  }
}

template <bool Adhesive, bool Damped>
[[gnu::always_inline]] inline void vector_batch(ContactBatch& b, int n, const PairConstants& k,
                                                const BatchParameters& p)
{
  detail::touch_or_break<Adhesive>(b, n, k);
  Carry w;
  // cos and sin of the twist: the Taylor terms of detail::twist_cos_sin lane-wide, libm where
  // |twist| >= 1e-3 rad

  for (int i = 0; i < L; ++i) {
    const double twist = 0.5 * p.dt * b.spin_n[i];
    const double t2 = twist * twist;
    w.tw_c[i] = 1.0 - t2 * (0.5 - t2 * (1.0 / 24.0));
    w.tw_s[i] = twist * (1.0 - t2 * (1.0 / 6.0 - t2 * (1.0 / 120.0)));
  }
  for (int i = 0; i < n; ++i) {
    const double twist = 0.5 * p.dt * b.spin_n[i];
    if (std::abs(twist) >= 1e-3) detail::twist_cos_sin(twist, w.tw_c[i], w.tw_s[i]);
  }
  carry_stage<Adhesive>(b, k, p.dt, w);
  if (Adhesive) {
    halley_rest(b, n, k.newton_c, w);
    // no warm start, no convergence: the closed form (jkr::contact_radius)
    for (int i = 0; i < n; ++i)
      if (w.a[i] < 0.0 && b.broken[i] == 0.0) {
        w.a[i] = jkr::contact_radius(b.delta[i], b.R[i], k.c.E_star, k.c.Gamma);
        w.u[i] = std::sqrt(w.a[i]);
      }
  }
  // one material pair per batch: mu = 0 for all its lanes or for none
  if (k.c.mu == 0.0) {
    if (p.tally) law_stage<Adhesive, Damped, true, true>(b, k, p, w);
    else law_stage<Adhesive, Damped, false, true>(b, k, p, w);
  } else {
    if (p.tally) law_stage<Adhesive, Damped, true, false>(b, k, p, w);
    else law_stage<Adhesive, Damped, false, false>(b, k, p, w);
  }
  if (p.energy) detail::stored_energies(b, n, k);
}

[[gnu::always_inline]] inline void vector_cube_roots(const double* x, double* y, int n)
{

  for (int i = 0; i < n; ++i) y[i] = simd_cbrt(x[i]);
}

}    // namespace

// the three builds of the same body
#define TYCORE_BATCH_BUILD(suffix, target_attribute)                                                   \
  namespace detail {                                                                             \
  template <bool Adhesive, bool Damped>                                                          \
  target_attribute void advance_batch_##suffix(                               \
      ContactBatch& b, int n, const PairConstants& k, const BatchParameters& p)                  \
  {                                                                                              \
    vector_batch<Adhesive, Damped>(b, n, k, p);                                                  \
  }                                                                                              \
  template void advance_batch_##suffix<false, false>(ContactBatch&, int, const PairConstants&,  \
                                                     const BatchParameters&);                    \
  template void advance_batch_##suffix<false, true>(ContactBatch&, int, const PairConstants&,   \
                                                    const BatchParameters&);                     \
  template void advance_batch_##suffix<true, false>(ContactBatch&, int, const PairConstants&,   \
                                                    const BatchParameters&);                     \
  template void advance_batch_##suffix<true, true>(ContactBatch&, int, const PairConstants&,    \
                                                   const BatchParameters&);                      \
  target_attribute void cube_roots_##suffix(const double* x, double* y,      \
                                                               int n)                            \
  {                                                                                              \
    vector_cube_roots(x, y, n);                                                                  \
  }                                                                                              \
  }

TYCORE_BATCH_BUILD(sse2, )
TYCORE_BATCH_BUILD(avx2, __attribute__((target("avx2"))))
TYCORE_BATCH_BUILD(avx512, __attribute__((target(TYCORE_AVX512))))

#undef TYCORE_BATCH_BUILD

void cube_roots(const double* x, double* y, int n, Isa isa)
{
  switch (isa) {
    case Isa::avx512: detail::cube_roots_avx512(x, y, n); return;
    case Isa::avx2: detail::cube_roots_avx2(x, y, n); return;
    case Isa::sse2: detail::cube_roots_sse2(x, y, n); return;
    case Isa::scalar: break;
  }
  for (int i = 0; i < n; ++i) y[i] = jkr::fast_cbrt(x[i]);
}

}    // namespace tycore
