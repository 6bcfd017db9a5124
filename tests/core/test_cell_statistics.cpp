#include "cell_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>

using tycore::ParticleSums;

// four particles with 0, 1, 2 and 3 contacts (a chain 2-3-4-3... as counted by hand):
// C = 3 contacts, 2C = 6 ends. Z = 6/4; Zm leaves out the rattlers: (6 - 1)/(4 - 1 - 1) = 2.5
// (Thornton 2000); the kinetic ratio counts the particles with 2 and 3 contacts only
TEST(CellStatistics, CoordinationAndKineticEnergyWithoutRattlers)
{
  ParticleSums s;
  const double zero[3] = {0.0, 0.0, 0.0};
  const double v_rattler[3] = {1.0, 0.0, 0.0}, v_bearing[3] = {0.0, 2.0, 0.0};
  const double f_one[3] = {0.0, 0.0, 3.0}, f_small[3] = {0.0, 0.0, 0.5};
  s.add(0, zero, 1.0, v_rattler);       // a rattler: E = 0.5
  s.add(1, f_one, 1.0, v_rattler);      // a rattler on one contact: E = 0.5, |F| = 3
  s.add(2, f_small, 2.0, v_bearing);    // E = 4
  s.add(3, zero, 1.0, zero);
  const double volume = 10.0, p = 0.5, contacts = 3.0, contact_forces = 6.0;
  const tycore::ParticleStatistics st =
      tycore::particle_statistics(s, contacts, contact_forces, volume, p);
  EXPECT_DOUBLE_EQ(st.Z, 1.5);
  EXPECT_DOUBLE_EQ(st.Zm, 2.5);
  // mean |F| per particle 3.5/4 over mean contact force 6/3
  EXPECT_DOUBLE_EQ(st.unbalanced, (3.5 / 4.0) / 2.0);
  // kinetic stress: sum m v_x^2 = 2, m v_y^2 = 8, over V
  EXPECT_DOUBLE_EQ(st.kinetic_stress[0], 0.2);
  EXPECT_DOUBLE_EQ(st.kinetic_stress[1], 0.8);
  EXPECT_DOUBLE_EQ(st.kinetic_stress[2], 0.0);
  EXPECT_DOUBLE_EQ(st.p_kinetic, 1.0 / 3.0);
  // only the bearing particle's E = 4 counts: 4/(p V)
  EXPECT_DOUBLE_EQ(st.kinetic_ratio, 4.0 / (p * volume));
}

TEST(CellStatistics, EmptyCellGivesNoRatios)
{
  ParticleSums s;
  const tycore::ParticleStatistics st = tycore::particle_statistics(s, 0.0, 0.0, 1.0, 1.0);
  EXPECT_TRUE(std::isnan(st.Z));
  EXPECT_EQ(st.Zm, 0.0);
  EXPECT_TRUE(std::isnan(st.unbalanced));
  EXPECT_EQ(st.kinetic_ratio, 0.0);
}
