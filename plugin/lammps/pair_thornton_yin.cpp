/* ----------------------------------------------------------------------
   pair_style thornton/yin — see docs/pair_thornton_yin.md and docs/theory.md.
   Physics: plugin/core/contact_law.hpp (tycore). Conventions follow pair granular:
   del = x_i - x_j, n = del/r points from j to i, P > 0 repulsive.
------------------------------------------------------------------------- */

#include "pair_thornton_yin.h"
#include "tylmp_citations.h"
#include "tylmp_numeric.h"

#include "box_rate.hpp"
#include "cell_stiffness.hpp"
#include "contact_geometry.hpp"
#include "contact_kernel.hpp"
#include "law_domain.hpp"

#include "atom.h"
#include "comm.h"
#include "compute.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "math_const.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "update.h"

#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>

using namespace LAMMPS_NS;
using MathConst::MY_PI;

namespace {

constexpr int HISTORY_SIZE = tycore::history_size;
constexpr double BIG = 1.0e20;
const char *const FIX_HISTORY_ID = "NEIGH_HISTORY_THORNTON_YIN";
const char *const FIX_DUMMY_ID = "NEIGH_HISTORY_THORNTON_YIN_DUMMY";

// the unit of an interface energy (energy per area) in the units the deck gave
std::string surface_energy_unit(const char *unit_style)
{
  const std::string u = unit_style;
  if (u == "si") return "J/m^2";
  if (u == "cgs") return "erg/cm^2";
  if (u == "micro") return "picogram/microsecond^2 ('units micro')";
  if (u == "nano") return "attogram/nanosecond^2 ('units nano')";
  return "energy/area of 'units " + u + "'";
}

// the global virial of one pair force as Pair::ev_tally_xyz adds it (its additions in its
// order): with newton_pair on once, else half for each local atom of the pair
inline void add_pair_virial(double vir[6], bool newton_pair, bool i_local, bool j_local, double fx,
                            double fy, double fz, double dx, double dy, double dz)
{
  const double w[6] = {dx * fx, dy * fy, dz * fz, dx * fy, dx * fz, dy * fz};
  if (newton_pair) {
    for (int k = 0; k < 6; ++k) vir[k] += w[k];
    return;
  }
  if (i_local)
    for (int k = 0; k < 6; ++k) vir[k] += 0.5 * w[k];
  if (j_local)
    for (int k = 0; k < 6; ++k) vir[k] += 0.5 * w[k];
}

inline tycore::ContactHistory load_history(const double *slot)
{
  tycore::ContactHistory h;
  std::memcpy(&h, slot, sizeof(h));
  return h;
}

}    // namespace

/* ---------------------------------------------------------------------- */

PairThorntonYin::PairThorntonYin(LAMMPS *lmp) : PairWithHistory(lmp)
{
  tylmp::cite(lmp, tylmp::cite_thornton_yin_1991);
  single_enable = 1;
  no_virial_fdotr_compute = 1;
  centroidstressflag = CENTROID_NOTAVAIL;
  finitecutflag = 1;
  restartinfo = 1;

  beyond_contact = 1;                 // adhesive contacts live beyond zero overlap
  nondefault_history_transfer = 1;    // scalars of the history keep their sign

  nextra = N_PVECTOR;
  pvector = new double[nextra];
  for (int k = 0; k < nextra; ++k) pvector[k] = 0.0;
  svector = new double[N_SVECTOR];
  single_extra = sub_style_of("hybrid") ? 0 : N_SVECTOR;

  youngs = poisson = nullptr;
  material_set = nullptr;
  E_star = G_star = friction = surface_energy = nullptr;
  damp_n = damp_t = nullptr;
  cut = nullptr;
  maxrad_type = nullptr;
  pair_constants = nullptr;
  adhesive = damped = 0;
  neighprev = 0;
  dt = 0.0;
  tally_cell = 0;
  batch_energy = false;
  principal_by_contact = true;
  lane_principal = lane_shear = -1;
  lane_entries = 0;
  record_contacts = 0;
  record_step = -1;
  isa = tycore::best_isa();
  for (double &h : box_h) h = 0.0;
  box_step = -1;
  box_from_setup = 1;
  box_rate_warned = 0;
  for (double &t : tallies.sum) t = 0.0;
  atom_contacts = nullptr;
  nmax_count = 0;
  comm_reverse = 1;

  // one instance only: its contact history has one store, named by fixed IDs (restart files)
  if (modify->find_fix(FIX_DUMMY_ID) >= 0 || modify->find_fix(FIX_HISTORY_ID) >= 0)
    error->all(FLERR,
               "pair thornton/yin may appear only once in a hybrid pair style (its "
               "contact history has one store): give all its type pairs to one thornton/yin "
               "('pair_coeff I J thornton/yin E nu mu Gamma'; the materials may differ by type)");

  // placeholder keeps the history fix at the position of the pair_style command
  fix_history = nullptr;
  modify->add_fix(std::string(FIX_DUMMY_ID) + " all DUMMY");
}

/* ---------------------------------------------------------------------- */

PairThorntonYin::~PairThorntonYin()
{
  if (copymode) return;
  delete[] pvector;
  delete[] svector;
  memory->destroy(atom_contacts);
  if (!fix_history)
    modify->delete_fix(FIX_DUMMY_ID);
  else
    modify->delete_fix(FIX_HISTORY_ID);

  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(cut);
    memory->destroy(E_star);
    memory->destroy(G_star);
    memory->destroy(friction);
    memory->destroy(surface_energy);
    memory->destroy(damp_n);
    memory->destroy(damp_t);
    delete[] youngs;
    delete[] poisson;
    delete[] material_set;
    delete[] maxrad_type;
    delete[] pair_constants;
  }
}

/* ---------------------------------------------------------------------- */

void PairThorntonYin::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  memory->create(cut, n + 1, n + 1, "pair:cut");
  memory->create(E_star, n + 1, n + 1, "pair:E_star");
  memory->create(G_star, n + 1, n + 1, "pair:G_star");
  memory->create(friction, n + 1, n + 1, "pair:friction");
  memory->create(surface_energy, n + 1, n + 1, "pair:surface_energy");
  memory->create(damp_n, n + 1, n + 1, "pair:damp_n");
  memory->create(damp_t, n + 1, n + 1, "pair:damp_t");
  youngs = new double[n + 1];
  poisson = new double[n + 1];
  material_set = new int[n + 1];
  maxrad_type = new double[n + 1];
  pair_constants = new tycore::PairConstants[(n + 1) * (n + 1)];
  for (int i = 0; i <= n; ++i) {
    youngs[i] = poisson[i] = maxrad_type[i] = 0.0;
    material_set[i] = 0;
    for (int j = 0; j <= n; ++j) {
      setflag[i][j] = 0;
      cut[i][j] = cutsq[i][j] = 0.0;
      E_star[i][j] = G_star[i][j] = friction[i][j] = surface_energy[i][j] = 0.0;
      damp_n[i][j] = damp_t[i][j] = 0.0;
    }
  }
}

/* ---------------------------------------------------------------------- */

