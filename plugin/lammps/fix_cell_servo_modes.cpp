/* ----------------------------------------------------------------------
   fix cell/servo: the test programmes (docs/fix_cell_servo.md, "Modes"; docs/theory.md §6.3,
   §13). Each mode is a six-component mixed control (plugin/core/cell_control.hpp); the
   principal programmes have idle shears and are stepped as the three-component servo
   (tycore::principal_control), the others need a triclinic box.
------------------------------------------------------------------------- */

#include "fix_cell_servo.h"

#include "comm.h"
#include "domain.h"
#include "error.h"
#include "input.h"
#include "modify.h"
#include "update.h"
#include "variable.h"

#include "tylmp_numeric.h"

#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;

namespace {

int axis_index(const char *name)
{
  if (strcmp(name, "x") == 0) return 0;
  if (strcmp(name, "y") == 0) return 1;
  if (strcmp(name, "z") == 0) return 2;
  return -1;
}

// a component of 'axes': x, y, z (or xx, yy, zz) and the shears xy, xz, yz (Voigt6 index)
int component_index(const char *name)
{
  const int axis = axis_index(name);
  if (axis >= 0) return axis;
  for (int k = 0; k < 6; ++k)
    if (strcmp(name, tycore::voigt_names[k]) == 0) return k;
  return -1;
}

// a plane xy, xz or yz: the edge along the second axis tilts towards the first
bool plane_of(const char *name, tycore::ShearPlane &plane)
{
  for (int k = 3; k < 6; ++k)
    if (strcmp(name, tycore::voigt_names[k]) == 0) {
      plane.direction = tycore::voigt_pairs[k][0];
      plane.normal = tycore::voigt_pairs[k][1];
      return true;
    }
  return false;
}

}    // namespace

// a finite floating-point argument: utils::numeric takes 1e400 (it overflows to inf in strtod)
// and its message does not say which argument was wrong
double FixCellServo::finite_number(const char *text, const std::string &what)
{
  return tylmp::finite_numeric(FLERR, text, "fix cell/servo: " + what, lmp);
}

int FixCellServo::positive_integer(const char *text, const std::string &what)
{
  char *end = nullptr;
  const long value = strtol(text, &end, 10);
  if (end == text || *end != '\0' || value <= 0 || value > std::numeric_limits<int>::max())
    error->all(FLERR, "fix cell/servo: {} must be a positive integer, got '{}'", what, text);
  return static_cast<int>(value);
}

/* ----------------------------------------------------------------------
   MODE args: see the header of docs/fix_cell_servo.md
------------------------------------------------------------------------- */

FixCellServo::AxisInput FixCellServo::parse_value(const char *text, tycore::AxisControl control,
                                                   const std::string &what)
{
  AxisInput in{control, 0.0, "", -1, what};
  if (strncmp(text, "v_", 2) == 0) in.variable = text + 2;
  else in.value = finite_number(text, what);
  return in;
}

// the axial strain rate of axisym and undrained: a number (non-zero) or a variable
void FixCellServo::parse_axial_rate(const std::string &name, const char *text)
{
  major_input = parse_value(text, tycore::AxisControl::STRAIN_RATE, name + " axial strain rate");
  major_rate = major_input.value;
  if (major_input.variable.empty() && major_rate == 0.0)
    error->all(FLERR, "fix cell/servo {}: axial strain rate must be non-zero (> 0 compression, "
               "< 0 extension)", name);
}

void FixCellServo::parse_mode(int narg, char **arg, int &iarg)
{
  const std::string name = arg[iarg++];
  if (name == "axes")
    parse_axes(narg, arg, iarg);
  else if (name == "shear" || name == "shear_cv" || name == "cyclic_shear" || name == "undrained"
           || name == "rotation")
    parse_cell_mode(name, narg, arg, iarg);
  else if (name == "iso" || name == "axisym" || name == "constant_b" || name == "deviatoric"
           || name == "circle" || name == "triangle" || name == "polygon")
    parse_principal_mode(name, narg, arg, iarg);
  else
    error->all(FLERR, "fix cell/servo: unknown mode '{}' (expected iso, axes, axisym, "
               "constant_b, deviatoric, circle, triangle, polygon, shear, shear_cv, "
               "cyclic_shear, undrained or rotation)", name);
}

// the arguments of a mode, read in turn from arg[iarg]; the messages name the mode
class FixCellServo::ModeArgs {
 public:
  ModeArgs(FixCellServo &fix, const std::string &name, int narg, char **arg, int &iarg) :
      name(name), fix(fix), narg(narg), arg(arg), iarg(iarg)
  {
  }
  const std::string &name;

