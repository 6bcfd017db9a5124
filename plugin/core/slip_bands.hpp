// The Mindlin-Deresiewicz memory of a Hertzian contact as slip bands (docs/theory.md §2.3):
// the state of the contact's tangential tractions, for any history of the normal and the
// tangential displacement, in the form the method of dimensionality reduction gives it
// (Popov & Hess 2015; docs/theory.md §2.3 derives every operation here).
//
// The traction field along the memory's axis is held as the slope m(w) = (du/dw)/kappa of the
// equivalent springs' tangential displacement u against their depth w = delta - x^2/R*
// (kappa = mu E*/(4 G*), the slope of the local Coulomb limit |u| <= kappa w). The slope is held
// piecewise linear in `memory_bands` bands from the contact's edge inwards, each with its slope
// at its outer and at its inner edge and its depth; the depths add up to the (effective)
// overlap. |m| <= 1 everywhere; where m = +1 or -1 the springs slip, in between they stick.
// Three operations change the memory, each exact:
//  * the overlap grows by d and the contact takes the tangential displacement s in the same
//    step: a band of slope s/(kappa d) enters at the edge (if that is above 1 in magnitude, a
//    band at the limit enters and the rest of s slips);
//  * the overlap shrinks by d: the outer depth d leaves, and the displacement its springs
//    carried, with s, slips at the new edge;
//  * a displacement D at the edge slips (forward for D > 0): the outer bands turn to the
//    limit's slope sign(D) to the depth where the displacement they absorb, kappa int
//    (1 - sign(D) m) dw, reaches |D|; beyond all bands the contact slides as a whole.
// A history with more bands than the memory holds has two neighbours merged into one band,
// the straight line that keeps their int m and int m w (the pair whose merge changes the slope
// least in the mean square; a line that would leave [-1, 1] becomes their mean): the memory's
// only approximation. A smoothly varying slope, which a contact that sticks while both loads
// change lays down, is held by a few lines to round-off.
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
    V outer[memory_bands];    // slope m at the band's outer edge, in [-1, 1]
    V inner[memory_bands];    // slope m at its inner edge
    V depth[memory_bands];    // its depth h >= 0, overlap units; sum = the overlap of the last step
  };

  // a in the lanes where `take` holds, else b, band for band
  template <class V, class M>
  [[gnu::always_inline]] inline Profile<V> select(M take, const Profile<V> &a, const Profile<V> &b)
  {
    Profile<V> p;
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j) {
      p.outer[j] = lane_select(take, a.outer[j], b.outer[j]);
      p.inner[j] = lane_select(take, a.inner[j], b.inner[j]);
      p.depth[j] = lane_select(take, a.depth[j], b.depth[j]);
    }
    return p;
  }

  // the overlap the profile covers (the effective overlap of the last step)
  template <class V> [[gnu::always_inline]] inline V covered_depth(const Profile<V> &p)
  {
    V total = p.depth[0];
    TYCORE_UNROLLED
    for (int j = 1; j < memory_bands; ++j) total = total + p.depth[j];
    return total;
  }

  // The one band that replaces the neighbours (a1, b1, h1) outside and (a2, b2, h2) inside: the
  // line of least squares over both, which keeps int m (the displacement their springs carry) and
  // int m w; where that line leaves [-1, 1] their mean slope, which keeps int m. `cost`: the mean
  // square of the slope change times the depth, int (m - line)^2 dw, zero where a band is empty.
  template <class V> struct Merged {
    V outer, inner, cost;
  };

  template <class V>
  [[gnu::always_inline]] inline Merged<V> merge(V a1, V b1, V h1, V a2, V b2, V h2)
  {
    const V H = h1 + h2;
    const auto some = H > 0.0;
    const V inv = 1.0 / lane_select(some, H, V(1.0));
    // int m and int m w over [0, H]
    const V M0 = 0.5 * (a1 + b1) * h1 + 0.5 * (a2 + b2) * h2;
    const V M1 = h1 * h1 * (a1 * (1.0 / 6.0) + b1 * (1.0 / 3.0)) + 0.5 * h1 * h2 * (a2 + b2) +
        h2 * h2 * (a2 * (1.0 / 6.0) + b2 * (1.0 / 3.0));
    const V mean = M0 * inv;
    const V half_rise = 6.0 * (M1 - 0.5 * M0 * H) * inv * inv;    // (inner - outer)/2
    const V line_outer = mean - half_rise, line_inner = mean + half_rise;
    const auto outer_bounded = std::abs(line_outer) <= 1.0;
    const auto bounded = outer_bounded & (std::abs(line_inner) <= 1.0);
    Merged<V> m;
    m.outer = lane_select(some, lane_select(bounded, line_outer, mean), a1);
    m.inner = lane_select(some, lane_select(bounded, line_inner, mean), b1);
    // the residual is linear on each band: int over a band of depth L of a line from e0 to e1,
    // squared, is L (e0^2 + e0 e1 + e1^2)/3
    const V at_seam = m.outer + (m.inner - m.outer) * h1 * inv;
    const V e0 = a1 - m.outer, e1 = b1 - at_seam, f0 = a2 - at_seam, f1 = b2 - m.inner;
    m.cost =
        (h1 * (e0 * e0 + e0 * e1 + e1 * e1) + h2 * (f0 * f0 + f0 * f1 + f1 * f1)) * (1.0 / 3.0);
    return m;
  }

  // a band of uniform slope m and depth h enters at the edge: into an empty edge band, or in front
  // of the others, the neighbours whose merge costs least (the new band among them) becoming one
  // band to make room; a band of no depth changes nothing
  template <class V> [[gnu::always_inline]] inline void enter_at_edge(Profile<V> &p, V m, V h)
  {
    constexpr int K = memory_bands;
    // the memory with the new band in front: K + 1 bands, e = extended index
    V ea[K + 1], eb[K + 1], eh[K + 1];
    ea[0] = m, eb[0] = m, eh[0] = h;
    TYCORE_UNROLLED
    for (int j = 0; j < K; ++j)
      ea[j + 1] = p.outer[j], eb[j + 1] = p.inner[j], eh[j + 1] = p.depth[j];
    // the pair (j*, j* + 1) of least cost, and its merge
    Merged<V> best = merge(ea[0], eb[0], eh[0], ea[1], eb[1], eh[1]);
    V chosen = V(0.0);
    TYCORE_UNROLLED
    for (int j = 1; j < K; ++j) {
      const Merged<V> here = merge(ea[j], eb[j], eh[j], ea[j + 1], eb[j + 1], eh[j + 1]);
      const auto cheaper = here.cost < best.cost;
      best.outer = lane_select(cheaper, here.outer, best.outer);
      best.inner = lane_select(cheaper, here.inner, best.inner);
      best.cost = lane_select(cheaper, here.cost, best.cost);
      chosen = lane_select(cheaper, V(double(j)), chosen);
    }
    const auto empty_edge = p.depth[0] == 0.0, nothing = !(h > 0.0);
    TYCORE_UNROLLED
    for (int i = 0; i < K; ++i) {
      // i < j*: extended band i; i = j*: the merged pair; i > j*: extended band i + 1
      const V at = V(double(i));
      const auto before = at < chosen, merged = at == chosen;
      const V outer = lane_select(before, ea[i], lane_select(merged, best.outer, ea[i + 1]));
      const V inner = lane_select(before, eb[i], lane_select(merged, best.inner, eb[i + 1]));
      const V depth = lane_select(before, eh[i], lane_select(merged, eh[i] + eh[i + 1], eh[i + 1]));
      // an empty edge band takes the new band in place
      const V placed_outer = i == 0 ? m : p.outer[i], placed_inner = i == 0 ? m : p.inner[i];
      const V placed_depth = i == 0 ? h : p.depth[i];
      p.outer[i] = lane_select(nothing, p.outer[i], lane_select(empty_edge, placed_outer, outer));
      p.inner[i] = lane_select(nothing, p.inner[i], lane_select(empty_edge, placed_inner, inner));
      p.depth[i] = lane_select(nothing, p.depth[i], lane_select(empty_edge, placed_depth, depth));
    }
  }

  // the outer depth d leaves (it empties the outer bands, the band it ends in starts at the slope
  // found there): returns int m dw over it, the displacement (over kappa) the leaving springs
  // carried
  template <class V> [[gnu::always_inline]] inline V leave_at_edge(Profile<V> &p, V d)
  {
    V begins = V(0.0), carried = V(0.0);
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j) {
      const V h = p.depth[j];
      const V take = lane_clamp(d - begins, V(0.0), h);
      const V fraction = take / lane_select(h > 0.0, h, V(1.0));
      const V cut = p.outer[j] + (p.inner[j] - p.outer[j]) * fraction;    // slope where it ends
      carried = carried + 0.5 * (p.outer[j] + cut) * take;
      begins = begins + h;
      p.outer[j] = cut;
      p.depth[j] = h - take;
    }
    return carried;
  }

  // the displacement D (over kappa: D_k = D/kappa, overlap units) slips at the edge: the outer
  // bands turn to slope sign(D) over the depth where they absorb |D_k|, int (1 - sign(D) m) dw.
  // Returns the part of |D_k| that no band absorbs (gross sliding; 0 while the contact sticks).
  template <class V> [[gnu::always_inline]] inline V slip_at_edge(Profile<V> &p, V D_k)
  {
    const V sense = lane_select(D_k < 0.0, V(-1.0), V(1.0));
    const V wanted = std::abs(D_k);
    V absorbed = V(0.0), reach = V(0.0);
    auto open = wanted == wanted;    // the slip zone has not stopped in an earlier band
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j) {
      const V h = p.depth[j];
      // what a depth x of the band absorbs: room_o x - (room_o - room_i) x^2/(2h), increasing
      const V room_o = 1.0 - sense * p.outer[j], room_i = 1.0 - sense * p.inner[j];
      const V band_absorbs = 0.5 * (room_o + room_i) * h;
      const V still = wanted - absorbed;
      const auto whole = open & (band_absorbs <= still);
      const auto ends_here = open & !whole;
      // the depth x where it has absorbed `still`: the smaller root, in a form without cancellation
      const V q = (room_o - room_i) / lane_select(h > 0.0, h, V(1.0));
      const V root = std::sqrt(lane_max(room_o * room_o - 2.0 * q * still, V(0.0)));
      const V denominator = room_o + root;
      const V x = lane_select(denominator > 0.0, 2.0 * still / denominator, h);
      const V part =
          lane_select(whole, h, lane_select(ends_here, lane_clamp(x, V(0.0), h), V(0.0)));
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
  [[gnu::always_inline]] inline V advance(Profile<V> &p, V overlap, V s, double kappa)
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
    p = select(grows, up, down);
    const V slid = slip_at_edge(p, to_slip);
    return lane_select(to_slip < 0.0, -slid, slid) * kappa;
  }

  // Each band's share of the force along the axis as a fraction of the sliding limit (§2.3):
  // with x = (overlap - w)/overlap the Hertz load fraction below depth w, band j from x0 (outer)
  // to x1 (inner) carries int m 1.5 sqrt(x) dx = b D + (a - b) Q/(sqrt(x0) + sqrt(x1)), a and b
  // its outer and inner slopes, D = x0^(3/2) - x1^(3/2) = e (x0 + s0 s1 + x1)/(s0 + s1) with
  // e = x0 - x1, s = sqrt(x), Q = 0.6 x0^2 + 0.6 x0 s0 s1 - 0.4 x0 x1 - 0.4 x1 s0 s1 - 0.4 x1^2
  // (derived here: the differences of powers factored, so that a thin band loses no digits).
  // The weights D, Q and s0 + s1 depend on the depths alone: a step that changes only the
  // slopes (the turn of micro_slip) weighs them again without recomputing them. A band below the
  // overlap (s0 + s1 = 0) weighs nothing.
  template <class V> struct BandWeights {
    V D[memory_bands], Q[memory_bands], roots[memory_bands];
  };

  template <class V>
  [[gnu::always_inline]] inline BandWeights<V> band_weights(const Profile<V> &p, V overlap)
  {
    BandWeights<V> w;
    const V inv = 1.0 / overlap;
    V begins = V(0.0), x0 = V(1.0), s0 = V(1.0);
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j) {
      const V e = p.depth[j] * inv;
      begins = begins + p.depth[j];
      const V x1 = lane_max(1.0 - begins * inv, V(0.0));
      const V s1 = std::sqrt(x1);
      const V roots = s0 + s1, ss = s0 * s1;
      const auto weighs = roots > 0.0;
      const V safe = lane_select(weighs, roots, V(1.0));
      const V D = e * (x0 + ss + x1) / safe;
      const V Q = 0.6 * x0 * x0 + 0.6 * x0 * ss - 0.4 * x0 * x1 - 0.4 * x1 * ss - 0.4 * x1 * x1;
      w.D[j] = lane_select(weighs, D, V(0.0));
      w.Q[j] = lane_select(weighs, Q, V(0.0));
      w.roots[j] = safe;
      x0 = x1, s0 = s1;
    }
    return w;
  }

  // A profile at m = 1 everywhere carries exactly 1.
  template <class V>
  [[gnu::always_inline]] inline V force_ratio(const Profile<V> &p, const BandWeights<V> &w)
  {
    V sum = V(0.0);
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j)
      sum = sum + (p.inner[j] * w.D[j] + (p.outer[j] - p.inner[j]) * w.Q[j] / w.roots[j]);
    return sum;
  }

  // the elastic energy of the springs, 4 G* int u^2 dxi over the half-row of springs at xi
  // (u = kappa phi(w), phi = int_0^w m, w = overlap - xi^2/R*): phi^2 is a polynomial of degree
  // 8 in xi on each band, integrated exactly by 5-point Gauss-Legendre in xi, phi evaluated from
  // the band's own depth t = w - W in [0, h] (no digits lost on a thin band). Returns
  // int phi^2 dxi; times 4 G* kappa^2 it is the energy (docs/theory.md §2.4).
  template <class V>
  [[gnu::always_inline]] inline V energy_factor(const Profile<V> &p, V overlap, V R)
  {
    constexpr double node[5] = {0.0, 0.5384693101056831, -0.5384693101056831, 0.9061798459386640,
                                -0.9061798459386640};
    constexpr double weight[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                  0.2369268850561891, 0.2369268850561891};
    const V Rinv = 1.0 / R;
    V begins = V(0.0), phi = V(0.0), sum = V(0.0);
    V xi0 = std::sqrt(R * lane_max(overlap, V(0.0)));
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j) {
      const V a = p.outer[j], b = p.inner[j], h = p.depth[j];
      begins = begins + h;
      // (a depth left within round-off of the overlap is none: its square root would not be)
      const V left = overlap - begins;
      const V xi1 = std::sqrt(R * lane_select(left > 16.0 * ulp_fraction * overlap, left, V(0.0)));
      const V mid = 0.5 * (xi0 + xi1), half = 0.5 * (xi0 - xi1);
      const V rise = 0.5 * (b - a) / lane_select(h > 0.0, h, V(1.0));
      V band = V(0.0);
      TYCORE_UNROLLED
      for (int q = 0; q < 5; ++q) {
        const V xi = mid + half * node[q];
        const V t = lane_clamp((xi0 - xi) * (xi0 + xi) * Rinv, V(0.0), h);    // w - W
        const V f = phi + t * (a + rise * t);
        band = band + weight[q] * f * f;
      }
      sum = sum + half * band;
      phi = phi + 0.5 * (a + b) * h;
      xi0 = xi1;
    }
    return sum;
  }

  // the profile of Mindlin & Deresiewicz's first loading at constant load to the force ratio
  // q = |T|/(mu P_H(overlap)) in [0, 1]: the slip annulus at slope +1 to the depth w_c where
  // P_H(overlap - w_c) = (1 - q) P_H(overlap), the rest untouched (slope 0)
  template <class V> [[gnu::always_inline]] inline void first_loading(Profile<V> &p, V overlap, V q)
  {
    const V inner = lane_max(1.0 - q, V(0.0));
    const V stuck = overlap * simd_cbrt(inner * inner);    // (1 - q)^(2/3) of the overlap
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j) p.outer[j] = p.inner[j] = p.depth[j] = V(0.0);
    p.outer[0] = p.inner[0] = V(1.0);
    p.depth[0] = overlap - stuck;
    p.depth[1] = stuck;
  }

  // the contact slides as a whole in the sense of `sense`: one band at the limit over the overlap
  template <class V> [[gnu::always_inline]] inline void sliding(Profile<V> &p, V overlap, V sense)
  {
    TYCORE_UNROLLED
    for (int j = 0; j < memory_bands; ++j) p.outer[j] = p.inner[j] = p.depth[j] = V(0.0);
    p.outer[0] = p.inner[0] = sense;
    p.depth[0] = overlap;
  }

}    // namespace bands

}    // namespace tycore

#endif
