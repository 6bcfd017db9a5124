// The Thornton-Yin contact law for adhesive, frictional elastic spheres (Thornton & Yin 1991;
// Thornton 1991; Thornton & Randall 1988): JKR normal force (jkr.hpp) and Thornton's tangential
// law with adhesion (mindlin_deresiewicz.hpp). One call = one contact, one step.
// Adhesive = false is the Hertz-Mindlin-Deresiewicz specialisation (Gamma = 0, no peeling).
#ifndef TYCORE_THORNTON_YIN_HPP
#define TYCORE_THORNTON_YIN_HPP

#include "contact_types.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"

#include <cmath>

namespace tycore {

// normal force at contact radius a
template <bool Adhesive>
inline double normal_force_of_radius(const PairCoefficients& c, double R, double a)
{
  if (Adhesive) return jkr::normal_force(a, R, c.E_star, c.Gamma);
  const double a3 = a * a * a;    // same operation order as jkr::normal_force: Gamma = 0 gives
  return 4.0 * c.E_star * a3 / (3.0 * R);    // bit-identical Hertz forces (docs/theory.md §1.6)
}

// Advance one contact by one step: overlap delta now, tangential displacement increment ds of j
// relative to i at the contact (already rotated into the current tangent plane, see
// rotate_history). h must have been started by begin_contact. The JKR radius is found by Newton
// warm-started from the previous step's (h.radius; closed form on the first step,
// docs/theory.md §1.4). `parts` selects the optional outputs (ResultParts); the others are
// left at 0.
template <bool Adhesive>
inline ContactResult evaluate_contact(const PairCoefficients& c, double R, double delta,
                                      const Eigen::Vector3d& ds, ContactHistory& h,
                                      unsigned parts = RESULT_ALL)
{
  ContactResult r{};
  r.contact_radius = Adhesive ? jkr::contact_radius_warm(delta, R, c.E_star, c.Gamma, h.radius)
                              : std::sqrt(R * std::max(delta, 0.0));
  h.radius = r.contact_radius;
  r.P = normal_force_of_radius<Adhesive>(c, R, r.contact_radius);
  r.dissipation = 0.0;
  tangential_step<Adhesive>(c, R, r.P, ds, h, r.dissipation, r.contact_radius);

  if (parts & RESULT_TANGENTIAL_RADIUS) {
    const double Pc = effective_pull_off<Adhesive>(c, R);
    if (Adhesive && h.peeling != 0.0) {
      const Eigen::Map<const Eigen::Vector3d> T(h.T);
      r.tangential_radius =
          peeled_radius(c, R, r.P, Pc, peeling_discriminant(c, r.P, Pc, T.squaredNorm()));
    } else {
      r.tangential_radius = (Pc == 0.0) ? r.contact_radius
                                        : micro_slip_radius(R, c.E_star, r.P + 2.0 * Pc);
    }
  }
  r.T = Eigen::Map<const Eigen::Vector3d>(h.T);
  if (parts & RESULT_NORMAL_ENERGY) {
    const double a = r.contact_radius, a2 = a * a;
    r.normal_energy = Adhesive ? jkr::stored_energy(a, R, c.E_star, c.Gamma)
                               : 8.0 * c.E_star * (a2 * a2 * a) / (15.0 * R * R);
  }
  r.tangential_energy = tangential_energy(h);
  r.sliding = h.sliding != 0.0;
  r.peeling = h.peeling != 0.0;
  return r;
}

// elastic energy stored in a contact of radius a: the JKR normal part (zero at first touch)
// plus the tangential part carried in the history (the normal force is not needed)
inline double contact_stored_energy(const PairCoefficients& c, double R, double a, double /*P*/,
                                    const ContactHistory& h)
{
  return jkr::stored_energy(a, R, c.E_star, c.Gamma) + tangential_energy(h);
}

}    // namespace tycore

#endif