  // n more arguments must follow
  void need(int n) const
  {
    if (iarg + n > narg)
      fix.error->all(FLERR, "Illegal fix cell/servo {} command: expected {} more argument(s)",
                     name, n);
  }
  const char *next() { return arg[iarg++]; }
  // a target stress: compressive
  double stress(const char *what)
  {
    const double value = fix.finite_number(next(), name + " " + what);
    if (!(value > 0.0))
      fix.error->all(FLERR, "fix cell/servo {}: target {} = {} must be positive (a granular "
                     "cell carries no tension)", name, what, value);
    return value;
  }
  // a number in (0, hi]
  double positive(const char *what, double hi)
  {
    return fix.number_in(next(), name + " " + what, 0.0, hi, true);
  }
  // a strain rate that is not zero
  double rate(const char *what)
  {
    const double value = fix.finite_number(next(), name + " " + what);
    if (value == 0.0) fix.error->all(FLERR, "fix cell/servo {}: {} must be non-zero", name, what);
    return value;
  }
  int axis()
  {
    const int axis = axis_index(arg[iarg]);
    if (axis < 0)
      fix.error->all(FLERR, "fix cell/servo {}: axis '{}' is not x, y or z", name, arg[iarg]);
    ++iarg;
    return axis;
  }
  tycore::ShearPlane plane()
  {
    tycore::ShearPlane plane;
    if (!plane_of(arg[iarg], plane))
      fix.error->all(FLERR, "fix cell/servo {}: plane '{}' is not xy, xz or yz (the edge along "
                     "the second axis tilts towards the first; LAMMPS's triclinic box has no "
                     "other shears)", name, arg[iarg]);
    ++iarg;
    return plane;
  }

 private:
  FixCellServo &fix;
  const int narg;
  char **const arg;
  int &iarg;
};

// the programmes of the paper: principal strain rates and Pi-plane paths at a held p
void FixCellServo::parse_principal_mode(const std::string &name, int narg, char **arg,
                                        int &iarg)
{
  ModeArgs a(*this, name, narg, arg, iarg);
  if (name == "iso") {
    mode = Mode::ISO;
    a.need(1);
    target_p = a.stress("mean stress p");
  } else if (name == "axisym") {
    mode = Mode::AXISYM;
    a.need(3);
    major_axis = a.axis();
    parse_axial_rate(name, a.next());
    target_p = a.stress("mean stress p");
  } else if (name == "constant_b") {
    parse_constant_b(a);
  } else if (name == "deviatoric") {
    mode = Mode::DEVIATORIC;
    a.need(4);
    for (int k = 0; k < 3; ++k)
      axis_input[k] = parse_value(a.next(), tycore::AxisControl::STRAIN_RATE,
                                  fmt::format("deviatoric strain rate R{}", k + 1));
    target_p = a.stress("mean stress p");
  } else if (name == "circle" || name == "triangle") {
    mode = Mode::PATH;
    a.need(2);
    prestrain = number_in(a.next(), name + " pre-strain", 0.0, 1.0, true, " (a natural strain)");
    target_p = a.stress("mean stress p");
    path_kind = name;    // built in parse_keywords(), after its options
  } else if (name == "polygon") {
    parse_polygon(a);
  }
}

// constant_b B AXIS RATE P: the major axis compressed at RATE, p and b held
void FixCellServo::parse_constant_b(ModeArgs &a)
{
  mode = Mode::CONSTANT_B;
  a.need(4);
  b_target = finite_number(a.next(), "constant_b b");
  if (!(b_target >= 0.0 && b_target <= 1.0))
    error->all(FLERR, "fix cell/servo constant_b: b = {} is outside [0, 1]", b_target);
  major_axis = a.axis();
  major_input = parse_value(a.next(), tycore::AxisControl::STRAIN_RATE,
                            "constant_b major-axis strain rate");
  major_rate = major_input.value;
  if (major_input.variable.empty() && !(major_rate > 0.0))
    error->all(FLERR, "fix cell/servo constant_b: the major-axis strain rate must be positive "
               "(compression of the major axis)");
  target_p = a.stress("mean stress p");
}

