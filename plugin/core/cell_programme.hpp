// A test programme of the periodic cell (fix cell/servo's MODE; docs/fix_cell_servo.md,
// docs/theory.md §6.3, §13): from the cell's state and time it says which of the six Voigt
// components are strain-rate and which stress controlled and at what rates and targets (a
// MixedControl6, stepped by servo_step on six components for every programme), which stiffness
// entries its servo needs, its own outputs and its restart state. Plain C++, no LAMMPS: the fix
// measures the cell, asks the programme for this step's control, steps the servo and moves the
// box; the programmes themselves are in cell_programmes.hpp, with their parsing.
//
// Adding a programme (e.g. a K0 oedometer test) is one small type and one registry row:
//   1. in cell_programmes.hpp, a class derived from CellProgramme with
//        * a constructor that reads its arguments from an ArgList (command_args.hpp: numbers in
//          their ranges, stresses, Settings that may be variables; errors name the argument);
//        * control(state, values): this step's MixedControl6, built from cell_control.hpp's
//          pieces (per_axis_control<6>, six_component_control of a principal control, ...);
//        * profile(): what it needs (a triclinic box, the shears it strains, a plane, the mean
//          stress it holds, its own record columns), and, only if it has any, keyword() for its
//          own keywords, outputs(), after_step(), and state()/restore() for its restart state;
//   2. a row of programme_kinds() (cell_programmes.hpp): its MODE word, a restart number never
//      used before, its usage line and its keywords;
//   3. its row in the MODE table of docs/fix_cell_servo.md and a test of its control.
// The fix needs no change: it knows programmes only through this interface.
#ifndef TYCORE_CELL_PROGRAMME_HPP
#define TYCORE_CELL_PROGRAMME_HPP

#include "cell_control.hpp"
#include "cell_kinematics.hpp"
#include "cell_outputs.hpp"
#include "cell_servo.hpp"
#include "cell_stiffness.hpp"
#include "command_args.hpp"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tycore {

// the cell as a programme reads it at the end of a step
struct CellState {
  double time = 0.0;                     // simulated time since the test began [s]
  double dt = 0.0;                       // the timestep [s]
  Vector6d stress = Vector6d::Zero();    // contact stress [Pa], compression positive
  Vector6d strain = Vector6d::Zero();    // cumulative strain (CumulativeStrain::voigt)
};

// what a programme asks of the cell and the fix, fixed once its keywords are read
struct ProgrammeProfile {
  bool triclinic = false;                 // it moves or holds a shear: needs a triclinic box
  std::array<bool, 3> strains_shear{};    // xy, xz, yz: the shears it moves (until gamma_ij)
  bool holds_shear_stress = false;        // the shear gains (docs/theory.md §11.2)
  // the stiffness entries its servo needs (bits of AffineStiffnessSums::index), when fewer
  // than the cell's (the principal block, or all 21 on a triclinic cell) are worth the saving
  std::optional<unsigned> stiffness_entries;
  std::optional<ShearPlane> plane;    // outputs gamma, tau, sig_n, angles of this plane
  double mean_stress = 0.0;           // the mean stress p it holds [Pa] (0: none)
  std::vector<int> columns;           // its own outputs (out::Output), after the cell's
  int equilibrium_every = 0;          // quasi-equilibrium checked every N steps (0: not)
};

// a constant rate of the programme, which the cell must resolve in a step (name, 1/s)
struct NamedRate {
  std::string what;
  double rate;
};

class CellProgramme {
 public:
  virtual ~CellProgramme() = default;

  // the registry's name of the programme and its number in restart records
  const std::string &name() const { return name_; }
  int restart_id() const { return restart_id_; }
  void set_kind(const std::string &name, int restart_id) { name_ = name, restart_id_ = restart_id; }

  // ---- its keywords and what it needs
  // read keyword `key`'s values from args when it is one of its own (true), else false
  virtual bool keyword(const std::string &, ArgList &) { return false; }
  // after the keywords: build what depends on them and refuse what does not fit (throws)
  virtual void finish() {}
  virtual ProgrammeProfile profile() const = 0;
  // its settings that are variables (the fix finds them at each run's init)
  virtual std::vector<Setting *> settings() { return {}; }

