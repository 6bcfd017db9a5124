// The per-contact inputs of the batch law (ContactBatch, contact_batch.hpp) from what a DEM
// engine holds per sphere: position difference, velocity, angular velocity, radius, mass.
// One place for both engines that run the law: the LAMMPS pair (pair_thornton_yin.cpp) and the
// LIGGGHTS model (plugin/liggghts/), so that both hand the law the same numbers.
//
// Two steps, so that the arithmetic runs in SIMD lanes: gather_contact copies a contact's
// sphere data into its lane (the engine's loop over neighbours: copies and one subtraction),
// contact_geometry derives the law's inputs of a lane from them (normal, overlap, R*, the
// relative velocity at the contact point, docs/theory.md §5.1). batch_geometry runs
// contact_geometry over the lanes of a batch, in the instruction set the law runs in.
#ifndef TYCORE_CONTACT_GEOMETRY_HPP
#define TYCORE_CONTACT_GEOMETRY_HPP

#include "contact_batch.hpp"

#include <cmath>
#include <limits>

namespace tycore {

// one sphere of a contact
struct SphereState {
  const double *v;        // velocity
  const double *omega;    // angular velocity
  double radius;
  double mass;
};

// the velocity gradient of a deforming cell, upper triangular as LAMMPS's box (L[1][0] =
// L[2][0] = L[2][1] = 0): the mean-field relative velocity of a contact is L (x_i - x_j)
struct AffineGradient {
  double L[3][3];
};

// Lane l of batch b for the contact of spheres i and j, del = x_i - x_j, rsq = |del|^2;
// first_touch: no history yet (JKR snap-on). Damped: the masses too (m* of the damping).
template <bool Damped>
inline void gather_contact(ContactBatch &b, int l, const double del[3], double rsq,
                           const SphereState &si, const SphereState &sj, bool first_touch)
{
  for (int d = 0; d < 3; ++d) {
    b.del[d][l] = del[d];
    b.v_rel[d][l] = si.v[d] - sj.v[d];
    b.w_i[d][l] = si.omega[d];
    b.w_j[d][l] = sj.omega[d];
  }
  b.rsq[l] = rsq;
  b.r_i[l] = si.radius;
  b.r_j[l] = sj.radius;
  if (Damped) b.m_i[l] = si.mass, b.m_j[l] = sj.mass;
  b.first_touch[l] = first_touch;
}

// The law's inputs of lane l from its gathered sphere data. With Affine the mean-field relative
// velocity L (x_i - x_j) of a deforming cell is added to the contact velocity (docs/theory.md
// §5.1); Damped: m* = m_i m_j / (m_i + m_j). Branch-free, for the lane loops.
template <bool Affine, bool Damped>
[[gnu::always_inline]] inline void contact_geometry(ContactBatch &b, int l, const AffineGradient &g)
{
  const double ri = b.r_i[l], rj = b.r_j[l];
  const double radsum = ri + rj;
  const double r = std::sqrt(b.rsq[l]);
  const double delta = radsum - r;
  // R* = ri rj/(ri + rj) and 1/R* from one division
  const double product = ri * rj;
  const double inv = 1.0 / (product * radsum);
  b.R[l] = product * product * inv;
  b.Rinv[l] = radsum * radsum * inv;
  b.delta[l] = delta;
  const double rinv = 1.0 / r;
  const double dx = b.del[0][l], dy = b.del[1][l], dz = b.del[2][l];
  const double nx = dx * rinv, ny = dy * rinv, nz = dz * rinv;
  b.n[0][l] = nx, b.n[1][l] = ny, b.n[2][l] = nz;
  // relative velocity of i with respect to j at the contact point (docs/theory.md §5.1)
  double vr1 = b.v_rel[0][l], vr2 = b.v_rel[1][l], vr3 = b.v_rel[2][l];
  if (Affine) {
    const auto &L = g.L;
    vr1 += L[0][0] * dx + L[0][1] * dy + L[0][2] * dz;
    vr2 += L[1][1] * dy + L[1][2] * dz;
    vr3 += L[2][2] * dz;
  }
  const double vn = vr1 * nx + vr2 * ny + vr3 * nz;
  const double lever_i = ri - 0.5 * delta, lever_j = rj - 0.5 * delta;
  const double wi[3] = {b.w_i[0][l], b.w_i[1][l], b.w_i[2][l]};
  const double wj[3] = {b.w_j[0][l], b.w_j[1][l], b.w_j[2][l]};
  const double wr1 = lever_i * wi[0] + lever_j * wj[0];
  const double wr2 = lever_i * wi[1] + lever_j * wj[1];
  const double wr3 = lever_i * wi[2] + lever_j * wj[2];
  b.vn[l] = vn;
  b.vt[0][l] = vr1 - vn * nx + (ny * wr3 - nz * wr2);
  b.vt[1][l] = vr2 - vn * ny + (nz * wr1 - nx * wr3);
  b.vt[2][l] = vr3 - vn * nz + (nx * wr2 - ny * wr1);
  b.spin_n[l] = (wi[0] + wj[0]) * nx + (wi[1] + wj[1]) * ny + (wi[2] + wj[2]) * nz;
  if (Damped) b.m_star[l] = b.m_i[l] * b.m_j[l] / (b.m_i[l] + b.m_j[l]);
}

// Whether the overlap of lane l is in the law's domain: Hertz/JKR contact mechanics assume
// delta << R; once the overlap exceeds the smaller radius the law and the explicit step have
// long failed. A NaN overlap (a NaN position or radius) fails too, and so does a contact torn
// apart by an infinite position.
[[gnu::always_inline]] inline bool overlap_valid(const ContactBatch &b, int l)
{
  const double delta = b.delta[l], ri = b.r_i[l], rj = b.r_j[l];
  const double smaller = ri < rj ? ri : rj;
  return (delta <= smaller) & (delta >= -std::numeric_limits<double>::max());
}

// contact_geometry over the whole batch: every lane in the vector builds (lanes at and beyond n
// are computed on whatever they hold and never read back, as in advance_batch), lanes 0 .. n-1
// in the scalar build. The same arithmetic in every build (no fused multiply-add), so the
// builds agree to the bit. Returns whether every overlap of lanes 0 .. n-1 is valid
// (overlap_valid).
template <bool Affine, bool Damped>
inline bool geometry_lanes(ContactBatch &b, int n, const AffineGradient &g)
{
  bool valid = true;
  for (int l = 0; l < n; ++l) {
    contact_geometry<Affine, Damped>(b, l, g);
    valid &= overlap_valid(b, l);
  }
  return valid;
}

#ifdef TYCORE_VECTOR_BUILDS
namespace detail {    // the vector builds, contact_batch.cpp
  template <bool Affine, bool Damped>
  bool batch_geometry_sse2(ContactBatch &, int, const AffineGradient &);
  template <bool Affine, bool Damped>
  __attribute__((target("avx2"))) bool batch_geometry_avx2(ContactBatch &, int,
                                                           const AffineGradient &);
  template <bool Affine, bool Damped>
  __attribute__((target(TYCORE_AVX512))) bool batch_geometry_avx512(ContactBatch &, int,
                                                                    const AffineGradient &);
}    // namespace detail
#endif

template <bool Affine, bool Damped>
inline bool batch_geometry(ContactBatch &b, int n, const AffineGradient &g, Isa isa = best_isa())
{
  switch (isa) {
#ifdef TYCORE_VECTOR_BUILDS
    case Isa::avx512:
      return detail::batch_geometry_avx512<Affine, Damped>(b, n, g);
    case Isa::avx2:
      return detail::batch_geometry_avx2<Affine, Damped>(b, n, g);
    case Isa::sse2:
      return detail::batch_geometry_sse2<Affine, Damped>(b, n, g);
#endif
    default:
      return geometry_lanes<Affine, Damped>(b, n, g);
  }
}

}    // namespace tycore

#endif
