/* -*- c++ -*- ----------------------------------------------------------
   fix damping/cundall: Cundall's local non-viscous damping of forces and torques,
   for preparation stages (isotropic compression); see docs/fix_damping_cundall.md.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_DAMPING_CUNDALL_H
#define LMP_FIX_DAMPING_CUNDALL_H

#include "fix.h"

namespace LAMMPS_NS {

class FixDampingCundall : public Fix {
 public:
  FixDampingCundall(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;

 protected:
  double lambda_linear, lambda_angular;
};

}    // namespace LAMMPS_NS

#endif
