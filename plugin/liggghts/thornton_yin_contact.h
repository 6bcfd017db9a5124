// The Thornton-Yin law for LIGGGHTS: what the LIGGGHTS contact model (normal_model_thornton_yin.h)
// needs from plugin/core, and nothing from LIGGGHTS. The law itself is not here: one contact is
// one lane of the core's batch entry, tycore::advance_batch (a step) or
// tycore::forces_without_step (LIGGGHTS's setup pass), the entry the LAMMPS pair runs
// (plugin/lammps/pair_thornton_yin.cpp), so that both engines evaluate the same code.
//  * contact_geometry: the per-contact inputs of the batch from positions, velocities and spins,
//    as pair_thornton_yin.cpp's eval() forms them (docs/theory.md §5.1);
//  * evaluate_contact: the ONE call into the core;
//  * the history layout: LIGGGHTS keeps named per-contact values (add_history_value) with a
//    newton flag (1: the value changes sign seen from j); ours are tycore::ContactHistory
//    verbatim, the flags from tycore::history_transfer_sign.
#ifndef TYLIGGGHTS_THORNTON_YIN_CONTACT_H
#define TYLIGGGHTS_THORNTON_YIN_CONTACT_H

#include "contact_batch.hpp"
#include "contact_kernel.hpp"
#include "contact_types.hpp"

#include <cmath>

namespace tyliggghts {

// ---- history layout: tycore::ContactHistory, in LIGGGHTS's named per-contact values ----
constexpr int history_size = tycore::history_size;
constexpr const char* history_names[history_size] = {
    "ty_T_x",      "ty_T_y",      "ty_T_z",   "ty_load_dir_x", "ty_load_dir_y",
    "ty_load_dir_z", "ty_T_star", "ty_T_star2", "ty_P_prev",   "ty_mode",
    "ty_peeling",  "ty_sliding",  "ty_stored_energy", "ty_radius"};
// LIGGGHTS's newtonflag of value k: "1" if it changes sign seen from the other sphere
inline const char* history_newton_flag(int k)
{
  return tycore::history_transfer_sign[k] < 0.0 ? "1" : "0";
}

// ---- one contact: sphere i (force on i) and sphere j ----
struct Sphere {
  const double* v;        // velocity
  const double* omega;    // angular velocity
  double radius;
  double mass;
};

// The batch lane of the contact of i and j, del = x_i - x_j: the same quantities in the same
// order of operations as PairThorntonYin::eval (plugin/lammps/pair_thornton_yin.cpp), so that
// both engines give the law the same numbers. first_touch: no history yet (JKR snap-on).
inline void contact_geometry(tycore::ContactBatch& b, int l, const double del[3], double rsq,
                             const Sphere& si, const Sphere& sj, bool first_touch)
{
  const double radsum = si.radius + sj.radius;
  const double r = std::sqrt(rsq);
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
  const double vr1 = si.v[0] - sj.v[0], vr2 = si.v[1] - sj.v[1], vr3 = si.v[2] - sj.v[2];
  const double vn = vr1 * nx + vr2 * ny + vr3 * nz;
  const double lever_i = si.radius - 0.5 * delta, lever_j = sj.radius - 0.5 * delta;
  const double* wi = si.omega;
  const double* wj = sj.omega;
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

// THE call into the core: contact 0 of batch b, with its history loaded, one step of the law
// (step) or its forces without a step (a setup pass). Adhesive: any Gamma > 0 in the
// simulation, Damped: any damping ratio > 0, as the LAMMPS pair chooses them. The scalar build:
// one contact at a time, bit for bit what the vector builds give (contact_batch.hpp).
template <bool Adhesive, bool Damped>
inline void evaluate_contact(tycore::ContactBatch& b, const tycore::PairConstants& k,
                             const tycore::BatchParameters& p, bool step)
{
  if (step) tycore::advance_batch<Adhesive, Damped>(b, 1, k, p, tycore::Isa::scalar);
  else tycore::forces_without_step<Adhesive, Damped>(b, 1, k, p);
}

}    // namespace tyliggghts

#endif
