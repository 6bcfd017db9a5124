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
  for (int d = 0; d < 3; ++d)
    h.T[d] = Layer::load(b.T[d] + i), h.dir[d] = Layer::load(b.dir[d] + i);
  h.T_star = Layer::load(b.T_star + i), h.T_star2 = Layer::load(b.T_star2 + i);
  h.P_prev = Layer::load(b.P_prev + i), h.mode = Layer::load(b.mode + i);
  h.peeling = Layer::load(b.peeling + i), h.sliding = Layer::load(b.sliding + i);
  h.stored_energy = Layer::load(b.stored_energy + i), h.radius = Layer::load(b.radius + i);
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
    V T[3];
    for (int d = 0; d < 3; ++d) {
      T[d] = lane_select(gone, zero, h.T[d]);
      Layer::store(T[d], b.T[d] + i);
      Layer::store(lane_select(gone, zero, h.dir[d]), b.dir[d] + i);
    }
    Layer::store(lane_select(gone, zero, h.T_star), b.T_star + i);
    Layer::store(lane_select(gone, zero, h.T_star2), b.T_star2 + i);
    Layer::store(lane_select(gone, zero, h.P_prev), b.P_prev + i);
    Layer::store(lane_select(gone, zero, h.mode), b.mode + i);
    Layer::store(lane_select(gone, zero, h.peeling), b.peeling + i);
    Layer::store(lane_select(gone, zero, h.sliding), b.sliding + i);
    Layer::store(lane_select(gone, zero, h.stored_energy), b.stored_energy + i);
    Layer::store(lane_select(gone, zero, h.radius), b.radius + i);
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
    for (int d = 0; d < 3; ++d)
      Layer::store(h.T[d], b.T[d] + i), Layer::store(h.dir[d], b.dir[d] + i);
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