void PairThorntonYin::settings(int narg, char **arg)
{
  // pair_style thornton/yin: no arguments
  if (narg > 0)
    error->all(FLERR,
               "pair_style thornton/yin takes no arguments, got '{}'; material "
               "parameters go in pair_coeff I J E nu mu Gamma [damping beta_n beta_t]",
               arg[0]);
  // the build of the batch law (tycore::advance_batch): the widest this processor runs
  // (tycore::best_isa). Tests and benchmarks may name another in the environment variable
  // TYLMP_LAW_ISA (scalar, sse2, avx2, avx512); all builds give the same forces to the bit.
  isa = tycore::best_isa();
  const char *forced = std::getenv("TYLMP_LAW_ISA");
  if (!forced) return;
  const std::string value = forced;
  for (const tycore::Isa choice :
       {tycore::Isa::scalar, tycore::Isa::sse2, tycore::Isa::avx2, tycore::Isa::avx512})
    if (value == tycore::isa_name(choice)) {
      if (!tycore::isa_supported(choice))
        error->all(FLERR,
                   "pair thornton/yin: TYLMP_LAW_ISA={}: this build or processor does "
                   "not run {} instructions (here the widest is {}); unset it or name a "
                   "narrower build",
                   value, value, tycore::isa_name(tycore::best_isa()));
      isa = choice;
      return;
    }
  error->all(FLERR,
             "pair thornton/yin: the environment variable TYLMP_LAW_ISA (a setting for "
             "tests and benchmarks) must be scalar, sse2, avx2 or avx512, got '{}'",
             value);
}

/* ----------------------------------------------------------------------
   pair_coeff I J E nu mu Gamma [damping beta_n beta_t]   (SI: Pa, -, -, J/m^2)
------------------------------------------------------------------------- */

void PairThorntonYin::coeff(int narg, char **arg)
{
  const char *usage = "pair_coeff I J E nu mu Gamma [damping beta_n beta_t]";
  if (narg < 6)
    error->all(FLERR, "Incorrect args for pair coefficients of thornton/yin: expected '{}'", usage);
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);

  const auto number = [&](int k, const char *name) {
    return tylmp::finite_numeric(FLERR, arg[k], fmt::format("pair_coeff thornton/yin: {}", name),
                                 lmp);
  };
  const double E = number(2, "Young's modulus E");
  const double nu = number(3, "Poisson's ratio nu");
  const double mu = number(4, "friction coefficient mu");
  const double Gamma = number(5, "interface energy Gamma");
  if (!(E > 0.0))
    error->all(FLERR, "pair_coeff thornton/yin: Young's modulus E must be > 0 (got {})", E);
  if (!(nu > -1.0 && nu < 0.5))
    error->all(FLERR,
               "pair_coeff thornton/yin: Poisson's ratio nu must lie in (-1, 0.5) "
               "(got {})",
               nu);
  if (!(mu >= 0.0))
    error->all(FLERR, "pair_coeff thornton/yin: friction coefficient mu must be >= 0 (got {})", mu);
  if (!(Gamma >= 0.0))
    error->all(FLERR,
               "pair_coeff thornton/yin: interface energy Gamma must be >= 0 {} "
               "(got {})",
               surface_energy_unit(update->unit_style), Gamma);

  double beta_n = 0.0, beta_t = 0.0;
  for (int iarg = 6; iarg < narg;) {
    if (strcmp(arg[iarg], "damping") == 0) {
      if (iarg + 3 > narg)
        error->all(FLERR, "pair_coeff thornton/yin: 'damping' needs two values beta_n beta_t");
      beta_n = number(iarg + 1, "damping ratio beta_n");
      beta_t = number(iarg + 2, "damping ratio beta_t");
      if (!(beta_n >= 0.0) || !(beta_t >= 0.0))
        error->all(FLERR, "pair_coeff thornton/yin: damping ratios must be >= 0 (got {} {})",
                   beta_n, beta_t);
      iarg += 3;
    } else {
      error->all(FLERR, "Unknown pair_coeff keyword '{}' for pair thornton/yin (expected '{}')",
                 arg[iarg], usage);
    }
  }

  int count = 0;
  for (int i = ilo; i <= ihi; ++i) {
    for (int j = MAX(jlo, i); j <= jhi; ++j) {
      // an explicit I J line describes both spheres as made of the given material
      E_star[i][j] = tycore::effective_modulus(E, nu, E, nu);
      G_star[i][j] = tycore::effective_shear_modulus(E, nu, E, nu);
      friction[i][j] = mu;
      surface_energy[i][j] = Gamma;
      damp_n[i][j] = beta_n;
      damp_t[i][j] = beta_t;
      if (i == j) {
        youngs[i] = E;
        poisson[i] = nu;
        material_set[i] = 1;
      }
      setflag[i][j] = 1;
      ++count;
    }
  }
  if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients of thornton/yin");
}

/* ----------------------------------------------------------------------
   unlike types I != J without an explicit pair_coeff: docs/theory.md §0
------------------------------------------------------------------------- */

void PairThorntonYin::mix_pair(int i, int j)
{
  if (!material_set[i] || !material_set[j])
    error->all(FLERR,
               "pair thornton/yin: coefficients for types {} {} are not set and cannot "
               "be mixed: give 'pair_coeff {} {} ...' and 'pair_coeff {} {} ...'",
               i, j, i, i, j, j);
  E_star[i][j] = tycore::effective_modulus(youngs[i], poisson[i], youngs[j], poisson[j]);
  G_star[i][j] = tycore::effective_shear_modulus(youngs[i], poisson[i], youngs[j], poisson[j]);
  friction[i][j] = std::sqrt(friction[i][i] * friction[j][j]);
  // work of adhesion of unlike surfaces ~ geometric mean (Berthelot rule)
  surface_energy[i][j] = std::sqrt(surface_energy[i][i] * surface_energy[j][j]);
  damp_n[i][j] = 0.5 * (damp_n[i][i] + damp_n[j][j]);
  damp_t[i][j] = 0.5 * (damp_t[i][i] + damp_t[j][j]);
}

/* ---------------------------------------------------------------------- */

void PairThorntonYin::init_style()
{
  tally_cell = 0;    // fix cell/servo switches the cell tallies on in its init(), after this
  // the contact computes read the contacts of every force evaluation
  record_contacts = 0;
  for (int k = 0; k < modify->ncompute; ++k)
    if (utils::strmatch(modify->compute[k]->style, "^thornton/yin/")) record_contacts = 1;
  if (!record_contacts) {
    records.clear();
    record_step = -1;
  }
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR,
               "pair thornton/yin requires atom style sphere (per-atom radius, rmass, "
               "omega and torque)");
  if (comm->ghost_velocity == 0)
    error->all(FLERR,
               "pair thornton/yin requires ghost velocities: add 'comm_modify vel yes' "
               "before the run");
  const std::string units = update->unit_style;
  if (units != "si" && units != "cgs" && units != "micro" && units != "nano")
    error->all(FLERR,
               "pair thornton/yin needs a mechanically consistent unit system "
               "(units si, cgs, micro or nano), got 'units {}'",
               units);

  check_hybrid_outputs();

  tylmp_compat::request_history_list(neighbor, this, instance_me);
  // one batch per type pair, made when its first contact comes (eval)
  batches.clear();
  batches.resize((atom->ntypes + 1) * (atom->ntypes + 1));
  batch_of_types.assign((atom->ntypes + 1) * (atom->ntypes + 1), nullptr);

  dt = update->dt;

  if (fix_history == nullptr) {
    fix_history = (FixNeighHistory *) modify->replace_fix(
        FIX_DUMMY_ID,
        fmt::format("{} all NEIGH_HISTORY/THORNTON_YIN {}", FIX_HISTORY_ID, HISTORY_SIZE), 1);
    fix_history->pair = this;
  } else {
    const int ifix = modify->find_fix(FIX_HISTORY_ID);
    if (ifix < 0) error->all(FLERR, "pair thornton/yin: could not find its history fix");
    fix_history = (FixNeighHistory *) modify->fix[ifix];
  }

  // largest radius per type, over all ranks (used by init_one and the checks below)
  const int ntypes = atom->ntypes;
  double *local_max = new double[ntypes + 1];
  for (int t = 0; t <= ntypes; ++t) local_max[t] = 0.0;
  for (int i = 0; i < atom->nlocal; ++i)
    local_max[atom->type[i]] = MAX(local_max[atom->type[i]], atom->radius[i]);
  MPI_Allreduce(local_max, maxrad_type, ntypes + 1, MPI_DOUBLE, MPI_MAX, world);
  delete[] local_max;

  // the checks below see the mixed coefficients of unlike types (init_one mixes them later)
  for (int i = 1; i <= ntypes; ++i)
    for (int j = i; j <= ntypes; ++j) {
      if (!handles(i, j)) continue;
      if (!setflag[i][j]) mix_pair(i, j);
      const double rad_i = largest_radius(i), rad_j = largest_radius(j);
      if (rad_i > 0.0 && rad_j > 0.0) check_law_domain(i, j, rad_i, rad_j, true);
    }
  check_break_against_skin();
  check_timestep_against_rayleigh();
}

