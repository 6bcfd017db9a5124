// The command of a cell test, `MODE args [keyword value ...]` (fix cell/servo,
// docs/fix_cell_servo.md "Syntax"): the programme (cell_programmes.hpp) and the keywords of the
// servo, the record and the end of the test; and `until NAME VALUE`, the measure that ends a
// test. Errors are std::invalid_argument naming the argument (command_args.hpp). Plain C++.
#ifndef TYCORE_CELL_COMMAND_HPP
#define TYCORE_CELL_COMMAND_HPP

#include "cell_programmes.hpp"

#include <cstdarg>
#include <cstdio>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace tycore {

// `until NAME VALUE`: the test ends when output NAME reaches VALUE from the side it started on
struct UntilTarget {
  int output = -1;    // out::Output; -1 without `until`
  double value = 0.0;
  std::string name;
  // the log line of a test ended at `step`, its measure now `now`
  std::string reached_message(double now, long long step) const;
};

struct CellCommand {
  std::unique_ptr<CellProgramme> programme;
  ServoSettings settings;    // max_strain_rate 0: chosen at each run's setup
  bool gains_given = false, max_rate_given = false;
  double inertial_cap = 1e-3;    // the default cap: the rate at this inertial number
  bool cap_warning = true, named_variables = false, continue_previous = true;
  std::string csv_path;
  int csv_every = 0;
  std::vector<std::pair<std::string, std::string>> extra;    // name, reference as given
  UntilTarget until;
  std::vector<std::string> warnings;    // of risky settings, for the fix to give
};

// the servo's defaults for a held shear stress (docs/theory.md §11.2), and the largest gain
// that is not warned about: from 0.02 on the shear components ring (docs/decks/rotation.md,
// "The servo's gain")
constexpr double SHEAR_GAIN = 0.015, SHEAR_INTEGRAL_GAIN = SHEAR_GAIN * SHEAR_GAIN / 8.0,
                 MAX_SHEAR_GAIN = 0.015;

// an error of the record's columns (`extra`, `csv`): the fix names itself in its message
struct RecordError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

inline void check_extra_column(const std::string &name, const std::string &ref,
                               const std::vector<std::pair<std::string, std::string>> &taken);

namespace command_detail {

  // gain, integral_gain, integral_band, max_rate, max_inertial, cap_warning
  inline bool servo_keyword(const std::string &key, ArgList &a, CellCommand &c)
  {
    if (key == "gain") {
      c.settings.gain = a.number("gain");
      c.gains_given = true;
    } else if (key == "integral_gain") {
      c.settings.integral_gain = a.number("integral_gain");
      c.gains_given = true;
    } else if (key == "integral_band") {
      c.settings.integral_band =
          a.number_in("integral_band", 0.0, 1.0, false, " (a fraction of the stress level)");
    } else if (key == "max_rate") {
      c.settings.max_strain_rate = a.number("max_rate");
      if (!(c.settings.max_strain_rate > 0.0))
        throw std::invalid_argument("max_rate must be positive, got " +
                                    number_text(c.settings.max_strain_rate));
      c.max_rate_given = true;    // its range needs the timestep: checked at setup
    } else if (key == "max_inertial") {
      c.inertial_cap =
          a.number_in("max_inertial", 0.0, 1.0, true, " (above 1 a packing flows like a gas)");
    } else if (key == "cap_warning") {
      c.cap_warning = a.yes_no("cap_warning");
    } else {
      return false;
    }
    return true;
  }

