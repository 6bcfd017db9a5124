// tyliggghts: Debian's LIGGGHTS 3.8 (libliggghts.so.3, unmodified) with the Thornton-Yin model of
// this project registered (thornton_yin_register.cpp, linked in). Same command line as
// `liggghts`: tyliggghts -in deck.in, under mpirun for several ranks.
#include <mpi.h>

#include "input.h"
#include "lammps.h"

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  LAMMPS_NS::LAMMPS *lmp = new LAMMPS_NS::LAMMPS(argc, argv, MPI_COMM_WORLD);
  lmp->input->file();
  delete lmp;
  MPI_Finalize();
  return 0;
}
