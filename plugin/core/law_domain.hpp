// Where the Thornton-Yin law means something: bounds on a type pair's coefficients derived from
// the law itself (docs/theory.md §1 and §4), checked by pair thornton/yin at init.
//  - JKR is a small-contact theory (a << R*): its zero-load radius a0 (a0^3 = 9 pi Gamma R*^2/E*,
//    theory.md §1) must be below R*, i.e. 9 pi Gamma/(E* R*) < 1;
//  - every quantity the pair computes must be representable over the law's range of overlaps,
//    from the break overlap delta_f (theory.md §1) to the largest overlap the pair accepts
//    (the smaller radius, beyond which it stops the run).
#ifndef TYCORE_LAW_DOMAIN_HPP
#define TYCORE_LAW_DOMAIN_HPP

#include "contact_law.hpp"
#include "contact_types.hpp"
#include "jkr.hpp"

#include <cmath>

namespace tycore {

// a0/R*, JKR's zero-load contact radius over the effective radius; 0 without adhesion
inline double zero_load_radius_ratio(const PairCoefficients &c, double R)
{
  return c.Gamma > 0.0 ? jkr::zero_load_radius(c.Gamma, R, c.E_star) / R : 0.0;
}

// first quantity of the law that is not finite (nullptr: none), and the overlap where
struct LawDomainFault {
  const char *quantity = nullptr;
  double delta = 0.0;
};

// the law at the ends of its range delta_f <= delta <= delta_max and at first touch: contact
// radius, normal force and stiffness (not at delta_f), stored energy, sliding limit
// mu (P + 2 Pc), tangential stiffness 8 G* a_T and the tangential energy stored at the sliding
// limit
inline LawDomainFault law_domain_fault(const PairCoefficients &c, double R, double delta_max)
{
  LawDomainFault fault;
  const auto bad = [&](double value, const char *quantity, double delta) {
    if (std::isfinite(value) || fault.quantity) return;
    fault.quantity = quantity;
    fault.delta = delta;
  };
  const PairConstants k = pair_constants(c);
  const double Pc = jkr::pull_off_force(c.Gamma, R);
  const double delta_f = jkr::break_overlap(R, c.E_star, c.Gamma);
  bad(Pc, "pull-off force Pc", 0.0);
  bad(delta_f, "break overlap delta_f", 0.0);
  if (fault.quantity) return fault;
  for (const double delta : {delta_f, 0.0, delta_max}) {
    const double a = jkr::contact_radius(delta, R, c.E_star, c.Gamma);
    bad(a, "contact radius a", delta);
    const double P = jkr::normal_force(a, R, c.E_star, c.Gamma);
    bad(P, "normal force P", delta);
    // k_N is infinite at delta_f itself (d delta/da = 0 there, theory.md §1): not a fault
    if (delta != delta_f)
      bad(jkr::normal_stiffness(a, R, c.E_star, c.Gamma), "normal stiffness", delta);
    bad(jkr::stored_energy(a, R, c.E_star, c.Gamma), "stored energy", delta);
    const double limit = law::sliding_limit(k, P + 2.0 * Pc);
    bad(limit, "sliding limit mu (P + 2 Pc)", delta);
    const double a_T = c.Gamma > 0.0 ? std::cbrt(law::micro_slip_radius_cubed(k, R, P + 2.0 * Pc))
                                     : a;
    const double k_T = 8.0 * c.G_star * a_T;
    bad(k_T, "tangential stiffness 8 G* a", delta);
    if (k_T > 0.0) bad(limit * limit / (2.0 * k_T), "tangential energy at sliding", delta);
    if (fault.quantity) break;
  }
  return fault;
}

}    // namespace tycore

#endif
