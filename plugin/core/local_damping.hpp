// Cundall's local non-viscous damping (Cundall 1987; YADE NewtonIntegrator; docs/theory.md §8):
// each component of the unbalanced force is reduced by a fraction lambda of its magnitude
// when it does positive work on the (fluctuation) velocity, and increased when it brakes.
#ifndef TYCORE_LOCAL_DAMPING_HPP
#define TYCORE_LOCAL_DAMPING_HPP

namespace tycore {

// F_k <- F_k (1 - lambda sign(F_k v_k))   (docs/theory.md §8)
inline double cundall_damped_component(double force, double velocity, double lambda)
{
  const double power = force * velocity;
  if (power > 0.0) return force * (1.0 - lambda);
  if (power < 0.0) return force * (1.0 + lambda);
  return force;
}

}    // namespace tycore

#endif
