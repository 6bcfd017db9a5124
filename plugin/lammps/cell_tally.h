/* -*- c++ -*- ----------------------------------------------------------
   Where pair thornton/yin and fix cell/servo meet: the sums the pair makes over the contacts
   of each force evaluation for the servo, declared once. The fix reads them through this
   interface from pair thornton/yin, which makes them exactly during its force evaluation, or,
   with any other granular pair style, from ComputeCellTally (compute_cell_tally.h), which
   estimates them from the contact forces (docs/theory.md §6.5).
------------------------------------------------------------------------- */

#ifndef LMP_TYLMP_CELL_TALLY_H
#define LMP_TYLMP_CELL_TALLY_H

namespace LAMMPS_NS {

// per-rank sums over the contacts of the last force evaluation (each contact once)
struct CellTallies {
  enum {
    STIFFNESS = 0,    // 21 entries: V C of the affine stiffness (docs/theory.md §6.1, §11.1) in
                      // the layout of tycore::AffineStiffnessSums (plugin/core/cell_stiffness.hpp):
                      // the principal block xx yy zz xy xz yz first (entries 0-5), then the 15
                      // entries with a shear component (6-20); only those asked for are made,
                      // the others stay zero
    CONTACTS = 21,    // number of contacts (touching pairs, tensile ones included)
    SLIDING = 22,     // number of contacts at the sliding limit
    FORCE = 23,       // sum of contact force magnitudes
    SIZE = 24
  };
  double sum[SIZE];
};

// what the servo asks of the pair
class CellTallySource {
 public:
  // make the tallies from the next force evaluation on (off again at the pair's init), with at
  // least the stiffness entries of the set `entries` (bit k for entry STIFFNESS + k, k =
  // tycore::AffineStiffnessSums::index(I, J)); returns the set made (a superset: a source makes
  // a few shapes of sets, each with its own branch-free summation). The source is told which
  // entries, never why: the set is the programme's (plugin/core/cell_programme.hpp)
  virtual unsigned request_cell_tallies(unsigned entries) = 0;
  virtual const CellTallies &cell_tallies() const = 0;
  // a source that does not make the tallies during the force evaluation (the route for other
  // pair styles, compute_cell_tally.h) makes them here, from that evaluation's contacts
  virtual void refresh_cell_tallies() {}
  // contacts per local atom of the last force evaluation (ghost contributions summed in);
  // nullptr before the first tallied one
  virtual const double *contact_count() const = 0;

 protected:
  ~CellTallySource() = default;
};

}    // namespace LAMMPS_NS

#endif