/* ----------------------------------------------------------------------
   A tensile JKR contact survives to delta_f < 0 (docs/theory.md §1.2). The size
   neighbor list keeps a pair only within radsum + skin at a rebuild, so skin > |delta_f| is
   required, otherwise adhesive contacts are silently lost.
------------------------------------------------------------------------- */

void PairThorntonYin::check_break_against_skin()
{
  const int ntypes = atom->ntypes;
  for (int i = 1; i <= ntypes; ++i) {
    for (int j = i; j <= ntypes; ++j) {
      if (maxrad_type[i] <= 0.0 || maxrad_type[j] <= 0.0 || !handles(i, j)) continue;
      const double R = tycore::effective_radius(maxrad_type[i], maxrad_type[j]);
      const double gap = -tycore::jkr::break_overlap(R, E_star[i][j], surface_energy[i][j]);
      if (gap > 0.0 && neighbor->skin <= gap)
        error->all(FLERR,
                   "pair thornton/yin: neighbor skin {:.6g} is not larger than the JKR "
                   "break separation |delta_f| = {:.6g} of types {} {}; adhesive contacts would "
                   "be lost at a neighbor-list rebuild. Use e.g. 'neighbor {:.3g} bin'",
                   neighbor->skin, gap, i, j, 2.0 * gap);
    }
  }
}

/* ----------------------------------------------------------------------
   Rayleigh time of the smallest sphere (docs/theory.md §4.1, Li, Xu & Thornton 2005):
   dt_R = pi R sqrt(rho/G) / (0.1631 nu + 0.8766)
------------------------------------------------------------------------- */

void PairThorntonYin::check_timestep_against_rayleigh()
{
  double local_min = BIG;
  for (int i = 0; i < atom->nlocal; ++i) {
    const int t = atom->type[i];
    const double r = atom->radius[i];
    if (!(r > 0.0) || !material_set[t]) continue;
    const double rho = atom->rmass[i] / (4.0 / 3.0 * MY_PI * r * r * r);
    const double G = youngs[t] / (2.0 * (1.0 + poisson[t]));
    const double t_rayleigh = MY_PI * r * std::sqrt(rho / G) / (0.1631 * poisson[t] + 0.8766);
    local_min = MIN(local_min, t_rayleigh);
  }
  double t_rayleigh;
  MPI_Allreduce(&local_min, &t_rayleigh, 1, MPI_DOUBLE, MPI_MIN, world);
  // no time step resolves a Rayleigh time that is zero, subnormal or NaN (E or the density
  // far out of range)
  if (!(t_rayleigh >= DBL_MIN))
    error->all(FLERR,
               "pair thornton/yin: the Rayleigh time pi R sqrt(rho/G)/(0.1631 nu + "
               "0.8766) of the smallest sphere is {:.4g}: no time step can resolve it; check E "
               "(pair_coeff) and the density or mass of the spheres",
               t_rayleigh);
  // viscous damping, -eta v with eta = 2 beta sqrt(m* k): beta > 1 is overdamped, and the
  // explicit step of the damping force is stable for every contact (angular frequency below
  // 2 pi/dt_R, theory.md §4) only while beta < dt_R/(2 pi dt)
  double beta_max = 0.0;
  for (int i = 1; i <= atom->ntypes; ++i)
    for (int j = i; j <= atom->ntypes; ++j)
      beta_max = MAX(beta_max, MAX(damp_n[i][j], damp_t[i][j]));
  const double beta_stable = t_rayleigh / (2.0 * MY_PI * update->dt);
  if (beta_max > 0.0 && t_rayleigh < BIG && (beta_max > 1.0 || beta_max > beta_stable) &&
      comm->me == 0)
    error->warning(
        FLERR,
        "pair thornton/yin: damping ratio {:.4g} is {}; use a damping ratio "
        "below {:.4g}",
        beta_max,
        beta_max > beta_stable
            ? "too large for the explicit step: a contact's "
              "damping force may grow without bound (it is stable for every contact only "
              "below dt_R/(2 pi dt))"
            : "above 1: contacts are overdamped and cannot "
              "rebound",
        MIN(1.0, beta_stable));
  if (t_rayleigh < BIG && update->dt > RAYLEIGH_WARN_FRACTION * t_rayleigh && comm->me == 0)
    error->warning(FLERR,
                   "pair thornton/yin: timestep {:.4g} exceeds {} x the Rayleigh time "
                   "{:.4g} of the smallest sphere; reduce the timestep to at most {:.4g} "
                   "(or scale the density up)",
                   update->dt, RAYLEIGH_WARN_FRACTION, t_rayleigh,
                   RAYLEIGH_WARN_FRACTION * t_rayleigh);
}

/* ----------------------------------------------------------------------
   largest radius of the spheres of type t (init_style), or of any type when type t has no
   spheres yet (its pair coefficients still get a cutoff and the checks)
------------------------------------------------------------------------- */

double PairThorntonYin::largest_radius(int t) const
{
  if (maxrad_type[t] > 0.0) return maxrad_type[t];
  double rad_any = 0.0;
  for (int k = 1; k <= atom->ntypes; ++k) rad_any = MAX(rad_any, maxrad_type[k]);
  return rad_any;
}

/* ---------------------------------------------------------------------- */

