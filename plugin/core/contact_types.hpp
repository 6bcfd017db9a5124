// Plain data of one Thornton-Yin contact: material pair and per-contact history.
// Symbols as in docs/theory.md §0: E*, G*, R*, Gamma (interface energy of each surface), mu.
#ifndef TYCORE_CONTACT_TYPES_HPP
#define TYCORE_CONTACT_TYPES_HPP

#include <cstddef>
#include <type_traits>

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

inline double effective_radius(double R1, double R2)
{
  return R1 * R2 / (R1 + R2);
}

// how many slip bands a contact's Mindlin-Deresiewicz memory holds (slip_bands.hpp, §2.3)
inline constexpr int memory_bands = 6;

// a loop over the bands (or other short fixed counts) taken apart into straight code: the lane
// loops of the vector builds (contact_batch_loops.hpp) vectorise only bodies with no inner loop
#define TYCORE_UNROLLED _Pragma("GCC unroll 8")

// ---- the history of a contact: ONE table, every listing generated from it ----
//
// TYCORE_HISTORY_FIELDS(X) calls X(name, values, carried, from_j, meaning) for each field of a
// contact's history (docs/theory.md §2.3), in storage order:
//  * values: 3 for a vector (lab frame, in the tangent plane, belonging to particle i of the
//    pair: the force on i), 1 for a scalar, memory_bands for the scalars of the slip bands;
//  * carried: what happens to it when the contact's tangent plane turns (law::carry,
//    docs/theory.md §2.3 step 1): `force` (T itself: projected onto the new plane with its
//    magnitude kept and twisted about the normal), `direction` (load_dir: the same, a unit
//    vector), `tangent` (any other tangent vector: projected, magnitude kept, twisted), `kept`
//    (scalars, unchanged);
//  * from_j: its sign when the pair is seen from particle j (LAMMPS's and LIGGGHTS's transfer
//    of the history to the partner): vectors -1, scalars +1 (the slopes are ratios along
//    load_dir of T, both of which flip);
//  * meaning: what it is.
// Generated from it: ContactHistory (LAMMPS's history page and restart files verbatim: the
// fields in this order, `values` doubles each), law::History (the law's lanes), the history
// arrays of ContactBatch and their load/store, the slot of each field (slot_index),
// history_size, history_transfer_sign, the LIGGGHTS history values' names and newton flags,
// and the pair's and the LIGGGHTS model's sizes of the history store. Adding a field is one
// row here (plus its physics in the law); its value starts at 0 in a new contact.
#define TYCORE_HISTORY_FIELDS(X)                                                                \
  X(T, 3, force, -1, "tangential force on i (elastic: damping is not in the history)")          \
  X(load_dir, 3, direction, -1,                                                                 \
    "unit axis of the Mindlin-Deresiewicz memory, along which the slip bands' slopes are "      \
    "counted (zero before any tangential displacement; §2.3)")                                  \
  X(band_outer, 6, kept, +1,                                                                    \
    "the memory's slip bands from the contact's edge inwards: the traction ratio m in [-1, 1] " \
    "at the outer edge of each (slip_bands.hpp, §2.3)")                                         \
  X(band_inner, 6, kept, +1, "the traction ratio m at the inner edge of each band (§2.3)")      \
  X(band_depth, 6, kept, +1,                                                                    \
    "the depth of each band, in units of the effective overlap; they add up to the effective "  \
    "overlap of the last step (§2.3)")                                                          \
  X(peeling, 1, kept, +1, "1 while Savkoor-Briggs peeling lasts (§2.2)")                        \
  X(sliding, 1, kept, +1, "1 if the contact is at the sliding limit this step")                 \
  X(stored_energy, 1, kept, +1,                                                                 \
    "tangential elastic energy: the energy of the memory's tractions, or while peeling the "    \
    "tangential work less dissipation (§2.4)")                                                  \
  X(radius, 1, kept, +1,                                                                        \
    "JKR contact radius of the last evaluated step: the warm start of the delta -> a "          \
    "inversion (law::halley_start, §1.4); 0 = none yet")

