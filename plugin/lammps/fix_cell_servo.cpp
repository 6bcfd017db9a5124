/* ----------------------------------------------------------------------
   fix ID all cell/servo MODE args [keyword value ...]      (docs/fix_cell_servo.md)

   Bookkeeping (docs/theory.md §5.1, as in TRUBAL): the cell edges L_i follow the
   principal strain rates, L_i <- L_i exp(-eps_dot_i dt) (compression positive); atoms are
   remapped affinely with the box and their velocities are fluctuations about the mean field.
   domain->h_rate carries L_ii = -eps_dot_i to pair thornton/yin, which adds L (x_i - x_j) to
   the contact relative velocity, so that tangential history sees the mean-field shear.

   Each step, after the forces: the contact (Love-Weber) stress from the pair virial and the
   affine stiffness from the pair's contact tallies go to the servo of plugin/core
   (cell_servo.hpp), whose strain rates deform the cell for the next step.
------------------------------------------------------------------------- */

#include "fix_cell_servo.h"
#include "tylmp_citations.h"
#include "cell_tally.h"

#include "cell_statistics.hpp"
#include "pi_plane.hpp"

#include "atom.h"
#include "comm.h"
#include "compute.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "irregular.h"
#include "math_const.h"
#include "modify.h"
#include "neighbor.h"
#include "timer.h"
#include "pair.h"
#include "update.h"
#include "variable.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
// the restart record starts with a tag, its version and its size (in doubles), so that a
// record of another programme or of another version of this fix is refused, not misread;
// version 3: six-component servo memory, cumulative shears, cyclic state
constexpr double RESTART_TAG = 8462.0;
constexpr int RESTART_VERSION = 3;

// the state a replaced fix leaves to the one that redefines it (same LAMMPS instance and ID):
// Modify deletes the old fix before it constructs the new one
std::map<std::string, FixCellServo::Continuation> &continuations()
{
  static std::map<std::string, FixCellServo::Continuation> stash;
  return stash;
}

std::string continuation_key(LAMMPS *lmp, const char *id)
{
  return fmt::format("{}/{}", static_cast<const void *>(lmp), id);
}


}    // namespace

/* ---------------------------------------------------------------------- */

FixCellServo::FixCellServo(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), target_p(0.0), major_axis(0), major_rate(0.0), b_target(0.0),
    initial_normal_stress(std::numeric_limits<double>::quiet_NaN()), path_speed(0.0),
    prestrain(0.0), inertial_cap(1e-3), equilibrium_every(0), equilibrium_reached(0),
    elapsed_time(0.0), clock_step(0), boundary_work(0.0), restored(0), continued(0),
    continue_previous(1), contacts(0.0), sliding(0.0), force_sum(0.0),
    measured_step(-1), output_step(-1), particle_step(-1), mean_diameter(0.0), mean_density(0.0),
    solid_volume(0.0), pressure(nullptr), pair(nullptr), csv_every(0),
    wall_start(0.0), step_start(0), saturated_steps(0), saturated_error(0.0),
    saturation_warned(false), cap_warning(true), named_variables(false)
{
  tylmp::cite(lmp, tylmp::cite_thornton_2000);
  if (narg < 5)
    error->all(FLERR, "Illegal fix cell/servo command: expected 'fix ID all cell/servo MODE ...' "
               "(modes: iso axes axisym constant_b deviatoric circle triangle polygon shear "
               "shear_cv cyclic_shear undrained rotation)");
  if (strcmp(arg[1], "all") != 0)
    error->all(FLERR, "fix cell/servo: group must be 'all' (every particle follows the "
               "homogeneous deformation of the cell)");
  if (domain->dimension != 3) error->all(FLERR, "fix cell/servo requires a 3d simulation");
  if (!domain->xperiodic || !domain->yperiodic || !domain->zperiodic)
    error->all(FLERR, "fix cell/servo requires a fully periodic box ('boundary p p p')");

  box_change |= BOX_CHANGE_SIZE | BOX_CHANGE_SHAPE;
  no_change_box = 1;
  restart_global = 1;
  vector_flag = 1;
  size_vector = N_OUTPUT;
  global_freq = 1;
  extvector = 0;
  array_flag = 1;          // the affine stiffness C_IJ (Voigt6) the servo used last
  size_array_rows = size_array_cols = 6;
  extarray = 0;
  nevery = 1;
  force_reneighbor = 1;    // a tilt flip (pre_exchange) needs a neighbor list rebuild
  next_reneighbor = -1;

  for (auto &a : axis_input) a = {tycore::AxisControl::STRAIN_RATE, 0.0, "", -1, ""};
  major_input = {tycore::AxisControl::STRAIN_RATE, 0.0, "", -1, ""};
  stress.setZero();
  for (double &s : stiffness_sums) s = 0.0;
  tallied_entries = 0;
  for (double &o : output) o = NaN;
  for (double &o : origin) o = NaN;
  for (int i = 0; i < 3; ++i) strain.reference_length(i) = domain->prd[i];
  clock_step = update->ntimestep;

  int iarg = 3;
  parse_mode(narg, arg, iarg);
  parse_keywords(narg, arg, iarg);
  if (mode == Mode::PATH) programme_path = path.to_array();
  if (needs_triclinic() && !domain->triclinic)
    error->all(FLERR, "fix cell/servo: this programme moves or holds a shear component, which "
               "needs a triclinic box: make the box triclinic first ('change_box all "
               "triclinic', or a triclinic region/data file)");
  require_controllable();
  choose_shear_gains();

  take_over_replaced_fix();
  if (mode == Mode::PATH) lead_into_path();

  pressure_id = std::string(id) + "_contact_stress";
  modify->add_compute(pressure_id + " all pressure NULL pair");
  // the contact tallies for a pair style other than thornton/yin (compute_cell_tally.h)
  tally_id = std::string(id) + "_contact_tally";
  modify->add_compute(tally_id + " all CELL_TALLY");
  irregular = new Irregular(lmp);
  if (named_variables) define_named_variables();
}

