// The servo's stiffness estimate for pair styles that cannot give their contact stiffness
// (docs/theory.md §6.5): the normal stiffness of a contact from its normal force and overlap
// alone, exact for a Hertz law. Pair thornton/yin gives k_N and k_T of its own law instead.
#ifndef TYCORE_CONTACT_STIFFNESS_ESTIMATE_HPP
#define TYCORE_CONTACT_STIFFNESS_ESTIMATE_HPP

namespace tycore {

// Hertz: F = (4/3) E* sqrt(R) delta^(3/2), so k_N = dF/d(delta) = 3F/(2 delta) at any E* and R.
// Zero for a contact without compressive force or overlap (it adds nothing to the estimate).
inline double hertz_normal_stiffness(double normal_force, double overlap)
{
  return (normal_force > 0.0 && overlap > 0.0) ? 1.5 * normal_force / overlap : 0.0;
}

}    // namespace tycore

#endif