  // csv, extra, until, variables, continue
  inline bool record_keyword(const std::string &key, ArgList &a, CellCommand &c)
  {
    if (key == "csv") {
      c.csv_path = a.next("csv FILE");
      if (c.csv_path.empty()) throw std::invalid_argument("csv needs a file name, got ''");
      c.csv_every = a.positive_integer("csv interval N");
    } else if (key == "extra") {
      const int n = a.positive_integer("extra column count N");
      if (a.remaining() < std::size_t(2 * n))
        throw std::invalid_argument("extra " + std::to_string(n) + " needs " + std::to_string(n) +
                                    " name-value pairs");
      for (int j = 0; j < n; ++j) {
        const std::string name = a.next("extra name"), ref = a.next("extra reference");
        check_extra_column(name, ref, c.extra);
        c.extra.emplace_back(name, ref);
      }
    } else if (key == "until") {
      c.until.name = a.next("until NAME");
      c.until.value = a.number("until value");
    } else if (key == "variables") {
      c.named_variables = a.yes_no("variables");
    } else if (key == "continue") {
      c.continue_previous = a.yes_no("continue");
    } else {
      return false;
    }
    return true;
  }

}    // namespace command_detail

// `until NAME VALUE` against what the programme reports and strains; throws if the test could
// never end by it
inline void check_until(UntilTarget &until, const CellProgramme &programme)
{
  if (until.name.empty()) return;
  const ProgrammeProfile p = programme.profile();
  const std::string &name = until.name;
  const int k = out::index(name);
  static const int plane_or_undrained[] = {out::GAMMA, out::TAU,    out::SIG_N, out::TAU_RATIO,
                                           out::R_U,   out::CYCLES, out::EPS_A, out::SIG_A,
                                           out::SIG_R, out::Q_A,    out::K0,    out::OCR};
  const bool of_a_programme =
      std::find(std::begin(plane_or_undrained), std::end(plane_or_undrained), k) !=
      std::end(plane_or_undrained);
  if (k < 0 || !(out::measure_of_a_test(k) || of_a_programme))
    throw std::invalid_argument("until: '" + name +
                                "' is not a strain, stress, void ratio, "
                                "time, boundary_work, shear or cycle output of the fix (names: "
                                "docs/fix_cell_servo.md)");
  if (of_a_programme && !reports(p, k))
    throw std::invalid_argument(
        "until " + name + ": " + programme.name() + " does not report " + name +
        (k == out::R_U                       ? " (r_u: shear_cv, cyclic_shear and cyclic_triaxial)"
             : k == out::CYCLES              ? " (cycles: cyclic_shear and cyclic_triaxial)"
             : k == out::K0 || k == out::OCR ? " (" + name + ": k0)"
             : k >= out::EPS_A               ? " (" + name + ": k0 and cyclic_triaxial)"
                               : " (it has no shear plane: use gamma_xy, gamma_xz or gamma_yz, "
                                 "or a programme with a plane)"));
  if (k >= out::GAMMA_XY && k <= out::GAMMA_YZ && !p.strains_shear[k - out::GAMMA_XY])
    throw std::invalid_argument("until " + name + ": " + programme.name() +
                                " does not strain "
                                "the " +
                                voigt_names[3 + k - out::GAMMA_XY] + " shear (" + name +
                                " stays 0)");
  if (k == out::R_U && until.value > 1.0)
    throw std::invalid_argument("until r_u " + number_text(until.value) + ": r_u = 1 - " +
                                (p.plane ? "sigma_n/sigma_n0" : "p/p0") +
                                " cannot exceed 1 "
                                "(a granular cell carries no tension, " +
                                (p.plane ? "sigma_n" : "p") + " >= 0): give a target <= 1");
  if (k == out::CYCLES && !(until.value > 0.0))
    throw std::invalid_argument("until cycles " + number_text(until.value) +
                                ": the cycle count "
                                "starts at 0 and grows: give a positive target");
  until.output = k;
}

