/* ----------------------------------------------------------------------
   fix ID all cell/servo MODE args [keyword value ...]      (docs/fix_cell_servo.md)

   Each step, after the forces (end_of_step): the contact (Love-Weber) stress from the pair
   virial, the affine stiffness from the pair's contact tallies, the programme's control and
   the servo's strain rates, which deform the cell at the next step's post_integrate
   (docs/theory.md §5.1, §10.1-10.3).
------------------------------------------------------------------------- */

#include "fix_cell_servo.h"
#include "cell_tally.h"
#include "fix_cell_servo_record.h"
#include "tylmp_citations.h"

#include "cell_statistics.hpp"

#include "atom.h"
#include "comm.h"
#include "compute.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "irregular.h"
#include "modify.h"
#include "neighbor.h"
#include "pair.h"
#include "timer.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
namespace out = tycore::out;

namespace {

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

// the key of a fix's carry (tycore::TestCarry): its LAMMPS instance and ID
std::string carry_key(LAMMPS *lmp, const char *id)
{
  return fmt::format("{}/{}", static_cast<const void *>(lmp), id);
}

}    // namespace

FixCellServo::FixCellServo(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  tylmp::cite(lmp, tylmp::cite_thornton_2000);
  if (narg < 5)
    error->all(FLERR,
               "Illegal fix cell/servo command: expected 'fix ID all cell/servo MODE "
               "...' (modes: {})",
               tycore::mode_names(" "));
  if (strcmp(arg[1], "all") != 0)
    error->all(FLERR,
               "fix cell/servo: group must be 'all' (every particle follows the "
               "homogeneous deformation of the cell)");
  if (domain->dimension != 3) error->all(FLERR, "fix cell/servo requires a 3d simulation");
  if (!domain->xperiodic || !domain->yperiodic || !domain->zperiodic)
    error->all(FLERR, "fix cell/servo requires a fully periodic box ('boundary p p p')");
  box_change |= BOX_CHANGE_SIZE | BOX_CHANGE_SHAPE;
  no_change_box = 1;
  restart_global = 1;
  vector_flag = array_flag = 1;
  size_vector = out::COUNT;
  size_array_rows = size_array_cols = 6;    // the affine stiffness C_IJ (Voigt6)
  global_freq = nevery = 1;
  extvector = extarray = 0;
  force_reneighbor = 1;    // a tilt flip (pre_exchange) needs a neighbor list rebuild
  next_reneighbor = -1;
  std::fill(std::begin(output), std::end(output), NaN);
  origin.fill(NaN);
  box_left.fill(NaN);
  for (int i = 0; i < 3; ++i) test.strain.reference_length(i) = domain->prd[i];
  test.clock_step = update->ntimestep;

  try {
    command = tycore::parse_cell_command(std::vector<std::string>(arg + 3, arg + narg),
                                         domain->triclinic);
  } catch (tycore::RecordError &e) {
    error->all(FLERR, "fix cell/servo {}: {}", id, e.what());
  } catch (std::exception &e) {
    error->all(FLERR, "fix cell/servo: {}", e.what());
  }
  for (const std::string &w : command.warnings)
    if (comm->me == 0) error->warning(FLERR, "fix cell/servo {}: {}", id, w);
  profile = programme().profile();
  cell.plane = profile.plane;
  if (!command.csv_path.empty())
    record =
        std::make_unique<CellRecord>(lmp, id, command.csv_path, command.csv_every, command.extra);
  take_over_replaced_fix();
  const std::string entered = programme().enter(test.strain.voigt(cell_matrix()), update->dt);
  if (!entered.empty() && comm->me == 0) utils::logmesg(lmp, "fix cell/servo: {}\n", entered);

  pressure_id = std::string(id) + "_contact_stress";
  modify->add_compute(pressure_id + " all pressure NULL pair");
  // the contact tallies for a pair style other than thornton/yin (compute_cell_tally.h)
  tally_id = std::string(id) + "_contact_tally";
  modify->add_compute(tally_id + " all CELL_TALLY");
  irregular = new Irregular(lmp);
  if (command.named_variables) define_named_variables(true);
}

