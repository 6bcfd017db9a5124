/* ----------------------------------------------------------------------
   compute ID group thornton/yin/micromechanics (docs/compute_thornton_yin_micromechanics.md)
   Sums over the contact records of pair thornton/yin (both atoms in the group), each contact
   once over all ranks:
     fabric      phi_ab = (1/Nc) sum n_a n_b,  n = l/|l|
     stress      sigma_ab = (1/V) sum l_a f_b, f = P n + T t the force on atom i, l = x_i - x_j
                 (Thornton 2000, eqs 3-4), split into its normal (P n) and tangential (T t)
                 parts and into the strong (P > <P>) and weak (P <= <P>) networks.
------------------------------------------------------------------------- */

#include "compute_thornton_yin_micromechanics.h"
#include "tylmp_citations.h"

#include "compute_thornton_yin_contacts.h"
#include "pair_thornton_yin.h"

#include "domain.h"
#include "error.h"
#include "force.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

namespace {

// the six components xx yy zz xy xz yz of a (x) b, as LAMMPS's virial (v[3] = del_x f_y ...)
constexpr int A_OF[6] = {0, 1, 2, 0, 0, 1}, B_OF[6] = {0, 1, 2, 1, 2, 2};

}    // namespace

ComputeThorntonYinMicromechanics::ComputeThorntonYinMicromechanics(LAMMPS *lmp, int narg,
                                                                   char **arg) :
    Compute(lmp, narg, arg)
{
  tylmp::cite(lmp, tylmp::cite_thornton_2000);
  if (narg != 3)
    error->all(FLERR,
               "Illegal compute thornton/yin/micromechanics command: expected 'compute "
               "ID group thornton/yin/micromechanics' (no arguments)");
  vector_flag = 1;
  size_vector = N_VECTOR;
  extvector = 0;
  vector = new double[N_VECTOR];
  for (int k = 0; k < N_VECTOR; ++k) vector[k] = 0.0;
}

ComputeThorntonYinMicromechanics::~ComputeThorntonYinMicromechanics()
{
  delete[] vector;
}

void ComputeThorntonYinMicromechanics::init()
{
  ComputeThorntonYinContacts::recording_pair(lmp, style);
  if (domain->dimension != 3)
    error->all(FLERR, "compute thornton/yin/micromechanics requires a 3d simulation");
}

void ComputeThorntonYinMicromechanics::compute_vector()
{
  invoked_vector = update->ntimestep;
  const PairThorntonYin *pair = ComputeThorntonYinContacts::recording_pair(lmp, style);
  if (!pair->contacts_recorded() || pair->contact_record_step() < 0)
    error->all(FLERR,
               "compute {}: pair thornton/yin has not evaluated forces since this compute "
               "was defined; define it before the run (or give 'run 0')",
               style);
  const auto &records = pair->contact_records();

  // pass 1: number of contacts, sliding ones, sum of P (for the mean)
  double counts[3] = {0.0, 0.0, 0.0}, total[3];
  for (const auto &rec : records) {
    if (!(rec.mask & groupbit)) continue;
    counts[0] += 1.0;
    counts[1] += rec.sliding;
    counts[2] += rec.P;
  }
  MPI_Allreduce(counts, total, 3, MPI_DOUBLE, MPI_SUM, world);
  const double contacts = total[0];
  const double mean_P = contacts > 0.0 ? total[2] / contacts : 0.0;

  // pass 2: strong count, fabric and the stress parts
  enum { STRONG_COUNT = 0, PHI = 1, S_N = 7, S_T = 13, S_STRONG = 19, S_WEAK = 25, N_SUM = 31 };
  double local[N_SUM] = {0.0}, sums[N_SUM];
  for (const auto &rec : records) {
    if (!(rec.mask & groupbit)) continue;
    const double *l = rec.branch, *fn = rec.normal_force, *ft = rec.tangential_force;
    const double length = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    const bool strong = rec.P > mean_P;
    if (strong) local[STRONG_COUNT] += 1.0;
    for (int k = 0; k < 6; ++k) {
      const int a = A_OF[k], b = B_OF[k];
      local[PHI + k] += l[a] * l[b] / (length * length);
      const double normal = l[a] * fn[b], tangential = l[a] * ft[b];
      local[S_N + k] += normal;
      local[S_T + k] += tangential;
      local[(strong ? S_STRONG : S_WEAK) + k] += normal + tangential;
    }
  }
  MPI_Allreduce(local, sums, N_SUM, MPI_DOUBLE, MPI_SUM, world);

  const double to_stress = force->nktv2p / (domain->xprd * domain->yprd * domain->zprd);
  vector[CONTACTS] = contacts;
  vector[SLIDING_FRACTION] = contacts > 0.0 ? total[1] / contacts : 0.0;
  vector[MEAN_NORMAL_FORCE] = mean_P;
  vector[STRONG_FRACTION] = contacts > 0.0 ? sums[STRONG_COUNT] / contacts : 0.0;
  double deviator2 = 0.0;
  for (int k = 0; k < 6; ++k) {
    const double phi = contacts > 0.0 ? sums[PHI + k] / contacts : 0.0;
    vector[FABRIC + k] = phi;
    // phi' = phi - (tr phi/3) I, tr phi = 1 (0 without contacts); off-diagonals count twice
    const double dev = k < 3 ? phi - (contacts > 0.0 ? 1.0 / 3.0 : 0.0) : phi;
    deviator2 += (k < 3 ? 1.0 : 2.0) * dev * dev;
    vector[STRESS_NORMAL + k] = sums[S_N + k] * to_stress;
    vector[STRESS_TANGENTIAL + k] = sums[S_T + k] * to_stress;
    vector[STRESS + k] = vector[STRESS_NORMAL + k] + vector[STRESS_TANGENTIAL + k];
    vector[STRESS_STRONG + k] = sums[S_STRONG + k] * to_stress;
    vector[STRESS_WEAK + k] = sums[S_WEAK + k] * to_stress;
  }
  vector[FABRIC_DEVIATOR] = std::sqrt(1.5 * deviator2);
}
