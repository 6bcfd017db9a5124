// The scalar entry of the Thornton-Yin contact law: one contact, one step, through the law's
// one text (contact_law.hpp) at the lane type double: the history carried onto the new tangent
// plane and twisted, the JKR radius (Halley rounds, the closed form where they fail), the
// normal force and the tangential law. The batch entry (contact_batch.hpp) runs the same text
// over the lanes of a batch; tests/core/test_contact_batch.cpp takes every step of long random
// contact paths (snap-in, peeling, micro-slip reversals, sliding, tension, break, twist, a
// turning normal) with this entry and with every build of the batch entry and asserts the same
// bits; the tests of tests/core/test_mindlin_deresiewicz.cpp and test_thornton_yin.cpp drive
// this entry against the closed forms of docs/theory.md.
#ifndef TYCORE_CONTACT_KERNEL_HPP
#define TYCORE_CONTACT_KERNEL_HPP

#include "contact_law.hpp"
#include "contact_types.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"

#include <algorithm>
#include <cmath>

namespace tycore {

struct KernelResult {
  double P;                 // normal force, positive repulsive
  double contact_radius;    // JKR radius a(delta)
};

// Whether a contact whose force is evaluated without a step of its history (the setup pass of
// a run: unchanged positions, history kept) slides under the coefficients in force now: its
// kept |T| at the Coulomb limit mu max(P + 2Pc, 0) (docs/theory.md §2), or a limit of zero (a
// frictionless contact, or a Hertz contact at zero load), which a step of the law also flags
// as sliding. The flag kept in the history belongs to the last step and to the mu of that
// step: after a change of mu (a new pair_coeff, fix adapt) it would be stale.
// The tolerance is wider than the law's (detail::limit_tolerance): P here is evaluated anew
// (normal_contact) and may differ in its last bits from the P of the step that capped T.
inline constexpr double setup_limit_tolerance = 1e-12;

inline bool slides_without_step(const PairConstants &k, double R, double P, const ContactHistory &h)
{
  const double Pc = jkr::pull_off_force(k.c.Gamma, R);
  const double limit = law::sliding_limit(k, P + 2.0 * Pc);
  if (limit <= 0.0) return true;
  const double T2 = h.T[0] * h.T[0] + h.T[1] * h.T[1] + h.T[2] * h.T[2];
  return T2 >= limit * limit * (1.0 - setup_limit_tolerance);
}

namespace law {

  // the JKR radius after halley_start at V = double: the later Halley rounds where pending, the
  // closed form where they found no radius
  inline void finish_radius(const PairConstants &k, double R, double Rinv, double delta,
                            Carry<double> &w)
  {
    for (int round = 3; round <= 6 && w.pending != 0.0; ++round)
      halley_again(Rinv, delta, k.newton_c, round == 6, w);
    if (w.a < 0.0) closed_form_radius(k.c, R, delta, w);
  }

  // the whole law for one contact at V = double: carry, the rest of the radius (finish_radius),
  // then the step; Rinv = 1/R
  template <bool Adhesive>
  inline Outputs<double> scalar_step(const PairConstants &k, double R, double Rinv, double delta,
                                     const double n[3], double twist, const double ds[3],
                                     History<double> &h)
  {
    double c = 1.0, s = 0.0;
    detail::twist_cos_sin(twist, c, s);
    Carry<double> w;
    carry<Adhesive>(k, n, c, s, twist != 0.0, Rinv, delta, h, w);
    if (Adhesive) finish_radius(k, R, Rinv, delta, w);
    return step<Adhesive, false>(k, R, Rinv, delta, ds, w, h);
  }

}    // namespace law

// The normal force and radius of the law at overlap delta without a step of the history (the
// setup pass, forces_without_step): the law's radius (halley_start from `radius`, the previous
// radius, <= 0: none; finish_radius) and normal_force
template <bool Adhesive>
inline KernelResult normal_contact(const PairConstants &k, double R, double delta, double radius)
{
  const double Rinv = 1.0 / R;
  law::Carry<double> w{};
  if (Adhesive) {
    law::halley_start(k, Rinv, delta, radius, w);
    law::finish_radius(k, R, Rinv, delta, w);
  }
  double a;
  const double P = law::normal_force<Adhesive>(k, R, Rinv, delta, w, a);
  return KernelResult{P, a};
}

// elastic energy stored in a contact of radius a: the JKR normal part (zero at first touch,
// jkr::stored_energy, docs/theory.md §1.7) plus the tangential part carried in the history
// (tangential work less frictional dissipation, §2.4)
inline double contact_stored_energy(const PairCoefficients &c, double R, double a, double /*P*/,
                                    const ContactHistory &h)
{
  return jkr::stored_energy(a, R, c.E_star, c.Gamma) + h.stored_energy;
}

// One contact, one step, after a previous step or begin_contact: the stored vectors are carried
// onto the tangent plane of n (magnitude kept) and twisted about n by the angle `twist`, then
// the normal force at overlap delta and the tangential law for the increment ds (in the new
// tangent plane). Adds the frictional dissipation of the step to `dissipation`.
template <bool Adhesive>
inline KernelResult advance_contact(const PairConstants &k, double R, double delta,
                                    const double n[3], double twist, const double ds[3],
                                    ContactHistory &h, double &dissipation)
{
  const law::Outputs<double> out =
      law::scalar_step<Adhesive>(k, R, 1.0 / R, delta, n, twist, ds, h);
  dissipation += out.dissipation;
  return KernelResult{out.P, out.a};
}

}    // namespace tycore

#endif