// a redefinition (same ID: Modify has just deleted the fix in this slot) continues the test
// of the fix it replaces, unless 'continue no'
void FixCellServo::take_over_replaced_fix()
{
  bool replacing = false;
  for (int i = 0; i < modify->nfix; ++i)
    if (modify->fix[i] == nullptr) replacing = true;
  auto &stash = continuations();
  const auto previous = stash.find(continuation_key(lmp, id));
  if (replacing && previous != stash.end()) {
    const Continuation &c = previous->second;
    if (continue_previous) {
      strain = c.strain;
      memory.last_strain_rate = c.last_strain_rate;
      initial_normal_stress = c.initial_normal_stress;
      elapsed_time = c.elapsed_time;
      clock_step = c.clock_step;
      boundary_work = c.boundary_work;
      continued = 1;
      continued_csv = c.csv_identity;
      std::copy(c.origin, c.origin + N_OUTPUT, origin);
    } else if (!csv_path.empty() && tycore::file_identity(csv_path) == c.csv_identity) {
      // by file identity: ./a.csv, a symbolic link or d/../a.csv name a.csv too
      error->all(FLERR, "fix cell/servo: 'continue no' starts a new test, whose record {} would "
                 "overwrite {}, the record of the test it replaces: name another file",
                 csv_path, c.csv_path);
    }
  }
  if (previous != stash.end()) stash.erase(previous);
}

// every path starts from the current strain (from the reference, kept by a continued test):
// a leg to the path's first point goes in front unless the follower can close the gap itself
void FixCellServo::lead_into_path()
{
  const Eigen::Vector2d from = tycore::pi_coordinates(principal_strain());
  const int legs = path.segment_count();
  path = path.starting_from(from, tycore::MIN_STEPS_PER_LEG * path_speed * update->dt);
  if (path.segment_count() > legs && comm->me == 0)
    utils::logmesg(lmp, "fix cell/servo: the path starts at the current strain, Pi point "
                   "({:.6g}, {:.6g}); a leg of length {:.6g} to its first point goes first\n",
                   from.x(), from.y(), path.segments().front().length());
}

// `variables yes`: an equal-style variable ID_NAME = f_ID[i] for every output, so that a deck
// reads the fix's state by the names of the Output table (output_name, the one list) instead
// of by position. A variable of that name that exists already is an error, not overwritten;
// the variables go with the fix.
std::string FixCellServo::output_variable(int i) const
{
  return fmt::format("{}_{}", id, output_name(i));
}

void FixCellServo::define_named_variables()
{
  for (int i = 0; i < N_OUTPUT; ++i)
    if (input->variable->find(output_variable(i).c_str()) >= 0)
      error->all(FLERR, "fix cell/servo: 'variables yes' defines the variable {} (output {} "
                 "of fix {}), which exists already: delete it or give the fix another ID",
                 output_variable(i), i + 1, id);
  for (int i = 0; i < N_OUTPUT; ++i)
    input->variable->set(fmt::format("{} equal f_{}[{}]", output_variable(i), id, i + 1));
}

void FixCellServo::delete_named_variables()
{
  for (int i = 0; i < N_OUTPUT; ++i)
    if (input->variable->find(output_variable(i).c_str()) >= 0)
      input->variable->set(output_variable(i) + " delete");
}

FixCellServo::~FixCellServo()
{
  // left for a fix that redefines this one (see the constructor)
  Continuation c;
  c.strain = strain;
  c.last_strain_rate = memory.last_strain_rate;
  c.initial_normal_stress = initial_normal_stress;
  c.elapsed_time = elapsed_time;
  c.clock_step = clock_step;
  c.boundary_work = boundary_work;
  c.csv_path = csv_path;
  if (!csv_path.empty()) c.csv_identity = tycore::file_identity(csv_path);
  std::copy(origin, origin + N_OUTPUT, c.origin);
  continuations()[continuation_key(lmp, id)] = c;

  if (modify->find_compute(pressure_id) >= 0) modify->delete_compute(pressure_id);
  if (modify->find_compute(tally_id) >= 0) modify->delete_compute(tally_id);
  if (named_variables) delete_named_variables();
  delete irregular;
  // (the pair may be gone already: pair thornton/yin clears its tally flag in init_style)
  // the box stops deforming with this fix: pair styles must not add an affine velocity
  for (int i = 0; i < 6; ++i) domain->h_rate[i] = 0.0;
  for (int i = 0; i < 3; ++i) domain->h_ratelo[i] = 0.0;
}

void FixCellServo::post_run()
{
  // a run stopped by 'until' leaves the timer expired: later runs must be allowed to run
  if (until_met) timer->reset_timeout();
  until_met = 0;
}

int FixCellServo::setmask()
{
  return POST_INTEGRATE | PRE_EXCHANGE | END_OF_STEP;
}

/* ----------------------------------------------------------------------
   keywords: see the table of docs/fix_cell_servo.md. Each group reads the keyword at hand if
   it is one of its own and returns how many arguments it took (0: not one of its keywords).
------------------------------------------------------------------------- */

// the keyword at arg[iarg] and its values; the messages name the keyword
class FixCellServo::KeywordArgs {
 public:
  KeywordArgs(Error *error, int narg, char **arg, int iarg) :
      key(arg[iarg]), narg(narg), arg(arg), iarg(iarg), error(error)
  {
  }
  const std::string key;
  const int narg;
  char **const arg;
  const int iarg;    // the keyword's index

