#include "fix_neigh_history_thornton_yin.h"

#include "lammps_compat.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "update.h"

using namespace LAMMPS_NS;

FixNeighHistoryThorntonYin::FixNeighHistoryThorntonYin(LAMMPS *lmp, int narg, char **arg) :
    FixNeighHistory(lmp, narg, arg)
{
}

void FixNeighHistoryThorntonYin::write_restart(FILE *fp)
{
  // during a run the list and the ghosts agree; between runs post_run() already copied
  if (update->whichflag != 0) pre_exchange();
  if (comm->me == 0) {
    int size = 0;
    fwrite(&size, sizeof(int), 1, fp);
  }
}

void FixNeighHistoryThorntonYin::unpack_restart(int nlocal, int nth)
{
  // the same walk through this atom's restart values as the base class (the sizes of the
  // fixes before this one, then ours: size, count, count x (partner ID, dnum values)): the
  // file's values per contact must be this build's (tycore::history_size), and the partner
  // IDs are read again in whichever encoding the file has
  const double *values = atom->extra[nlocal];
  int m = 0;
  for (int i = 0; i < nth; ++i) m += static_cast<int>(values[m]);
  const int size = static_cast<int>(values[m]), count = static_cast<int>(values[m + 1]);
  if (count > 0 && size != 2 + count * (dnum + 1))
    error->one(FLERR,
               "pair thornton/yin: the restart file keeps {} values per contact "
               "history, this build of the plugin {}: it was written by a build with another "
               "contact history and cannot be continued with this one",
               (size - 2) / count - 1, dnum);
  FixNeighHistory::unpack_restart(nlocal, nth);
  m += 2;
  for (int n = 0; n < npartner[nlocal]; ++n, m += dnum + 1)
    partner[nlocal][n] = tylmp_compat::restart_partner_tag(values[m]);
}
