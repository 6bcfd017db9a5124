// The glass pair of docs/theory.md §1.8 shared by the contact-law unit tests: two equal spheres
// with R = 0.1 mm (R* = 0.05 mm), E = 70 GPa, nu = 0.3.
#ifndef TYCORE_TESTS_GLASS_PAIR_HPP
#define TYCORE_TESTS_GLASS_PAIR_HPP

#include "contact_types.hpp"

namespace glass_pair {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kE = 70e9, kNu = 0.3, kRstar = 5e-5;
inline const double kEstar = kE / (2.0 * (1.0 - kNu * kNu));                  // 1/E* = 2(1-nu^2)/E
inline const double kGstar = kE / (2.0 * (1.0 + kNu)) / (2.0 * (2.0 - kNu));  // G/(2(2-nu))

inline tycore::PairCoefficients coefficients(double mu, double Gamma)
{
  return tycore::PairCoefficients{kEstar, kGstar, mu, Gamma};
}

}    // namespace glass_pair

#endif
