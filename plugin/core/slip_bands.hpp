// The Mindlin-Deresiewicz memory of a Hertzian contact as slip bands (docs/theory.md §2.3):
// the state of the contact's tangential tractions, for any history of the normal and the
// tangential displacement, in the form the method of dimensionality reduction gives it
// (Popov & Hess 2015; docs/theory.md §2.3 derives every operation here).
//
// The traction field along the memory's axis is held as the slope m(w) = (du/dw)/kappa of the
// equivalent springs' tangential displacement u against their depth w = delta - x^2/R*
// (kappa = mu E*/(4 G*), the slope of the local Coulomb limit |u| <= kappa w). The slope is
// piecewise constant: `bands` slope/depth pairs from the contact's edge inwards, their depths
// adding up to the (effective) overlap. |m| <= 1 everywhere; a band at m = +1 or -1 slips,
// one in between sticks. Three operations change it, each exact:
//  * the overlap grows by d and the contact takes the tangential displacement s in the same
//    step: a band of slope s/(kappa d) enters at the edge (if that is above 1 in magnitude, a
//    band at the limit enters and the rest of s slips);
//  * the overlap shrinks by d: the outer depth d leaves, and the displacement its springs
//    carried, with s, slips at the new edge;
//  * a displacement D at the edge slips (forward for D > 0): the outer bands turn to the
//    limit's slope sign(D) to the depth where the displacement they absorb, kappa int
//    (1 - sign(D) m) dw, reaches |D|; beyond all bands the contact slides as a whole.
// The force they carry is T = mu sum_j m_j [P_H(delta - W_j) - P_H(delta - W_j - h_j)], W_j the
// depth where band j begins, P_H(x) = (4/3) E* sqrt(R*) x^(3/2) the Hertz load of overlap x
// (law::band_load_fractions, contact_law.hpp).
//
// At constant P these operations are Mindlin & Deresiewicz's loading, unloading and reloading
// curves (Thornton's theta forms of §2.1); when P changes they remain exact, which the forms
// with shifted reversal points are not. A history with more distinct bands than `bands` merges
// the two neighbours whose merge changes the force least (the only approximation).
//
// Written once over a lane type V (as contact_law.hpp): each operation computes every branch
// and selects; loops run over the fixed band count, so that the SIMD builds vectorise them.
#ifndef TYCORE_SLIP_BANDS_HPP
#define TYCORE_SLIP_BANDS_HPP

#include "contact_types.hpp"
#include "simd_math.hpp"

#include <cmath>

