#include "local_damping.hpp"

#include <gtest/gtest.h>

#include <cmath>

// Cundall damping removes the fraction lambda of the work done per cycle of a harmonic
// oscillator: amplitude decay per half period follows from energy = (1-lambda)/(1+lambda).
TEST(LocalDamping, HarmonicOscillatorLosesTheExpectedEnergyFraction)
{
  const double k = 1.0, m = 1.0, lambda = 0.1;
  const double omega = std::sqrt(k / m), dt = 1e-4 * 2 * M_PI / omega;
  double x = 1.0, v = 0.0;
  // one quarter period from rest at x=1 (force towards 0, velocity same sign: power > 0)
  // then the next quarter (power < 0). Integrate half a period with semi-implicit Euler.
  int steps = 0;
  double x_turn = 0.0;
  bool moving_negative = false;
  while (true) {
    const double f = tycore::cundall_damped_component(-k * x, v, lambda);
    v += f / m * dt;
    x += v * dt;
    ++steps;
    if (v < 0) moving_negative = true;
    if (moving_negative && v >= 0) { x_turn = x; break; }
  }
  // during the accelerating quarter the force is scaled by (1-lambda), braking by (1+lambda):
  // the turning amplitude satisfies (1-lambda) = (1+lambda) A^2, i.e. A = sqrt((1-l)/(1+l))
  EXPECT_NEAR(-x_turn, std::sqrt((1 - lambda) / (1 + lambda)), 2e-3);
  EXPECT_GT(steps, 1000);
}

// zero velocity or zero force: nothing to damp
TEST(LocalDamping, NoPowerNoChange)
{
  EXPECT_EQ(tycore::cundall_damped_component(2.0, 0.0, 0.3), 2.0);
  EXPECT_EQ(tycore::cundall_damped_component(0.0, 5.0, 0.3), 0.0);
  EXPECT_DOUBLE_EQ(tycore::cundall_damped_component(-2.0, 1.0, 0.3), -2.6);
}
