/* ----------------------------------------------------------------------
   fix cell/servo: its outputs (the global vector, the record's columns, the stiffness array;
   docs/fix_cell_servo.md, "Output info"). The names are the one list OUTPUT_NAMES; which of
   them a record carries is csv_columns().
------------------------------------------------------------------------- */

#include "fix_cell_servo.h"
#include "cell_tally.h"

#include "cell_statistics.hpp"
#include "pi_plane.hpp"

#include "atom.h"
#include "domain.h"
#include "update.h"

#include <cmath>
#include <limits>

using namespace LAMMPS_NS;

namespace {

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

const char *const OUTPUT_NAMES[] = {
    "eps1", "eps2", "eps3", "eps_v", "eps_q", "eps_d13", "sig1", "sig2", "sig3", "p", "q", "b",
    "lode_deg", "eta_LD", "sinphi", "void_ratio", "solid_fraction", "Z", "Zm",
    "sliding_fraction", "unbalanced", "inertial_number", "pi_x", "pi_y", "pi_ex", "pi_ey",
    "progress", "eta_seconds", "equilibrium", "rate1", "rate2", "rate3", "boundary_work",
    "p_kinetic", "volume", "time", "eq_stress_ok", "eq_unbalanced_ok", "eq_kinetic_ok",
    "eq_coordination_ok", "kinetic_ratio",
    "sig_xy", "sig_xz", "sig_yz", "gamma_xy", "gamma_xz", "gamma_yz", "rate_xy", "rate_xz",
    "rate_yz", "sig_major", "sig_inter", "sig_minor",
    "gamma", "tau", "sig_n", "tau_ratio", "stress_angle", "rate_angle", "noncoaxiality",
    "r_u", "cycles", "N_L_ru", "N_L_gamma"};
// the CSV columns after `step` of every record (one list, used for the header and every row)
const int CSV_COLUMNS[] = {
    FixCellServo::TIME, FixCellServo::EPS1, FixCellServo::EPS2, FixCellServo::EPS3,
    FixCellServo::EPS_V, FixCellServo::EPS_Q, FixCellServo::EPS_D13, FixCellServo::SIG1,
    FixCellServo::SIG2, FixCellServo::SIG3, FixCellServo::P, FixCellServo::Q, FixCellServo::B,
    FixCellServo::LODE_DEG, FixCellServo::ETA_LD, FixCellServo::SINPHI,
    FixCellServo::VOID_RATIO, FixCellServo::SOLID_FRACTION, FixCellServo::Z, FixCellServo::ZM,
    FixCellServo::SLIDING_FRACTION, FixCellServo::UNBALANCED, FixCellServo::INERTIAL_NUMBER,
    FixCellServo::PI_X, FixCellServo::PI_Y, FixCellServo::PI_EX, FixCellServo::PI_EY,
    FixCellServo::RATE1, FixCellServo::RATE2, FixCellServo::RATE3, FixCellServo::BOUNDARY_WORK,
    FixCellServo::P_KINETIC, FixCellServo::VOLUME, FixCellServo::PROGRESS};
static_assert(sizeof(OUTPUT_NAMES) / sizeof(OUTPUT_NAMES[0]) == FixCellServo::N_OUTPUT,
              "one name per output");

// a triclinic cell's record adds the full stress, the cumulative shears and their rates, and
// the principal stresses; a test with a plane adds its shear and angles; the constant-volume
// shears their r_u and cycle counts
const int CELL_COLUMNS[] = {
    FixCellServo::SIG_XY, FixCellServo::SIG_XZ, FixCellServo::SIG_YZ, FixCellServo::GAMMA_XY,
    FixCellServo::GAMMA_XZ, FixCellServo::GAMMA_YZ, FixCellServo::RATE_XY, FixCellServo::RATE_XZ,
    FixCellServo::RATE_YZ, FixCellServo::SIG_MAJOR, FixCellServo::SIG_INTER,
    FixCellServo::SIG_MINOR};
const int PLANE_COLUMNS[] = {
    FixCellServo::GAMMA, FixCellServo::TAU, FixCellServo::SIG_N, FixCellServo::TAU_RATIO,
    FixCellServo::STRESS_ANGLE, FixCellServo::RATE_ANGLE, FixCellServo::NONCOAXIALITY};
const int CYCLIC_COLUMNS[] = {FixCellServo::R_U, FixCellServo::CYCLES, FixCellServo::N_L_RU,
                              FixCellServo::N_L_GAMMA};

}    // namespace

const char *FixCellServo::output_name(int i)
{
  return OUTPUT_NAMES[i];
}

