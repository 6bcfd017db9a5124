/* ----------------------------------------------------------------------
   The servo's contact tallies for any granular pair style (compute_cell_tally.h): one pass
   over the pair's own neighbor list after its force evaluation. Each contact (overlap > 0)
   counts once: a pair with a ghost partner is seen by both ranks without newton_pair and
   counts half on each. Its normal force comes from the pair's single() (the force on atom i
   along the branch vector, damping included), its normal stiffness from
   tycore::hertz_normal_stiffness, its tangential stiffness is left out (docs/theory.md §6.5);
   with shears asked for, the 15 entries with a shear component of §11.1 too.
------------------------------------------------------------------------- */

#include "compute_cell_tally.h"

#include "cell_stiffness.hpp"
#include "contact_stiffness_estimate.hpp"
#include "lammps_compat.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "neigh_list.h"
#include "pair.h"

#include <cmath>
#include <limits>

using namespace LAMMPS_NS;

ComputeCellTally::ComputeCellTally(LAMMPS *lmp, int narg, char **arg) : Compute(lmp, narg, arg)
{
  if (narg != 3)
    error->all(FLERR, "Illegal compute CELL_TALLY command (internal to fix cell/servo)");
  comm_reverse = 1;
}

ComputeCellTally::~ComputeCellTally()
{
  memory->destroy(count);
}

void ComputeCellTally::init() {}

// fix cell/servo asks for the tallies in its init(), after the computes' init(): the pair is
// checked here, each run, and the warning given once
unsigned ComputeCellTally::request_cell_tallies(unsigned entries)
{
  // the principal block alone, or all 21 entries (the estimate walks the neighbor list once
  // per measurement, not the pair's contact loop)
  using Sums = tycore::AffineStiffnessSums;
  with_shear = (entries & ~Sums::principal_entries) != 0;
  Pair *pair = force->pair;
  if (!pair)
    error->all(FLERR,
               "fix cell/servo needs a pair style: the servo's stress and stiffness "
               "come from the contacts");
  if (utils::strmatch(force->pair_style, "^hybrid"))
    error->all(FLERR,
               "fix cell/servo cannot estimate the contact stiffness of pair_style {}: "
               "use pair_style thornton/yin, or one granular pair style alone",
               force->pair_style);
  if (!pair->finitecutflag)
    error->all(FLERR,
               "fix cell/servo needs a granular pair style (contacts of spheres of "
               "finite size, as pair_style thornton/yin, granular or gran/*): pair_style {} is "
               "not one",
               force->pair_style);
  if (!atom->radius_flag)
    error->all(FLERR, "fix cell/servo requires per-atom radii (atom_style sphere)");
  if (!pair->single_enable)
    error->all(FLERR,
               "fix cell/servo: pair_style {} cannot report single contact forces "
               "(no single()), so the servo cannot estimate its contact stiffness; use pair_style "
               "thornton/yin or a granular pair style with single()",
               force->pair_style);
  if (comm->me == 0 && !warned)
    error->warning(FLERR,
                   "fix cell/servo with pair_style {}: the servo's stiffness is estimated "
                   "from the contact forces as for a Hertz law, without the tangential part, and "
                   "the pair does not add the affine contact velocity L (x_i - x_j) of the "
                   "deforming cell (docs/theory.md §5.2, §6.5): its tangential forces miss the "
                   "mean-field shear; pair_style thornton/yin has both",
                   force->pair_style);
  warned = true;
  return with_shear ? Sums::all_entries : Sums::principal_entries;
}

void ComputeCellTally::refresh_cell_tallies()
{
  Pair *pair = force->pair;
  NeighList *list = pair->list;
  if (!list)
    error->all(FLERR,
               "fix cell/servo: pair_style {} has no neighbor list to find its contacts "
               "in",
               force->pair_style);
  for (double &t : tallies.sum) t = 0.0;
  // which contacts slide is the pair's own state, which other styles do not expose
  tallies.sum[CellTallies::SLIDING] = std::numeric_limits<double>::quiet_NaN();
  if (atom->nmax > nmax) {
    memory->destroy(count);
    nmax = atom->nmax;
    memory->create(count, nmax, "cell/tally:count");
  }
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  for (int k = 0; k < nall; ++k) count[k] = 0.0;

  double **x = atom->x;
  const double *radius = atom->radius;
  const int *type = atom->type;
  const int newton_pair = force->newton_pair;
  for (int ii = 0; ii < list->inum; ++ii) {
    const int i = list->ilist[ii];
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; ++jj) {
      const int j = jlist[jj] & NEIGHMASK;
      const Eigen::Vector3d branch(x[j][0] - x[i][0], x[j][1] - x[i][1], x[j][2] - x[i][2]);
      const double rsq = branch.squaredNorm(), radsum = radius[i] + radius[j];
      if (rsq >= radsum * radsum) continue;
      const double r = std::sqrt(rsq);
      double fpair = 0.0;    // LAMMPS convention: F on i = fpair (x_i - x_j)
      pair->single(i, j, type[i], type[j], rsq, 1.0, 1.0, fpair);
      const double normal_force = fpair * r;    // compression positive
      const bool j_owned = j < nlocal || newton_pair;
      const double share = j_owned ? 1.0 : 0.5;
      const double k_N = tycore::hertz_normal_stiffness(normal_force, radsum - r);
      // the principal block, and with shears asked for the 15 entries with a shear component
      using Sums = tycore::AffineStiffnessSums;
      Sums::contact_entries(branch, k_N, 0.0, [&](int k, double value) {
        if (k < Sums::principal_size || with_shear)
          tallies.sum[CellTallies::STIFFNESS + k] += share * value;
      });
      tallies.sum[CellTallies::CONTACTS] += share;
      tallies.sum[CellTallies::FORCE] += share * std::fabs(normal_force);
      count[i] += 1.0;
      if (j_owned) count[j] += 1.0;
    }
  }
  if (newton_pair) tylmp_compat::reverse_comm(comm, this);
  tallied = true;
}

int ComputeCellTally::pack_reverse_comm(int n, int first, double *buf)
{
  for (int k = 0; k < n; ++k) buf[k] = count[first + k];
  return n;
}

void ComputeCellTally::unpack_reverse_comm(int n, int *list, double *buf)
{
  for (int k = 0; k < n; ++k) count[list[k]] += buf[k];
}

double ComputeCellTally::memory_usage()
{
  return static_cast<double>(nmax) * sizeof(double);
}
