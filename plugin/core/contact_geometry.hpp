// The per-contact inputs of the batch law (ContactBatch, contact_batch.hpp) from what a DEM
// engine holds per sphere: position difference, velocity, angular velocity, radius, mass.
// One place for both engines that run the law: the LAMMPS pair (pair_thornton_yin.cpp) and the
// LIGGGHTS model (plugin/liggghts/), so that both hand the law the same numbers.
#ifndef TYCORE_CONTACT_GEOMETRY_HPP
#define TYCORE_CONTACT_GEOMETRY_HPP

#include "contact_batch.hpp"

#include <cmath>

namespace tycore {

// one sphere of a contact
struct SphereState {
  const double* v;        // velocity
  const double* omega;    // angular velocity
  double radius;
  double mass;
};

// Lane l of batch b for the contact of spheres i and j, del = x_i - x_j, rsq = |del|^2, r its
// root; first_touch: no history yet (JKR snap-on). With Affine, affine_v is the mean-field
// relative velocity L (x_i - x_j) of a deforming cell, added to the contact velocity
// (docs/theory.md §5.1).
template <bool Affine>
inline void contact_geometry(ContactBatch& b, int l, const double del[3], double rsq, double r,
                             const SphereState& si, const SphereState& sj, bool first_touch,
                             const double* affine_v = nullptr)
{
  const double radsum = si.radius + sj.radius;
  const double delta = radsum - r;
  // R* = ri rj/(ri + rj) and 1/R* from one division
  const double product = si.radius * sj.radius;
  const double inv = 1.0 / (product * radsum);
  b.R[l] = product * product * inv;
  b.Rinv[l] = radsum * radsum * inv;
  b.delta[l] = delta;
  b.rsq[l] = rsq;
  const double rinv = 1.0 / r;
  const double nx = del[0] * rinv, ny = del[1] * rinv, nz = del[2] * rinv;
  b.n[0][l] = nx, b.n[1][l] = ny, b.n[2][l] = nz;
  // relative velocity of i with respect to j at the contact point (docs/theory.md §5.1)
  double vr1 = si.v[0] - sj.v[0];
  double vr2 = si.v[1] - sj.v[1];
  double vr3 = si.v[2] - sj.v[2];
  if (Affine) {
    vr1 += affine_v[0];
    vr2 += affine_v[1];
    vr3 += affine_v[2];
  }
  const double vn = vr1 * nx + vr2 * ny + vr3 * nz;
  const double lever_i = si.radius - 0.5 * delta, lever_j = sj.radius - 0.5 * delta;
  const double *wi = si.omega, *wj = sj.omega;
  const double wr1 = lever_i * wi[0] + lever_j * wj[0];
  const double wr2 = lever_i * wi[1] + lever_j * wj[1];
  const double wr3 = lever_i * wi[2] + lever_j * wj[2];
  b.vn[l] = vn;
  b.vt[0][l] = vr1 - vn * nx + (ny * wr3 - nz * wr2);
  b.vt[1][l] = vr2 - vn * ny + (nz * wr1 - nx * wr3);
  b.vt[2][l] = vr3 - vn * nz + (nx * wr2 - ny * wr1);
  b.spin_n[l] = (wi[0] + wj[0]) * nx + (wi[1] + wj[1]) * ny + (wi[2] + wj[2]) * nz;
  b.m_star[l] = si.mass * sj.mass / (si.mass + sj.mass);
  b.first_touch[l] = first_touch;
}

}    // namespace tycore

#endif