  const char *value(int k = 1) const
  {
    if (iarg + k >= narg)
      error->all(FLERR, "fix cell/servo: keyword '{}' needs a value", key);
    return arg[iarg + k];
  }
  bool yes_no() const
  {
    const std::string v = value();
    if (v != "yes" && v != "no")
      error->all(FLERR, "fix cell/servo: {} must be yes or no, got '{}'", key, v);
    return v == "yes";
  }

 private:
  Error *error;
};

// the options of a Pi-plane path, built after the keywords (build_path)
struct FixCellServo::PathOptions {
  tycore::Rotation rotation = tycore::Rotation::CLOCKWISE;
  tycore::DeviatoricStrainMeasure measure = tycore::DeviatoricStrainMeasure::STRAIN_DIFFERENCE_13;
  bool with_prestrain = true;
  double sweep = 360.0;
};

void FixCellServo::parse_keywords(int narg, char **arg, int iarg)
{
  settings.max_strain_rate = 0.0;    // 0: default set in init() from the inertial number
  PathOptions options;
  std::set<std::string> seen;
  while (iarg < narg) {
    const KeywordArgs k(error, narg, arg, iarg);
    if (!seen.insert(k.key).second)
      error->all(FLERR, "fix cell/servo: keyword '{}' is given twice", k.key);
    int used = path_keyword(k, options);
    if (!used) used = servo_keyword(k);
    if (!used) used = record_keyword(k);
    if (!used) used = equilibrium_keyword(k);
    if (!used) used = cell_mode_keyword(k);
    if (!used) error->all(FLERR, "fix cell/servo: unknown keyword '{}'", k.key);
    iarg += used;
  }
  build_path(options);
  check_keyword_combinations();
}

// speed, rotation, measure, prestrain_leg, sweep, close, plane_strain
int FixCellServo::path_keyword(const KeywordArgs &k, PathOptions &options)
{
  auto path_only = [&]() {
    if (mode != Mode::PATH)
      error->all(FLERR, "fix cell/servo: keyword '{}' applies only to circle, triangle and "
                 "polygon paths", k.key);
  };
  if (k.key == "rotation") {
    path_only();
    const std::string v = k.value();
    if (v == "cw") options.rotation = tycore::Rotation::CLOCKWISE;
    else if (v == "ccw") options.rotation = tycore::Rotation::ANTICLOCKWISE;
    else error->all(FLERR, "fix cell/servo: rotation must be cw or ccw, got '{}'", v);
  } else if (k.key == "measure") {
    path_only();
    const std::string v = k.value();
    if (v == "d13") options.measure = tycore::DeviatoricStrainMeasure::STRAIN_DIFFERENCE_13;
    else if (v == "q") options.measure = tycore::DeviatoricStrainMeasure::EPS_Q;
    else error->all(FLERR, "fix cell/servo: measure must be d13 or q, got '{}'", v);
  } else if (k.key == "prestrain_leg") {
    path_only();
    options.with_prestrain = k.yes_no();
  } else if (k.key == "sweep") {
    if (path_kind != "circle")
      error->all(FLERR, "fix cell/servo: keyword 'sweep' applies only to the circle path");
    options.sweep = number_in(k.value(), "sweep", 0.0, 36000.0, true, " degrees (100 turns)");
  } else if (k.key == "close") {
    if (path_kind != "polygon")
      error->all(FLERR, "fix cell/servo: keyword 'close' applies only to the polygon path");
    close_polygon = k.yes_no();
  } else if (k.key == "plane_strain") {
    path_only();
    const std::string v = k.value();
    if (v == "total") plane_strain = tycore::PlaneStrain::TOTAL;
    else if (v == "deviatoric") plane_strain = tycore::PlaneStrain::DEVIATORIC;
    else error->all(FLERR, "fix cell/servo: plane_strain must be total or deviatoric, got '{}'", v);
  } else if (k.key == "speed") {
    path_speed = finite_number(k.value(), "speed");
    if (!(path_speed > 0.0))
      error->all(FLERR, "fix cell/servo: path speed must be positive, got {}", path_speed);
  } else {
    return 0;
  }
  return 2;
}

// gain, integral_gain, integral_band, max_rate, max_inertial, cap_warning
int FixCellServo::servo_keyword(const KeywordArgs &k)
{
  if (k.key == "gain") {
    settings.gain = finite_number(k.value(), "gain");
    gains_given = true;
  } else if (k.key == "integral_gain") {
    settings.integral_gain = finite_number(k.value(), "integral_gain");
    gains_given = true;
  } else if (k.key == "integral_band") {
    settings.integral_band = number_in(k.value(), "integral_band", 0.0, 1.0, false,
                                       " (a fraction of the stress level)");
  } else if (k.key == "max_rate") {
    settings.max_strain_rate = finite_number(k.value(), "max_rate");
    if (!(settings.max_strain_rate > 0.0))
      error->all(FLERR, "fix cell/servo: max_rate must be positive, got {}",
                 settings.max_strain_rate);
    max_rate_given = true;    // its range needs the timestep: check_rates_resolvable()
  } else if (k.key == "max_inertial") {
    inertial_cap = number_in(k.value(), "max_inertial", 0.0, 1.0, true,
                             " (above 1 a packing flows like a gas)");
  } else if (k.key == "cap_warning") {
    cap_warning = k.yes_no();
  } else {
    return 0;
  }
  return 2;
}

// the record and the test's bounds: csv, extra, until, variables, continue
int FixCellServo::record_keyword(const KeywordArgs &k)
{
  if (k.key == "csv") {
    csv_path = k.value(1);
    csv_every = positive_integer(k.value(2), "csv interval N");
    return 3;
  }
  if (k.key == "extra") return parse_extra(k);
  if (k.key == "until") {
    const std::string name = k.value(1);
    parse_until(name, k.value(2));
    return 3;
  }
  if (k.key == "variables") {
    named_variables = k.yes_no();
    return 2;
  }
  if (k.key == "continue") {
    continue_previous = k.yes_no();
    return 2;
  }
  return 0;
}