double PairThorntonYin::init_one(int i, int j)
{
  if (setflag[i][j] == 0) mix_pair(i, j);
  // fix adapt changes mu and Gamma through extract() and calls init_one again
  if (!(std::isfinite(friction[i][j]) && friction[i][j] >= 0.0))
    error->all(FLERR,
               "pair thornton/yin: friction coefficient mu of types {} {} must be finite "
               "and >= 0 (got {}; set by pair_coeff or fix adapt)",
               i, j, friction[i][j]);
  if (!(std::isfinite(surface_energy[i][j]) && surface_energy[i][j] >= 0.0))
    error->all(FLERR,
               "pair thornton/yin: interface energy Gamma of types {} {} must be finite "
               "and >= 0 {} (got {}; set by pair_coeff or fix adapt)",
               i, j, surface_energy_unit(update->unit_style), surface_energy[i][j]);
  E_star[j][i] = E_star[i][j];
  G_star[j][i] = G_star[i][j];
  friction[j][i] = friction[i][j];
  surface_energy[j][i] = surface_energy[i][j];
  damp_n[j][i] = damp_n[i][j];
  damp_t[j][i] = damp_t[i][j];
  const int ntp1 = atom->ntypes + 1;
  pair_constants[i * ntp1 + j] = pair_constants[j * ntp1 + i] = tycore::pair_constants(
      tycore::PairCoefficients{E_star[i][j], G_star[i][j], friction[i][j], surface_energy[i][j]});

  // cutoff: touching largest spheres plus the adhesive tensile range
  const double rad_i = largest_radius(i), rad_j = largest_radius(j);
  // again here: fix adapt changes mu and Gamma and calls init_one (warnings come from init_style)
  if (rad_i > 0.0 && rad_j > 0.0) check_law_domain(i, j, rad_i, rad_j, false);
  double cutoff = rad_i + rad_j;
  if (cutoff > 0.0)
    cutoff -= tycore::jkr::break_overlap(tycore::effective_radius(rad_i, rad_j), E_star[i][j],
                                         surface_energy[i][j]);
  cut[i][j] = cut[j][i] = cutoff;
  return cutoff;
}

/* ----------------------------------------------------------------------
   Coefficients that make the law meaningless for the spheres of types i j (largest radii
   rad_i, rad_j): bounds derived from the law, plugin/core/law_domain.hpp
------------------------------------------------------------------------- */

void PairThorntonYin::check_law_domain(int i, int j, double rad_i, double rad_j, bool warn)
{
  const tycore::PairCoefficients c{E_star[i][j], G_star[i][j], friction[i][j],
                                   surface_energy[i][j]};
  const double R = tycore::effective_radius(rad_i, rad_j);
  const double a0_ratio = tycore::zero_load_radius_ratio(c, R);
  if (!(a0_ratio < 1.0))
    error->all(FLERR,
               "pair thornton/yin: types {} {}: the JKR zero-load contact radius a0 = "
               "(9 pi Gamma R*^2/E*)^(1/3) = {:.4g} is not smaller than R* = {:.4g}, so the "
               "contact law (small contacts, a << R*) does not apply; Gamma = {:.4g} must be "
               "below E* R*/(9 pi) = {:.4g} (or E larger)",
               i, j, a0_ratio * R, R, c.Gamma, c.E_star * R / (9.0 * MY_PI));
  if (warn && a0_ratio > A0_WARN_FRACTION && comm->me == 0)
    error->warning(FLERR,
                   "pair thornton/yin: types {} {}: the JKR zero-load contact radius a0 "
                   "= {:.4g} R*: the contact is large before any load and the small-contact "
                   "law is strained; lower Gamma or raise E if this is not intended",
                   i, j, a0_ratio);
  const double delta_max = MIN(rad_i, rad_j);
  const tycore::LawDomainFault fault = tycore::law_domain_fault(c, R, delta_max);
  if (fault.quantity)
    error->all(FLERR,
               "pair thornton/yin: types {} {}: the {} of the contact law is not finite "
               "at overlap {:.4g} (the law's range is delta_f to the smaller radius {:.4g}) with "
               "E* = {:.4g}, G* = {:.4g}, mu = {:.4g}, Gamma = {:.4g}, R* = {:.4g}: these "
               "coefficients are far outside what the law can represent in 'units {}'",
               i, j, fault.quantity, fault.delta, delta_max, c.E_star, c.G_star, c.mu, c.Gamma, R,
               update->unit_style);
}

/* ----------------------------------------------------------------------
   Mean-field velocity gradient L = Hdot H^-1 of a deforming box (fix deform remap x,
   fix cell/servo). With remap x particle velocities are fluctuations, so the affine
   relative velocity L (x_i - x_j) must be added to the contact velocity (docs/theory.md §5.1).
   Returns max |L_ab| (0 when the box does not deform or velocities already stream).
------------------------------------------------------------------------- */

double PairThorntonYin::affine_velocity_gradient(double L[3][3]) const
{
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) L[a][b] = 0.0;
  if (domain->deform_vremap) return 0.0;
  const double *hd = domain->h_rate, *hi = domain->h_inv;
  L[0][0] = hd[0] * hi[0];
  L[0][1] = hd[0] * hi[5] + hd[5] * hi[1];
  L[0][2] = hd[0] * hi[4] + hd[5] * hi[3] + hd[4] * hi[2];
  L[1][1] = hd[1] * hi[1];
  L[1][2] = hd[1] * hi[3] + hd[3] * hi[2];
  L[2][2] = hd[2] * hi[2];
  double largest = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) largest = MAX(largest, std::fabs(L[a][b]));
  return largest;
}

/* ----------------------------------------------------------------------
   The affine contact velocity is built from domain->h_rate (affine_velocity_gradient).
   A fix that changes the box without setting h_rate (in LAMMPS 2021: fix deform 'volume'
   dimensions, barostats) silently removes part of it: warn once when h_rate does not explain
   the box change since the previous step (tycore::unexplained_box_change, box_rate.hpp).
------------------------------------------------------------------------- */

void PairThorntonYin::check_box_rate()
{
  const bigint step = update->ntimestep;
  const double *h = domain->h;
  // compare only step to step within a run: fix deform sets h_rate at init but changes the
  // box at the end of each step, so the first step after setup has not moved yet
  const bool comparable = step == box_step + 1 && !box_from_setup;
  box_from_setup = update->setupflag;
  if (!update->setupflag && !domain->deform_vremap && !box_rate_warned && comparable) {
    static const char *const component[6] = {"xx", "yy", "zz", "yz", "xz", "xy"};
    const tycore::BoxChange c =
        tycore::unexplained_box_change(box_h, h, domain->h_rate, update->dt);
    if (c.component >= 0) {
      box_rate_warned = 1;
      if (comm->me == 0)
        error->warning(FLERR,
                       "pair thornton/yin: box component h_{} changed by {:.4g} in the "
                       "last step but its rate h_rate dt = {:.4g}: a fix changes the box "
                       "without setting domain->h_rate (fix deform 'volume' in this LAMMPS "
                       "version, a barostat), so the affine part of the contact velocity "
                       "is missing for that direction. Use fix cell/servo, fix deform with "
                       "erate/trate/final on every changing dimension, or fix deform remap v",
                       component[c.component], c.change, c.from_rate);
    }
  }
  for (int k = 0; k < 6; ++k) box_h[k] = h[k];
  box_step = step;
}

/* ----------------------------------------------------------------------
   a contact the law cannot take: name the atoms and what is wrong (error path only)
------------------------------------------------------------------------- */

