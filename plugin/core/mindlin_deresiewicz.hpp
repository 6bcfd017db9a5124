// Closed-form pieces of Thornton's tangential law with adhesion (docs/theory.md §2) that the
// law (contact_law.hpp, its one text) calls: the Savkoor-Briggs shear factor, the
// Mindlin-Deresiewicz annulus dissipation, the tolerance of the Coulomb cap, the cos and sin of
// a twist of the history, and the history of a new contact. The law itself (peeling,
// micro-slip memory, sliding, energy balance) is written once, in contact_law.hpp.
#ifndef TYCORE_MINDLIN_DERESIEWICZ_HPP
#define TYCORE_MINDLIN_DERESIEWICZ_HPP

#include "contact_types.hpp"

#include <cmath>
#include <limits>

namespace tycore {

// coefficient of T^2 in the Savkoor-Briggs discriminant, E*/(4G*), from Thornton (1991)
// and not re-derived (docs/theory.md §2.2)
inline constexpr double savkoor_briggs_shear_factor = 0.25;

// a new contact (JKR snap-on or Hertz touch): no tangential force, an empty memory (its first
// step lays the first band), peeling if adhesive
inline void begin_contact(ContactHistory &h, bool adhesive)
{
  h = ContactHistory{};
  h.peeling = adhesive ? 1.0 : 0.0;
}

namespace detail {

  // cos and sin of a per-step twist t: below 1e-3 rad (twist_series_exact) the Taylor
  // polynomials, whose remainders t^6/720 and t^7/5040 are < 1.5e-21, replace the libm calls
  // exactly to round-off; the series alone is branch-free, for the lane loops
  [[gnu::always_inline]] inline bool twist_series_exact(double twist)
  {
    return std::abs(twist) < 1e-3;
  }

  [[gnu::always_inline]] inline void twist_cos_sin_series(double twist, double &c, double &s)
  {
    const double t2 = twist * twist;
    c = 1.0 - t2 * (0.5 - t2 * (1.0 / 24.0));
    s = twist * (1.0 - t2 * (1.0 / 6.0 - t2 * (1.0 / 120.0)));
  }

  inline void twist_cos_sin(double twist, double &c, double &s)
  {
    if (twist_series_exact(twist)) {
      twist_cos_sin_series(twist, c, s);
    } else {
      c = std::cos(twist);
      s = std::sin(twist);
    }
  }

  // relative tolerance (a few ulps) for "|T| is at the sliding limit"
  inline constexpr double limit_tolerance = 4.0 * std::numeric_limits<double>::epsilon();

  // Mindlin-Deresiewicz annulus dissipation per unit tangential displacement on a branch with
  // stiffness factor theta at constant P: mu Peff (1 - theta)^2 (1 + theta/2). It is the Masing /
  // Iwan-consistent rate (virgin curve f: f - x f'; Masing branch g = 2f(u/2): (g - u g')/2, both
  // equal to the expression above), zero without micro-slip, mu Peff at gross sliding, >= 0, and
  // it reproduces the Mindlin-Deresiewicz loop loss and the stored energy 1.2 (mu P)^2/(2 k_T) of
  // the fully mobilised (Hertzian-traction) contact (docs/theory.md §2.4).
  inline double annulus_dissipation_rate(double limit, double theta)
  {
    return limit * (1.0 - theta) * (1.0 - theta) * (1.0 + 0.5 * theta);
  }

}    // namespace detail

}    // namespace tycore

#endif
