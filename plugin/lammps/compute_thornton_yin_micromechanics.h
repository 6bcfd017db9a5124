/* -*- c++ -*- ----------------------------------------------------------
   compute ID group thornton/yin/micromechanics: global micromechanical measures of the
   contacts of pair thornton/yin as of its last force evaluation (Thornton 2000,
   Geotechnique 50(1)): contact-normal fabric, stress split into normal/tangential parts and
   into the strong/weak networks, sliding fraction. See docs/compute_thornton_yin_micromechanics.md.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_THORNTON_YIN_MICROMECHANICS_H
#define LMP_COMPUTE_THORNTON_YIN_MICROMECHANICS_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeThorntonYinMicromechanics : public Compute {
 public:
  // vector entries (0-based here, 1-based as c_ID[k] in LAMMPS): each tensor as xx yy zz xy
  // xz yz; stresses in pressure units with LAMMPS's virial convention (compression > 0,
  // xy = sum l_x f_y / V); names in analysis/tyanalysis/micromechanics.py
  enum {
    CONTACTS = 0,              // number of contacts
    SLIDING_FRACTION,          // fraction of them at the sliding limit
    MEAN_NORMAL_FORCE,         // <P> over the contacts
    STRONG_FRACTION,           // fraction with P > <P>
    FABRIC = 4,                // phi = <n n>, 6 entries
    FABRIC_DEVIATOR = 10,      // sqrt(3/2 phi':phi')  (= phi1 - phi3 when phi2 = phi3)
    STRESS = 11,               // (1/V) sum l (x) f, 6 entries
    STRESS_NORMAL = 17,        // normal forces only
    STRESS_TANGENTIAL = 23,    // tangential forces only
    STRESS_STRONG = 29,        // contacts with P > <P>
    STRESS_WEAK = 35,          // contacts with P <= <P>
    N_VECTOR = 41
  };

  ComputeThorntonYinMicromechanics(class LAMMPS *, int, char **);
  ~ComputeThorntonYinMicromechanics() override;
  void init() override;
  void compute_vector() override;
};

}    // namespace LAMMPS_NS

#endif