void PairThorntonYin::contact_fault(int i, int j, double delta, bool force)
{
  const tagint ti = atom->tag[i], tj = atom->tag[j];
  const auto vector_bad = [](const double *q) {
    return !(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]));
  };
  std::string bad;
  for (const int k : {i, j}) {
    const std::string of = fmt::format(" of atom {}", atom->tag[k]);
    if (vector_bad(atom->x[k])) bad += ", position" + of;
    if (vector_bad(atom->v[k])) bad += ", velocity" + of;
    if (vector_bad(atom->omega[k])) bad += ", angular velocity" + of;
    if (!std::isfinite(atom->radius[k])) bad += ", radius" + of;
    if (!std::isfinite(atom->rmass[k])) bad += ", mass" + of;
  }
  if (!bad.empty())
    error->one(FLERR,
               "pair thornton/yin: non-finite value at step {} in the contact of atoms "
               "{} and {} ({}); the run stops here instead of spreading NaN: look for what set "
               "it (set, velocity, a fix or a variable)",
               update->ntimestep, ti, tj, bad.substr(2));
  if (force || !std::isfinite(delta)) {
    const double *vi = atom->v[i], *vj = atom->v[j];
    const double speed = std::hypot(std::hypot(vi[0] - vj[0], vi[1] - vj[1]), vi[2] - vj[2]);
    error->one(FLERR,
               "pair thornton/yin: the contact force of atoms {} and {} is not finite at "
               "step {} although their positions, velocities and radii are (relative speed "
               "{:.4g}): a pair coefficient too large for this contact (see the warnings at "
               "init, e.g. the damping ratio) or a non-finite value in its history",
               ti, tj, update->ntimestep, speed);
  }
  error->one(FLERR,
             "pair thornton/yin: overlap {:.4g} of atoms {} and {} exceeds the radius of "
             "the smaller sphere {:.4g}: the contact law is no longer valid; reduce the timestep "
             "(see the Rayleigh-time warning) or the impact velocity",
             delta, ti, tj, MIN(atom->radius[i], atom->radius[j]));
}

/* ---------------------------------------------------------------------- */

void PairThorntonYin::compute(int eflag, int vflag)
{
  check_box_rate();

  // model only what the scene needs: specialised loops chosen once per call
  adhesive = damped = 0;
  for (int i = 1; i <= atom->ntypes; ++i)
    for (int j = i; j <= atom->ntypes; ++j) {
      if (surface_energy[i][j] > 0.0) adhesive = 1;
      if (damp_n[i][j] > 0.0 || damp_t[i][j] > 0.0) damped = 1;
    }
  if (adhesive) {
    if (damped)
      eval<true, true>(eflag, vflag);
    else
      eval<true, false>(eflag, vflag);
  } else {
    if (damped)
      eval<false, true>(eflag, vflag);
    else
      eval<false, false>(eflag, vflag);
  }
}

/* ---------------------------------------------------------------------- */

template <bool ADHESIVE, bool DAMPED> void PairThorntonYin::eval(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  // in setup the forces are recomputed at unchanged positions: no history increment
  const bool step = !update->setupflag;
  dt = update->dt;
  Sweep sweep;
  sweep.step = step;
  sweep.affine = affine_velocity_gradient(sweep.gradient.L) > 0.0;

  double **x = atom->x;
  double **v = atom->v;
  double **omega = atom->omega;
  const double *radius = atom->radius;
  const double *rmass = atom->rmass;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;
  const int ntypes_plus_1 = atom->ntypes + 1;
  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  int **firsttouch = fix_history->firstflag;
  double **firsthistory = fix_history->firstvalue;

  begin_tallies();
  begin_batches(evflag && eflag_either);
  const bool by_contact = principal_by_contact;
  const auto run = [&](Batch &bt) {
    if (by_contact)
      run_batch<ADHESIVE, DAMPED, true>(bt, sweep);
    else
      run_batch<ADHESIVE, DAMPED, false>(bt, sweep);
  };

  // the neighbour loop: each touching pair's sphere data and history into its lane
  for (int ii = 0; ii < inum; ++ii) {
    const int i = ilist[ii];
    const double radi = radius[i];
    const tycore::SphereState si{v[i], omega[i], radi, rmass[i]};
    Batch **batch_of_j = &batch_of_types[type[i] * ntypes_plus_1];
    int *touch = firsttouch[i];
    double *allhistory = firsthistory[i];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];

    for (int jj = 0; jj < jnum; ++jj) {
      const int j = jlist[jj] & NEIGHMASK;
      const double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
      const double rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
      const double radj = radius[j];
      const double radsum = radi + radj;
      if (!touch[jj] && rsq > radsum * radsum) continue;    // apart, never touched (delta < 0)

      Batch *batch = batch_of_j[type[j]];
      if (!batch) batch = make_batch(type[i], type[j]);
      Batch &bt = *batch;
      const int l = bt.n;
      const tycore::SphereState sj{v[j], omega[j], radj, rmass[j]};
      tycore::gather_contact<DAMPED>(bt.b, l, del, rsq, si, sj, !touch[jj]);
      double *slot = &allhistory[HISTORY_SIZE * jj];
      tycore::load_history(bt.b, l, slot);
      bt.i[l] = i, bt.j[l] = j;
      bt.touch[l] = &touch[jj];
      bt.slot[l] = slot;
      bt.share[l] = (newton_pair || j < nlocal) ? 1.0 : 0.5;
      if (++bt.n == tycore::batch_lanes) run(bt);
    }
  }
  for (auto &bt : batches)
    if (bt && bt->n) run(*bt);
  end_tallies();

  pvector[DISSIPATION_FRICTION] += sweep.friction;
  pvector[DISSIPATION_BREAK] += sweep.breaks;
  pvector[DISSIPATION_DAMPING] += sweep.damping;
}

template void PairThorntonYin::eval<true, true>(int, int);
template void PairThorntonYin::eval<true, false>(int, int);
template void PairThorntonYin::eval<false, true>(int, int);
template void PairThorntonYin::eval<false, false>(int, int);

/* ----------------------------------------------------------------------
   the batches of this force evaluation: one per pair of atom types (advance_batch takes one
   material pair), made when its first contact comes; the table batch_of_types finds it from
   either order of the types
------------------------------------------------------------------------- */

void PairThorntonYin::begin_batches(bool energy)
{
  batch_energy = energy;
  const int ntypes_plus_1 = atom->ntypes + 1;
  for (int itype = 1; itype < ntypes_plus_1; ++itype)
    for (int jtype = itype; jtype < ntypes_plus_1; ++jtype) {
      auto &bt = batches[itype * ntypes_plus_1 + jtype];
      if (bt) bt->p = batch_parameters(itype, jtype);
    }
}

// this evaluation's parameters of the batch of types itype, jtype
tycore::BatchParameters PairThorntonYin::batch_parameters(int itype, int jtype) const
{
  return tycore::BatchParameters{dt, damp_n[itype][jtype], damp_t[itype][jtype], tally_cell != 0,
                                 batch_energy};
}

PairThorntonYin::Batch *PairThorntonYin::make_batch(int itype, int jtype)
{
  const int ntypes_plus_1 = atom->ntypes + 1;
  const int pair = MIN(itype, jtype) * ntypes_plus_1 + MAX(itype, jtype);
  batches[pair].reset(new Batch{});    // value-initialised: lanes past n hold numbers
  Batch *bt = batches[pair].get();
  bt->constants = &pair_constants[pair];
  bt->p = batch_parameters(itype, jtype);
  batch_of_types[itype * ntypes_plus_1 + jtype] = bt;
  batch_of_types[jtype * ntypes_plus_1 + itype] = bt;
  return bt;
}

/* ----------------------------------------------------------------------
   the contacts of one batch through the core (their geometry, then a step, or in setup the
   forces without one), then their forces, torques, history and tallies back to LAMMPS
------------------------------------------------------------------------- */

