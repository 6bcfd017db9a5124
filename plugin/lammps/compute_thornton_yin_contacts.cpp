/* ----------------------------------------------------------------------
   compute ID group thornton/yin/contacts      (docs/compute_thornton_yin_contacts.md)
   Copies the contact records that pair thornton/yin keeps of its last force evaluation
   while a compute thornton/yin/... exists (PairThorntonYin::contact_records).
------------------------------------------------------------------------- */

#include "compute_thornton_yin_contacts.h"

#include "pair_thornton_yin.h"

#include "error.h"
#include "force.h"
#include "memory.h"
#include "update.h"

using namespace LAMMPS_NS;

ComputeThorntonYinContacts::ComputeThorntonYinContacts(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0)
{
  if (narg != 3)
    error->all(FLERR,
               "Illegal compute thornton/yin/contacts command: expected 'compute ID "
               "group thornton/yin/contacts' (no arguments)");
  local_flag = 1;
  size_local_rows = 0;
  size_local_cols = N_COLUMNS;
  array_local = nullptr;
}

ComputeThorntonYinContacts::~ComputeThorntonYinContacts()
{
  memory->destroy(array_local);
}

PairThorntonYin *ComputeThorntonYinContacts::recording_pair(LAMMPS *lmp, const char *style)
{
  auto pair = dynamic_cast<PairThorntonYin *>(lmp->force->pair_match("thornton/yin", 1));
  if (!pair) lmp->error->all(FLERR, "compute {} requires pair_style thornton/yin", style);
  return pair;
}

void ComputeThorntonYinContacts::init()
{
  recording_pair(lmp, style);
}

void ComputeThorntonYinContacts::compute_local()
{
  invoked_local = update->ntimestep;
  const PairThorntonYin *pair = recording_pair(lmp, style);
  if (!pair->contacts_recorded() || pair->contact_record_step() < 0)
    error->all(FLERR,
               "compute {}: pair thornton/yin has not evaluated forces since this compute "
               "was defined; define it before the run (or give 'run 0')",
               style);
  const auto &records = pair->contact_records();
  int n = 0;
  for (const auto &rec : records)
    if (rec.mask & groupbit) ++n;
  if (n > nmax) {
    memory->destroy(array_local);
    nmax = n;
    memory->create(array_local, nmax, N_COLUMNS, "thornton/yin/contacts:array_local");
  }
  size_local_rows = n;
  int row = 0;
  for (const auto &rec : records) {
    if (!(rec.mask & groupbit)) continue;
    double *out = array_local[row++];
    out[ID_I] = rec.id_i;
    out[ID_J] = rec.id_j;
    for (int k = 0; k < 3; ++k) {
      out[FN_X + k] = rec.normal_force[k];
      out[FT_X + k] = rec.tangential_force[k];
      out[L_X + k] = rec.branch[k];
    }
    out[NORMAL_FORCE] = rec.P;
    out[OVERLAP] = rec.overlap;
    out[CONTACT_RADIUS] = rec.contact_radius;
    out[SLIDING] = rec.sliding;
    out[PEELING] = rec.peeling;
  }
}

double ComputeThorntonYinContacts::memory_usage()
{
  return (double) nmax * N_COLUMNS * sizeof(double);
}
