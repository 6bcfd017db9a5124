// The Thornton-Yin law for LIGGGHTS: what the LIGGGHTS contact model (normal_model_thornton_yin.h)
// needs from plugin/core, and nothing from LIGGGHTS. The law itself is not here: a contact is
// one lane of the core's batch entry, tycore::advance_batch (a step) or
// tycore::forces_without_step (LIGGGHTS's setup pass), the entry the LAMMPS pair runs
// (plugin/lammps/pair_thornton_yin.cpp), so that both engines evaluate the same code.
//  * the per-contact inputs of the batch come from tycore::contact_geometry, as in the pair;
//  * evaluate_contacts: the ONE call into the core;
//  * the history layout: LIGGGHTS keeps named per-contact values (add_history_value) with a
//    newton flag (1: the value changes sign seen from j); ours are tycore::ContactHistory
//    verbatim, the flags from tycore::history_transfer_sign.
#ifndef TYLIGGGHTS_THORNTON_YIN_CONTACT_H
#define TYLIGGGHTS_THORNTON_YIN_CONTACT_H

#include "contact_batch.hpp"
#include "contact_geometry.hpp"
#include "contact_kernel.hpp"
#include "contact_types.hpp"

#include <cmath>

namespace tyliggghts {

// ---- history layout: tycore::ContactHistory, in LIGGGHTS's named per-contact values: one
// per value of TYCORE_HISTORY_FIELDS, "ty_<field>" for a scalar, "ty_<field>_x" .. "_z"
// for a vector ----
constexpr int history_size = tycore::history_size;
#define TYLIGGGHTS_HISTORY_NAMES_1(name) "ty_" #name,
#define TYLIGGGHTS_HISTORY_NAMES_3(name) "ty_" #name "_x", "ty_" #name "_y", "ty_" #name "_z",
#define TYLIGGGHTS_HISTORY_NAMES_6(name)                                                    \
  "ty_" #name "_0", "ty_" #name "_1", "ty_" #name "_2", "ty_" #name "_3", "ty_" #name "_4", \
      "ty_" #name "_5",
#define TYLIGGGHTS_HISTORY_NAMES(name, values, carried, from_j, meaning) \
  TYLIGGGHTS_HISTORY_NAMES_##values(name)
constexpr const char *history_names[history_size] = {
    TYCORE_HISTORY_FIELDS(TYLIGGGHTS_HISTORY_NAMES)};
#undef TYLIGGGHTS_HISTORY_NAMES
#undef TYLIGGGHTS_HISTORY_NAMES_1
#undef TYLIGGGHTS_HISTORY_NAMES_3
#undef TYLIGGGHTS_HISTORY_NAMES_6
// LIGGGHTS's newtonflag of value k: "1" if it changes sign seen from the other sphere
inline const char *history_newton_flag(int k)
{
  return tycore::history_transfer_sign[k] < 0.0 ? "1" : "0";
}

// THE call into the core: contacts 0 .. n-1 of batch b, with their history loaded and their
// geometry computed, one step of the law (step) or their forces without a step (a setup pass).
// Adhesive: any Gamma > 0 in the simulation, Damped: any damping ratio > 0, as the LAMMPS pair
// chooses them. isa: the build of the law (contact_batch.hpp: every build gives the same bits);
// a single contact runs in the scalar build.
template <bool Adhesive, bool Damped>
inline void evaluate_contacts(tycore::ContactBatch &b, int n, const tycore::PairConstants &k,
                              const tycore::BatchParameters &p, bool step, tycore::Isa isa)
{
  if (step)
    tycore::advance_batch<Adhesive, Damped>(b, n, k, p, isa);
  else
    tycore::forces_without_step<Adhesive, Damped>(b, n, k, p);
}

}    // namespace tyliggghts

#endif
