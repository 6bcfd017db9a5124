/* ----------------------------------------------------------------------
   fix ID group damping/cundall lambda_linear lambda_angular
   F_k <- F_k (1 - lambda sign(F_k v_k)) per component (tycore::cundall_damped_component),
   torques likewise with the angular velocity. With fix cell/servo (and fix deform
   remap x) the particle velocities are fluctuations about the affine field, so the
   damping acts on fluctuations only (docs/theory.md §8, §5.1).
------------------------------------------------------------------------- */

#include "fix_damping_cundall.h"
#include "tylmp_numeric.h"

#include "local_damping.hpp"

#include "atom.h"
#include "error.h"
#include "respa.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixDampingCundall::FixDampingCundall(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  if (narg != 5)
    error->all(FLERR,
               "Illegal fix damping/cundall command: expected 'fix ID group "
               "damping/cundall lambda_linear lambda_angular'");
  lambda_linear = tylmp::finite_numeric(FLERR, arg[3], "fix damping/cundall: lambda_linear", lmp);
  lambda_angular = tylmp::finite_numeric(FLERR, arg[4], "fix damping/cundall: lambda_angular", lmp);
  if (!(lambda_linear >= 0.0 && lambda_linear < 1.0) ||
      !(lambda_angular >= 0.0 && lambda_angular < 1.0))
    error->all(FLERR, "fix damping/cundall: damping coefficients must lie in [0, 1) (got {} {})",
               lambda_linear, lambda_angular);
  if (!atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "fix damping/cundall requires atom style sphere (omega and torque)");
}

int FixDampingCundall::setmask()
{
  return POST_FORCE;
}

void FixDampingCundall::init()
{
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "fix damping/cundall does not support run_style respa");
}

void FixDampingCundall::setup(int vflag)
{
  post_force(vflag);
}

void FixDampingCundall::post_force(int)
{
  double **f = atom->f, **v = atom->v, **torque = atom->torque, **omega = atom->omega;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(mask[i] & groupbit)) continue;
    for (int k = 0; k < 3; ++k) {
      f[i][k] = tycore::cundall_damped_component(f[i][k], v[i][k], lambda_linear);
      torque[i][k] = tycore::cundall_damped_component(torque[i][k], omega[i][k], lambda_angular);
    }
  }
}
