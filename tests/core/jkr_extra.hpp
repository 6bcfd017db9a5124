// Closed forms of the JKR contact (docs/theory.md §1, §3.2) that the tests and benchmarks use
// and the plugin does not: the overlap of a contact radius (the inverse of
// jkr::contact_radius), the break radius, the safeguarded Newton inversion of §1.4(b) (the
// reference the law's Halley iteration is compared with), and the separation work, sticking
// velocity and restitution of a head-on impact (§3.2). In tycore::jkr beside the plugin's
// closed forms (plugin/core/jkr.hpp).
#ifndef TYTESTS_JKR_EXTRA_HPP
#define TYTESTS_JKR_EXTRA_HPP

#include "jkr.hpp"

#include <algorithm>
#include <cmath>

namespace tycore::jkr {

// delta = a^2/R* - 2 sqrt(pi Gamma a / E*)                           (docs/theory.md §1.1)
inline double overlap(double a, double R, double E, double Gamma)
{
  return a * a / R - 2.0 * std::sqrt(pi * Gamma * a / E);
}

// contact radius at separation, a_f = 6^(-2/3) a0                    (docs/theory.md §1.2)
inline double break_radius(double R, double E, double Gamma)
{
  return zero_load_radius(Gamma, R, E) / std::cbrt(36.0);
}

// safeguarded Newton on f(a) = delta(a) - delta, monotonic for a > a_f (docs/theory.md §1.4);
// `guess` warm-starts it (e.g. the previous step's radius)
inline double contact_radius_newton(double delta, double R, double E, double Gamma, double guess,
                                    int* iterations = nullptr, double rel_tol = 1e-14)
{
  if (Gamma == 0.0) return std::sqrt(R * std::max(delta, 0.0));
  double lo = break_radius(R, E, Gamma);
  double hi = std::max(2.0 * lo, std::sqrt(R * std::abs(delta)) + 2.0 * zero_load_radius(Gamma, R, E));
  double a = (guess > lo && guess < hi) ? guess : 0.5 * (lo + hi);
  int k = 0;
  for (; k < 100; ++k) {
    const double f = overlap(a, R, E, Gamma) - delta;
    if (f < 0.0) lo = a;
    else hi = a;
    const double slope = 2.0 * a / R - std::sqrt(pi * Gamma / (E * a));
    const double step = f / slope;
    // converged Newton step: accept it before the bracket test (a step below rounding gives
    // next == a == lo or hi, which the strict bracket test would throw away for a bisection)
    if (slope > 0.0 && std::abs(step) <= rel_tol * a) {
      a = std::clamp(a - step, lo, hi);
      break;
    }
    double next = a - step;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool converged = std::abs(next - a) <= rel_tol * a;
    a = next;
    if (converged) break;
  }
  if (iterations) *iterations = k + 1;
  return a;
}

// work lost in a normal approach-separation cycle, W = U(a_f) = 0.93550 Pc |delta_f| (§3.2)
inline double separation_work(double R, double E, double Gamma)
{
  return stored_energy(break_radius(R, E, Gamma), R, E, Gamma);
}

// critical sticking velocity of a head-on impact, V_s = sqrt(2W/m*) (docs/theory.md §3.2)
inline double sticking_velocity(double R, double E, double Gamma, double m_star)
{
  return std::sqrt(2.0 * separation_work(R, E, Gamma) / m_star);
}

// restitution of the purely elastic JKR impact, e = sqrt(1 - (V_s/V)^2) (docs/theory.md §3.2)
inline double restitution(double V, double V_s)
{
  return V <= V_s ? 0.0 : std::sqrt(1.0 - (V_s / V) * (V_s / V));
}

}    // namespace tycore::jkr

#endif
