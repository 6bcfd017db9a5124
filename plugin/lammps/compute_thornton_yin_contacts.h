/* -*- c++ -*- ----------------------------------------------------------
   compute ID group thornton/yin/contacts: the contacts of pair thornton/yin as of its last
   force evaluation, one row per contact (both atoms in the group); always current, unlike
   compute pair/local, whose neighbor list goes stale in a deforming box.
   See docs/compute_thornton_yin_contacts.md.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_THORNTON_YIN_CONTACTS_H
#define LMP_COMPUTE_THORNTON_YIN_CONTACTS_H

#include "compute.h"

namespace LAMMPS_NS {

class PairThorntonYin;

class ComputeThorntonYinContacts : public Compute {
 public:
  // columns of the local array, in order (docs/compute_thornton_yin_contacts.md)
  // clang-format off
  enum {
    ID_I, ID_J, FN_X, FN_Y, FN_Z, FT_X, FT_Y, FT_Z, L_X, L_Y, L_Z, NORMAL_FORCE, OVERLAP,
    CONTACT_RADIUS, SLIDING, PEELING, N_COLUMNS
  };
  // clang-format on

  ComputeThorntonYinContacts(class LAMMPS *, int, char **);
  ~ComputeThorntonYinContacts() override;
  void init() override;
  void compute_local() override;
  double memory_usage() override;

  // the pair's records for a compute of style `style` (errors if there are none to read)
  static PairThorntonYin *recording_pair(class LAMMPS *, const char *style);

 private:
  int nmax;
};

}    // namespace LAMMPS_NS

#endif