template <bool ADHESIVE, bool DAMPED, bool BY_CONTACT>
void PairThorntonYin::run_batch(Batch &bt, Sweep &sweep)
{
  tycore::ContactBatch &b = bt.b;
  const int n = bt.n;
  bt.n = 0;
  const tycore::AffineGradient &g = sweep.gradient;
  const bool valid = sweep.affine ? tycore::batch_geometry<true, DAMPED>(b, n, g, isa)
                                  : tycore::batch_geometry<false, DAMPED>(b, n, g, isa);
  if (!valid) report_overlap(bt, n);
  if (sweep.step)
    tycore::advance_batch<ADHESIVE, DAMPED>(b, n, *bt.constants, bt.p, isa);
  else
    tycore::forces_without_step<ADHESIVE, DAMPED>(b, n, *bt.constants, bt.p);
  scatter<DAMPED>(bt, n, sweep);
  if (tally_cell) tally_batch<BY_CONTACT>(bt, n);
}

// the first lane whose overlap is out of the law's domain (tycore::overlap_valid), as an error
void PairThorntonYin::report_overlap(const Batch &bt, int n)
{
  for (int l = 0; l < n; ++l)
    if (!tycore::overlap_valid(bt.b, l)) contact_fault(bt.i[l], bt.j[l], bt.b.delta[l], false);
}

// forces, torques and history of a batch back to LAMMPS, and the energy sums
template <bool DAMPED> void PairThorntonYin::scatter(const Batch &bt, int n, Sweep &sweep)
{
  const tycore::ContactBatch &b = bt.b;
  double **f = atom->f;
  double **torque = atom->torque;
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;
  // the global virial, when it alone is asked, in registers over the batch (the additions of
  // Pair::ev_tally_xyz in the same order)
  const bool virial_inline = evflag && vflag_global && !eflag_either && !vflag_atom;
  double vir[6];
  for (int k = 0; k < 6; ++k) vir[k] = virial[k];
  for (int l = 0; l < n; ++l) {
    const int i = bt.i[l], j = bt.j[l];
    const double share = bt.share[l];
    if (b.broken[l] != 0.0) {    // separated at the break overlap: the contact is forgotten
      sweep.breaks += share * b.break_energy[l];
      *bt.touch[l] = 0;
      for (int k = 0; k < HISTORY_SIZE; ++k) bt.slot[l][k] = 0.0;
      continue;
    }
    *bt.touch[l] = 1;
    tycore::store_history(b, l, bt.slot[l]);
    sweep.friction += share * b.dissipation[l];
    if (DAMPED) sweep.damping += share * b.damping_dissipation[l];

    const double fx = b.force[0][l], fy = b.force[1][l], fz = b.force[2][l];
    // a NaN or inf anywhere upstream (velocity, spin, history, ...) reaches the force: stop
    // here rather than propagate it (one comparison; NaN fails it)
    if (!(std::fabs(fx + fy + fz) <= DBL_MAX)) contact_fault(i, j, 0.0, true);
    const bool j_owned = newton_pair || j < nlocal;
    if (record_contacts && (j_owned || atom->tag[i] < atom->tag[j])) {
      double Fn, fs[3];
      tycore::force_parts<DAMPED>(b, l, bt.constants->c, bt.p, Fn, fs);
      record_contact(bt, l, Fn, fs);
    }
    // the tangential force acts at the contact point: levers r - delta/2
    const double lever_i = b.r_i[l] - 0.5 * b.delta[l];
    f[i][0] += fx;
    f[i][1] += fy;
    f[i][2] += fz;
    torque[i][0] -= lever_i * b.moment[0][l];
    torque[i][1] -= lever_i * b.moment[1][l];
    torque[i][2] -= lever_i * b.moment[2][l];
    if (j_owned) {
      const double lever_j = b.r_j[l] - 0.5 * b.delta[l];
      f[j][0] -= fx;
      f[j][1] -= fy;
      f[j][2] -= fz;
      torque[j][0] -= lever_j * b.moment[0][l];
      torque[j][1] -= lever_j * b.moment[1][l];
      torque[j][2] -= lever_j * b.moment[2][l];
    }
    if (!evflag) continue;
    const double dx = b.del[0][l], dy = b.del[1][l], dz = b.del[2][l];
    if (virial_inline) {    // the servo's stress every step
      add_pair_virial(vir, newton_pair, i < nlocal, j < nlocal, fx, fy, fz, dx, dy, dz);
    } else {
      ev_tally_xyz(i, j, nlocal, newton_pair, bt.p.energy ? b.energy[l] : 0.0, 0.0, fx, fy, fz, dx,
                   dy, dz);
    }
  }
  if (virial_inline)
    for (int k = 0; k < 6; ++k) virial[k] = vir[k];
}

// the servo's sums of a batch (docs/theory.md §6.1, §11.1), each contact once
template <bool BY_CONTACT> void PairThorntonYin::tally_batch(const Batch &bt, int n)
{
  const tycore::ContactBatch &b = bt.b;
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;
  // the sums in registers over the batch (the same additions in the same order)
  double stiffness[6], contacts = tallies.sum[CellTallies::CONTACTS],
                       sliding = tallies.sum[CellTallies::SLIDING],
                       force_sum = tallies.sum[CellTallies::FORCE];
  for (int k = 0; k < 6; ++k) stiffness[k] = tallies.sum[CellTallies::STIFFNESS + k];
  for (int l = 0; l < n; ++l) {
    if (b.broken[l] != 0.0) continue;
    const double share = bt.share[l];
    if (BY_CONTACT)
      for (int k = 0; k < 6; ++k) stiffness[k] += share * b.affine_stiffness[k][l];
    contacts += share;
    sliding += share * b.slides[l];
    force_sum += share * b.force_magnitude[l];
    atom_contacts[bt.i[l]] += 1.0;
    if (newton_pair || bt.j[l] < nlocal) atom_contacts[bt.j[l]] += 1.0;
  }
  for (int k = 0; k < 6; ++k) tallies.sum[CellTallies::STIFFNESS + k] = stiffness[k];
  tallies.sum[CellTallies::CONTACTS] = contacts;
  tallies.sum[CellTallies::SLIDING] = sliding;
  tallies.sum[CellTallies::FORCE] = force_sum;
  if (lane_principal >= 0) tally_principal_lane(bt, n);
  if (lane_shear >= 0) (this->*shear_lane_tally(lane_shear))(bt, n);
}

// the per-lane stiffness sums into the tallies, and the reverse communication of the contact
// counts, after the last batch
void PairThorntonYin::end_tallies()
{
  if (!tally_cell) return;
  for (int k = 0; k < tycore::AffineStiffnessSums::size; ++k)
    if (lane_entries >> k & 1u)
      for (int l = 0; l < tycore::batch_lanes; ++l)
        tallies.sum[CellTallies::STIFFNESS + k] += stiffness_lanes[k][l];
  if (force->newton_pair) tylmp_compat::reverse_comm(comm, this);
}

/* ----------------------------------------------------------------------
   the servo's stiffness sums: which entries, and how they are summed
------------------------------------------------------------------------- */