namespace tycore {

namespace bands {

// the relative spacing of doubles, 2^-52
inline constexpr double ulp_fraction = 2.220446049250313e-16;

template <class V> struct Profile {
  V slope[memory_bands];    // m_j in [-1, 1], from the contact's edge inwards
  V depth[memory_bands];    // h_j >= 0, overlap units; sum = the overlap of the last step
};

// the overlap the profile covers (the effective overlap of the last step)
template <class V> [[gnu::always_inline]] inline V covered_depth(const Profile<V>& p)
{
  V total = p.depth[0];
  for (int j = 1; j < memory_bands; ++j) total = total + p.depth[j];
  return total;
}

// how much the force would change if bands j and j + 1 became one band of their mean slope:
// |m_j - m_j+1| h_j h_j+1 / (h_j + h_j+1), zero where either is empty (so empty bands go first)
template <class V> [[gnu::always_inline]] inline V merge_cost(const Profile<V>& p, int j)
{
  const V hj = p.depth[j], hk = p.depth[j + 1], sum = hj + hk;
  const V cost = std::abs(p.slope[j] - p.slope[j + 1]) * hj * hk / sum;
  return lane_select(sum > 0.0, cost, V(0.0));
}

// a band of slope m and depth h enters at the edge: into an empty edge band, or merged with an
// edge band of the same slope, or in front of the others, the cheapest pair of neighbours
// merged to make room; a band of no depth changes nothing
template <class V> [[gnu::always_inline]] inline void enter_at_edge(Profile<V>& p, V m, V h)
{
  const auto empty_edge = p.depth[0] == 0.0, same_slope = p.slope[0] == m;
  // the pair (j*, j* + 1) to merge: the first of least cost
  V best = merge_cost(p, 0), chosen = V(0.0);
  for (int j = 1; j < memory_bands - 1; ++j) {
    const V cost = merge_cost(p, j);
    const auto cheaper = cost < best;
    best = lane_select(cheaper, cost, best);
    chosen = lane_select(cheaper, V(double(j)), chosen);
  }
  Profile<V> shifted;
  shifted.slope[0] = m, shifted.depth[0] = h;
  for (int i = 1; i < memory_bands; ++i) {
    // i <= j*: band i - 1 moves in by one; i = j* + 1: bands j* and j* + 1 merged; beyond: kept
    const V ha = p.depth[i - 1], hb = p.depth[i], sum = ha + hb;
    const V mean = lane_select(sum > 0.0, (p.slope[i - 1] * ha + p.slope[i] * hb) / sum,
                               p.slope[i - 1]);
    const auto moved = V(double(i)) <= chosen, merged = V(double(i)) == chosen + 1.0;
    shifted.slope[i] = lane_select(moved, p.slope[i - 1], lane_select(merged, mean, p.slope[i]));
    shifted.depth[i] = lane_select(moved, p.depth[i - 1], lane_select(merged, sum, p.depth[i]));
  }
  const auto nothing = !(h > 0.0);    // a band of no depth changes nothing
  const auto in_place = empty_edge | same_slope | nothing;
  for (int i = 0; i < memory_bands; ++i) {
    const V slope0 = lane_select(empty_edge & !nothing, m, p.slope[0]);
    const V depth0 = p.depth[0] + h;
    p.slope[i] = lane_select(in_place, i == 0 ? slope0 : p.slope[i], shifted.slope[i]);
    p.depth[i] = lane_select(in_place, i == 0 ? depth0 : p.depth[i], shifted.depth[i]);
  }
}

// the outer depth d leaves (it empties the outer bands): returns int m dw over it, the
// displacement (over kappa) the leaving springs carried
template <class V> [[gnu::always_inline]] inline V leave_at_edge(Profile<V>& p, V d)
{
  V begins = V(0.0), carried = V(0.0);
  for (int j = 0; j < memory_bands; ++j) {
    const V take = lane_clamp(d - begins, V(0.0), p.depth[j]);
    begins = begins + p.depth[j];
    carried = carried + p.slope[j] * take;
    p.depth[j] = p.depth[j] - take;
  }
  return carried;
}

// the displacement D (over kappa: D_k = D/kappa, overlap units) slips at the edge: the outer
// bands turn to slope sign(D) over the depth where they absorb |D_k|. Returns the part of
// |D_k| that no band absorbs (gross sliding; 0 while the contact sticks somewhere).
template <class V> [[gnu::always_inline]] inline V slip_at_edge(Profile<V>& p, V D_k)
{
  const V sense = lane_select(D_k < 0.0, V(-1.0), V(1.0));
  const V wanted = std::abs(D_k);
  V absorbed = V(0.0), reach = V(0.0);
  auto open = wanted == wanted;    // the slip zone has not stopped in an earlier band
  for (int j = 0; j < memory_bands; ++j) {
    const V room = 1.0 - sense * p.slope[j];          // what one unit of depth absorbs
    const V band_absorbs = room * p.depth[j];
    const V still = wanted - absorbed;
    const auto whole = open & (band_absorbs <= still);
    const auto ends_here = open & !whole;
    const V part = lane_select(whole, p.depth[j], lane_select(ends_here, still / room, V(0.0)));
    reach = reach + part;
    absorbed = absorbed + lane_select(whole, band_absorbs, lane_select(ends_here, still, V(0.0)));
    open = whole;
  }
  leave_at_edge(p, reach);
  enter_at_edge(p, sense, reach);
  return lane_max(wanted - absorbed, V(0.0));
}

// One step of the memory: from the covered overlap to `overlap` while the contact takes the
// tangential displacement s along the memory's axis; kappa = mu E*/(4G*). Returns the part of
// s slid by the contact as a whole (docs/theory.md §2.3).
template <class V>
[[gnu::always_inline]] inline V advance(Profile<V>& p, V overlap, V s, double kappa)
{
  const V from = covered_depth(p);
  // a change within the round-off of the overlap and of the bands' sum (a few ulps each) is none
  const V change = overlap - from;
  const V grown = lane_select(std::abs(change) <= 16.0 * ulp_fraction * overlap, V(0.0), change);
  const V s_k = s / kappa;
  // growing: a band of slope s_k/d enters; beyond the limit, one at the limit and the rest slips
  const V entering = s_k / grown;
  const auto grows = grown > 0.0, over = std::abs(entering) > 1.0;
  const V limit_slope = lane_select(entering < 0.0, V(-1.0), V(1.0));
  Profile<V> up = p;
  enter_at_edge(up, lane_select(over, limit_slope, entering), lane_max(grown, V(0.0)));
  const V rest = lane_select(over, s_k - limit_slope * grown, V(0.0));
  // shrinking: the outer depth leaves and what it carried slips with s
  Profile<V> down = p;
  const V carried = leave_at_edge(down, lane_max(-grown, V(0.0)));
  const V to_slip = lane_select(grows, rest, s_k + carried);
  for (int j = 0; j < memory_bands; ++j) {
    p.slope[j] = lane_select(grows, up.slope[j], down.slope[j]);
    p.depth[j] = lane_select(grows, up.depth[j], down.depth[j]);
  }
  const V slid = slip_at_edge(p, to_slip);
  return lane_select(to_slip < 0.0, -slid, slid) * kappa;
}

// the elastic energy of the springs, 4 G* int u^2 dx over the half-row (u = kappa phi(w),
// phi = int_0^w m, w = overlap - x^2/R*): per band, phi = A - m x^2/R* with A = phi_j +
// m (overlap - W_j), and int (A - m x^2/R*)^2 dx = A^2 x - 2 A m x^3/(3R*) + m^2 x^5/(5R*^2).
// Returns int phi^2 dx; times 4 G* kappa^2 it is the energy (docs/theory.md §2.4).
template <class V>
[[gnu::always_inline]] inline V energy_factor(const Profile<V>& p, V overlap, V R)
{
  const V Rinv = 1.0 / R;
  V begins = V(0.0), phi = V(0.0), sum = V(0.0);
  V x = std::sqrt(R * lane_max(overlap, V(0.0)));
  for (int j = 0; j < memory_bands; ++j) {
    const V m = p.slope[j];
    const V A = phi + m * (overlap - begins);
    begins = begins + p.depth[j];
    // (a depth left within round-off of the overlap is none: its square root would not be)
    const V left = overlap - begins;
    const V x_next = std::sqrt(R * lane_select(left > 16.0 * ulp_fraction * overlap, left, V(0.0)));
    const V x2 = x * x, x2n = x_next * x_next;
    const V upper = x * (A * A - x2 * Rinv * m * (2.0 / 3.0 * A - 0.2 * m * x2 * Rinv));
    const V lower = x_next * (A * A - x2n * Rinv * m * (2.0 / 3.0 * A - 0.2 * m * x2n * Rinv));
    sum = sum + (upper - lower);
    phi = phi + m * p.depth[j];
    x = x_next;
  }
  return sum;
}

// the profile of Mindlin & Deresiewicz's first loading at constant load to the force ratio
// q = |T|/(mu P_H(overlap)) in [0, 1]: the slip annulus at slope +1 to the depth w_c where
// P_H(overlap - w_c) = (1 - q) P_H(overlap), the rest untouched (slope 0)
template <class V> [[gnu::always_inline]] inline void first_loading(Profile<V>& p, V overlap, V q)
{
  const V inner = lane_max(1.0 - q, V(0.0));
  const V stuck = overlap * simd_cbrt(inner * inner);    // (1 - q)^(2/3) of the overlap
  for (int j = 0; j < memory_bands; ++j) p.slope[j] = p.depth[j] = V(0.0);
  p.slope[0] = V(1.0);
  p.depth[0] = overlap - stuck;
  p.depth[1] = stuck;
}

// the contact slides as a whole in the sense of `sense`: one band at the limit over the overlap
template <class V> [[gnu::always_inline]] inline void sliding(Profile<V>& p, V overlap, V sense)
{
  for (int j = 0; j < memory_bands; ++j) p.slope[j] = p.depth[j] = V(0.0);
  p.slope[0] = sense;
  p.depth[0] = overlap;
}

}    // namespace bands

}    // namespace tycore

#endif
