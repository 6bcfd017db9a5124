// Plain data of one Thornton-Yin contact: material pair and per-contact history.
// Symbols as in docs/theory.md §0: E*, G*, R*, Gamma (interface energy of each surface), mu.
#ifndef TYCORE_CONTACT_TYPES_HPP
#define TYCORE_CONTACT_TYPES_HPP

#include <Eigen/Core>

namespace tycore {

struct PairCoefficients {
  double E_star;    // contact modulus, 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2      (docs/theory.md §0)
  double G_star;    // Mindlin shear modulus, 1/G* = (2-nu1)/G1 + (2-nu2)/G2    (docs/theory.md §0)
  double mu;        // interparticle friction coefficient
  double Gamma;     // interface energy per surface [J/m^2]; Pc = 3 pi Gamma R*
};

inline double effective_modulus(double E1, double nu1, double E2, double nu2)
{
  return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
}

inline double effective_shear_modulus(double E1, double nu1, double E2, double nu2)
{
  const double G1 = E1 / (2.0 * (1.0 + nu1)), G2 = E2 / (2.0 * (1.0 + nu2));
  return 1.0 / ((2.0 - nu1) / G1 + (2.0 - nu2) / G2);
}

inline double effective_radius(double R1, double R2) { return R1 * R2 / (R1 + R2); }

// Mindlin-Deresiewicz branch of the tangential law (docs/theory.md §2.1: k = 0, 1, 2)
enum TangentialMode : int { LOADING = 0, UNLOADING = 1, RELOADING = 2 };

// Per-contact memory, stored verbatim in LAMMPS' contact history (14 doubles).
// Vectors are in the lab frame and belong to particle i of the pair (force on i).
struct ContactHistory {
  double T[3];          // tangential force on i
  double load_dir[3];   // unit direction of the current MD loading (zero before any slip)
  double T_star;        // T* : T along load_dir at the last loading->unloading reversal
  double T_star2;       // T**: T along load_dir at the last unloading->reloading reversal
  double P_prev;        // normal force of the previous step
  double mode;          // TangentialMode
  double peeling;       // 1 while Savkoor-Briggs peeling lasts (docs/theory.md §2.2)
  double sliding;       // 1 if the contact is at the sliding limit this step
  double stored_energy; // tangential elastic energy = tangential work - frictional dissipation
                        // (a path quantity: the incremental law has no potential when P varies)
  double radius;        // JKR contact radius of the last evaluated step: warm start of the
                        // delta -> a inversion (law::halley_start); 0 = none yet
};

constexpr int history_size = 14;
static_assert(sizeof(ContactHistory) == history_size * sizeof(double),
              "ContactHistory must be a packed array of doubles");

// the pair seen from j: vectors flip sign, scalars stay
constexpr double history_transfer_sign[history_size] = {-1, -1, -1, -1, -1, -1,
                                                        1,  1,  1,  1,  1,  1, 1, 1};

}    // namespace tycore

#endif