std::vector<int> FixCellServo::csv_columns() const
{
  std::vector<int> columns(std::begin(CSV_COLUMNS), std::end(CSV_COLUMNS));
  if (domain->triclinic) columns.insert(columns.end(), std::begin(CELL_COLUMNS), std::end(CELL_COLUMNS));
  if (has_plane) columns.insert(columns.end(), std::begin(PLANE_COLUMNS), std::end(PLANE_COLUMNS));
  if (mode == Mode::SHEAR_CV) columns.push_back(R_U);
  if (mode == Mode::CYCLIC_SHEAR)
    columns.insert(columns.end(), std::begin(CYCLIC_COLUMNS), std::end(CYCLIC_COLUMNS));
  return columns;
}

std::string FixCellServo::csv_header() const
{
  std::string header = "step";
  for (int k : csv_columns()) header += std::string(",") + OUTPUT_NAMES[k];
  for (const auto &e : extra_columns) header += "," + e.first;
  return header;
}

/* ---------------------------------------------------------------------- */

void FixCellServo::compute_outputs()
{
  const double volume = cell_volume();
  const Eigen::Vector3d eps = principal_strain();
  const Eigen::Vector3d sig = stress.head<3>();
  output[EPS1] = eps(0), output[EPS2] = eps(1), output[EPS3] = eps(2);
  output[EPS_V] = tycore::volumetric_strain(eps);
  output[EPS_Q] = tycore::deviatoric_strain(eps);
  output[EPS_D13] = tycore::strain_difference_13(eps);
  output[SIG1] = sig(0), output[SIG2] = sig(1), output[SIG3] = sig(2);
  output[P] = tycore::mean_stress(sig);
  output[Q] = tycore::deviatoric_stress(sig);
  output[B] = tycore::b_value(sig);
  const Eigen::Vector2d pi_stress = tycore::pi_coordinates(sig);
  const Eigen::Vector2d pi_strain = tycore::pi_coordinates(eps);
  output[LODE_DEG] = tycore::lode_angle_deg(pi_stress);
  output[ETA_LD] = sig.minCoeff() > 0.0 ? tycore::lade_duncan_eta(sig) : NaN;
  output[SINPHI] = sig.maxCoeff() + sig.minCoeff() > 0.0 ? tycore::mobilised_sinphi(sig) : NaN;
  output[SOLID_FRACTION] = solid_volume / volume;
  output[VOID_RATIO] = volume / solid_volume - 1.0;

  output[SLIDING_FRACTION] = contacts > 0.0 ? sliding / contacts : 0.0;

  const Eigen::Vector3d rate = memory.last_strain_rate.head<3>();
  // I = eps_dot_q d sqrt(rho/p), eps_dot_q = sqrt(2/3 e':e')   (docs/theory.md §4.2), the
  // tensor's shears gamma_dot/2 included
  const double shear_rate =
      std::sqrt(2.0 / 3.0)
      * std::sqrt(tycore::deviator(rate).squaredNorm()
                  + 0.5 * memory.last_strain_rate.tail<3>().squaredNorm());
  output[INERTIAL_NUMBER] =
      output[P] > 0.0 ? shear_rate * mean_diameter * std::sqrt(mean_density / output[P]) : NaN;
  output[PI_X] = pi_stress.x(), output[PI_Y] = pi_stress.y();
  output[PI_EX] = pi_strain.x(), output[PI_EY] = pi_strain.y();

  // progress: to the 'until' target, else along the path, else through the current run;
  // ETA in wall-clock seconds
  const bigint done_steps = update->ntimestep - step_start;
  const double wall = MPI_Wtime() - wall_start;
  const double wall_per_step = done_steps > 0 ? wall / done_steps : NaN;
  if (until_output >= 0) {
    output[TIME] = elapsed_time;
    output[BOUNDARY_WORK] = boundary_work;
    if (std::isnan(until_start)) until_start = output[until_output];
    output[PROGRESS] = tycore::progress_towards(until_start, output[until_output], until_value);
    const double gained = output[PROGRESS] - progress_at_setup;
    output[ETA_SECONDS] = gained > 0.0 ? wall / gained * (1.0 - output[PROGRESS]) : NaN;
  } else if (mode == Mode::PATH) {
    output[PROGRESS] = path.progress(memory.path_length).fraction;
    output[ETA_SECONDS] =
        path.remaining_time(memory.path_length, path_speed) / update->dt * wall_per_step;
  } else {
    const bigint span = update->endstep - update->beginstep;
    output[PROGRESS] = span > 0 ? double(update->ntimestep - update->beginstep) / span : 1.0;
    output[ETA_SECONDS] = double(update->endstep - update->ntimestep) * wall_per_step;
  }
  output[EQUILIBRIUM] = equilibrium_reached;
  output[RATE1] = rate(0), output[RATE2] = rate(1), output[RATE3] = rate(2);
  output[BOUNDARY_WORK] = boundary_work;
  output[VOLUME] = volume;
  output[TIME] = elapsed_time;
  compute_cell_outputs();
  output_step = update->ntimestep;
  // the state the test began in (a test restored from a restart file does not know it)
  if (std::isnan(origin[TIME]) && !restored) std::copy(output, output + N_OUTPUT, origin);
}