// extra N name1 value1 ... : columns of the record from computes, fixes or variables
int FixCellServo::parse_extra(const KeywordArgs &k)
{
  const int n = positive_integer(k.value(1), "extra column count N");
  if (k.iarg + 2 + 2 * n > k.narg)
    error->all(FLERR, "fix cell/servo: extra {} needs {} name-value pairs", n, n);
  for (int j = 0; j < n; ++j) {
    const std::string name = k.arg[k.iarg + 2 + 2 * j], ref = k.arg[k.iarg + 3 + 2 * j];
    check_extra_name(name, ref, extra_requests);
    if (!utils::strmatch(ref, "^[cfv]_"))
      error->all(FLERR, "fix cell/servo {}: extra column {}: '{}' is not a c_ID, c_ID[i], "
                 "f_ID, f_ID[i] or v_name reference", id, name, ref);
    extra_requests.emplace_back(name, ref);
  }
  return 2 + 2 * n;
}

// until NAME VALUE: an output of the programme, reached from either side
void FixCellServo::parse_until(const std::string &name, const char *target)
{
  until_value = finite_number(target, "until value");
  until_output = -1;
  for (int k : {EPS1, EPS2, EPS3, EPS_V, EPS_Q, EPS_D13, SIG1, SIG2, SIG3, P, Q, B, LODE_DEG,
                ETA_LD, SINPHI, VOID_RATIO, SOLID_FRACTION, PI_X, PI_Y, PI_EX, PI_EY, TIME,
                BOUNDARY_WORK, SIG_XY, SIG_XZ, SIG_YZ, GAMMA_XY, GAMMA_XZ, GAMMA_YZ, GAMMA,
                TAU, SIG_N, TAU_RATIO, R_U, CYCLES})
    if (name == output_name(k)) until_output = k;
  if (until_output < 0)
    error->all(FLERR, "fix cell/servo: until: '{}' is not a strain, stress, void ratio, "
               "time, boundary_work, shear or cycle output of the fix (names: "
               "docs/fix_cell_servo.md)", name);
  if ((until_output == GAMMA || until_output == TAU || until_output == SIG_N
       || until_output == TAU_RATIO) && !has_plane)
    error->all(FLERR, "fix cell/servo: until {}: this programme has no shear plane (use "
               "gamma_xy, gamma_xz or gamma_yz, or a shear mode)", name);
  if ((until_output == R_U || until_output == CYCLES)
      && !(mode == Mode::SHEAR_CV || mode == Mode::CYCLIC_SHEAR))
    error->all(FLERR, "fix cell/servo: until {}: only the constant-volume shear modes "
               "report it", name);
}

// equilibrium, eq_stress, eq_unbalanced, eq_kinetic, eq_coordination, eq_window
int FixCellServo::equilibrium_keyword(const KeywordArgs &k)
{
  // the tolerances are fractions (of p*, of the mean contact force, of p* V, of a contact per
  // particle)
  auto fraction = [&]() { return number_in(k.value(), k.key, 0.0, 1.0, true); };
  if (k.key == "equilibrium")
    equilibrium_every = positive_integer(k.value(), "equilibrium interval N");
  else if (k.key == "eq_stress")
    criteria.stress_tolerance = fraction();
  else if (k.key == "eq_unbalanced")
    criteria.max_unbalanced_force_ratio = fraction();
  else if (k.key == "eq_kinetic")
    criteria.max_kinetic_energy_ratio = fraction();
  else if (k.key == "eq_coordination")
    criteria.coordination_tolerance = fraction();
  else if (k.key == "eq_window")
    criteria.window = positive_integer(k.value(), "eq_window");
  else
    return 0;
  return 2;
}

// the options of the six-component modes: ru_limit, da_limit (cyclic_shear), angle (rotation)
int FixCellServo::cell_mode_keyword(const KeywordArgs &k)
{
  if (k.key == "ru_limit" || k.key == "da_limit") {
    if (mode != Mode::CYCLIC_SHEAR)
      error->all(FLERR, "fix cell/servo: keyword '{}' applies only to cyclic_shear", k.key);
    if (k.key == "ru_limit")
      liquefaction.pore_pressure_ratio = number_in(k.value(), k.key, 0.0, 1.0, true);
    else
      liquefaction.double_amplitude_strain = number_in(k.value(), k.key, 0.0, 1.0, true,
                                                       " (a double-amplitude shear strain)");
  } else if (k.key == "angle") {
    if (mode != Mode::ROTATION)
      error->all(FLERR, "fix cell/servo: keyword 'angle' applies only to rotation");
    stress_rotation.initial_angle_deg = number_in(k.value(), k.key, -360.0, 360.0, false,
                                                  " degrees");
  } else {
    return 0;
  }
  return 2;
}

// the Pi-plane path of circle, triangle and polygon, from the mode's arguments and the keywords
void FixCellServo::build_path(const PathOptions &options)
{
  if (path_kind.empty()) return;
  try {
    if (path_kind == "circle")
      path = tycore::constant_deviatoric_strain_path(prestrain, options.measure,
                                                    options.rotation, options.with_prestrain,
                                                    options.sweep);
    else if (path_kind == "triangle")
      path = tycore::multiaxial_plane_strain_path(prestrain, options.measure, options.rotation,
                                                  options.with_prestrain);
    else
      path = tycore::PiPath::polygon(polygon_vertices, close_polygon);
  } catch (std::exception &e) {
    error->all(FLERR, "fix cell/servo {}: {}", path_kind, e.what());
  }
}

