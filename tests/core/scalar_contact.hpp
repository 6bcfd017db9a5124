// One contact of the glass pair (glass_pair.hpp) stepped by the law's scalar instantiation
// (law::scalar_step, what advance_contact and the scalar batch build run), for the closed-form
// tests of the law (test_mindlin_deresiewicz.cpp, test_thornton_yin.cpp): at a prescribed
// overlap, or at a prescribed normal force (the overlap of that force on the law's JKR or
// Hertz curve, docs/theory.md §1.1, found here by bisection).
#ifndef TYCORE_TESTS_SCALAR_CONTACT_HPP
#define TYCORE_TESTS_SCALAR_CONTACT_HPP

#include "contact_kernel.hpp"
#include "contact_law.hpp"
#include "contact_types.hpp"
#include "jkr.hpp"
#include "jkr_extra.hpp"
#include "mindlin_deresiewicz.hpp"

#include "glass_pair.hpp"

#include <Eigen/Core>

#include <cmath>

namespace scalar_contact {

using Eigen::Vector3d;

// what one step of the law gives
struct Result {
  double P;                   // normal force, > 0 repulsive
  double contact_radius;      // a(delta)
  double stiffness;           // k_T the law used this step, -1 where none (frictionless, peeled)
  Vector3d T;                 // tangential force on i after the step
  double normal_energy;       // JKR elastic + surface energy at a, zero at first touch (§1.7)
  double tangential_energy;   // the stored tangential energy of the history (§2.4)
  double dissipation;         // frictional dissipation of the step
  bool sliding, peeling;
};

// the overlap at which the law's normal force is P: Hertz delta = a^2/R*, a^3 = 3R*P/(4E*);
// JKR delta(a) with a on the branch where P(a) increases (a >= a0/4^(1/3), P >= -Pc), by
// bisection of P(a) = 4E*a^3/(3R*) - 4 sqrt(pi Gamma E* a^3)
inline double overlap_of_load(const tycore::PairCoefficients& c, double R, double P)
{
  if (c.Gamma == 0.0) {
    const double a = std::cbrt(3.0 * R * std::max(P, 0.0) / (4.0 * c.E_star));
    return a * a / R;
  }
  const double a0 = tycore::jkr::zero_load_radius(c.Gamma, R, c.E_star);
  double lo = a0 / std::cbrt(4.0), hi = 2.0 * a0 + std::cbrt(3.0 * R * std::abs(P) / c.E_star);
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (lo + hi);
    (tycore::jkr::normal_force(m, R, c.E_star, c.Gamma) < P ? lo : hi) = m;
  }
  return tycore::jkr::overlap(0.5 * (lo + hi), R, c.E_star, c.Gamma);
}

template <bool Adhesive> struct Contact {
  tycore::PairCoefficients c;
  tycore::PairConstants k;
  double R = glass_pair::kRstar;
  tycore::ContactHistory h;

  // a new contact (begin_contact): its memory starts empty, its first step lays the first band
  explicit Contact(const tycore::PairCoefficients& coefficients)
      : c(coefficients), k(tycore::pair_constants(coefficients))
  {
    tycore::begin_contact(h, Adhesive);
  }

  // one step at overlap delta with the tangential increment ds (in the tangent plane of n), the
  // history twisted about n by `twist`
  Result step(double delta, const Vector3d& ds, const Vector3d& n = Vector3d(0, 0, 1),
              double twist = 0.0)
  {
    const double nv[3] = {n.x(), n.y(), n.z()}, dsv[3] = {ds.x(), ds.y(), ds.z()};
    const tycore::law::Outputs<double> out =
        tycore::law::scalar_step<Adhesive>(k, R, 1.0 / R, delta, nv, twist, dsv, h);
    Result r;
    r.P = out.P;
    r.contact_radius = out.a;
    r.stiffness = out.stiffness;
    r.T = Vector3d(h.T[0], h.T[1], h.T[2]);
    r.normal_energy = tycore::jkr::stored_energy(out.a, R, c.E_star, c.Gamma);
    r.tangential_energy = h.stored_energy;
    r.dissipation = out.dissipation;
    r.sliding = h.sliding != 0.0;
    r.peeling = h.peeling != 0.0;
    return r;
  }

  // one step at the overlap of normal force P (overlap_of_load), the normal along z unless given
  Result step_at_load(double P, const Vector3d& ds, const Vector3d& n = Vector3d(0, 0, 1),
                      double twist = 0.0)
  {
    if (!(P == load_)) {
      load_ = P;
      overlap_ = overlap_of_load(c, R, P);
    }
    return step(overlap_, ds, n, twist);
  }

 private:
  double load_ = std::nan(""), overlap_ = 0.0;
};

}    // namespace scalar_contact

#endif