// The entries asked for (bits of tycore::AffineStiffnessSums::index) are made in one of a few
// shapes, each with its own branch-free summation: the principal block contact by contact (the
// batch law computes it for every contact), or one of its entries per batch lane; and none, one
// or all 15 of the entries with a shear component per lane. Returns the set made, a superset.
unsigned PairThorntonYin::request_cell_tallies(unsigned entries)
{
  using Sums = tycore::AffineStiffnessSums;
  tally_cell = 1;
  const unsigned principal = entries & Sums::principal_entries;
  const unsigned shear = (entries & Sums::all_entries) >> Sums::principal_size;
  const auto single = [](unsigned bits) {
    return bits != 0 && (bits & (bits - 1)) == 0;
  };
  const auto lowest = [](unsigned bits) {
    return __builtin_ctz(bits);
  };
  lane_shear = shear == 0 ? -1 : single(shear) ? lowest(shear) : ALL_SHEAR;
  principal_by_contact = principal != 0 && !(single(principal) && lane_shear != ALL_SHEAR);
  lane_principal = principal != 0 && !principal_by_contact ? lowest(principal) : -1;
  lane_entries = (lane_principal >= 0 ? 1u << lane_principal : 0u) |
      (lane_shear == ALL_SHEAR ? Sums::all_entries & ~Sums::principal_entries
           : lane_shear >= 0   ? 1u << (Sums::principal_size + lane_shear)
                               : 0u);
  return (principal_by_contact ? Sums::principal_entries : 0u) | lane_entries;
}

// one principal entry of a batch summed lane by lane (the batch law's, as the block's)
void PairThorntonYin::tally_principal_lane(const Batch &bt, int n)
{
  double *__restrict sum = stiffness_lanes[lane_principal];
  const double *__restrict share = bt.share;
  const double *__restrict c = bt.b.affine_stiffness[lane_principal];
#pragma GCC ivdep
  for (int l = 0; l < n; ++l) sum[l] += share[l] * c[l];
}

// the entries with a shear component of a batch, lane by lane (a broken lane has k_N = k_T = 0):
// all 15 (K = ALL_SHEAR, docs/theory.md §11.1) or entry K alone. K is fixed at compile time, so
// that the lane loop has no branch and computes no entry it does not keep.
template <int K> void PairThorntonYin::tally_shear_lane(const Batch &bt, int n)
{
  constexpr int P = tycore::AffineStiffnessSums::principal_size;
  const tycore::ContactBatch &b = bt.b;
  if constexpr (K == ALL_SHEAR) {
    for (int l = 0; l < n; ++l) {
      const double share = bt.share[l];
      tycore::affine_shear_entries(b.n[0][l], b.n[1][l], b.n[2][l], b.rsq[l], b.normal_stiffness[l],
                                   b.tangential_stiffness[l], [&](int k, double value) {
                                     stiffness_lanes[P + k][l] += share * value;
                                   });
    }
  } else {
    // one sum that aliases nothing the loop reads, so that it vectorises
    double *__restrict sum = stiffness_lanes[P + K];
    const double *__restrict share = bt.share;
#pragma GCC ivdep
    for (int l = 0; l < n; ++l) {
      double value = 0.0;
      tycore::affine_shear_entries(b.n[0][l], b.n[1][l], b.n[2][l], b.rsq[l], b.normal_stiffness[l],
                                   b.tangential_stiffness[l], [&](int k, double entry) {
                                     if (k == K) value = entry;
                                   });
      sum[l] += share[l] * value;
    }
  }
}

// the summation of shear entry K (0..14) or of all (ALL_SHEAR), as a member pointer
template <std::size_t... K>
std::array<PairThorntonYin::ShearLaneTally, sizeof...(K)>
PairThorntonYin::shear_lane_tallies(std::index_sequence<K...>)
{
  return {&PairThorntonYin::tally_shear_lane<int(K)>...};
}

PairThorntonYin::ShearLaneTally PairThorntonYin::shear_lane_tally(int k)
{
  static const auto table = shear_lane_tallies(std::make_index_sequence<ALL_SHEAR + 1>());
  return table[k];
}

/* ----------------------------------------------------------------------
   zero the servo's cell tallies and the contact records before a force evaluation
------------------------------------------------------------------------- */

void PairThorntonYin::begin_tallies()
{
  if (tally_cell) {
    for (double &t : tallies.sum) t = 0.0;
    for (int k = 0; k < tycore::AffineStiffnessSums::size; ++k)
      if (lane_entries >> k & 1u)
        for (double &t : stiffness_lanes[k]) t = 0.0;
    if (atom->nmax > nmax_count) {
      memory->destroy(atom_contacts);
      nmax_count = atom->nmax;
      memory->create(atom_contacts, nmax_count, "pair:contact_count");
    }
    const int nall = atom->nlocal + atom->nghost;
    for (int k = 0; k < nall; ++k) atom_contacts[k] = 0.0;
  }
  if (record_contacts) {
    records.clear();
    record_step = update->ntimestep;
  }
}

/* ----------------------------------------------------------------------
   one contact for the contact computes, with the force it applied this evaluation
------------------------------------------------------------------------- */

void PairThorntonYin::record_contact(const Batch &bt, int l, double Fn, const double fs[3])
{
  const tycore::ContactBatch &b = bt.b;
  ContactRecord rec;
  const int i = bt.i[l], j = bt.j[l];
  rec.id_i = atom->tag[i];
  rec.id_j = atom->tag[j];
  for (int k = 0; k < 3; ++k) {
    rec.normal_force[k] = Fn * b.n[k][l];
    rec.tangential_force[k] = fs[k];
    rec.branch[k] = b.del[k][l];
  }
  rec.P = Fn;
  rec.overlap = b.delta[l];
  rec.contact_radius = b.contact_radius[l];
  rec.sliding = b.slides[l];
  rec.peeling = b.peeling[l];
  rec.mask = atom->mask[i] & atom->mask[j];
  records.push_back(rec);
}

/* ----------------------------------------------------------------------
   pair thornton/yin as a sub-style of pair_style STYLE (exactly): while LAMMPS creates the
   sub-styles of a hybrid (pair_style or read_restart), force->pair is the hybrid already.
   Under plain 'hybrid' the pair offers no extra single() values (single_extra = 0): LAMMPS's
   PairHybrid::copy_svector copies them in a loop that never ends (its condition is the
   sub-style's count, not the index; 29 Sep 2021 and 4 Feb 2025), so compute pair/local crashed
   on the first contact. Force and energy of single() stay available.
------------------------------------------------------------------------- */

// the type pairs this pair computes: all of them alone; under a hybrid style those given to
// it by pair_coeff, and the unlike pairs hybrid lets it mix (I I and J J both its own)
bool PairThorntonYin::handles(int i, int j) const
{
  return force->pair == this || setflag[i][j] || (material_set[i] && material_set[j]);
}

bool PairThorntonYin::sub_style_of(const char *style) const
{
  return force->pair && force->pair != this && force->pair_style &&
      strcmp(force->pair_style, style) == 0;
}

/* ----------------------------------------------------------------------
   outputs under a hybrid pair style. pair_style hybrid/scaled s multiplies the forces on the
   atoms by s, but not the contact records, tallies and stiffness that the contact computes
   and fix cell/servo read from this pair: they would report 1/s of the applied force, so the
   combination is refused while one of them reads the pair. Under plain hybrid compute
   pair/local gets force and energy only (see sub_style_of): said before LAMMPS's own error
   for a requested p1..pN ("Pair style does not have extra field").
------------------------------------------------------------------------- */