// MODE args [keyword value ...], args without the fix's ID, group and style, for a cell with
// shears (triclinic) or without
inline CellCommand parse_cell_command(const std::vector<std::string> &args, bool triclinic)
{
  ArgList a(args);
  CellCommand c;
  c.programme = parse_programme(a);
  std::set<std::string> seen;
  while (!a.done()) {
    const std::string key = a.next("keyword");
    if (!seen.insert(key).second)
      throw std::invalid_argument("keyword '" + key + "' is given twice");
    if (c.programme->keyword(key, a) || command_detail::servo_keyword(key, a, c) ||
        command_detail::record_keyword(key, a, c))
      continue;
    const std::string owners = owners_of(key);
    if (!owners.empty())
      throw std::invalid_argument("keyword '" + key + "' applies only to " + owners);
    const std::string old = renamed(key);
    throw std::invalid_argument(old.empty() ? "unknown keyword '" + key + "'" : old);
  }
  c.programme->finish();
  if (!c.extra.empty() && c.csv_path.empty())
    throw RecordError("'extra' adds columns to the record, but this fix writes none: add 'csv "
                      "FILE N'");
  check_until(c.until, *c.programme);
  const ProgrammeProfile p = c.programme->profile();
  if (p.triclinic && !triclinic)
    throw std::invalid_argument(
        "this programme moves or holds a shear component, which needs a triclinic box: make "
        "the box triclinic before this fix is defined ('change_box all triclinic' while no fix "
        "cell/servo is defined: unfix the one of an earlier stage first), or read a triclinic "
        "region or data file");
  // a held shear stress: the shear gains unless gains are given (docs/theory.md §11.2); a
  // larger gain overshoots, as the packing's response relaxes over tens of steps
  if (p.holds_shear_stress && !c.gains_given) {
    c.settings.gain = SHEAR_GAIN;
    c.settings.integral_gain = SHEAR_INTEGRAL_GAIN;
  } else if (p.holds_shear_stress && c.settings.gain > MAX_SHEAR_GAIN) {
    c.warnings.push_back("gain " + g_text(c.settings.gain) +
                         " on a held shear stress "
                         "overshoots and rings (the packing's shear response relaxes to a "
                         "fraction of the affine estimate over tens of steps): use gain <= " +
                         g_text(MAX_SHEAR_GAIN) + " (default " + g_text(SHEAR_GAIN) +
                         " when a shear stress is held)");
  }
  return c;
}

// the names of extra columns: not a built-in column, not one taken already, nothing that
// breaks a CSV line; `ref` a c_, f_ or v_ reference (the message names the column)
inline void check_extra_column(const std::string &name, const std::string &ref,
                               const std::vector<std::pair<std::string, std::string>> &taken)
{
  if (name.empty() || name.find_first_of(",\"' ") != std::string::npos)
    throw RecordError("extra column name '" + name +
                      "' may not hold commas, quotes "
                      "or blanks");
  if (name == "step")
    throw RecordError("extra column " + name + " (" + ref +
                      ") has the name of the "
                      "record's built-in column step: choose another name");
  const int k = out::index(name);
  if (k >= 0)
    throw RecordError("extra column " + name + " (" + ref +
                      ") has the name of the "
                      "fix's built-in output " +
                      name + " (output " + std::to_string(k + 1) + "): choose another name");
  for (const auto &e : taken)
    if (name == e.first)
      throw RecordError("extra column " + name + " (" + ref +
                        ") has the name of "
                        "extra column " +
                        e.first + " (" + e.second +
                        "): choose "
                        "another name");
  if (ref.size() < 3 || ref[1] != '_' || (ref[0] != 'c' && ref[0] != 'f' && ref[0] != 'v'))
    throw RecordError("extra column " + name + ": '" + ref +
                      "' is not a c_ID, "
                      "c_ID[i], f_ID, f_ID[i] or v_name reference");
}

// ---------------------------------------------------------------------------------------------
// The extra columns of a record (`extra N name ref ...`): a reference c_ID, c_ID[i], f_ID, f_ID[i]
// or v_name names a global scalar or vector or an equal-style variable; an unindexed global
// vector gives one column per element, name[1] ... name[n]