// a redefinition (same ID: Modify has just deleted the fix in this slot) continues the test
// of the fix it replaces, unless 'continue no'
void FixCellServo::take_over_replaced_fix()
{
  const bool replacing = std::count(modify->fix, modify->fix + modify->nfix, nullptr) > 0;
  auto &carries = tycore::test_carries();
  const auto previous = carries.find(carry_key(lmp, id));
  if (replacing && previous != carries.end()) {
    const tycore::TestCarry &c = previous->second;
    if (command.continue_previous) {
      tycore::continue_test(c, test, programme());
      continued = true;
      continued_csv = c.record;
      origin = c.origin;
      box_left = c.box;
    } else if (record) {
      const std::string overwrite = tycore::overwritten_record_error(record->path(), c);
      if (!overwrite.empty()) error->all(FLERR, "fix cell/servo: {}", overwrite);
    }
  }
  if (previous != carries.end()) carries.erase(previous);
}

// `variables yes`: an equal-style variable ID_NAME = f_ID[i] for every output, so that a deck
// reads the outputs by name; one that exists already is an error, never overwritten
void FixCellServo::define_named_variables(bool define)
{
  const auto name = [this](int i) {
    return fmt::format("{}_{}", id, out::name(i));
  };
  for (int i = 0; define && i < out::COUNT; ++i)
    if (input->variable->find(name(i).c_str()) >= 0)
      error->all(FLERR,
                 "fix cell/servo: 'variables yes' defines the variable {} (output {} "
                 "of fix {}), which exists already: delete it or give the fix another ID",
                 name(i), i + 1, id);
  for (int i = 0; i < out::COUNT; ++i) {
    if (define)
      input->variable->set(fmt::format("{} equal f_{}[{}]", name(i), id, i + 1));
    else if (input->variable->find(name(i).c_str()) >= 0)
      input->variable->set(name(i) + " delete");
  }
}

FixCellServo::~FixCellServo()
{
  // left for a fix that redefines this one (take_over_replaced_fix), with the box as this fix
  // left it (a change since is a change behind the test's back)
  tycore::TestCarry c{test, programme().carried(), {}, "", box_left, origin};
  if (record) c.record_path = record->path(), c.record = tycore::file_identity(c.record_path);
  if (std::isnan(box_left[0])) std::copy(domain->h, domain->h + 6, c.box.begin());
  tycore::test_carries()[carry_key(lmp, id)] = c;

  if (modify->find_compute(pressure_id) >= 0) modify->delete_compute(pressure_id);
  if (modify->find_compute(tally_id) >= 0) modify->delete_compute(tally_id);
  if (command.named_variables) define_named_variables(false);
  delete irregular;
  // the box stops deforming with this fix: pair styles must not add an affine velocity
  for (int i = 0; i < 6; ++i) domain->h_rate[i] = 0.0;
  for (int i = 0; i < 3; ++i) domain->h_ratelo[i] = 0.0;
}

int FixCellServo::setmask()
{
  return POST_INTEGRATE | PRE_EXCHANGE | END_OF_STEP;
}

void FixCellServo::post_run()
{
  // a run stopped by 'until' leaves the timer expired: later runs must be allowed to run
  if (until_met) timer->reset_timeout();
  until_met = false;
}

/* ---------------------------------------------------------------------- */

void FixCellServo::init()
{
  if (update->whichflag == 2)
    error->all(FLERR,
               "fix cell/servo cannot be used with minimize: it deforms the cell by "
               "strain rates in time and holds stresses by a servo, neither of which a "
               "minimizer steps through (use fix box/relax to minimize with a stress-controlled "
               "box, and unfix the cell/servo first)");
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "fix cell/servo does not support run_style respa");
  for (int i = 0; i < modify->nfix; ++i)
    if (modify->fix[i] != this && modify->fix[i]->box_change)
      error->all(FLERR,
                 "fix cell/servo cannot be combined with fix {} ({}), which also "
                 "changes the box",
                 modify->fix[i]->id, modify->fix[i]->style);
  if (profile.triclinic && !domain->triclinic)
    error->all(FLERR,
               "fix cell/servo: the box was made orthogonal, but this programme moves "
               "or holds a shear component, which needs a triclinic box");

  // the contact tallies: exact from pair thornton/yin, else estimated (docs/theory.md §6.5),
  // from the setup force computation on; the stiffness entries are the programme's
  pair = dynamic_cast<CellTallySource *>(force->pair_match("thornton/yin", 1));
  if (!pair) {
    const int itally = modify->find_compute(tally_id);
    if (itally < 0) error->all(FLERR, "fix cell/servo: its contact tally compute was deleted");
    pair = dynamic_cast<CellTallySource *>(modify->compute[itally]);
  }
  tallied_entries =
      pair->request_cell_tallies(tycore::stiffness_entries_of(profile, domain->triclinic));
  const int icompute = modify->find_compute(pressure_id);
  if (icompute < 0) error->all(FLERR, "fix cell/servo: its stress compute was deleted");
  pressure = modify->compute[icompute];

  variable_index.clear();
  for (tycore::Setting *s : programme().settings()) {
    if (!s->is_variable()) continue;
    const int ivar = input->variable->find(s->variable.c_str());
    if (ivar < 0) error->all(FLERR, "fix cell/servo: variable {} does not exist", s->variable);
    if (!input->variable->equalstyle(ivar))
      error->all(FLERR, "fix cell/servo: variable {} is not equal-style", s->variable);
    variable_index[s->variable] = ivar;
  }

  // number-mean diameter and density, solid volume
  tycore::ParticleSizes local, total;
  for (int i = 0; i < atom->nlocal; ++i) local.add(atom->radius[i], atom->rmass[i]);
  MPI_Allreduce(local.sum, total.sum, total.size, MPI_DOUBLE, MPI_SUM, world);
  if (total.sum[0] == 0.0) error->all(FLERR, "fix cell/servo: the cell holds no particles");
  cell.mean_diameter = total.mean_diameter();
  cell.mean_density = total.mean_density();
  cell.solid_volume = total.solid_volume();
  if (record) record->resolve_extra();
  cap_watch = {};
}