/* ----------------------------------------------------------------------
   per-particle statistics (a pass over the atoms and a reduction): only on the steps that
   output or test them, not on every servo step
------------------------------------------------------------------------- */

bool FixCellServo::is_particle_output(int n)
{
  return n == Z || n == ZM || n == UNBALANCED || n == P_KINETIC || n == KINETIC_RATIO;
}

void FixCellServo::compute_particle_outputs()
{
  if (particle_step == update->ntimestep) return;
  // Z, Zm, unbalanced force, kinetic stress and the kinetic energy of the load-bearing
  // particles (plugin/core/cell_statistics.hpp)
  const double *count = pair->contact_count();
  tycore::ParticleSums local, total;
  for (int i = 0; i < atom->nlocal; ++i)
    local.add(count ? std::lround(count[i]) : 0, atom->f[i], atom->rmass[i], atom->v[i]);
  MPI_Allreduce(local.sum, total.sum, tycore::ParticleSums::size, MPI_DOUBLE, MPI_SUM, world);
  const double volume = cell_volume();
  // the kinetic ratio relative to the target p (iso), else to the measured one
  const tycore::ParticleStatistics st = tycore::particle_statistics(
      total, contacts, force_sum, volume, target_p > 0.0 ? target_p : output[P]);
  output[Z] = st.Z;
  output[ZM] = st.Zm;
  output[UNBALANCED] = st.unbalanced;
  output[P_KINETIC] = st.p_kinetic;
  output[KINETIC_RATIO] = st.kinetic_ratio;
  particle_step = update->ntimestep;
}

double FixCellServo::compute_vector(int n)
{
  if (output_step != update->ntimestep) {
    measure();
    compute_outputs();
  }
  if (is_particle_output(n)) compute_particle_outputs();
  return output[n];
}


/* ----------------------------------------------------------------------
   the six-component outputs (docs/theory.md §10.4-10.5, §13): shears in the tilt sense
   (gamma_ij = int L_ij dt, rate_ij = L_ij), tau = -sigma_ij and sigma_n = sigma_jj of the
   plane (i, j), principal directions and the non-coaxiality angle in that plane, both
   tensors compression positive
------------------------------------------------------------------------- */

void FixCellServo::compute_cell_outputs()
{
  const tycore::Vector6d &rate = memory.last_strain_rate;
  for (int k = 0; k < 3; ++k) {
    output[SIG_XY + k] = stress(3 + k);
    output[GAMMA_XY + k] = strain.shear(k);
    output[RATE_XY + k] = -rate(3 + k);
  }
  const Eigen::Matrix3d sigma = tycore::tensor_from_stress(stress);
  const tycore::PrincipalAxes principal = tycore::principal_axes(sigma);
  output[SIG_MAJOR] = principal.values(0);
  output[SIG_INTER] = principal.values(1);
  output[SIG_MINOR] = principal.values(2);
  if (has_plane) {
    const int i = plane.direction, j = plane.normal;
    const Eigen::Matrix3d strain_rate = tycore::tensor_from_strain(rate);
    output[GAMMA] = strain.shear(plane.component() - 3);
    output[TAU] = tycore::shear_stress(stress, plane);
    output[SIG_N] = tycore::normal_stress(stress, plane);
    output[TAU_RATIO] = output[SIG_N] > 0.0 ? output[TAU] / output[SIG_N] : NaN;
    output[STRESS_ANGLE] = tycore::major_angle_in_plane_deg(sigma, i, j);
    output[RATE_ANGLE] = rate.norm() > 0.0 ? tycore::major_angle_in_plane_deg(strain_rate, i, j) : NaN;
    output[NONCOAXIALITY] =
        rate.norm() > 0.0 ? tycore::non_coaxiality_deg(sigma, strain_rate, i, j) : NaN;
  }
  if (mode == Mode::SHEAR_CV || mode == Mode::CYCLIC_SHEAR)
    output[R_U] = tycore::pore_pressure_ratio(output[SIG_N], initial_normal_stress);
  if (mode == Mode::CYCLIC_SHEAR) {
    const tycore::CyclicSimpleShear programme = cyclic_programme();
    output[CYCLES] = programme.cycles(cyclic);
    output[N_L_RU] = cyclic.cycles_to_pore_pressure;
    output[N_L_GAMMA] = cyclic.cycles_to_double_amplitude;
  }
}

// the affine stiffness C_IJ (Voigt6, engineering shears) of the last measurement [Pa]; NaN for
// an entry the tallies do not make (FixCellServo::stiffness_entries)
double FixCellServo::compute_array(int i, int j)
{
  if (!(tallied_entries >> tycore::AffineStiffnessSums::index(i, j) & 1u))
    return std::numeric_limits<double>::quiet_NaN();
  if (output_step != update->ntimestep) {
    measure();
    compute_outputs();
  }
  return cell_measurement().stiffness(i, j);
}