void PairThorntonYin::check_hybrid_outputs()
{
  if (force->pair == this) return;
  for (int k = 0; k < modify->ncompute && single_extra == 0 && comm->me == 0; ++k)
    if (strcmp(modify->compute[k]->style, "pair/local") == 0) {
      error->warning(FLERR,
                     "pair thornton/yin under pair_style hybrid: compute {} (pair/local) "
                     "gets the force and energy of each contact, but not the pair's extra "
                     "values p1..p{} (overlap, contact radius, ...), which LAMMPS's pair hybrid "
                     "cannot pass on without crashing; for them use pair_style hybrid/overlay "
                     "or compute thornton/yin/contacts",
                     modify->compute[k]->id, static_cast<int>(N_SVECTOR));
      break;
    }
  if (!utils::strmatch(force->pair_style, "^hybrid/scaled")) return;
  std::string reader;
  for (int k = 0; k < modify->ncompute && reader.empty(); ++k)
    if (utils::strmatch(modify->compute[k]->style, "^thornton/yin/"))
      reader = fmt::format("compute {} ({})", modify->compute[k]->id, modify->compute[k]->style);
  for (int k = 0; k < modify->nfix && reader.empty(); ++k)
    if (strcmp(modify->fix[k]->style, "cell/servo") == 0)
      reader = fmt::format("fix {} (cell/servo)", modify->fix[k]->id);
  if (!reader.empty())
    error->all(FLERR,
               "pair thornton/yin under pair_style {}: the scale factor multiplies the "
               "forces on the atoms, but {} reads the unscaled contact forces of the pair and "
               "would report them, not the applied ones; scale the material instead (E and "
               "Gamma in pair_coeff), or use pair_style hybrid or hybrid/overlay",
               force->pair_style, reader);
}

/* ----------------------------------------------------------------------
   history seen from the partner: vectors flip sign, scalars do not
------------------------------------------------------------------------- */

void PairThorntonYin::transfer_contact_history(const double *source, double *target)
{
  for (int k = 0; k < HISTORY_SIZE; ++k) target[k] = tycore::history_transfer_sign[k] * source[k];
}

/* ----------------------------------------------------------------------
   for compute pair/local: never changes the history
------------------------------------------------------------------------- */

double PairThorntonYin::single(int i, int j, int itype, int jtype, double rsq,
                               double /*factor_coul*/, double /*factor_lj*/, double &fforce)
{
  for (int k = 0; k < single_extra; ++k) svector[k] = 0.0;
  fforce = 0.0;

  const double radi = atom->radius[i], radj = atom->radius[j];
  const double radsum = radi + radj;
  const double R = radi * radj / radsum;
  const tycore::PairCoefficients c{E_star[itype][jtype], G_star[itype][jtype],
                                   friction[itype][jtype], surface_energy[itype][jtype]};
  svector[S_PULL_OFF_FORCE] = tycore::jkr::pull_off_force(c.Gamma, R);
  svector[S_BREAK_OVERLAP] = tycore::jkr::break_overlap(R, c.E_star, c.Gamma);

  // find the contact's history slot in the pair's own neighbor list
  const int jnum = list->numneigh[i];
  const int *jlist = list->firstneigh[i];
  int found = -1;
  for (int k = 0; k < jnum; ++k) {
    neighprev = (neighprev + 1 < jnum) ? neighprev + 1 : 0;
    if ((jlist[neighprev] & NEIGHMASK) == j) {
      found = neighprev;
      break;
    }
  }
  if (found < 0 || !fix_history->firstflag[i][found]) return 0.0;
  const tycore::ContactHistory h = load_history(&fix_history->firstvalue[i][HISTORY_SIZE * found]);

  const double r = std::sqrt(rsq);
  const double delta = radsum - r;
  if (tycore::law::separates(c, R, delta, c.Gamma > 0.0)) return 0.0;
  // the law's normal contact, as the last force evaluation computed it (the same Adhesive
  // instantiation, the iteration warm-started from the radius it kept)
  const tycore::PairConstants &k = pair_constants[itype * (atom->ntypes + 1) + jtype];
  const tycore::KernelResult normal = adhesive
      ? tycore::normal_contact<true>(k, R, delta, h.radius)
      : tycore::normal_contact<false>(k, R, delta, h.radius);
  const double a = normal.contact_radius, P = normal.P;
  fforce = P / r;
  svector[S_NORMAL_FORCE] = P;
  svector[S_TANGENTIAL_FORCE] = std::sqrt(h.T[0] * h.T[0] + h.T[1] * h.T[1] + h.T[2] * h.T[2]);
  svector[S_CONTACT_RADIUS] = a;
  svector[S_OVERLAP] = delta;
  svector[S_SLIDING] = h.sliding;
  svector[S_PEELING] = h.peeling;
  return tycore::contact_stored_energy(c, R, a, P, h);
}

/* ---------------------------------------------------------------------- */

void PairThorntonYin::write_restart(FILE *fp)
{
  const int n = atom->ntypes;
  fwrite(material_set + 1, sizeof(int), n, fp);
  fwrite(youngs + 1, sizeof(double), n, fp);
  fwrite(poisson + 1, sizeof(double), n, fp);
  for (int i = 1; i <= n; ++i)
    for (int j = i; j <= n; ++j) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (setflag[i][j]) {
        const double values[6] = {E_star[i][j],         G_star[i][j], friction[i][j],
                                  surface_energy[i][j], damp_n[i][j], damp_t[i][j]};
        fwrite(values, sizeof(double), 6, fp);
      }
    }
}

void PairThorntonYin::read_restart(FILE *fp)
{
  allocate();
  const int n = atom->ntypes;
  const int me = comm->me;
  if (me == 0) {
    utils::sfread(FLERR, material_set + 1, sizeof(int), n, fp, nullptr, error);
    utils::sfread(FLERR, youngs + 1, sizeof(double), n, fp, nullptr, error);
    utils::sfread(FLERR, poisson + 1, sizeof(double), n, fp, nullptr, error);
  }
  MPI_Bcast(material_set + 1, n, MPI_INT, 0, world);
  MPI_Bcast(youngs + 1, n, MPI_DOUBLE, 0, world);
  MPI_Bcast(poisson + 1, n, MPI_DOUBLE, 0, world);
  for (int i = 1; i <= n; ++i)
    for (int j = i; j <= n; ++j) {
      if (me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      if (setflag[i][j]) {
        double values[6];
        if (me == 0) utils::sfread(FLERR, values, sizeof(double), 6, fp, nullptr, error);
        MPI_Bcast(values, 6, MPI_DOUBLE, 0, world);
        E_star[i][j] = values[0];
        G_star[i][j] = values[1];
        friction[i][j] = values[2];
        surface_energy[i][j] = values[3];
        damp_n[i][j] = values[4];
        damp_t[i][j] = values[5];
      }
    }
}

void PairThorntonYin::write_restart_settings(FILE *) {}
void PairThorntonYin::read_restart_settings(FILE *) {}

/* ---------------------------------------------------------------------- */

double PairThorntonYin::memory_usage()
{
  double bytes = Pair::memory_usage();
  for (const auto &bt : batches)
    if (bt) bytes += sizeof(Batch);
  return bytes;
}

int PairThorntonYin::pack_reverse_comm(int n, int first, double *buf)
{
  for (int k = 0; k < n; ++k) buf[k] = atom_contacts[first + k];
  return n;
}

void PairThorntonYin::unpack_reverse_comm(int n, int *list, double *buf)
{
  for (int k = 0; k < n; ++k) atom_contacts[list[k]] += buf[k];
}

// mu and Gamma per type pair, for fix adapt (the servo's sums: cell_tally.h)
void *PairThorntonYin::extract(const char *name, int &dim)
{
  if (strcmp(name, "mu") == 0) {
    dim = 2;
    return (void *) friction;
  }
  if (strcmp(name, "Gamma") == 0) {
    dim = 2;
    return (void *) surface_energy;
  }
  return nullptr;
}