// a setting's value at this step: the number, or its equal-style variable, checked
double FixCellServo::operator()(tycore::Setting &s)
{
  if (!s.is_variable()) return s.value;
  modify->clearstep_compute();
  const double value = input->variable->compute_equal(variable_index.at(s.variable));
  modify->addstep_compute(update->ntimestep + 1);
  const std::string refused = s.refusal(value);
  if (!refused.empty())
    error->all(FLERR, "fix cell/servo: variable {} ({}) evaluated to {} at step {}: {}", s.variable,
               s.what, value, update->ntimestep, refused);
  return s.value = value;
}

tycore::CellState FixCellServo::cell_state() const
{
  return {test.elapsed_time, update->dt, cell.stress, test.strain.voigt(cell_matrix())};
}

void FixCellServo::setup(int)
{
  // the box as this test left it (this fix's last move, or the fix it continues)
  const std::string changed = tycore::box_changed_error(box_left.data(), domain->h);
  if (!changed.empty()) error->all(FLERR, "fix cell/servo {}: {}", id, changed);
  std::copy(domain->h, domain->h + 6, box_left.begin());
  // the rate of the last step carries on across runs and restarts
  set_box_rate(test.memory.last_strain_rate, cell_matrix());
  test.advance_clock(update->ntimestep, update->dt);
  measure();
  run = {update->beginstep, update->endstep, update->ntimestep, run.progress_at_setup};
  try {
    const std::string warning = programme().begin_run(cell_state(), *this);
    if (!warning.empty() && comm->me == 0)
      error->warning(FLERR, "fix cell/servo {}: {}", id, warning);
  } catch (std::exception &e) {
    error->all(FLERR, "fix cell/servo {}: {}", id, e.what());
  }
  compute_outputs();
  compute_particle_outputs();
  check_rates();
  run.progress_at_setup = output[out::PROGRESS];
  const int until = command.until.output;
  until_run_start = until >= 0 ? output[until] : NaN;
  until_direction_checked = false;
  wall_start = MPI_Wtime();
  if (!record) return;
  // a new test starts its record, a continued one appends to it; the row of the run's start
  // is written unless the record holds this step already
  const bool resume = restored ||
      (continued && tycore::file_identity(record->path()) == continued_csv);
  record_columns = out::record_columns(domain->triclinic, profile.columns);
  if (!record->open(out::record_header(record_columns), resume, update->ntimestep)) write_row();
}

