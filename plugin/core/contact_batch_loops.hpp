// The lane loops of tycore::advance_batch's vector builds (contact_batch.hpp) and of
// tycore::batch_geometry (contact_geometry.hpp): the contact law's one text (contact_law.hpp,
// lane type double) and the contact geometry's over the lanes of a ContactBatch, one loop per
// stage, each loop body branch-free so that the compiler turns it into SIMD code
// (every lane_select a blend, every stage computed for all lanes and the lane's own result
// kept), and TYCORE_DEFINE_BATCH_BUILDS, which compiles an entry once per instruction set.
// contact_batch.cpp defines the builds of the law with it; bench/ defines benchmark builds
// of the plugin (bench/plumbing_batch.cpp, bench/generic_batch.cpp) with it, in their own
// targets, so that the product carries no benchmark variant.
//
// What does not vectorise runs lane by lane where it is rare: first touch and separation
// (detail::touch_or_break), cos/sin of a twist above 1e-3 rad, the JKR closed form where the
// warm-started Halley iteration does not converge (first steps, large jumps).
//
// The loops have a fixed trip count (batch_lanes) and no branches, local arrays only of
// constant index, masks combined by & and | (not && and ||, which GCC keeps as control flow),
// so that GCC's auto-vectoriser takes them whole (check: -fopt-info-vec). Compiled with
// -fno-trapping-math (the loops compute divisions whose lanes are then not selected; without
// it GCC keeps such code in branches), -ffp-contract=off (no fused multiply-add: the scalar
// build's roundings, so that every build agrees to the bit), -fno-tree-pre and
// -fno-thread-jumps (both otherwise rewrite comparisons of selected values into selects of
// masks that GCC 12 does not vectorise); CMakeLists.txt sets them for the files that include
// this header. With them every lane loop here vectorises in all three builds; the loops that
// stay scalar are the rare-case ones named above.
#ifndef TYCORE_CONTACT_BATCH_LOOPS_HPP
#define TYCORE_CONTACT_BATCH_LOOPS_HPP

#include "contact_batch.hpp"
#include "contact_geometry.hpp"
#include "contact_law.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"
#include "simd_math.hpp"

#include <cmath>

namespace tycore::batch_loops {

constexpr int L = batch_lanes;

// the per-lane state the carry stage hands to the law stage (law::Carry as arrays), and the
// twist's cos and sin
struct CarryLanes {
  alignas(64) double tw_c[L], tw_s[L];
  alignas(64) double u[L], f1[L], f2[L], step[L], a[L], pending[L];

  [[gnu::always_inline]] law::Carry<double> lane(int i) const
  {
    return law::Carry<double>{u[i], f1[i], f2[i], step[i], a[i], pending[i]};
  }
  [[gnu::always_inline]] void store(int i, const law::Carry<double> &w, bool adhesive)
  {
    if (!adhesive) return;
    u[i] = w.u, f1[i] = w.f1, f2[i] = w.f2, step[i] = w.step, a[i] = w.a, pending[i] = w.pending;
  }
};

using detail::lane_outputs;

// Stage 1 of every lane: law::carry (the history onto the new tangent plane; with adhesion the
// first Halley rounds). (Every loop body reads its inputs before any select and takes the
// constants by value: a load under a condition may fault, and GCC would keep it in a branch.)
template <bool Adhesive>
[[gnu::always_inline]] inline void carry_stage(ContactBatch &b, const PairConstants k, double dt,
                                               CarryLanes &w)
{
  for (int i = 0; i < L; ++i) {
    const double n[3] = {b.n[0][i], b.n[1][i], b.n[2][i]};
    const bool twisted = 0.5 * dt * b.spin_n[i] != 0.0;
    law::History<double> h = detail::lane_history(b, i);
    law::Carry<double> lane{};
    law::carry<Adhesive>(k, n, w.tw_c[i], w.tw_s[i], twisted, b.Rinv[i], b.delta[i], h, lane);
    // the carried tangent vectors back (the scalars are kept)
#define TYCORE_CARRIED_FIELD(name, values, carried, from_j, meaning) \
  if constexpr (history::carried != history::kept)                   \
    for (int k = 0; k < values; ++k) batch_value(b.name, k)[i] = history::value(h.name, k);
    TYCORE_HISTORY_FIELDS(TYCORE_CARRIED_FIELD)
#undef TYCORE_CARRIED_FIELD
    w.store(i, lane, Adhesive);
  }
}

// the later Halley rounds (law::halley_again) while a lane of the batch needs one
[[gnu::always_inline]] inline void halley_rounds(const ContactBatch &b, int n,
                                                 const double newton_c, CarryLanes &w)
{
  for (int round = 3; round <= 6; ++round) {
    bool any = false;
    for (int i = 0; i < n; ++i) any |= w.pending[i] != 0.0;
    if (!any) return;
    const bool last = round == 6;
    for (int i = 0; i < L; ++i) {
      law::Carry<double> lane = w.lane(i);
      law::halley_again(b.Rinv[i], b.delta[i], newton_c, last, lane);
      w.store(i, lane, true);
    }
  }
}

// Stage 2 of every lane: law::step, the lane's new history and outputs (store_lane), then
// lane_outputs (damping, force, torque, tallies)
template <bool Adhesive, bool Damped, bool Tally, bool Frictionless>
[[gnu::always_inline]] inline void law_stage(ContactBatch &b, const PairConstants k,
                                             const BatchParameters p, const CarryLanes &w)
{
  const double dt = p.dt;
  for (int i = 0; i < L; ++i) {
    const bool gone = b.broken[i] != 0.0;
    const double ds[3] = {-b.vt[0][i] * dt, -b.vt[1][i] * dt, -b.vt[2][i] * dt};
    law::History<double> h = detail::lane_history(b, i);
    const law::Outputs<double> out =
        law::step<Adhesive, Frictionless>(k, b.R[i], b.Rinv[i], b.delta[i], ds, w.lane(i), h);
    detail::store_lane(b, i, h, out, gone);
    lane_outputs<Adhesive, Damped, Tally>(b, i, k, p, out.stiffness);
  }
}

template <bool Adhesive, bool Damped>
[[gnu::always_inline]] inline void vector_batch(ContactBatch &b, int n, const PairConstants &k,
                                                const BatchParameters &p)
{
  detail::touch_or_break<Adhesive>(b, n, k);
  CarryLanes w;
  // cos and sin of the twist: the series of detail::twist_cos_sin lane-wide, libm where
  // |twist| >= its bound
  for (int i = 0; i < L; ++i)
    detail::twist_cos_sin_series(0.5 * p.dt * b.spin_n[i], w.tw_c[i], w.tw_s[i]);
  for (int i = 0; i < n; ++i) {
    const double twist = 0.5 * p.dt * b.spin_n[i];
    if (!detail::twist_series_exact(twist)) detail::twist_cos_sin(twist, w.tw_c[i], w.tw_s[i]);
  }
  carry_stage<Adhesive>(b, k, p.dt, w);
  if (Adhesive) {
    halley_rounds(b, n, k.newton_c, w);
    for (int i = 0; i < n; ++i)
      if (w.a[i] < 0.0 && b.broken[i] == 0.0) {
        law::Carry<double> lane = w.lane(i);
        law::closed_form_radius(k.c, b.R[i], b.delta[i], lane);
        w.store(i, lane, true);
      }
  }
  // one material pair per batch: mu = 0 for all its lanes or for none
  if (k.c.mu == 0.0) {
    if (p.tally)
      law_stage<Adhesive, Damped, true, true>(b, k, p, w);
    else
      law_stage<Adhesive, Damped, false, true>(b, k, p, w);
  } else {
    if (p.tally)
      law_stage<Adhesive, Damped, true, false>(b, k, p, w);
    else
      law_stage<Adhesive, Damped, false, false>(b, k, p, w);
  }
  if (p.energy) detail::stored_energies(b, n, k);
}

// the law's inputs of every lane from the gathered sphere data (contact_geometry); whether the
// overlaps of lanes 0 .. n-1 are valid (overlap_valid)
template <bool Affine, bool Damped>
[[gnu::always_inline]] inline bool geometry_stage(ContactBatch &b, int n, const AffineGradient g)
{
  for (int i = 0; i < L; ++i) contact_geometry<Affine, Damped>(b, i, g);
  // a loop of its own, with an integer reduction: GCC keeps either in the loop above scalar
  unsigned invalid = 0u;
  for (int i = 0; i < L; ++i) invalid |= unsigned(i < n) & unsigned(!overlap_valid(b, i));
  return invalid == 0u;
}

}    // namespace tycore::batch_loops