// keywords that need a mode or another keyword
void FixCellServo::check_keyword_combinations()
{
  if (mode == Mode::PATH && !(path_speed > 0.0))
    error->all(FLERR, "fix cell/servo: a Pi-plane path needs 'speed V' (|de/dt|, 1/s)");
  if (mode != Mode::PATH && path_speed > 0.0)
    error->all(FLERR, "fix cell/servo: keyword 'speed' applies only to circle, triangle and "
               "polygon paths");
  if (!extra_requests.empty() && csv_path.empty())
    error->all(FLERR, "fix cell/servo {}: 'extra' adds columns to the record, but this fix "
               "writes none: add 'csv FILE N'", id);
  if (equilibrium_every > 0 && mode != Mode::ISO)
    error->all(FLERR, "fix cell/servo: the equilibrium check applies to the iso mode only");
}

/* ---------------------------------------------------------------------- */

/* ---------------------------------------------------------------------- */

void FixCellServo::init()
{
  if (update->whichflag == 2)
    error->all(FLERR, "fix cell/servo cannot be used with minimize: it deforms the cell by "
               "strain rates in time and holds stresses by a servo, neither of which a "
               "minimizer steps through (use fix box/relax to minimize with a stress-controlled "
               "box, and unfix the cell/servo first)");
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "fix cell/servo does not support run_style respa");
  for (int i = 0; i < modify->nfix; ++i)
    if (modify->fix[i] != this && modify->fix[i]->box_change)
      error->all(FLERR, "fix cell/servo cannot be combined with fix {} ({}), which also "
                 "changes the box", modify->fix[i]->id, modify->fix[i]->style);

  // the contact tallies: exact from pair thornton/yin, else estimated (docs/theory.md §6.5)
  pair = dynamic_cast<CellTallySource *>(force->pair_match("thornton/yin", 1));
  if (!pair) {
    const int itally = modify->find_compute(tally_id);
    if (itally < 0) error->all(FLERR, "fix cell/servo: its contact tally compute was deleted");
    pair = dynamic_cast<CellTallySource *>(modify->compute[itally]);
  }
  // from the setup force computation on, the stiffness entries the servo uses (at least)
  tallied_entries = pair->request_cell_tallies(stiffness_entries());
  if (needs_triclinic() && !domain->triclinic)
    error->all(FLERR, "fix cell/servo: the box was made orthogonal, but this programme moves "
               "or holds a shear component, which needs a triclinic box");

  const int icompute = modify->find_compute(pressure_id);
  if (icompute < 0) error->all(FLERR, "fix cell/servo: its stress compute was deleted");
  pressure = modify->compute[icompute];

  for (AxisInput *in : {&axis_input[0], &axis_input[1], &axis_input[2], &axis_input[3],
                        &axis_input[4], &axis_input[5], &major_input}) {
    AxisInput &a = *in;
    if (a.variable.empty()) continue;
    a.ivar = input->variable->find(a.variable.c_str());
    if (a.ivar < 0)
      error->all(FLERR, "fix cell/servo: variable {} does not exist", a.variable);
    if (!input->variable->equalstyle(a.ivar))
      error->all(FLERR, "fix cell/servo: variable {} is not equal-style", a.variable);
  }

  // particle statistics: number-mean diameter and density, solid volume
  double local[4] = {0.0, 0.0, 0.0, 0.0}, total[4];
  for (int i = 0; i < atom->nlocal; ++i) {
    const double r = atom->radius[i];
    const double volume = 4.0 / 3.0 * MathConst::MY_PI * r * r * r;
    local[0] += 1.0;
    local[1] += 2.0 * r;
    local[2] += volume > 0.0 ? atom->rmass[i] / volume : 0.0;
    local[3] += volume;
  }
  MPI_Allreduce(local, total, 4, MPI_DOUBLE, MPI_SUM, world);
  if (total[0] == 0.0) error->all(FLERR, "fix cell/servo: the cell holds no particles");
  mean_diameter = total[1] / total[0];
  mean_density = total[2] / total[0];
  solid_volume = total[3];

  resolve_extra_columns();
  saturated_steps = 0;
  saturation_warned = false;
}

// the default cap and the check of the servo settings need the stress-held targets, which may
// be variables that read this fix's own outputs: they are evaluated only after the first
// measurement (in setup), not in init where no stress has been tallied yet
void FixCellServo::choose_rate_cap()
{
  if (!major_input.variable.empty()) major_strain_rate();
  if (settings.max_strain_rate == 0.0) {
    settings.max_strain_rate = default_max_rate();
    if (target_p == 0.0) {
      // a programme that holds no mean stress (axes, shear): take the level of the held
      // stresses, not 1 Pa, whose inertial-number rate would all but freeze the servo
      const double level = stress_level();
      if (level > 0.0)
        settings.max_strain_rate =
            tycore::quasi_static_strain_rate(inertial_cap, level, mean_diameter, mean_density);
    }
  }
  try {
    tycore::require_valid(settings);
  } catch (std::exception &e) {
    error->all(FLERR, "fix cell/servo: {}", e.what());
  }
  // the free axes must be able to follow the prescribed ones (isochoric axisymmetric
  // compression needs half the axial rate on each lateral axis, plus dilatancy)
  if (prescribed_rate() > 0.0 && settings.max_strain_rate < prescribed_rate() && comm->me == 0)
    error->warning(FLERR, "fix cell/servo: max_rate {:.3g} is below the prescribed strain rate "
                   "{:.3g}; the servo cannot keep up and the stress will drift (raise max_rate)",
                   settings.max_strain_rate, prescribed_rate());
}