void FixCellServo::end_of_step()
{
  test.advance_clock(update->ntimestep, update->dt);
  measure();
  compute_outputs();
  check_until();
  const tycore::CellState state = cell_state();
  programme().after_step(state);
  tycore::ServoCommandOf<6> next;
  try {
    next = tycore::servo_step(programme().control(state, *this), cell_measurement(),
                              command.settings, update->dt, test.memory);
  } catch (std::exception &e) {
    error->all(FLERR, "fix cell/servo: {}", e.what());
  }
  check_equilibrium();
  // a servo at its cap whose stress error grows (tycore::CapWatch), once per run
  if (cap_watch.due(next, command.cap_warning, cell.contacts > 0.0) && comm->me == 0)
    error->warning(FLERR, "fix cell/servo: {}",
                   cap_watch.message(command.settings.max_strain_rate, next.stress_error,
                                     programme().held_targets(cell.stress),
                                     programme().largest_rate()));
  const std::string too_fast =
      tycore::step_strain_error(next.strain_rate, update->dt, update->ntimestep);
  if (!too_fast.empty()) error->all(FLERR, "fix cell/servo: {}", too_fast);
  test.add_boundary_work(domain->xprd * domain->yprd * domain->zprd, cell.stress, next.strain_rate,
                         update->dt, domain->triclinic ? 6 : 3);
}

// the record's row of this step, and the end of the test once 'until' is met: the last row,
// and the run stops after this step (as fix halt does)
void FixCellServo::check_until()
{
  const int k = command.until.output;
  const bool due = record && record->due(update->ntimestep);
  const bool met = k >= 0 && tycore::reached(test.until_start, output[k], command.until.value);
  if (due || met) write_row();
  if (met && !until_met) {
    if (comm->me == 0)
      utils::logmesg(lmp, "fix cell/servo: {}\n",
                     command.until.reached_message(output[k], update->ntimestep));
    timer->force_timeout();
    until_met = true;
  }
  // moving away from the target: the run would not stop by it (tycore::judge_until_direction)
  if (k < 0 || until_direction_checked) return;
  const tycore::UntilDirection d = tycore::judge_until_direction(
      command.until, until_run_start, output[k], origin[k], continued, update->ntimestep);
  until_direction_checked = d.judged;
  if (!d.error.empty()) error->all(FLERR, "fix cell/servo {}: {}", id, d.error);
  if (!d.warning.empty() && comm->me == 0)
    error->warning(FLERR, "fix cell/servo {}: {}", id, d.warning);
}

// the quasi-equilibrium check of a preparation ('equilibrium N'), every N steps
void FixCellServo::check_equilibrium()
{
  const int every = profile.equilibrium_every;
  if (!(every > 0 && update->ntimestep % every == 0)) return;
  compute_particle_outputs();
  const tycore::EquilibriumSample sample =
      tycore::equilibrium_sample(cell.stress, profile.mean_stress, output);
  tycore::equilibrium_outputs(programme().check_equilibrium(sample), output);
}

// the servo's cap and the prescribed rates (tycore::settle_rates)
void FixCellServo::check_rates()
{
  tycore::RateReport r;
  try {
    r = tycore::settle_rates(command, profile.mean_stress, update->dt, cell.mean_diameter,
                             cell.mean_density);
  } catch (std::exception &e) {
    error->all(FLERR, "fix cell/servo: {}", e.what());
  }
  if (!r.slow_cap.empty() && comm->me == 0) error->warning(FLERR, "fix cell/servo: {}", r.slow_cap);
  if (!r.unresolvable.empty()) error->all(FLERR, "fix cell/servo {}: {}", id, r.unresolvable);
  if (!r.inertial.empty() && comm->me == 0)
    error->warning(FLERR, "fix cell/servo {}: {}", id, r.inertial);
}

/* ----------------------------------------------------------------------
   the measurement: stress (compression positive) from the pair virial, affine stiffness and
   contact statistics from the pair's tallies
------------------------------------------------------------------------- */

void FixCellServo::measure()
{
  if (measured_step == update->ntimestep) return;
  pressure->compute_vector();
  pressure->addstep(update->ntimestep + 1);
  // LAMMPS's pressure tensor xx yy zz xy xz yz is the compression-positive stress (Voigt6)
  for (int k = 0; k < 6; ++k) cell.stress(k) = pressure->vector[k];
  pair->refresh_cell_tallies();
  CellTallies total;
  MPI_Allreduce(const_cast<double *>(pair->cell_tallies().sum), total.sum, CellTallies::SIZE,
                MPI_DOUBLE, MPI_SUM, world);
  std::copy(total.sum + CellTallies::STIFFNESS,
            total.sum + CellTallies::STIFFNESS + stiffness_sums.size, stiffness_sums.sum.begin());
  cell.contacts = total.sum[CellTallies::CONTACTS];
  cell.sliding = total.sum[CellTallies::SLIDING];
  force_sum = total.sum[CellTallies::FORCE];
  measured_step = update->ntimestep;
}

Eigen::Matrix3d FixCellServo::cell_matrix() const
{
  return tycore::cell_matrix_from_lammps(domain->h);
}