// polygon N x1 y1 ... xN yN P: the vertices on the strain Pi-plane (the path is built in
// parse_keywords(), after its options)
void FixCellServo::parse_polygon(ModeArgs &a)
{
  mode = Mode::PATH;
  a.need(1);
  const int n = positive_integer(a.next(), "polygon vertex count N");
  if (n < 2) error->all(FLERR, "fix cell/servo polygon: needs at least 2 vertices, got {}", n);
  a.need(2 * n + 1);
  polygon_vertices.clear();
  for (int k = 0; k < n; ++k) {
    const char *x = a.next(), *y = a.next();
    polygon_vertices.emplace_back(
        number_in(x, fmt::format("polygon vertex {} x", k + 1), -1.0, 1.0, false,
                  " (a natural strain)"),
        number_in(y, fmt::format("polygon vertex {} y", k + 1), -1.0, 1.0, false,
                  " (a natural strain)"));
  }
  target_p = a.stress("mean stress p");
  path_kind = a.name;
}

// axes C1 stress|rate V1 ...: each of the six components at a target stress or a strain rate;
// the normal axes must all be given, a shear not given is held at zero rate
void FixCellServo::parse_axes(int narg, char **arg, int &iarg)
{
  mode = Mode::AXES;
  bool given[6] = {false, false, false, false, false, false};
  while (iarg < narg && component_index(arg[iarg]) >= 0) {
    const int k = component_index(arg[iarg]);
    if (given[k])
      error->all(FLERR, "fix cell/servo axes: component {} ({}) is given twice", arg[iarg],
                 tycore::voigt_names[k]);
    if (iarg + 3 > narg)
      error->all(FLERR, "fix cell/servo axes: component {} needs 'stress VALUE' or 'rate VALUE'",
                 arg[iarg]);
    const std::string kind = arg[iarg + 1];
    tycore::AxisControl control;
    if (kind == "stress") control = tycore::AxisControl::STRESS;
    else if (kind == "rate") control = tycore::AxisControl::STRAIN_RATE;
    else
      error->all(FLERR, "fix cell/servo axes: control '{}' of component {} is neither 'stress' "
                 "nor 'rate'", kind, arg[iarg]);
    axis_input[k] = parse_value(arg[iarg + 2], control,
                                fmt::format("axes {} {}", arg[iarg], kind));
    axis_input[k].positive = k < 3;    // a normal stress is compressive, a shear any sign
    if (control == tycore::AxisControl::STRESS && k < 3 && axis_input[k].variable.empty() &&
        !(axis_input[k].value > 0.0))
      error->all(FLERR, "fix cell/servo axes: target stress of axis {} = {} must be positive",
                 arg[iarg], axis_input[k].value);
    given[k] = true;
    iarg += 3;
  }
  if (iarg < narg && (strcmp(arg[iarg], "yx") == 0 || strcmp(arg[iarg], "zx") == 0
                      || strcmp(arg[iarg], "zy") == 0))
    error->all(FLERR, "fix cell/servo axes: component {}: LAMMPS's triclinic box cannot deform "
               "it (its tilts are xy, xz and yz: the edge along the second axis tilts towards "
               "the first); use {}{}", arg[iarg], arg[iarg][1], arg[iarg][0]);
  for (int k = 0; k < 3; ++k)
    if (!given[k])
      error->all(FLERR, "fix cell/servo axes: axis {} has no control: give it 'stress VALUE' "
                 "or 'rate VALUE'", tycore::axis_name(k));
}