  // ---- levels for the servo's defaults and the warnings (values of the last evaluation)
  // the stress of the inertial number and of the default rate cap (p, or the held stresses)
  virtual double stress_level() const { return profile().mean_stress; }
  // the largest prescribed strain rate (or path speed) [1/s]
  virtual double largest_rate() const = 0;
  // the rates given as numbers, which the cell must resolve
  virtual std::vector<NamedRate> constant_rates() const = 0;
  // the held stresses and their targets, for the cap warning
  virtual std::string held_targets(const Vector6d &stress) const = 0;

  // ---- the test
  // enter from the cumulative strain of the test (paths: a leg to their first point); the text
  // to log, if any
  virtual std::string enter(const Vector6d &, double) { return ""; }
  // at the setup of each run: what needs the cell (sigma_n0), evaluations and checks (throws);
  // returns a warning to give, if any
  virtual std::string begin_run(const CellState &, SettingValues &) { return ""; }
  // the control of this step (called once per step, after the step's outputs)
  virtual MixedControl6 control(const CellState &, SettingValues &) = 0;
  // the programme's state after the step's outputs (cyclic reversals)
  virtual void after_step(const CellState &) {}
  // quasi-equilibrium (profile().equilibrium_every > 0): the check of a sample
  virtual EquilibriumCheck check_equilibrium(const EquilibriumSample &) { return {}; }
  virtual bool equilibrium_reached() const { return false; }

  // ---- its outputs
  // its own outputs (profile().columns) into the output vector o
  virtual void outputs(const CellState &, double *) const {}
  // the fraction of its own course done, and the simulated time left (paths); NaN if none
  virtual double progress() const { return std::numeric_limits<double>::quiet_NaN(); }
  virtual double remaining_time() const { return std::numeric_limits<double>::quiet_NaN(); }

  // ---- restart and continuation
  // what a restart must match (a path, a plane), and the message when it does not
  virtual std::vector<double> identity() const { return {}; }
  virtual std::string identity_mismatch() const { return ""; }
  virtual std::vector<double> state() const { return {}; }
  virtual void restore(const std::vector<double> &) {}
  // what a redefinition continuing the test takes over (sigma_n0 of a plane); passed on by
  // programmes that do not use it
  virtual std::vector<double> carried() const { return carry_; }
  virtual void take_carried(const std::vector<double> &carry) { carry_ = carry; }

 protected:
  std::vector<double> carry_;

 private:
  std::string name_;
  int restart_id_ = -1;
};

// the entries of the affine stiffness a control's servo uses (docs/theory.md §6.2, §11.2): C_IJ
// of each held row I and each component J it strains (a prescribed rate or an actuator)
inline unsigned servo_stiffness_entries(const MixedControl6 &c)
{
  unsigned entries = 0;
  for (int k = 0; k < c.actuator_count; ++k)
    for (int I = 0; I < 6; ++I)
      for (int J = 0; J < 6; ++J)
        if (c.stress_rows(k, I) != 0.0 &&
            (c.prescribed_strain_rate(J) != 0.0 || c.actuators.row(J).any()))
          entries |= 1u << AffineStiffnessSums::index(I, J);
  return entries;
}

// the entries the fix asks the tallies for: the programme's own set, or the cell's
inline unsigned stiffness_entries_of(const ProgrammeProfile &p, bool triclinic)
{
  if (p.stiffness_entries) return *p.stiffness_entries;
  return triclinic ? AffineStiffnessSums::all_entries : AffineStiffnessSums::principal_entries;
}

// the outputs a programme reports: the measures of every test and its own
inline bool reports(const ProgrammeProfile &p, int output)
{
  if (out::measure_of_a_test(output)) return true;
  for (int k : p.columns)
    if (k == output) return true;
  return false;
}

}    // namespace tycore

#endif