// the stiffness entries the tallies do not make read 0 here (the servo uses none of them)
tycore::CellMeasurementOf<6> FixCellServo::cell_measurement() const
{
  return {cell.stress, stiffness_sums.stiffness(domain->xprd * domain->yprd * domain->zprd),
          test.strain.voigt(cell_matrix())};
}

/* ----------------------------------------------------------------------
   the cell deforms at the next step's post_integrate, before its forces: the positions written
   at the end of a step are those its forces were computed at, so that a restart (or a new run)
   recomputes the same forces in setup and continues the trajectory exactly. h <- exp(L dt) h
   about the fixed box centre, atoms remapped affinely; a tilt past half its box length is
   flipped in pre_exchange of this step (a neighbor list rebuild is forced)
------------------------------------------------------------------------- */

// domain->h_rate = L h, with which the pair reads L back as h_rate h^-1 (docs/theory.md §5.1,
// §10.1); an orthogonal cell has only the diagonal, h_rate_k = -eps_dot_k l_k
void FixCellServo::set_box_rate(const tycore::Vector6d &rate, const Eigen::Matrix3d &h)
{
  if (domain->triclinic) {
    const std::array<double, 6> h_rate = tycore::lammps_h_rate(tycore::velocity_gradient(rate), h);
    for (int k = 0; k < 6; ++k) domain->h_rate[k] = h_rate[k];
  } else {
    for (int k = 0; k < 3; ++k) domain->h_rate[k] = -rate(k) * h(k, k);
  }
  for (int k = 0; k < 3; ++k) domain->h_ratelo[k] = -0.5 * domain->h_rate[k];
}

void FixCellServo::post_integrate()
{
  const tycore::Vector6d &rate = test.memory.last_strain_rate;
  domain->x2lamda(atom->nlocal);
  const double dt = update->dt;
  const Eigen::Matrix3d L = tycore::velocity_gradient(rate);
  // (for an orthogonal cell next(k, k) = l_k exp(-eps_dot_k dt), docs/theory.md §5.1)
  const Eigen::Matrix3d next = tycore::advance_cell(cell_matrix(), L, dt);
  for (int k = 0; k < 3; ++k) {
    const double length = next(k, k);
    if (length < 2.0 * neighbor->cutneighmax)
      error->all(FLERR,
                 "fix cell/servo: cell edge {} = {:.4g} has shrunk below twice the "
                 "neighbor cutoff ({:.4g}); use a larger specimen or a smaller skin",
                 tycore::axis_name(k), length, 2.0 * neighbor->cutneighmax);
    const double centre = 0.5 * (domain->boxlo[k] + domain->boxhi[k]);
    domain->boxlo[k] = centre - 0.5 * length;
    domain->boxhi[k] = centre + 0.5 * length;
  }
  if (domain->triclinic) {
    domain->xy = next(0, 1);
    domain->xz = next(0, 2);
    domain->yz = next(1, 2);
    test.strain.advance(L, dt);
  }
  domain->set_global_box();
  domain->set_local_box();
  domain->lamda2x(atom->nlocal);
  set_box_rate(rate, next);    // (next, not boxhi - boxlo, which differs by round-off)
  std::copy(domain->h, domain->h + 6, box_left.begin());
  if (domain->triclinic) {
    pending_flip = tycore::tilt_flip_of(cell_matrix());
    if (pending_flip.any()) next_reneighbor = update->ntimestep;
  }
}

// a tilt flip (docs/theory.md §10.3), as fix deform's pre_exchange: the equivalent cell h M,
// image flags by Domain::image_flip, atoms remapped into the new cell and migrated; h_rate =
// L h M so that the pair reads the same L. The cumulative strain does not change.
void FixCellServo::pre_exchange()
{
  if (!pending_flip.any()) return;
  const Eigen::Matrix3d flipped = tycore::flipped_cell(cell_matrix(), pending_flip);
  domain->xy = flipped(0, 1);
  domain->xz = flipped(0, 2);
  domain->yz = flipped(1, 2);
  domain->set_global_box();
  domain->set_local_box();
  // b' = b + m a, c' = c + p b + n a with (m, n, p) = LAMMPS's (flipxy, flipxz, flipyz)
  domain->image_flip(pending_flip.xy, pending_flip.xz, pending_flip.yz);
  for (int i = 0; i < atom->nlocal; ++i) domain->remap(atom->x[i], atom->image[i]);
  domain->x2lamda(atom->nlocal);
  irregular->migrate_atoms();
  domain->lamda2x(atom->nlocal);
  set_box_rate(test.memory.last_strain_rate, flipped);
  std::copy(domain->h, domain->h + 6, box_left.begin());
  pending_flip = {};
}