// the held stresses and their targets, for messages (variables named, not evaluated)
std::string FixCellServo::held_targets() const
{
  if (mode == Mode::SHEAR)
    return fmt::format("sig_n = {:.4g}, target {:.4g}", output[SIG_N], normal_target);
  if (mode == Mode::UNDRAINED)
    return fmt::format("sig2 - sig3 = {:.4g}, target 0", stress((major_axis + 1) % 3)
                       - stress((major_axis + 2) % 3));
  if (mode != Mode::AXES) return fmt::format("p = {:.4g}, target {:.4g}", output[P], target_p);
  std::string text;
  for (int k = 0; k < 6; ++k)
    if (axis_input[k].control == tycore::AxisControl::STRESS)
      text += fmt::format("{}sig_{} = {:.4g}, target {}", text.empty() ? "" : "; ",
                          tycore::voigt_names[k], stress(k), axis_input[k].variable.empty()
                              ? fmt::format("{:.4g}", axis_input[k].value)
                              : "v_" + axis_input[k].variable);
  return text;
}

// largest prescribed principal strain rate (or path speed) of the programme [1/s]
double FixCellServo::prescribed_rate() const
{
  double rate = std::max({std::fabs(major_input.variable.empty() ? major_rate : major_rate_now),
                          path_speed, std::fabs(shear_rate)});
  for (const auto &a : axis_input)
    if (a.control == tycore::AxisControl::STRAIN_RATE && a.variable.empty())
      rate = std::max(rate, std::fabs(a.value));
  return rate;
}

// cap of the servo part: the strain rate at inertial number max_inertial (docs/theory.md §4.2),
// and at least four times the prescribed rate (the minor axis of a constant-b path extends at
// about the major rate, plus dilatancy)
double FixCellServo::default_max_rate() const
{
  return std::max(tycore::quasi_static_strain_rate(inertial_cap,
                                                   target_p > 0.0 ? target_p : 1.0,
                                                   mean_diameter, mean_density),
                  4.0 * prescribed_rate());
}

void FixCellServo::setup(int)
{
  // the rate of the last step carries on across runs and restarts
  set_box_rate(memory.last_strain_rate, cell_matrix());
  advance_clock();
  measure();
  // sigma_n0 of r_u and of the cyclic amplitude: the normal stress when the test began
  if (has_plane && std::isnan(initial_normal_stress)) initial_normal_stress = stress(plane.normal);
  if (mode == Mode::CYCLIC_SHEAR) {
    try {
      cyclic_programme().require_valid();
    } catch (std::exception &e) {
      error->all(FLERR, "fix cell/servo: {} (sigma_n0 = {:.4g} when the test began)", e.what(),
                 initial_normal_stress);
    }
  }
  compute_outputs();
  compute_particle_outputs();
  choose_rate_cap();
  check_rates_resolvable();
  warn_inertial_number();
  progress_at_setup = output[PROGRESS];
  until_run_start = until_output >= 0 ? output[until_output] : NaN;
  until_direction_checked = false;
  if (mode == Mode::PATH && path_speed > tycore::max_followable_speed(path, update->dt))
    error->all(FLERR, "fix cell/servo: at speed {:.4g} the shortest leg of the Pi-plane path "
               "(length {:.4g}) takes {:.3g} steps, and the cell cannot follow a leg in fewer "
               "than {}: use speed <= {:.4g} (or a smaller timestep)", path_speed,
               path.shortest_leg(), path.shortest_leg() / (path_speed * update->dt),
               tycore::MIN_STEPS_PER_LEG, tycore::max_followable_speed(path, update->dt));
  wall_start = MPI_Wtime();
  step_start = update->ntimestep;

  open_csv();
  // the state at the start of the run, unless the record holds this step already (a
  // continued test, or a run resumed at the step of its restart file)
  int first_row = csv_every > 0 && update->ntimestep % csv_every == 0 &&
      (comm->me != 0 || csv.last_step() < update->ntimestep);
  MPI_Bcast(&first_row, 1, MPI_INT, 0, world);    // (extra columns evaluate on every rank)
  if (first_row) write_csv_row();
}

// a new test starts its record; a test continued from a restart file or from the fix this
// one redefines appends to it (tycore::CsvRecord: superseded rows of a crashed run dropped)
void FixCellServo::open_csv()
{
  if (csv_path.empty() || comm->me != 0 || csv.is_open()) return;
  refuse_record_aliases();
  try {
    if (restored || (continued && tycore::file_identity(csv_path) == continued_csv))
      csv.resume(csv_path, csv_header(), update->ntimestep);
    else
      csv.start(csv_path, csv_header());
  } catch (std::exception &e) {
    error->one(FLERR, "fix cell/servo: {}", e.what());
  }
  if (csv.dropped_rows() > 0)
    utils::logmesg(lmp, "fix cell/servo: {} continues at step {}: dropped {} row(s) written "
                   "after that step by an earlier run\n", csv_path, update->ntimestep,
                   csv.dropped_rows());
}

// simulated time since the test started, at the current timestep size of each step
void FixCellServo::advance_clock()
{
  if (update->ntimestep > clock_step)
    elapsed_time += double(update->ntimestep - clock_step) * update->dt;
  clock_step = update->ntimestep;
}

/* ---------------------------------------------------------------------- */

void FixCellServo::end_of_step()
{
  advance_clock();
  measure();
  compute_outputs();
  check_until_direction();
  write_record_rows();
  after_step();
  const tycore::CellMeasurementOf<6> cell = cell_measurement();
  const tycore::ServoCommandOf<6> command = next_command(cell);
  check_equilibrium(cell);
  watch_rate_cap(command);
  require_followable(command);
  add_boundary_work(command);
  // the cell deforms at the next step's post_integrate, before its forces: the positions
  // written at the end of a step are those its forces were computed at, so a restart (or a
  // new run) recomputes the same forces in setup and continues the trajectory exactly
}

