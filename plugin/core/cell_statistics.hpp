// Per-particle statistics of a cell (fix cell/servo outputs Z, Zm, unbalanced, p_kinetic,
// kinetic_ratio). The fix adds every local particle to a ParticleSums, reduces the sums over
// the ranks (as_array/size) and turns them into the statistics here. Plain C++, no LAMMPS.
//
//   Z  = 2C/N, the contact ends per particle;
//   Zm = (2C - N1)/(N - N0 - N1), the mechanical coordination number of Thornton (2000):
//        rattlers (N0 particles without a contact, N1 with one) carry no load;
//   unbalanced = mean |resultant force on a particle| / mean |contact force|;
//   kinetic stress sigma_k = sum m v_k^2 / V of the fluctuation velocities, p_kinetic its mean;
//   kinetic_ratio = E_kin of the load-bearing particles (two or more contacts) / (p V): the
//        quasi-equilibrium test leaves the rattlers out as Zm does, since they move freely in
//        their cages whatever the packing does.
#ifndef TYCORE_CELL_STATISTICS_HPP
#define TYCORE_CELL_STATISTICS_HPP

#include <cmath>
#include <limits>

namespace tycore {

struct ParticleSums {
  static constexpr int size = 9;
  // particles, contact ends, N0, N1, sum |F|, sum m v_x^2, m v_y^2, m v_z^2, E_kin bearing
  double sum[size] = {0, 0, 0, 0, 0, 0, 0, 0, 0};

  void add(long contacts, const double force[3], double mass, const double velocity[3])
  {
    sum[0] += 1.0;
    sum[1] += static_cast<double>(contacts);
    sum[2] += contacts == 0;
    sum[3] += contacts == 1;
    sum[4] += std::sqrt(force[0] * force[0] + force[1] * force[1] + force[2] * force[2]);
    double energy = 0.0;
    for (int k = 0; k < 3; ++k) {
      sum[5 + k] += mass * velocity[k] * velocity[k];
      energy += 0.5 * mass * velocity[k] * velocity[k];
    }
    if (contacts >= 2) sum[8] += energy;
  }
};

struct ParticleStatistics {
  double Z, Zm, unbalanced, kinetic_stress[3], p_kinetic, kinetic_ratio;
};

// contacts and contact_force_sum: the number of contacts and the sum of their force
// magnitudes (each contact once); p_ref the stress level of the kinetic ratio
inline ParticleStatistics particle_statistics(const ParticleSums &s, double contacts,
                                              double contact_force_sum, double volume, double p_ref)
{
  constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
  const double n = s.sum[0], ends = s.sum[1], n0 = s.sum[2], n1 = s.sum[3];
  ParticleStatistics out;
  out.Z = n > 0.0 ? ends / n : NaN;
  out.Zm = n - n0 - n1 > 0.0 ? (ends - n1) / (n - n0 - n1) : 0.0;
  out.unbalanced =
      contact_force_sum > 0.0 && n > 0.0 ? (s.sum[4] / n) / (contact_force_sum / contacts) : NaN;
  for (int k = 0; k < 3; ++k) out.kinetic_stress[k] = s.sum[5 + k] / volume;
  out.p_kinetic = (out.kinetic_stress[0] + out.kinetic_stress[1] + out.kinetic_stress[2]) / 3.0;
  out.kinetic_ratio = p_ref > 0.0 ? s.sum[8] / (p_ref * volume) : NaN;
  return out;
}

// the sizes of the particles: number-mean diameter and density, solid volume
struct ParticleSizes {
  static constexpr int size = 4;
  double sum[size] = {0, 0, 0, 0};    // particles, diameters, densities, volumes

  void add(double radius, double mass)
  {
    const double volume = 4.0 / 3.0 * M_PI * radius * radius * radius;
    sum[0] += 1.0;
    sum[1] += 2.0 * radius;
    sum[2] += volume > 0.0 ? mass / volume : 0.0;
    sum[3] += volume;
  }
  double mean_diameter() const { return sum[1] / sum[0]; }
  double mean_density() const { return sum[2] / sum[0]; }
  double solid_volume() const { return sum[3]; }
};

}    // namespace tycore

#endif
