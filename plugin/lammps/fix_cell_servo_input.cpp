/* ----------------------------------------------------------------------
   fix cell/servo: checks of the programme that need the run (time step, particles, the
   first steps): accepted ranges of the numeric keywords, strain rates the cell can resolve,
   the quasi-static inertial number, and an 'until' target the test moves away from
   (docs/fix_cell_servo.md, "Accepted ranges" and "Warnings")
------------------------------------------------------------------------- */

#include "fix_cell_servo.h"

#include "comm.h"
#include "error.h"
#include "update.h"

#include "tylmp_numeric.h"

#include <cmath>

using namespace LAMMPS_NS;

// a number of the command that must lie in [lo, hi] ((lo, hi] with open_low): the message
// states the accepted range
double FixCellServo::number_in(const char *text, const std::string &what, double lo, double hi,
                               bool open_low, const char *unit)
{
  const double v = tylmp::finite_numeric(FLERR, text, "fix cell/servo: " + what, lmp);
  if ((open_low ? !(v > lo) : !(v >= lo)) || !(v <= hi))
    error->all(FLERR, "fix cell/servo: {} = {} is outside the accepted range {}{:g}, {:g}]{}",
               what, text, open_low ? "(" : "[", lo, hi, unit);
  return v;
}

// every constant prescribed rate (and path speed, and a given cap) strains the cell by rate*dt
// per step; below MIN_STRAIN_PER_STEP the round-off of the cell edges (a double resolves
// 2.2e-16 of an edge) distorts that by more than 10 % (and loses it at 1e-16), above
// tycore::MAX_STRAIN_PER_STEP the cell cannot follow it
void FixCellServo::check_rates_resolvable()
{
  const double dt = update->dt;
  auto check = [&](double rate, const std::string &what) {
    const double strain = std::fabs(rate) * dt;
    if (rate != 0.0 && (strain < MIN_STRAIN_PER_STEP || strain > tycore::MAX_STRAIN_PER_STEP))
      error->all(FLERR, "fix cell/servo {}: {} = {:.4g} 1/s strains the cell by {:.3g} per step "
                 "(timestep {:.4g}); the accepted range is {:.3g} to {:.3g} 1/s ({:g} to {:g} "
                 "per step: below, round-off of the cell edges distorts the strain; above, the "
                 "cell cannot follow)", id, what, rate, strain, dt, MIN_STRAIN_PER_STEP / dt,
                 tycore::MAX_STRAIN_PER_STEP / dt, MIN_STRAIN_PER_STEP,
                 tycore::MAX_STRAIN_PER_STEP);
  };
  if (major_input.variable.empty()) check(major_rate, major_input.what);
  for (const auto &a : axis_input)
    if (a.control == tycore::AxisControl::STRAIN_RATE && a.variable.empty()) check(a.value, a.what);
  check(path_speed, "speed");
  if (max_rate_given) check(settings.max_strain_rate, "max_rate");
}

// the stress that sets the inertial number: the target p, else (axes) the largest held stress
double FixCellServo::stress_level()
{
  if (target_p > 0.0) return target_p;
  double level = 0.0;
  for (auto &a : axis_input)
    if (a.control == tycore::AxisControl::STRESS)
      level = std::max(level, a.variable.empty() ? a.value : evaluate(a));
  return level;
}

// I = eps_dot d sqrt(rho/p) of the prescribed rate (docs/theory.md §4.2): above max_inertial
// (1e-3 unless given) the test is not quasi-static; the rate at the limit is
// tycore::quasi_static_strain_rate, the one that sets the default servo cap
void FixCellServo::warn_inertial_number()
{
  const double rate = prescribed_rate(), level = stress_level();
  if (!(rate > 0.0 && level > 0.0) || comm->me != 0) return;
  const double limit =
      tycore::quasi_static_strain_rate(inertial_cap, level, mean_diameter, mean_density);
  if (rate > limit)
    error->warning(FLERR, "fix cell/servo {}: the prescribed strain rate {:.4g} 1/s gives an "
                   "inertial number I = {:.3g} at stress {:.4g} (mean diameter {:.4g}, density "
                   "{:.4g}), above the quasi-static limit max_inertial = {:g}: use a rate <= "
                   "{:.4g} 1/s", id, rate, inertial_cap * rate / limit, level, mean_diameter,
                   mean_density, inertial_cap, limit);
}

// 'until NAME VALUE' while NAME moves away from VALUE: the run would not stop by it. Judged
// once NAME has moved by UNTIL_DIRECTION_FRACTION of its distance to VALUE (a strain under a
// prescribed rate moves so from the first steps, a stress once it rises out of its noise): an
// error when the test this fix continues has passed VALUE already (it lies between the test's
// start and where this run began), a warning otherwise (a programme may turn back later)
void FixCellServo::check_until_direction()
{
  if (until_output < 0 || until_direction_checked) return;
  const double now = output[until_output], distance = until_value - until_run_start;
  if (!(std::fabs(now - until_run_start) > UNTIL_DIRECTION_FRACTION * std::fabs(distance)))
    return;
  until_direction_checked = true;
  if ((now - until_run_start) * distance >= 0.0) return;
  const char *name = output_name(until_output);
  const double start = origin[until_output];
  if (continued && (until_value - start) * (until_run_start - until_value) > 0.0)
    error->all(FLERR, "fix cell/servo {}: until {} {:g}: the test this fix continues has passed "
               "that target already ({} went from {:.6g} at its start to {:.6g} when this "
               "fix took over) and moves on away from it: give a target beyond {:.6g}, or "
               "'continue no' to start a new test", id, name, until_value, name, start + 0.0,
               until_run_start + 0.0, until_run_start + 0.0);    // (+ 0.0: no "-0")
  if (comm->me == 0)
    error->warning(FLERR, "fix cell/servo {}: until {} {:g}: {} moves away from the target "
                   "(from {:.6g} at the start of the run to {:.6g} at step {}): the run will "
                   "not stop there unless the programme turns back; check the sign of the "
                   "target and of the rates", id, name, until_value, name,
                   until_run_start + 0.0, now, update->ntimestep);
}