// the record's row of this step, and the end of the test once 'until' is met
void FixCellServo::write_record_rows()
{
  if (csv_every > 0 && update->ntimestep % csv_every == 0) {
    compute_particle_outputs();
    write_csv_row();
  }

  if (until_output >= 0 && tycore::reached(until_start, output[until_output], until_value)) {
    // the test is over: the last row, and the run stops after this step (as fix halt does)
    if (csv_every > 0 && update->ntimestep % csv_every != 0) {
      compute_particle_outputs();
      write_csv_row();
    }
    if (!until_met) {
      if (comm->me == 0)
        utils::logmesg(lmp, "fix cell/servo: {} = {:.6g} reached the target {:.6g} at step {}: "
                       "the run stops\n", output_name(until_output), output[until_output],
                       until_value, update->ntimestep);
      timer->force_timeout();
      until_met = 1;
    }
  }
}

// the strain rates of the next step
tycore::ServoCommandOf<6> FixCellServo::next_command(const tycore::CellMeasurementOf<6> &cell)
{
  tycore::ServoCommandOf<6> command;
  try {
    command = servo_command(cell);
  } catch (std::exception &e) {
    error->all(FLERR, "fix cell/servo: {}", e.what());
  }
  return command;
}

// the quasi-equilibrium check of a preparation ('equilibrium N'), every N steps
void FixCellServo::check_equilibrium(const tycore::CellMeasurementOf<6> &cell)
{
  if (!(equilibrium_every > 0 && update->ntimestep % equilibrium_every == 0)) return;
  compute_particle_outputs();
  tycore::EquilibriumSample sample;
  sample.stress = cell.stress.head<3>();
  sample.target_stress = Eigen::Vector3d::Constant(target_p);
  sample.unbalanced_force_ratio = output[UNBALANCED];
  sample.kinetic_energy_ratio = output[KINETIC_RATIO];
  sample.coordination = output[Z];
  const tycore::EquilibriumCheck check = tycore::update_equilibrium(equilibrium, sample, criteria);
  equilibrium_reached = check.reached;
  output[EQUILIBRIUM] = equilibrium_reached;
  output[EQ_STRESS_OK] = check.stress_ok;
  output[EQ_UNBALANCED_OK] = check.force_ok;
  output[EQ_KINETIC_OK] = check.energy_ok;
  output[EQ_COORDINATION_OK] = check.coordination_ok;
}

// a servo at its cap whose stress error has grown since it reached the cap has lost control
// of the stress: say what to change, once per run. At the cap while the error shrinks (an
// approach to a far target at the cap's pace) the cap only sets the pace, and is no fault;
// `cap_warning no` silences the warning where a deck compresses at the cap on purpose.
void FixCellServo::watch_rate_cap(const tycore::ServoCommandOf<6> &command)
{
  if (!command.saturated) {
    saturated_steps = 0;
  } else if (++saturated_steps == 1) {
    saturated_error = command.stress_error;
  } else if (saturated_steps % SATURATION_WARN_STEPS == 0 && cap_warning && !saturation_warned
             && contacts > 0.0 && command.stress_error > saturated_error) {
    saturation_warned = true;
    if (comm->me == 0)
      error->warning(FLERR, "fix cell/servo: the servo has been at its strain-rate cap "
                     "max_rate = {:.3g} for {} steps and its stress error grew from {:.4g} to "
                     "{:.4g} ({}; prescribed rate {:.4g} 1/s); raise max_rate or lower the "
                     "prescribed rate (said once per run)", settings.max_strain_rate,
                     saturated_steps, saturated_error, command.stress_error, held_targets(),
                     prescribed_rate());
  }
}

// the cell follows at most MAX_STRAIN_PER_STEP in one step
void FixCellServo::require_followable(const tycore::ServoCommandOf<6> &command)
{
  const double fastest = command.strain_rate.cwiseAbs().maxCoeff();
  if (fastest * update->dt > tycore::MAX_STRAIN_PER_STEP)
    error->all(FLERR, "fix cell/servo: at step {} the strain rate {:.4g} 1/s strains the cell by "
               "{:.3g} in one step; the cell cannot follow more than {} per step: use rates "
               "<= {:.4g} 1/s (or a smaller timestep)", update->ntimestep,
               fastest, fastest * update->dt, tycore::MAX_STRAIN_PER_STEP,
               tycore::MAX_STRAIN_PER_STEP / update->dt);
}

// boundary work V sigma : deps over this step (contact stress; docs/theory.md §5.3; Voigt6
// with engineering shears, so that sigma : deps = sum_I sigma_I deps_I)
void FixCellServo::add_boundary_work(const tycore::ServoCommandOf<6> &command)
{
  const double volume = cell_volume();
  const int components = domain->triclinic ? 6 : 3;
  for (int k = 0; k < components; ++k)
    boundary_work += volume * stress(k) * command.strain_rate(k) * update->dt;
}

void FixCellServo::write_csv_row()
{
  // the extra columns first, on every rank (computes and variables are collective)
  std::vector<double> extra;
  if (!extra_columns.empty()) {
    modify->clearstep_compute();
    for (const auto &e : extra_columns) extra.push_back(input->variable->compute_equal(e.second));
    modify->addstep_compute(update->ntimestep + 1);
  }
  if (comm->me != 0 || !csv.is_open()) return;
  std::vector<double> row;
  for (int k : csv_columns()) row.push_back(output[k]);
  row.insert(row.end(), extra.begin(), extra.end());
  try {
    csv.write_row(update->ntimestep, row);
  } catch (std::exception &e) {
    error->one(FLERR, "fix cell/servo: {}", e.what());
  }
}

