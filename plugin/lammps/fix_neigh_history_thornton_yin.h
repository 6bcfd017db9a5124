/* -*- c++ -*- ----------------------------------------------------------
   fix NEIGH_HISTORY/THORNTON_YIN: the contact-history store of pair thornton/yin.

   LAMMPS 29Sep2021's FixNeighHistory::write_restart() copies the history from the
   neighbor list into per-atom arrays again, but the write_restart command has already
   re-exchanged atoms and rebuilt the ghosts by then: with a box that changed since the
   last neighbor build (fix cell/servo, fix deform), ghost indices no longer match the list
   and the copy reads uninitialised counts ("Neighbor history overflow") or files a
   history under the wrong atom. The copy made by post_run() at the end of the run, while
   list and ghosts still agreed, is what must be written; only restart files written
   during a run (the `restart` command) need a fresh copy.

   unpack_restart() reads the partner IDs of restart files of either LAMMPS version
   (tylmp_compat::restart_partner_tag; docs/lammps_versions.md).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_NEIGH_HISTORY_THORNTON_YIN_H
#define LMP_FIX_NEIGH_HISTORY_THORNTON_YIN_H

#include "fix_neigh_history.h"

namespace LAMMPS_NS {

class FixNeighHistoryThorntonYin : public FixNeighHistory {
 public:
  FixNeighHistoryThorntonYin(class LAMMPS *, int, char **);
  void write_restart(FILE *) override;
  void unpack_restart(int, int) override;
};

}    // namespace LAMMPS_NS

#endif
