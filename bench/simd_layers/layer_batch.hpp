// tycore::advance_batch (plugin/core/contact_batch.hpp) with the contact law's one text
// (plugin/core/contact_law.hpp) instantiated on an explicit SIMD lane type, Layer::V, instead of
// on double inside auto-vectorised lane loops (plugin/core/contact_batch_loops.hpp): stage for
// stage the vector build of the product (the same twist, carry, Halley rounds, closed form,
// step and outputs, the same rare-case lane-by-lane code), Layer::width lanes per operation.
// Include after contact_batch.hpp (and the layer's lanes header before it). Only what the
// benchmark runs: the damped and undamped laws, without the affine-stiffness tally.
// Benchmark only (bench/simd_layers.cpp).
#ifndef TYBENCH_LAYER_BATCH_HPP
#define TYBENCH_LAYER_BATCH_HPP

#include "contact_batch.hpp"
#include "contact_batch_loops.hpp"
#include "contact_law.hpp"

#include <cstdio>
#include <cstdlib>

namespace tybench {

using namespace tycore;

template <class Layer>
inline law::History<typename Layer::V> load_history(const ContactBatch& b, int i)
{
  law::History<typename Layer::V> h;
#define TYBENCH_LOAD_FIELD(name, values, carried, from_j, meaning) \
  for (int k = 0; k < values; ++k)                                 \
    history::value(h.name, k) = Layer::load(batch_value(b.name, k) + i);
  TYCORE_HISTORY_FIELDS(TYBENCH_LOAD_FIELD)
#undef TYBENCH_LOAD_FIELD
  return h;
}

template <class Layer>
inline law::Carry<typename Layer::V> load_carry(const batch_loops::CarryLanes& w, int i)
{
  return law::Carry<typename Layer::V>{Layer::load(w.T_magnitude + i), Layer::load(w.u + i),
                                       Layer::load(w.f1 + i),          Layer::load(w.f2 + i),
                                       Layer::load(w.step + i),        Layer::load(w.a + i),
                                       Layer::load(w.pending + i)};
}

template <class Layer>
inline void store_carry(batch_loops::CarryLanes& w, int i, const law::Carry<typename Layer::V>& c,
                        bool adhesive)
{
  Layer::store(c.T_magnitude, w.T_magnitude + i);
  if (!adhesive) return;
  Layer::store(c.u, w.u + i), Layer::store(c.f1, w.f1 + i), Layer::store(c.f2, w.f2 + i);
  Layer::store(c.step, w.step + i), Layer::store(c.a, w.a + i);
  Layer::store(c.pending, w.pending + i);
}

// detail::law_stage + store_lane + lane_outputs (no tally) for lanes i .. i + width - 1
template <class Layer, bool Adhesive, bool Damped, bool Frictionless>
inline void law_stage(ContactBatch& b, const PairConstants& k, const BatchParameters& p,
                      const batch_loops::CarryLanes& w)
{
  using V = typename Layer::V;
  const PairCoefficients c = k.c;
  const double dt = p.dt;
  const V zero(0.0);
  for (int i = 0; i < batch_lanes; i += Layer::width) {
    const auto gone = Layer::load(b.broken + i) != 0.0;
    const V ds[3] = {-Layer::load(b.vt[0] + i) * dt, -Layer::load(b.vt[1] + i) * dt,
                     -Layer::load(b.vt[2] + i) * dt};
    law::History<V> h = load_history<Layer>(b, i);
    const law::Outputs<V> out = law::step<Adhesive, Frictionless>(
        k, Layer::load(b.R + i), Layer::load(b.Rinv + i), Layer::load(b.delta + i), ds,
        load_carry<Layer>(w, i), h);
    // detail::store_lane
#define TYBENCH_STORE_FIELD(name, values, carried, from_j, meaning) \
  for (int k = 0; k < values; ++k)                                  \
    Layer::store(lane_select(gone, zero, history::value(h.name, k)), batch_value(b.name, k) + i);
    TYCORE_HISTORY_FIELDS(TYBENCH_STORE_FIELD)
#undef TYBENCH_STORE_FIELD
    const V T[3] = {lane_select(gone, zero, h.T[0]), lane_select(gone, zero, h.T[1]),
                    lane_select(gone, zero, h.T[2])};
    const V P = lane_select(gone, zero, out.P), a = lane_select(gone, zero, out.a);
    Layer::store(P, b.P + i);
    Layer::store(a, b.contact_radius + i);
    Layer::store(lane_select(gone, zero, out.dissipation), b.dissipation + i);
    // detail::lane_outputs<Adhesive, Damped, false>: damped_force, force, moment
    const V nx = Layer::load(b.n[0] + i), ny = Layer::load(b.n[1] + i);
    const V nz = Layer::load(b.n[2] + i);
    V Fn = P, fs1 = T[0], fs2 = T[1], fs3 = T[2], lost = zero;
    if (Damped) {
      const V vn = Layer::load(b.vn + i), vt1 = Layer::load(b.vt[0] + i),
              vt2 = Layer::load(b.vt[1] + i), vt3 = Layer::load(b.vt[2] + i);
      const V m_star = Layer::load(b.m_star + i);
      const V eta_n = 2.0 * p.beta_n * std::sqrt(m_star * 2.0 * c.E_star * a);
      const V eta_t = 2.0 * p.beta_t * std::sqrt(m_star * 8.0 * c.G_star * a);
      Fn = Fn - eta_n * vn;
      fs1 = fs1 - eta_t * vt1, fs2 = fs2 - eta_t * vt2, fs3 = fs3 - eta_t * vt3;
      lost = p.dt * (eta_n * vn * vn + eta_t * (vt1 * vt1 + vt2 * vt2 + vt3 * vt3));
    }
    Layer::store(lane_select(gone, zero, lost), b.damping_dissipation + i);
    Layer::store(lane_select(gone, zero, nx * Fn + fs1), b.force[0] + i);
    Layer::store(lane_select(gone, zero, ny * Fn + fs2), b.force[1] + i);
    Layer::store(lane_select(gone, zero, nz * Fn + fs3), b.force[2] + i);
    Layer::store(lane_select(gone, zero, ny * fs3 - nz * fs2), b.moment[0] + i);
    Layer::store(lane_select(gone, zero, nz * fs1 - nx * fs3), b.moment[1] + i);
    Layer::store(lane_select(gone, zero, nx * fs2 - ny * fs1), b.moment[2] + i);
  }
}

// batch_loops::vector_batch with Layer::V lanes
template <class Layer, bool Adhesive, bool Damped>
void layer_batch(ContactBatch& b, int n, const PairConstants& k, const BatchParameters& p)
{
  using V = typename Layer::V;
  constexpr int W = Layer::width;
  static_assert(batch_lanes % W == 0, "whole registers per batch");
  if (p.tally) {
    std::fprintf(stderr, "bench/simd_layers: the affine-stiffness tally is not written\n");
    std::abort();
  }
  detail::touch_or_break<Adhesive>(b, n, k);
  batch_loops::CarryLanes w;
  for (int i = 0; i < batch_lanes; i += W) {
    const V twist = 0.5 * p.dt * Layer::load(b.spin_n + i);
    const V t2 = twist * twist;
    Layer::store(1.0 - t2 * (0.5 - t2 * (1.0 / 24.0)), w.tw_c + i);
    Layer::store(twist * (1.0 - t2 * (1.0 / 6.0 - t2 * (1.0 / 120.0))), w.tw_s + i);
  }
  for (int i = 0; i < n; ++i) {
    const double twist = 0.5 * p.dt * b.spin_n[i];
    if (std::abs(twist) >= 1e-3) detail::twist_cos_sin(twist, w.tw_c[i], w.tw_s[i]);
  }
  // carry stage
  for (int i = 0; i < batch_lanes; i += W) {
    const V nn[3] = {Layer::load(b.n[0] + i), Layer::load(b.n[1] + i), Layer::load(b.n[2] + i)};
    const auto twisted = 0.5 * p.dt * Layer::load(b.spin_n + i) != 0.0;
    law::History<V> h = load_history<Layer>(b, i);
    law::Carry<V> lane{};
    law::carry<Adhesive>(k, nn, Layer::load(w.tw_c + i), Layer::load(w.tw_s + i), twisted,
                         Layer::load(b.Rinv + i), Layer::load(b.delta + i), h, lane);
#define TYBENCH_CARRIED_FIELD(name, values, carried, from_j, meaning) \
  if constexpr (history::carried != history::kept)                    \
    for (int k = 0; k < values; ++k)                                  \
      Layer::store(history::value(h.name, k), batch_value(b.name, k) + i);
    TYCORE_HISTORY_FIELDS(TYBENCH_CARRIED_FIELD)
#undef TYBENCH_CARRIED_FIELD
    store_carry<Layer>(w, i, lane, Adhesive);
  }
  if (Adhesive) {
    for (int round = 3; round <= 6; ++round) {
      bool any = false;
      for (int i = 0; i < n; ++i) any |= w.pending[i] != 0.0;
      if (!any) break;
      const bool last = round == 6;
      for (int i = 0; i < batch_lanes; i += W) {
        law::Carry<V> lane = load_carry<Layer>(w, i);
        law::halley_again(Layer::load(b.Rinv + i), Layer::load(b.delta + i), k.newton_c, last,
                          lane);
        store_carry<Layer>(w, i, lane, true);
      }
    }
    for (int i = 0; i < n; ++i)
      if (w.a[i] < 0.0 && b.broken[i] == 0.0) {
        law::Carry<double> lane = w.lane(i);
        law::closed_form_radius(k.c, b.R[i], b.delta[i], lane);
        w.store(i, lane, true);
      }
  }
  if (k.c.mu == 0.0) law_stage<Layer, Adhesive, Damped, true>(b, k, p, w);
  else law_stage<Layer, Adhesive, Damped, false>(b, k, p, w);
  if (p.energy) detail::stored_energies(b, n, k);
  for (int i = 0; i < n; ++i) b.slides[i] = b.sliding[i];
}

}    // namespace tybench

#endif