/* ----------------------------------------------------------------------
   restart: reference cell, servo memory (integral, last rate, path progress),
   equilibrium state, boundary work
------------------------------------------------------------------------- */

// [tag, version, size, mode, programme path (n, ...), cumulative strain (reference edges 3,
//  shears 3), servo memory (6 components), equilibrium state, equilibrium reached, boundary
//  work, elapsed time, clock step, until start, sigma_n0, cyclic state, followed path (n, ...)]
std::vector<double> FixCellServo::restart_record() const
{
  std::vector<double> list{RESTART_TAG, RESTART_VERSION, 0.0, double(static_cast<int>(mode))};
  list.push_back(double(programme_path.size()));
  list.insert(list.end(), programme_path.begin(), programme_path.end());
  double c[tycore::CumulativeStrain::size];
  strain.to_array(c);
  list.insert(list.end(), c, c + tycore::CumulativeStrain::size);
  double m[tycore::ServoMemoryOf<6>::size];
  memory.to_array(m);
  list.insert(list.end(), m, m + tycore::ServoMemoryOf<6>::size);
  double e[tycore::EquilibriumState::size];
  equilibrium.to_array(e);
  list.insert(list.end(), e, e + tycore::EquilibriumState::size);
  list.push_back(equilibrium_reached);
  list.push_back(boundary_work);
  list.push_back(elapsed_time);
  list.push_back(double(clock_step));
  list.push_back(until_start);
  list.push_back(initial_normal_stress);
  double cy[tycore::CyclicSimpleShear::State::size];
  cyclic.to_array(cy);
  list.insert(list.end(), cy, cy + tycore::CyclicSimpleShear::State::size);
  const std::vector<double> followed = mode == Mode::PATH ? path.to_array() : std::vector<double>{};
  list.push_back(double(followed.size()));
  list.insert(list.end(), followed.begin(), followed.end());
  list[2] = double(list.size());
  return list;
}

void FixCellServo::write_restart(FILE *fp)
{
  const std::vector<double> list = restart_record();
  if (comm->me == 0) {
    const int size = static_cast<int>(list.size() * sizeof(double));
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list.data(), sizeof(double), list.size(), fp);
  }
}

void FixCellServo::restart(char *buf)
{
  // 'continue no' asks for a new test: the state in the restart file is not taken up
  if (!continue_previous) {
    if (comm->me == 0)
      utils::logmesg(lmp, "fix cell/servo {}: continue no: the test whose state the restart "
                     "file holds is not continued; a new test starts (strains, time and "
                     "boundary work from zero)\n", id);
    return;
  }
  const double *list = reinterpret_cast<double *>(buf);
  if (list[0] != RESTART_TAG)
    error->all(FLERR, "fix cell/servo: the restart file's record for fix {} is not a cell/servo "
               "record; define the fix under a new ID", id);
  if (static_cast<int>(list[1]) != RESTART_VERSION)
    error->all(FLERR, "fix cell/servo: the restart record of fix {} has version {}, this build "
               "reads version {}", id, list[1], RESTART_VERSION);
  if (static_cast<int>(list[3]) != static_cast<int>(mode))
    error->all(FLERR, "fix cell/servo: the restart file holds the state of another cell/servo "
               "mode; use the same mode as the run that wrote it, or a new fix ID");
  // the path: the same kind, pre-strain, rotation, sweep or vertices as the run that wrote it
  const std::size_t size = static_cast<std::size_t>(list[2]);
  const std::size_t n_programme = programme_path.size();
  bool same_path = size >= 5 && static_cast<std::size_t>(list[4]) == n_programme &&
      size >= 5 + n_programme;
  for (std::size_t i = 0; same_path && i < n_programme; ++i)
    same_path = list[5 + i] == programme_path[i];
  if (!same_path)
    error->all(FLERR, "fix cell/servo: the restart file was written by a run on another "
               "Pi-plane path (another path kind, pre-strain, rotation, sweep or vertices); "
               "resume it with the same path, or define the fix under a new ID");
  // sizes: the record must be exactly as long as its parts say
  const std::vector<double> own = restart_record();
  const std::size_t fixed = own.size() - 1 - (mode == Mode::PATH ? path.to_array().size() : 0);
  if (size < fixed + 1)
    error->all(FLERR, "fix cell/servo: the restart record of fix {} holds {} numbers, fewer "
               "than the {} of this programme: the file is damaged or was written by another "
               "programme", id, size, fixed + 1);
  if (size != fixed + 1 + static_cast<std::size_t>(list[fixed]))
    error->all(FLERR, "fix cell/servo: the restart record of fix {} says it holds {} numbers, "
               "but its parts hold {}: the file is damaged or was written by another programme",
               id, size, fixed + 1 + static_cast<std::size_t>(list[fixed]));
  int k = 5;
  k += static_cast<int>(n_programme);
  strain = tycore::CumulativeStrain::from_array(list + k);
  k += tycore::CumulativeStrain::size;
  memory = tycore::ServoMemoryOf<6>::from_array(list + k);
  k += tycore::ServoMemoryOf<6>::size;
  equilibrium = tycore::EquilibriumState::from_array(list + k);
  k += tycore::EquilibriumState::size;
  equilibrium_reached = static_cast<int>(list[k++]);
  boundary_work = list[k++];
  elapsed_time = list[k++];
  clock_step = static_cast<bigint>(list[k++]);
  until_start = list[k++];
  initial_normal_stress = list[k++];
  cyclic = tycore::CyclicSimpleShear::State::from_array(list + k);
  k += tycore::CyclicSimpleShear::State::size;
  if (static_cast<int>(list[k++]) > 0) path = tycore::PiPath::from_array(list + k);
  restored = 1;
}
