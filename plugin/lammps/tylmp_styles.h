// The list of styles this library provides: one line per LAMMPS style.
#ifndef TYLMP_STYLES_H
#define TYLMP_STYLES_H

#include "compute_cell_tally.h"
#include "compute_thornton_yin_contacts.h"
#include "compute_thornton_yin_micromechanics.h"
#include "fix_cell_servo.h"
#include "fix_damping_cundall.h"
#include "fix_neigh_history_thornton_yin.h"
#include "pair_thornton_yin.h"

#define TYLMP_STYLE_LIST                                                         \
  TYLMP_PAIR("thornton/yin", LAMMPS_NS::PairThorntonYin)                         \
  TYLMP_FIX("damping/cundall", LAMMPS_NS::FixDampingCundall)                     \
  TYLMP_FIX("cell/servo", LAMMPS_NS::FixCellServo)                               \
  TYLMP_FIX("NEIGH_HISTORY/THORNTON_YIN", LAMMPS_NS::FixNeighHistoryThorntonYin) \
  TYLMP_COMPUTE("CELL_TALLY", LAMMPS_NS::ComputeCellTally)                       \
  TYLMP_COMPUTE("thornton/yin/contacts", LAMMPS_NS::ComputeThorntonYinContacts)  \
  TYLMP_COMPUTE("thornton/yin/micromechanics", LAMMPS_NS::ComputeThorntonYinMicromechanics)

#endif