struct Reference {
  char kind;         // 'c' compute, 'f' fix, 'v' variable
  std::string id;    // its ID or name
  int index = 0;     // [i], 0 without
};

inline Reference parse_reference(const std::string &ref)
{
  const std::size_t open = ref.find('[');
  Reference r{ref[0], ref.substr(2, open == std::string::npos ? open : open - 2)};
  if (open != std::string::npos) r.index = std::atoi(ref.c_str() + open + 1);
  return r;
}

// what a reference names, as the fix finds it
struct ReferenceTarget {
  bool exists = false;
  bool scalar = false, vector = false, array = false, peratom = false, local = false;
  int size = 0;                  // of a global vector
  bool variable_size = false;    // its size known only when it is computed
  bool equal_style = false, atom_style = false, vector_style = false;    // a variable
};

// the columns (name, reference) of the request `name ref`; a RecordError names what is wrong
inline std::vector<std::pair<std::string, std::string>>
extra_columns_of(const std::string &name, const std::string &ref, const ReferenceTarget &t)
{
  const char *accepted = "extra takes global scalars and vectors (c_ID, c_ID[i], f_ID, f_ID[i]) "
                         "and equal-style variables (v_name)";
  const Reference r = parse_reference(ref);
  const std::string column = "extra column " + name + ": ";
  if (r.kind == 'v') {
    if (!t.exists) throw RecordError(column + "variable " + r.id + " does not exist");
    if (!t.equal_style)
      throw RecordError(column + "variable " + r.id + " is not a number each step (" +
                        (t.atom_style         ? "it is per-atom"
                             : t.vector_style ? "it is vector-style"
                                              : "it is a string, read as 0") +
                        "); " + accepted);
    return {{name, ref}};
  }
  const std::string source = (r.kind == 'c' ? "compute " : "fix ") + r.id;
  if (!t.exists) throw RecordError(column + source + " does not exist");
  const bool indexed = r.index != 0 || ref.find('[') != std::string::npos;
  const char *kind = (!indexed && t.scalar) || t.vector ? nullptr
      : t.array                                         ? "a global array"
      : t.peratom                                       ? "per-atom (not global)"
      : t.local                                         ? "local (not global)"
      : indexed                                         ? "no global vector"
                                                        : "no global scalar or vector";
  if (kind)
    throw RecordError(column + source + " is " + kind + "; " + accepted +
                      " (reduce per-atom or "
                      "local values first, e.g. with compute reduce)");
  if (indexed && !t.variable_size && (r.index < 1 || r.index > t.size))
    throw RecordError(column + ref + " is out of range: " + source + " has a global vector of " +
                      std::to_string(t.size) + " values (index 1 to " + std::to_string(t.size) +
                      ")");
  if (indexed || t.scalar) return {{name, ref}};
  std::vector<std::pair<std::string, std::string>> columns;
  for (int k = 1; k <= t.size; ++k)
    columns.emplace_back(name + "[" + std::to_string(k) + "]", ref + "[" + std::to_string(k) + "]");
  return columns;
}

// ---------------------------------------------------------------------------------------------
// Checks of a test at the setup of each run and while it runs: the messages (empty when all is
// well), which the fix gives as errors or warnings naming itself