// the tests of the six-component cell (docs/theory.md §13):
//   shear PLANE GAMMA_DOT SIGMA_N      drained simple shear at constant normal stress
//   shear_cv PLANE GAMMA_DOT           constant-volume simple shear
//   cyclic_shear PLANE GAMMA_DOT CSR   cyclic constant-volume simple shear, tau_cyc = CSR sigma_n0
//   undrained AXIS RATE                undrained (constant-volume) triaxial test, sigma2 = sigma3
//   rotation PLANE P Q B RATE_DEG      principal stress rotation at constant p, q, b
void FixCellServo::parse_cell_mode(const std::string &name, int narg, char **arg, int &iarg)
{
  ModeArgs a(*this, name, narg, arg, iarg);
  auto plane_arg = [&]() {
    plane = a.plane();
    has_plane = true;
  };
  constexpr double MAX_STRESS = 1e15;    // Pa: beyond any granular material
  if (name == "shear") {
    mode = Mode::SHEAR;
    a.need(3);
    plane_arg();
    shear_rate = a.rate("shear rate gamma_dot");
    normal_target = a.positive("normal stress sigma_n", MAX_STRESS);
  } else if (name == "shear_cv") {
    mode = Mode::SHEAR_CV;
    a.need(2);
    plane_arg();
    shear_rate = a.rate("shear rate gamma_dot");
  } else if (name == "cyclic_shear") {
    mode = Mode::CYCLIC_SHEAR;
    a.need(3);
    plane_arg();
    shear_rate = a.positive("shear rate gamma_dot", 1.0 / update->dt);
    cyclic_stress_ratio = a.positive("CSR", 10.0);
  } else if (name == "undrained") {
    mode = Mode::UNDRAINED;
    a.need(2);
    major_axis = a.axis();
    parse_axial_rate(name, a.next());
  } else {    // rotation
    mode = Mode::ROTATION;
    a.need(5);
    plane_arg();
    stress_rotation.i = plane.direction, stress_rotation.j = plane.normal;
    stress_rotation.mean_stress = a.positive("mean stress p", MAX_STRESS);
    stress_rotation.deviatoric_stress = number_in(a.next(), "rotation deviatoric stress q", 0.0,
                                           MAX_STRESS, false);
    stress_rotation.b = number_in(a.next(), "rotation b", 0.0, 1.0, false);
    stress_rotation.rotation_rate_deg = finite_number(a.next(), "rotation rate (degree/s)");
    target_p = stress_rotation.mean_stress;
    // sigma_3 = p - (1 + b) q/3 must stay compressive
    if (!(stress_rotation.mean_stress - (1.0 + stress_rotation.b) * stress_rotation.deviatoric_stress / 3.0 > 0.0))
      error->all(FLERR, "fix cell/servo rotation: q = {:g} at p = {:g} and b = {:g} puts the "
                 "minor principal stress p - (1 + b) q/3 in tension (a granular cell carries "
                 "none): use q < {:g}", stress_rotation.deviatoric_stress, stress_rotation.mean_stress,
                 stress_rotation.b, 3.0 * stress_rotation.mean_stress / (1.0 + stress_rotation.b));
  }
}

// the programme moves or holds a shear component, which only a triclinic box can
bool FixCellServo::needs_triclinic() const
{
  if (mode == Mode::SHEAR || mode == Mode::SHEAR_CV || mode == Mode::CYCLIC_SHEAR
      || mode == Mode::ROTATION)
    return true;
  if (mode != Mode::AXES) return false;
  for (int k = 3; k < 6; ++k)
    if (axis_input[k].control == tycore::AxisControl::STRESS || !axis_input[k].variable.empty()
        || axis_input[k].value != 0.0)
      return true;
  return false;
}

bool FixCellServo::holds_shear_stress() const
{
  if (mode == Mode::ROTATION) return true;
  if (mode != Mode::AXES) return false;
  for (int k = 3; k < 6; ++k)
    if (axis_input[k].control == tycore::AxisControl::STRESS) return true;
  return false;
}

// A held shear stress answers an affine step of the cell with the affine stiffness at once,
// then relaxes to about a quarter of it over tens of steps as the grains rearrange (measured
// on the 500-sphere dense glass specimen: 0.28), and the specimen's undamped shear modes ring
// meanwhile: at the default gain 0.25 the servo on a shear stress overshoots and rings at its
// cap. Programmes that hold a shear stress default to SHEAR_GAIN, and a larger gain given is
// warned about (docs/fix_cell_servo.md, "The six-component cell").
void FixCellServo::choose_shear_gains()
{
  if (!holds_shear_stress()) return;
  if (!gains_given) {
    settings.gain = SHEAR_GAIN;
    settings.integral_gain = SHEAR_INTEGRAL_GAIN;
  } else if (settings.gain > MAX_SHEAR_GAIN && comm->me == 0) {
    error->warning(FLERR, "fix cell/servo {}: gain {:g} on a held shear stress overshoots and "
                   "rings (the packing's shear response relaxes to a fraction of the affine "
                   "estimate over tens of steps): use gain <= {:g} (default {:g} when a shear "
                   "stress is held)", id, settings.gain, MAX_SHEAR_GAIN, SHEAR_GAIN);
  }
}

// controllability depends on which components hold a stress, not on the values; equal-style
// variables are looked up only in init(), so they are not evaluated here
void FixCellServo::require_controllable()
{
  try {
    if (mode == Mode::AXES) {
      std::array<tycore::AxisProgramme, 6> c;
      for (int k = 0; k < 6; ++k)
        c[k] = {axis_input[k].control, axis_input[k].variable.empty() ? axis_input[k].value : 1.0};
      tycore::require_controllable(tycore::per_axis_control<6>(c));
    } else if (mode == Mode::ISO) {
      tycore::require_controllable(tycore::isotropic_compression_control(target_p));
    }    // the other modes always are
  } catch (std::exception &e) {
    error->all(FLERR, "fix cell/servo: {}", e.what());
  }
}