#ifdef TYCORE_VECTOR_BUILDS
// The builds of one batch entry Law<Adhesive, Damped>(b, n, k, p) for every instruction set
// of Isa (tycore::detail::advance_batch_*, declared in contact_batch.hpp) and of the contact
// geometry (batch_geometry_*). Once per program, at namespace scope.
#define TYCORE_BATCH_BUILD(Law, suffix, target_attribute)                                          \
  namespace tycore::detail {                                                                       \
    template <bool Adhesive, bool Damped>                                                          \
    target_attribute void advance_batch_##suffix(ContactBatch &b, int n, const PairConstants &k,   \
                                                 const BatchParameters &p)                         \
    {                                                                                              \
      Law<Adhesive, Damped>(b, n, k, p);                                                           \
    }                                                                                              \
    template void advance_batch_##suffix<false, false>(ContactBatch &, int, const PairConstants &, \
                                                       const BatchParameters &);                   \
    template void advance_batch_##suffix<false, true>(ContactBatch &, int, const PairConstants &,  \
                                                      const BatchParameters &);                    \
    template void advance_batch_##suffix<true, false>(ContactBatch &, int, const PairConstants &,  \
                                                      const BatchParameters &);                    \
    template void advance_batch_##suffix<true, true>(ContactBatch &, int, const PairConstants &,   \
                                                     const BatchParameters &);                     \
    template <bool Affine, bool Damped>                                                            \
    target_attribute bool batch_geometry_##suffix(ContactBatch &b, int n, const AffineGradient &g) \
    {                                                                                              \
      return tycore::batch_loops::geometry_stage<Affine, Damped>(b, n, g);                         \
    }                                                                                              \
    template bool batch_geometry_##suffix<false, false>(ContactBatch &, int,                       \
                                                        const AffineGradient &);                   \
    template bool batch_geometry_##suffix<false, true>(ContactBatch &, int,                        \
                                                       const AffineGradient &);                    \
    template bool batch_geometry_##suffix<true, false>(ContactBatch &, int,                        \
                                                       const AffineGradient &);                    \
    template bool batch_geometry_##suffix<true, true>(ContactBatch &, int,                         \
                                                      const AffineGradient &);                     \
  }
#define TYCORE_DEFINE_BATCH_BUILDS(Law)                          \
  TYCORE_BATCH_BUILD(Law, sse2, )                                \
  TYCORE_BATCH_BUILD(Law, avx2, __attribute__((target("avx2")))) \
  TYCORE_BATCH_BUILD(Law, avx512, __attribute__((target(TYCORE_AVX512))))
#else
#define TYCORE_DEFINE_BATCH_BUILDS(Law)
#endif

#endif