static_assert(memory_bands == 6, "the table's band rows hold memory_bands values");

namespace history {

  // how a field is carried onto a turned tangent plane (the table's `carried` column)
  enum Carried { force, direction, tangent, kept };

  // the type of a field of `values` values of type V: V for a scalar, V[3] for a vector
  template <class V, int values> struct field_type {
    using type = V[values];
  };
  template <class V> struct field_type<V, 1> {
    using type = V;
  };
  template <class V, int values> using field = typename field_type<V, values>::type;

  // value k of a field, scalar (k = 0) or vector alike
  template <class X> [[gnu::always_inline]] constexpr auto &value(X &x, int k)
  {
    if constexpr (std::is_array_v<X>)
      return x[k];
    else
      return x;
  }

}    // namespace history

// The history of one contact with values of type V: ContactHistory (V = double) and the law's
// lanes (law::History, contact_law.hpp). Vectors are in the lab frame and belong to particle i
// of the pair (force on i).
template <class V> struct HistoryOf {
#define TYCORE_HISTORY_MEMBER(name, values, carried, from_j, meaning) \
  history::field<V, values> name;
  TYCORE_HISTORY_FIELDS(TYCORE_HISTORY_MEMBER)
#undef TYCORE_HISTORY_MEMBER
};

// Per-contact memory, stored verbatim in LAMMPS's contact history (history_size doubles)
using ContactHistory = HistoryOf<double>;

#define TYCORE_HISTORY_COUNT(name, values, carried, from_j, meaning) +values
constexpr int history_size = 0 TYCORE_HISTORY_FIELDS(TYCORE_HISTORY_COUNT);
#undef TYCORE_HISTORY_COUNT
static_assert(sizeof(ContactHistory) == history_size * sizeof(double),
              "ContactHistory must be a packed array of doubles");

// the slot of each field in the history (ContactHistory as history_size doubles)
namespace slot_index {
#define TYCORE_SLOT_INDEX(name, values, carried, from_j, meaning) \
  constexpr int name = offsetof(ContactHistory, name) / sizeof(double);
  TYCORE_HISTORY_FIELDS(TYCORE_SLOT_INDEX)
#undef TYCORE_SLOT_INDEX
}    // namespace slot_index

// the sign of each history value when the pair is seen from j
#define TYCORE_TRANSFER_SIGN_1(from_j) from_j,
#define TYCORE_TRANSFER_SIGN_3(from_j) from_j, from_j, from_j,
#define TYCORE_TRANSFER_SIGN_6(from_j) from_j, from_j, from_j, from_j, from_j, from_j,
#define TYCORE_TRANSFER_SIGN(name, values, carried, from_j, meaning) \
  TYCORE_TRANSFER_SIGN_##values(from_j)
constexpr double history_transfer_sign[history_size] = {
    TYCORE_HISTORY_FIELDS(TYCORE_TRANSFER_SIGN)};
#undef TYCORE_TRANSFER_SIGN
#undef TYCORE_TRANSFER_SIGN_1
#undef TYCORE_TRANSFER_SIGN_3
#undef TYCORE_TRANSFER_SIGN_6

// checks of the table: a vector lies in the tangent plane and flips seen from j, a scalar is
// kept and does not
#define TYCORE_HISTORY_CHECK(name, values, carried, from_j, meaning)                           \
  static_assert((values == 3 && history::carried != history::kept && from_j == -1) ||          \
                    ((values == 1 || values == memory_bands) &&                                \
                     history::carried == history::kept && from_j == +1),                       \
                "history field " #name ": a vector is carried in the tangent plane and flips " \
                "sign seen from j, a scalar is kept and does not");
TYCORE_HISTORY_FIELDS(TYCORE_HISTORY_CHECK)
#undef TYCORE_HISTORY_CHECK

}    // namespace tycore

#endif
