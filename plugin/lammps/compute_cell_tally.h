/* -*- c++ -*- ----------------------------------------------------------
   compute ID all CELL_TALLY (internal; fix cell/servo creates it): the servo's contact tallies
   (cell_tally.h) for a granular pair style other than thornton/yin, from the contacts of that
   pair's last force evaluation: the contact force from the pair's single(), the normal
   stiffness estimated from force and overlap (docs/theory.md §6.5; all 21 entries of §11.1
   when the servo controls shears), contacts per atom.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_CELL_TALLY_H
#define LMP_COMPUTE_CELL_TALLY_H

#include "cell_tally.h"
#include "compute.h"

namespace LAMMPS_NS {

class ComputeCellTally : public Compute, public CellTallySource {
 public:
  ComputeCellTally(class LAMMPS *, int, char **);
  ~ComputeCellTally() override;
  void init() override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  unsigned request_cell_tallies(unsigned entries) override;
  const CellTallies &cell_tallies() const override { return tallies; }
  const double *contact_count() const override { return tallied ? count : nullptr; }
  void refresh_cell_tallies() override;

 private:
  bool warned = false;    // the warning of request_cell_tallies, once
  bool tallied = false;
  bool with_shear = false;    // the 15 stiffness entries with a shear component too
  CellTallies tallies{};
  double *count = nullptr;    // contacts per atom, ghosts summed into their owners
  int nmax = 0;
};

}    // namespace LAMMPS_NS

#endif