// printf into a string
inline std::string printf_text(const char *format, ...) __attribute__((format(printf, 1, 2)));
inline std::string printf_text(const char *format, ...)
{
  char text[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  return text;
}

// a constant rate must strain the cell by at least this per step: below, the round-off of the
// cell edges (a double resolves 2.2e-16 of an edge) distorts a step's strain by over 10 %
constexpr double MIN_STRAIN_PER_STEP = 1e-15;

// a constant prescribed rate (or path speed, or cap) the cell cannot resolve or follow
inline std::string unresolvable_rate(const NamedRate &r, double dt)
{
  const double strain = std::fabs(r.rate) * dt;
  if (r.rate == 0.0 || (strain >= MIN_STRAIN_PER_STEP && strain <= MAX_STRAIN_PER_STEP)) return "";
  return printf_text("%s = %.4g 1/s strains the cell by %.3g per step (timestep %.4g); the "
                     "accepted range is %.3g to %.3g 1/s (%g to %g per step: below, round-off "
                     "of the cell edges distorts the strain; above, the cell cannot follow)",
                     r.what.c_str(), r.rate, strain, dt, MIN_STRAIN_PER_STEP / dt,
                     MAX_STRAIN_PER_STEP / dt, MIN_STRAIN_PER_STEP, MAX_STRAIN_PER_STEP);
}

// the servo's rates of a step that strain the cell by more than it can follow in one step
// (MAX_STRAIN_PER_STEP; a variable rate, or a cap not given)
inline std::string step_strain_error(const Vector6d &rate, double dt, long long step)
{
  const double fastest = rate.cwiseAbs().maxCoeff();
  if (!(fastest * dt > MAX_STRAIN_PER_STEP)) return "";
  return printf_text("at step %lld the strain rate %.4g 1/s strains the cell by %.3g in one step; "
                     "the cell cannot follow more than %g per step: use rates <= %.4g 1/s (or a "
                     "smaller timestep)",
                     step, fastest, fastest * dt, MAX_STRAIN_PER_STEP, MAX_STRAIN_PER_STEP / dt);
}

// the default cap of the servo part: the strain rate at inertial number `inertial` at the held
// p, and at least four times the largest prescribed rate (the minor axis of a constant-b path
// extends at about the major rate, plus dilatancy); a programme that holds no p takes the level
// of its held stresses (docs/theory.md §4.2)
inline double default_rate_cap(double p, double level, double rate, double inertial,
                               double diameter, double density)
{
  if (p == 0.0 && level > 0.0) return quasi_static_strain_rate(inertial, level, diameter, density);
  return std::max(quasi_static_strain_rate(inertial, p > 0.0 ? p : 1.0, diameter, density),
                  4.0 * rate);
}

// I = eps_dot d sqrt(rho/p) of the largest prescribed rate above the quasi-static limit
inline std::string inertial_number_warning(double rate, double level, double inertial,
                                           double diameter, double density)
{
  const double limit = quasi_static_strain_rate(inertial, level, diameter, density);
  if (!(rate > 0.0 && level > 0.0 && rate > limit)) return "";
  return printf_text("the prescribed strain rate %.4g 1/s gives an inertial number I = %.3g at "
                     "stress %.4g (mean diameter %.4g, density %.4g), above the quasi-static "
                     "limit max_inertial = %g: use a rate <= %.4g 1/s",
                     rate, inertial * rate / limit, level, diameter, density, inertial, limit);
}

// The rates at a run's setup: the servo's cap, when not given, chosen (at the first run, after
// the first measurement: targets may read the fix's outputs) and checked (throws); what the fix
// is to say: a warning when the cap is below the prescribed rate (the free axes cannot follow
// the prescribed ones), an error for a constant rate (or a given cap) the cell cannot resolve
// or follow, a warning when the largest prescribed rate is not quasi-static
struct RateReport {
  std::string slow_cap, unresolvable, inertial;
};
inline RateReport settle_rates(CellCommand &c, double mean_stress, double dt, double diameter,
                               double density)
{
  const CellProgramme &p = *c.programme;
  const double rate = p.largest_rate(), level = p.stress_level();
  double &cap = c.settings.max_strain_rate;
  if (cap == 0.0)
    cap = default_rate_cap(mean_stress, level, rate, c.inertial_cap, diameter, density);
  require_valid(c.settings);
  RateReport r;
  if (rate > 0.0 && cap < rate)
    r.slow_cap = printf_text("max_rate %.3g is below the prescribed strain rate %.3g; the servo "
                             "cannot keep up and the stress will drift (raise max_rate)",
                             cap, rate);
  std::vector<NamedRate> rates = p.constant_rates();
  if (c.max_rate_given) rates.push_back({"max_rate", cap});
  for (std::size_t k = 0; k < rates.size() && r.unresolvable.empty(); ++k)
    r.unresolvable = unresolvable_rate(rates[k], dt);
  r.inertial = inertial_number_warning(rate, level, c.inertial_cap, diameter, density);
  return r;
}

inline std::string UntilTarget::reached_message(double now, long long step) const
{
  return printf_text("%s = %.6g reached the target %.6g at step %lld: the run stops", name.c_str(),
                     now, value, step);
}

// 'until NAME VALUE' while NAME moves away from VALUE: the run would not stop by it. Judged
// once NAME has moved by this fraction of its distance to VALUE (the servo's first steps move
// a strain by ~1e-5 either way): an error when the test a fix continues has passed VALUE
// already (it lies between the test's start and where this run began), else a warning (a
// programme may turn back)
constexpr double UNTIL_DIRECTION_FRACTION = 0.1;
struct UntilDirection {
  bool judged = false;
  std::string error, warning;
};
inline UntilDirection judge_until_direction(const UntilTarget &u, double run_start, double now,
                                            double test_start, bool continued, long long step)
{
  UntilDirection d;
  const double distance = u.value - run_start;
  if (!(std::fabs(now - run_start) > UNTIL_DIRECTION_FRACTION * std::fabs(distance))) return d;
  d.judged = true;
  if ((now - run_start) * distance >= 0.0) return d;
  const char *name = u.name.c_str();
  if (continued && (u.value - test_start) * (run_start - u.value) > 0.0)
    d.error = printf_text("until %s %g: the test this fix continues has passed that target "
                          "already (%s went from %.6g at its start to %.6g when this fix took "
                          "over) and moves on away from it: give a target beyond %.6g, or "
                          "'continue no' to start a new test",
                          name, u.value, name, test_start + 0.0, run_start + 0.0,
                          run_start + 0.0);    // (no "-0")
  else
    d.warning = printf_text("until %s %g: %s moves away from the target (from %.6g at the start "
                            "of the run to %.6g at step %lld): the run will not stop there "
                            "unless the programme turns back; check the sign of the target and "
                            "of the rates",
                            name, u.value, name, run_start + 0.0, now, step);
  return d;
}

// A servo at its cap whose stress error has grown since it reached the cap has lost control of
// the stress: a warning says what to change, once per run. At the cap while the error shrinks
// (an approach to a far target at the cap's pace) the cap only sets the pace, and is no fault.
struct CapWatch {
  static constexpr int WARN_STEPS = 1000;    // at the cap this long before a warning
  long long steps = 0;                       // steps at the cap in a row
  double error_at_cap = 0.0;                 // the stress error when it reached the cap
  bool warned = false;                       // in this run

  // whether the warning is due after a step (enabled: keyword cap_warning; loaded: contacts)
  bool due(const ServoCommandOf<6> &c, bool enabled, bool loaded)
  {
    if (!c.saturated) {
      steps = 0;
      return false;
    }
    if (++steps == 1) {
      error_at_cap = c.stress_error;
      return false;
    }
    if (steps % WARN_STEPS != 0 || !enabled || warned || !loaded ||
        !(c.stress_error > error_at_cap))
      return false;
    return warned = true;
  }
  std::string message(double cap, double error_now, const std::string &held, double rate) const
  {
    return printf_text("the servo has been at its strain-rate cap max_rate = %.3g for %lld "
                       "steps and its stress error grew from %.4g to %.4g (%s; prescribed rate "
                       "%.4g 1/s); raise max_rate or lower the prescribed rate (said once per "
                       "run)",
                       cap, steps, error_at_cap, error_now, held.c_str(), rate);
  }
};

}    // namespace tycore

#endif
