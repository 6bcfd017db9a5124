#include "fix_neigh_history_thornton_yin.h"

#include "comm.h"
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