/* ----------------------------------------------------------------------
   outputs (plugin/core/cell_outputs.hpp)
------------------------------------------------------------------------- */

void FixCellServo::compute_outputs()
{
  cell.strain = test.strain.axial(cell_matrix());
  cell.shear = test.strain.shear;
  cell.last_strain_rate = test.memory.last_strain_rate;
  cell.volume = domain->xprd * domain->yprd * domain->zprd;
  tycore::principal_outputs(cell, output);
  output[out::TIME] = test.elapsed_time;
  output[out::BOUNDARY_WORK] = test.boundary_work;
  tycore::cell_outputs(cell, output);
  programme().outputs(cell_state(), output);
  const int k = command.until.output;
  if (k >= 0 && std::isnan(test.until_start)) test.until_start = output[k];
  run.outputs(command.until, test.until_start, programme().progress(), programme().remaining_time(),
              update->ntimestep, MPI_Wtime() - wall_start, update->dt, output);
  output[out::EQUILIBRIUM] = programme().equilibrium_reached();
  output_step = update->ntimestep;
  // the state the test began in (a test restored from a restart file does not know it)
  if (std::isnan(origin[out::TIME]) && !restored)
    std::copy(output, output + out::COUNT, origin.begin());
}

// Z, Zm, unbalanced force, kinetic stress and the kinetic energy of the load-bearing
// particles (cell_statistics.hpp): a pass over the atoms, only on the steps that need them
void FixCellServo::compute_particle_outputs()
{
  if (particle_step == update->ntimestep) return;
  const double *count = pair->contact_count();
  tycore::ParticleSums local, total;
  for (int i = 0; i < atom->nlocal; ++i)
    local.add(count ? std::lround(count[i]) : 0, atom->f[i], atom->rmass[i], atom->v[i]);
  MPI_Allreduce(local.sum, total.sum, tycore::ParticleSums::size, MPI_DOUBLE, MPI_SUM, world);
  // the kinetic ratio relative to the held p, else to the measured one
  const double p = profile.mean_stress;
  tycore::particle_outputs(tycore::particle_statistics(total, cell.contacts, force_sum,
                                                       domain->xprd * domain->yprd * domain->zprd,
                                                       p > 0.0 ? p : output[out::P]),
                           output);
  particle_step = update->ntimestep;
}

void FixCellServo::write_row()
{
  if (!record) return;
  compute_particle_outputs();
  record->write(update->ntimestep, out::record_row(record_columns, output));
}

double FixCellServo::compute_vector(int n)
{
  if (output_step != update->ntimestep) measure(), compute_outputs();
  if (out::of_particles(n)) compute_particle_outputs();
  return output[n];
}

// the affine stiffness C_IJ (Voigt6, engineering shears) of the last measurement [Pa]; NaN for
// an entry the tallies do not make (the programme's servo does not use it)
double FixCellServo::compute_array(int i, int j)
{
  if (!(tallied_entries & tycore::AffineStiffnessSums::entry(i, j))) return NaN;
  if (output_step != update->ntimestep) measure(), compute_outputs();
  return cell_measurement().stiffness(i, j);
}

/* ----------------------------------------------------------------------
   restart (plugin/core/cell_restart.hpp)
------------------------------------------------------------------------- */

void FixCellServo::write_restart(FILE *fp)
{
  const std::vector<double> list = tycore::restart_record(test, programme());
  if (comm->me == 0) {
    const int size = static_cast<int>(list.size() * sizeof(double));
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list.data(), sizeof(double), list.size(), fp);
  }
}

void FixCellServo::restart(char *buf)
{
  // 'continue no' asks for a new test: the state in the restart file is not taken up
  if (!command.continue_previous) {
    if (comm->me == 0)
      utils::logmesg(lmp,
                     "fix cell/servo {}: continue no: the test whose state the restart "
                     "file holds is not continued; a new test starts (strains, time and "
                     "boundary work from zero)\n",
                     id);
    return;
  }
  try {
    tycore::read_restart_record(reinterpret_cast<double *>(buf), test, programme(), id);
  } catch (std::exception &e) {
    error->all(FLERR, "fix cell/servo: {}", e.what());
  }
  restored = true;
}