double FixCellServo::evaluate(AxisInput &in)
{
  if (in.variable.empty()) return in.value;
  modify->clearstep_compute();
  const double value = input->variable->compute_equal(in.ivar);
  modify->addstep_compute(update->ntimestep + 1);
  if (!std::isfinite(value))
    error->all(FLERR, "fix cell/servo: variable {} ({}) evaluated to {} at step {}: not a "
               "finite number", in.variable, in.what, value, update->ntimestep);
  if (in.control == tycore::AxisControl::STRESS && in.positive && !(value > 0.0))
    error->all(FLERR, "fix cell/servo: variable {} ({}) evaluated to {} at step {}: a target "
               "stress must be positive", in.variable, in.what, value, update->ntimestep);
  return value;
}

// the major-axis rate of axisym and constant_b: a number, or a variable evaluated every step
double FixCellServo::major_strain_rate()
{
  if (major_input.variable.empty()) return major_rate;
  const double rate = evaluate(major_input);
  if (mode == Mode::CONSTANT_B && rate < 0.0)
    error->all(FLERR, "fix cell/servo: variable {} ({}) evaluated to {} at step {}: the major "
               "axis of a constant-b path is compressed (rate >= 0)", major_input.variable,
               major_input.what, rate, update->ntimestep);
  major_rate_now = rate;
  return rate;
}

tycore::CyclicSimpleShear FixCellServo::cyclic_programme() const
{
  return {plane, shear_rate, cyclic_stress_ratio, initial_normal_stress, liquefaction};
}

// the control of this step, in six components
tycore::MixedControl6 FixCellServo::current_control()
{
  using tycore::six_component_control;
  switch (mode) {
    case Mode::ISO: return six_component_control(tycore::isotropic_compression_control(target_p));
    case Mode::AXISYM:
      return six_component_control(
          tycore::axisymmetric_control(major_axis, major_strain_rate(), target_p));
    case Mode::CONSTANT_B:
      return six_component_control(
          tycore::constant_b_control(target_p, b_target, major_strain_rate(), major_axis,
                                     (major_axis + 1) % 3, (major_axis + 2) % 3));
    case Mode::DEVIATORIC: {
      Eigen::Vector3d rate;
      for (int k = 0; k < 3; ++k) rate(k) = evaluate(axis_input[k]);
      return six_component_control(tycore::mean_stress_control(target_p, rate));
    }
    case Mode::AXES: {
      std::array<tycore::AxisProgramme, 6> c;
      for (int k = 0; k < 6; ++k) c[k] = {axis_input[k].control, evaluate(axis_input[k])};
      return tycore::per_axis_control<6>(c);
    }
    case Mode::SHEAR: return tycore::DrainedSimpleShear{plane, shear_rate, normal_target}.control();
    case Mode::SHEAR_CV: return tycore::ConstantVolumeSimpleShear{plane, shear_rate}.control();
    case Mode::CYCLIC_SHEAR: return cyclic_programme().control(cyclic);
    case Mode::UNDRAINED: return tycore::UndrainedTriaxial{major_axis, major_strain_rate()}.control();
    case Mode::ROTATION: return stress_rotation.control(elapsed_time);
    case Mode::PATH: break;
  }
  return {};
}

// the strain rates of the next step: a Pi-plane path or a principal programme by the
// three-component servo, the others by the six-component one (docs/theory.md §11.2)
tycore::ServoCommandOf<6> FixCellServo::servo_command(const tycore::CellMeasurementOf<6> &cell)
{
  tycore::ServoMemory principal_memory = tycore::principal_memory(memory);
  if (mode == Mode::PATH) {
    const tycore::ServoCommand command =
        tycore::path_servo_step(path, path_speed, target_p, tycore::principal_measurement(cell),
                                settings, update->dt, principal_memory, plane_strain);
    memory = tycore::six_component_memory(principal_memory);
    return tycore::six_component_command(command);
  }
  const tycore::MixedControl6 control = current_control();
  if (const auto principal = tycore::principal_control(control)) {
    const tycore::ServoCommand command =
        tycore::servo_step(*principal, tycore::principal_measurement(cell), settings,
                           update->dt, principal_memory);
    memory = tycore::six_component_memory(principal_memory);
    return tycore::six_component_command(command);
  }
  return tycore::servo_step(control, cell, settings, update->dt, memory);
}

// a programme's state after the step: the reversals and N_L of a cyclic test
void FixCellServo::after_step()
{
  if (mode != Mode::CYCLIC_SHEAR) return;
  cyclic_programme().update(cyclic, output[TAU], output[GAMMA], output[SIG_N]);
}
