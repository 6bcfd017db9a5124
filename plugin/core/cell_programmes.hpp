// The test programmes of fix cell/servo (docs/fix_cell_servo.md, "MODE"; docs/theory.md §6.3,
// §13), each a small type with the parsing of its arguments and keywords, and their registry
// (programme_kinds, at the end: how to add one is said in cell_programme.hpp). The physics of
// each control is cell_control.hpp's and cell_servo.hpp's; a programme states what it holds and
// strains, its outputs and its restart state. Plain C++, no LAMMPS.
#ifndef TYCORE_CELL_PROGRAMMES_HPP
#define TYCORE_CELL_PROGRAMMES_HPP

#include "cell_programme.hpp"
#include "strain_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace tycore {

namespace programme_detail {

  // a number as %.4g writes it (messages)
  inline std::string g4(double value)
  {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
  }

  inline int axis_of(ArgList &a, const std::string &mode)
  {
    const std::string &name = a.next(mode + " axis");
    if (name == "x") return 0;
    if (name == "y") return 1;
    if (name == "z") return 2;
    throw std::invalid_argument(mode + ": axis '" + name + "' is not x, y or z");
  }

  // a plane xy, xz or yz: the edge along the second axis tilts towards the first
  inline ShearPlane plane_of(ArgList &a, const std::string &mode)
  {
    const std::string &name = a.next(mode + " plane");
    for (int k = 3; k < 6; ++k)
      if (name == voigt_names[k]) return {voigt_pairs[k][0], voigt_pairs[k][1]};
    throw std::invalid_argument(mode + ": plane '" + name +
                                "' is not xy, xz or yz (the edge "
                                "along the second axis tilts towards the first; LAMMPS's "
                                "triclinic box has no other shears)");
  }

  // a strain rate that is a variable or a non-zero number
  inline Setting nonzero_rate(ArgList &a, const std::string &what, const std::string &hint = "")
  {
    Setting s = a.setting(what);
    if (!s.is_variable() && s.value == 0.0)
      throw std::invalid_argument(what + " must be non-zero" + hint);
    return s;
  }

  inline std::string held_mean_stress(const Vector6d &stress, double p)
  {
    return "p = " + g4(mean_stress(stress.head<3>())) + ", target " + g4(p);
  }

  // the rates of Settings given as numbers
  inline void add_constant(std::vector<NamedRate> &rates, const Setting &s)
  {
    if (!s.is_variable()) rates.push_back({s.what, s.value});
  }

}    // namespace programme_detail

// ---------------------------------------------------------------------------------------------
// RATE CSR and the liquefaction criteria (keywords ru_limit, da_limit) of the cyclic tests,
// cyclic_shear and cyclic_triaxial: one parser, so that both read and check them alike

struct CyclicArguments {
  // below this CSR the amplitude (CSR sigma_n0 or 2 CSR p0) is a strain of about CSR sigma/G,
  // a few 1e-9 on the specimens of the tests: the cycles would be round-off of the cell
  static constexpr double MIN_CSR = 1e-6;
  LiquefactionCriteria criteria;
  double rate = 0.0, csr = 0.0;
  std::string rate_name;    // as messages name it ("cyclic_shear shear rate gamma_dot")

  explicit CyclicArguments(const LiquefactionCriteria &defaults = {}) : criteria(defaults) {}

  // RATE CSR of `mode`: `rate_word` names the rate in messages, `first_half` says what the
  // first half cycle does (the rate must be positive: each reversal turns its sign)
  void read(ArgList &a, const std::string &mode, const std::string &rate_word,
            const std::string &first_half)
  {
    rate_name = mode + " " + rate_word;
    rate = a.number(rate_name);
    if (!(rate > 0.0))
      throw std::invalid_argument(rate_name + " = " + number_text(rate) +
                                  " must be positive (the first half cycle " + first_half +
                                  "; each reversal turns its sign)");
    csr = a.number_in(mode + " CSR", MIN_CSR, 10.0, false,
                      " (below, the cyclic amplitude is lost in round-off)");
  }
  // ru_limit or da_limit (true), else false; `strain` names the double amplitude's strain
  bool keyword(const std::string &key, ArgList &a, const std::string &strain)
  {
    if (key == "ru_limit")
      criteria.pore_pressure_ratio = a.number_in(key, 0.0, 1.0, true);
    else if (key == "da_limit")
      criteria.double_amplitude_strain =
          a.number_in(key, 0.0, 1.0, true, " (a double-amplitude " + strain + " strain)");
    else
      return false;
    return true;
  }
};

// ---------------------------------------------------------------------------------------------
// iso P: isotropic compression to sigma_i = P (preparation), with the quasi-equilibrium check
// (docs/theory.md §6.4) of keyword `equilibrium N` and its criteria

class IsotropicCompression : public CellProgramme {
 public:
  explicit IsotropicCompression(ArgList &a)
  {
    a.need(1, "iso P");
    p_ = a.stress("iso mean stress p");
  }
  bool keyword(const std::string &key, ArgList &a) override
  {
    auto fraction = [&]() {
      return a.number_in(key, 0.0, 1.0, true);
    };
    if (key == "equilibrium")
      every_ = a.positive_integer("equilibrium interval N");
    else if (key == "eq_stress")
      criteria_.stress_tolerance = fraction();
    else if (key == "eq_unbalanced")
      criteria_.max_unbalanced_force_ratio = fraction();
    else if (key == "eq_kinetic")
      criteria_.max_kinetic_energy_ratio = fraction();
    else if (key == "eq_coordination")
      criteria_.coordination_tolerance = fraction();
    else if (key == "eq_window")
      criteria_.window = a.positive_integer("eq_window");
    else
      return false;
    return true;
  }
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p;
    p.mean_stress = p_;
    p.equilibrium_every = every_;
    return p;
  }
  double largest_rate() const override { return 0.0; }
  std::vector<NamedRate> constant_rates() const override { return {}; }
  std::string held_targets(const Vector6d &s) const override
  {
    return programme_detail::held_mean_stress(s, p_);
  }
  MixedControl6 control(const CellState &, SettingValues &) override
  {
    return six_component_control(isotropic_compression_control(p_));
  }
  EquilibriumCheck check_equilibrium(const EquilibriumSample &sample) override
  {
    const EquilibriumCheck check = update_equilibrium(state_, sample, criteria_);
    reached_ = check.reached;
    return check;
  }
  bool equilibrium_reached() const override { return reached_; }
  std::vector<double> state() const override
  {
    double e[EquilibriumState::size];
    state_.to_array(e);
    return {e[0], e[1], reached_ ? 1.0 : 0.0};
  }
  void restore(const std::vector<double> &s) override
  {
    state_ = EquilibriumState::from_array(s.data());
    reached_ = s[2] != 0.0;
  }

 private:
  double p_;
  int every_ = 0;
  EquilibriumCriteria criteria_;
  EquilibriumState state_;
  bool reached_ = false;
};

// ---------------------------------------------------------------------------------------------
// axisym AXIS RATE P and constant_b B AXIS RATE P: the major axis at a prescribed rate (a
// number or a variable), p held and b = (sigma2 - sigma3)/(sigma1 - sigma3) (0 for axisym, the
// two lateral stresses equal; paper eq. 1)

class MajorAxisProgramme : public CellProgramme {
 public:
  MajorAxisProgramme(ArgList &a, bool constant_b)
  {
    using namespace programme_detail;
    const std::string mode = constant_b ? "constant_b" : "axisym";
    if (constant_b) {
      a.need(4, "constant_b B AXIS RATE P");
      b_ = a.number_in("constant_b b", 0.0, 1.0, false);
      axis_ = axis_of(a, mode);
      rate_ = a.setting("constant_b major-axis strain rate");
      rate_.sign = Setting::Sign::NOT_NEGATIVE;
      rate_.sign_reason = "the major axis of a constant-b path is compressed (rate >= 0)";
      if (!rate_.is_variable() && !(rate_.value > 0.0))
        throw std::invalid_argument("constant_b: the major-axis strain rate must be positive "
                                    "(compression of the major axis)");
    } else {
      a.need(3, "axisym AXIS RATE P");
      axis_ = axis_of(a, mode);
      rate_ = nonzero_rate(a, "axisym axial strain rate", " (> 0 compression, < 0 extension)");
    }
    p_ = a.stress(mode + " mean stress p");
  }
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p;
    p.mean_stress = p_;
    return p;
  }
  std::vector<Setting *> settings() override { return {&rate_}; }
  double largest_rate() const override { return std::fabs(rate_.value); }
  std::vector<NamedRate> constant_rates() const override
  {
    std::vector<NamedRate> r;
    programme_detail::add_constant(r, rate_);
    return r;
  }
  std::string held_targets(const Vector6d &s) const override
  {
    return programme_detail::held_mean_stress(s, p_);
  }
  std::string begin_run(const CellState &, SettingValues &values) override
  {
    if (rate_.is_variable()) values(rate_);
    return "";
  }
  MixedControl6 control(const CellState &, SettingValues &values) override
  {
    // (axisym: axisymmetric_control, the constant-b control at b = 0)
    return six_component_control(
        constant_b_control(p_, b_, values(rate_), axis_, (axis_ + 1) % 3, (axis_ + 2) % 3));
  }

 private:
  double b_ = 0.0, p_;
  int axis_;
  Setting rate_;
};

// ---------------------------------------------------------------------------------------------
// deviatoric R1 R2 R3 P: the deviatoric part of (R1, R2, R3) prescribed, p held

class DeviatoricStrainRate : public CellProgramme {
 public:
  explicit DeviatoricStrainRate(ArgList &a)
  {
    a.need(4, "deviatoric R1 R2 R3 P");
    for (int k = 0; k < 3; ++k)
      rate_[k] = a.setting("deviatoric strain rate R" + std::to_string(k + 1));
    p_ = a.stress("deviatoric mean stress p");
  }
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p;
    p.mean_stress = p_;
    return p;
  }
  std::vector<Setting *> settings() override { return {&rate_[0], &rate_[1], &rate_[2]}; }
  double largest_rate() const override
  {
    double r = 0.0;
    for (const Setting &s : rate_)
      if (!s.is_variable()) r = std::max(r, std::fabs(s.value));
    return r;
  }
  std::vector<NamedRate> constant_rates() const override
  {
    std::vector<NamedRate> r;
    for (const Setting &s : rate_) programme_detail::add_constant(r, s);
    return r;
  }
  std::string held_targets(const Vector6d &s) const override
  {
    return programme_detail::held_mean_stress(s, p_);
  }
  MixedControl6 control(const CellState &, SettingValues &values) override
  {
    Eigen::Vector3d rate;
    for (int k = 0; k < 3; ++k) rate(k) = values(rate_[k]);
    return six_component_control(mean_stress_control(p_, rate));
  }

 private:
  Setting rate_[3];
  double p_;
};

// ---------------------------------------------------------------------------------------------
// axes x C V y C V z C V [xy C V] [xz C V] [yz C V]: each component at a target stress or a
// strain rate (C = stress | rate), numbers or variables; a shear not given at rate 0

class PerComponent : public CellProgramme {
 public:
  explicit PerComponent(ArgList &a)
  {
    bool given[6] = {false, false, false, false, false, false};
    for (int k = 0; k < 6; ++k) value_[k].what = std::string("axes ") + voigt_names[k] + " rate";
    while (!a.done() && component(a.peek()) >= 0) {
      const std::string name = a.next("axes component");
      const int k = component(name);
      if (given[k])
        throw std::invalid_argument("axes: component " + name + " (" + voigt_names[k] +
                                    ") is given twice");
      if (a.remaining() < 2)
        throw std::invalid_argument("axes: component " + name +
                                    " needs 'stress VALUE' or 'rate VALUE'");
      const int kind = a.choice("axes: the control of component " + name, {"stress", "rate"});
      control_[k] = kind == 0 ? AxisControl::STRESS : AxisControl::STRAIN_RATE;
      value_[k] = a.setting("axes " + name + (kind == 0 ? " stress" : " rate"),
                            kind == 0 ? Setting::Kind::STRESS : Setting::Kind::STRAIN_RATE);
      if (kind == 0 && k < 3) {    // a normal stress is compressive, a shear any sign
        value_[k].sign = Setting::Sign::POSITIVE;
        value_[k].sign_reason = "a target stress must be positive";
        if (!value_[k].is_variable() && !(value_[k].value > 0.0))
          throw std::invalid_argument("axes: target stress of axis " + name + " = " +
                                      number_text(value_[k].value) + " must be positive");
      }
      given[k] = true;
    }
    const std::string &next = a.peek();
    if (next == "yx" || next == "zx" || next == "zy")
      throw std::invalid_argument("axes: component " + next +
                                  ": LAMMPS's triclinic box cannot "
                                  "deform it (its tilts are xy, xz and yz: the edge along the "
                                  "second axis tilts towards the first); use " +
                                  std::string{next[1], next[0]});
    for (int k = 0; k < 3; ++k)
      if (!given[k])
        throw std::invalid_argument(std::string("axes: axis ") + axis_name(k) +
                                    " has no control: give it 'stress VALUE' or 'rate VALUE'");
  }
  // controllability depends on which components hold a stress, not on the values
  void finish() override
  {
    std::array<AxisProgramme, 6> c;
    for (int k = 0; k < 6; ++k)
      c[k] = {control_[k], value_[k].is_variable() ? 1.0 : value_[k].value};
    require_controllable(per_axis_control<6>(c));
  }
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p;
    for (int k = 3; k < 6; ++k) {
      const bool held = control_[k] == AxisControl::STRESS;
      p.strains_shear[k - 3] = held || value_[k].is_variable() || value_[k].value != 0.0;
      p.triclinic = p.triclinic || p.strains_shear[k - 3];
      p.holds_shear_stress = p.holds_shear_stress || held;
    }
    return p;
  }
  std::vector<Setting *> settings() override
  {
    std::vector<Setting *> s;
    for (Setting &v : value_) s.push_back(&v);
    return s;
  }
  // the largest held stress (variables at their value when the run began)
  double stress_level() const override
  {
    double level = 0.0;
    for (int k = 0; k < 6; ++k)
      if (control_[k] == AxisControl::STRESS) level = std::max(level, value_[k].value);
    return level;
  }
  double largest_rate() const override
  {
    double r = 0.0;
    for (const NamedRate &n : constant_rates()) r = std::max(r, std::fabs(n.rate));
    return r;
  }
  std::vector<NamedRate> constant_rates() const override
  {
    std::vector<NamedRate> r;
    for (int k = 0; k < 6; ++k)
      if (control_[k] == AxisControl::STRAIN_RATE) programme_detail::add_constant(r, value_[k]);
    return r;
  }
  std::string held_targets(const Vector6d &stress) const override
  {
    using programme_detail::g4;
    std::string text;
    for (int k = 0; k < 6; ++k)
      if (control_[k] == AxisControl::STRESS)
        text += (text.empty() ? "" : "; ") + std::string("sig_") + voigt_names[k] + " = " +
            g4(stress(k)) + ", target " +
            (value_[k].is_variable() ? "v_" + value_[k].variable : g4(value_[k].value));
    return text;
  }
  std::string begin_run(const CellState &, SettingValues &values) override
  {
    for (int k = 0; k < 6; ++k)
      if (control_[k] == AxisControl::STRESS && value_[k].is_variable()) values(value_[k]);
    return "";
  }
  MixedControl6 control(const CellState &, SettingValues &values) override
  {
    std::array<AxisProgramme, 6> c;
    for (int k = 0; k < 6; ++k) c[k] = {control_[k], values(value_[k])};
    return per_axis_control<6>(c);
  }

 private:
  // x, y, z (or xx, yy, zz) and the shears xy, xz, yz: its Voigt6 index, -1 if none
  static int component(const std::string &name)
  {
    for (int k = 0; k < 3; ++k)
      if (name == axis_name(k)) return k;
    for (int k = 0; k < 6; ++k)
      if (name == voigt_names[k]) return k;
    return -1;
  }
  AxisControl control_[6] = {AxisControl::STRAIN_RATE, AxisControl::STRAIN_RATE,
                             AxisControl::STRAIN_RATE, AxisControl::STRAIN_RATE,
                             AxisControl::STRAIN_RATE, AxisControl::STRAIN_RATE};
  Setting value_[6];
};

// ---------------------------------------------------------------------------------------------
// circle PRESTRAIN P, triangle PRESTRAIN P, polygon N x1 y1 ... xN yN P: the deviatoric strain
// follows a path of the strain Pi-plane at speed V (keyword `speed`), p held (paper sections
// 3-5; docs/theory.md §7.4)

class PiPlanePath : public CellProgramme {
 public:
  enum class Kind { CIRCLE, TRIANGLE, POLYGON };
  PiPlanePath(ArgList &a, Kind kind) : kind_(kind)
  {
    const std::string mode = kind == Kind::CIRCLE ? "circle"
        : kind == Kind::TRIANGLE                  ? "triangle"
                                                  : "polygon";
    if (kind != Kind::POLYGON) {
      a.need(2, mode + " PRESTRAIN P");
      prestrain_ = a.number_in(mode + " pre-strain", 0.0, 1.0, true, " (a natural strain)");
    } else {
      a.need(1, "polygon N x1 y1 ... xN yN P");
      const int n = a.positive_integer("polygon vertex count N");
      if (n < 2)
        throw std::invalid_argument("polygon: needs at least 2 vertices, got " + std::to_string(n));
      a.need(2 * n + 1, "polygon N x1 y1 ... xN yN P");
      for (int k = 0; k < n; ++k) {
        const std::string v = "polygon vertex " + std::to_string(k + 1);
        const double x = a.number_in(v + " x", -1.0, 1.0, false, " (a natural strain)");
        const double y = a.number_in(v + " y", -1.0, 1.0, false, " (a natural strain)");
        vertices_.emplace_back(x, y);
      }
    }
    p_ = a.stress(mode + " mean stress p");
  }
  bool keyword(const std::string &key, ArgList &a) override
  {
    if (key == "speed") {
      speed_ = a.number("speed");
      if (!(speed_ > 0.0))
        throw std::invalid_argument("path speed must be positive, got " + number_text(speed_));
    } else if (key == "rotation") {
      rotation_ = a.choice("rotation", {"cw", "ccw"}) == 0 ? Rotation::CLOCKWISE
                                                           : Rotation::ANTICLOCKWISE;
    } else if (key == "measure") {
      measure_ = a.choice("measure", {"d13", "q"}) == 0
          ? DeviatoricStrainMeasure::STRAIN_DIFFERENCE_13
          : DeviatoricStrainMeasure::EPS_Q;
    } else if (key == "prestrain_leg") {
      with_prestrain_ = a.yes_no("prestrain_leg");
    } else if (key == "sweep") {
      sweep_ = a.number_in("sweep", 0.0, 36000.0, true, " degrees (100 turns)");
    } else if (key == "close") {
      close_ = a.yes_no("close");
    } else if (key == "plane_strain") {
      plane_strain_ = a.choice("plane_strain", {"total", "deviatoric"}) == 0
          ? PlaneStrain::TOTAL
          : PlaneStrain::DEVIATORIC;
    } else {
      return false;
    }
    return true;
  }
  void finish() override
  {
    if (!(speed_ > 0.0))
      throw std::invalid_argument("a Pi-plane path needs 'speed V' (|de/dt|, 1/s)");
    if (kind_ == Kind::CIRCLE)
      path_ =
          constant_deviatoric_strain_path(prestrain_, measure_, rotation_, with_prestrain_, sweep_);
    else if (kind_ == Kind::TRIANGLE)
      path_ = multiaxial_plane_strain_path(prestrain_, measure_, rotation_, with_prestrain_);
    else
      path_ = PiPath::polygon(vertices_, close_);
    programme_path_ = path_.to_array();
  }
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p;
    p.mean_stress = p_;
    return p;
  }
  double largest_rate() const override { return speed_; }
  std::vector<NamedRate> constant_rates() const override { return {{"speed", speed_}}; }
  std::string held_targets(const Vector6d &s) const override
  {
    return programme_detail::held_mean_stress(s, p_);
  }
  // every path starts from the current strain (from the reference, kept by a continued test):
  // a leg to the path's first point goes in front unless the follower can close the gap itself
  std::string enter(const Vector6d &strain, double dt) override
  {
    const Eigen::Vector2d from = pi_coordinates(Eigen::Vector3d(strain.head<3>()));
    const int legs = path_.segment_count();
    path_ = path_.starting_from(from, MIN_STEPS_PER_LEG * speed_ * dt);
    if (path_.segment_count() == legs) return "";
    char text[200];
    std::snprintf(text, sizeof text,
                  "the path starts at the current strain, Pi point (%.6g, "
                  "%.6g); a leg of length %.6g to its first point goes first",
                  from.x(), from.y(), path_.segments().front().length());
    return text;
  }
  std::string begin_run(const CellState &state, SettingValues &) override
  {
    const double fastest = max_followable_speed(path_, state.dt);
    if (speed_ > fastest) {
      char text[400];
      std::snprintf(text, sizeof text,
                    "at speed %.4g the shortest leg of the Pi-plane path "
                    "(length %.4g) takes %.3g steps, and the cell cannot follow a leg in fewer "
                    "than %d: use speed <= %.4g (or a smaller timestep)",
                    speed_, path_.shortest_leg(), path_.shortest_leg() / (speed_ * state.dt),
                    MIN_STEPS_PER_LEG, fastest);
      throw std::invalid_argument(text);
    }
    return "";
  }
  MixedControl6 control(const CellState &state, SettingValues &) override
  {
    const Eigen::Vector3d strain = state.strain.head<3>();
    return six_component_control(
        path_control(path_, speed_, p_, strain, state.dt, done_, plane_strain_));
  }
  double progress() const override { return path_.progress(done_).fraction; }
  double remaining_time() const override { return path_.remaining_time(done_, speed_); }
  // the path's kind, pre-strain, rotation, sweep or vertices, without the lead-in leg
  std::vector<double> identity() const override { return programme_path_; }
  std::string identity_mismatch() const override
  {
    return "the restart file was written by a run on another Pi-plane path (another path "
           "kind, pre-strain, rotation, sweep or vertices); resume it with the same path, or "
           "define the fix under a new ID";
  }
  // the progress along the path and the path followed (with its lead-in leg)
  std::vector<double> state() const override
  {
    std::vector<double> s{done_};
    const std::vector<double> followed = path_.to_array();
    s.insert(s.end(), followed.begin(), followed.end());
    return s;
  }
  void restore(const std::vector<double> &s) override
  {
    done_ = s[0];
    path_ = PiPath::from_array(s.data() + 1);
  }

 private:
  Kind kind_;
  double prestrain_ = 0.0, p_;
  std::vector<Eigen::Vector2d> vertices_;
  double speed_ = 0.0;
  Rotation rotation_ = Rotation::CLOCKWISE;
  DeviatoricStrainMeasure measure_ = DeviatoricStrainMeasure::STRAIN_DIFFERENCE_13;
  bool with_prestrain_ = true, close_ = false;
  double sweep_ = 360.0;
  PlaneStrain plane_strain_ = PlaneStrain::TOTAL;
  PiPath path_;
  std::vector<double> programme_path_;
  double done_ = 0.0;    // the progress s along the path
};

// ---------------------------------------------------------------------------------------------
// The programmes with a plane (docs/theory.md §13): they need a triclinic box, output the
// plane's shear and angles, and know sigma_n0, the normal stress of the plane when the test
// began (r_u), which a continued test on the same plane takes over and restarts keep

class PlaneProgramme : public CellProgramme {
 public:
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p;
    p.triclinic = true;
    p.strains_shear[plane_.component() - 3] = true;
    p.plane = plane_;
    p.columns = out::plane_columns();
    return p;
  }
  std::string begin_run(const CellState &state, SettingValues &) override
  {
    if (std::isnan(initial_normal_stress_))
      initial_normal_stress_ = normal_stress(state.stress, plane_);
    return "";
  }
  std::vector<double> identity() const override { return {double(plane_.component())}; }
  std::string identity_mismatch() const override
  {
    return std::string("the restart file was written by a run on another plane; this one "
                       "shears ") +
        voigt_names[plane_.component()] +
        ": resume it on the same "
        "plane, or define the fix under a new ID";
  }
  std::vector<double> state() const override { return {initial_normal_stress_}; }
  void restore(const std::vector<double> &s) override { initial_normal_stress_ = s[0]; }
  std::vector<double> carried() const override
  {
    return {double(plane_.component()), initial_normal_stress_};
  }
  void take_carried(const std::vector<double> &c) override
  {
    if (c.size() == 2 && c[0] == plane_.component()) initial_normal_stress_ = c[1];
  }

 protected:
  ShearPlane plane_;
  double initial_normal_stress_ = std::numeric_limits<double>::quiet_NaN();    // sigma_n0
  // sigma_n0 of r_u must be a compressive stress
  void require_initial_normal_stress(const std::string &mode) const
  {
    if (!(initial_normal_stress_ > 0.0))
      throw std::invalid_argument(
          mode + ": the normal stress sigma_" + voigt_names[plane_.normal] + " is " +
          programme_detail::g4(initial_normal_stress_) +
          " when the test begins (sigma_n0), "
          "so r_u = 1 - sigma_n/sigma_n0 is undefined: load the specimen first (e.g. fix "
          "cell/servo iso P or shear PLANE GDOT SN)");
  }
};

// shear PLANE GDOT SN: drained simple shear at sigma_n = SN; shear_cv PLANE GDOT: constant
// volume, r_u = 1 - sigma_n/sigma_n0
class SimpleShear : public PlaneProgramme {
 public:
  SimpleShear(ArgList &a, bool drained) : drained_(drained)
  {
    const std::string mode = drained ? "shear" : "shear_cv";
    a.need(drained ? 3 : 2, drained ? "shear PLANE GDOT SN" : "shear_cv PLANE GDOT");
    plane_ = programme_detail::plane_of(a, mode);
    rate_ = a.number(mode + " shear rate gamma_dot");
    if (rate_ == 0.0) throw std::invalid_argument(mode + ": shear rate gamma_dot must be non-zero");
    if (drained) normal_ = a.number_in("shear normal stress sigma_n", 0.0, MAX_STRESS, true);
  }
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p = PlaneProgramme::profile();
    // drained: the held sigma_jj and its coupling to gamma_ij alone (docs/theory.md §11.2)
    if (drained_)
      p.stiffness_entries = servo_stiffness_entries(simple_shear());
    else
      p.columns.push_back(out::R_U);
    return p;
  }
  double largest_rate() const override { return std::fabs(rate_); }
  std::vector<NamedRate> constant_rates() const override
  {
    return {{(drained_ ? "shear" : "shear_cv") + std::string(" shear rate gamma_dot"), rate_}};
  }
  std::string held_targets(const Vector6d &s) const override
  {
    using programme_detail::g4;
    return drained_ ? "sig_n = " + g4(normal_stress(s, plane_)) + ", target " + g4(normal_) : "";
  }
  std::string begin_run(const CellState &state, SettingValues &values) override
  {
    PlaneProgramme::begin_run(state, values);
    if (!drained_) require_initial_normal_stress("shear_cv");
    return "";
  }
  MixedControl6 control(const CellState &, SettingValues &) override { return simple_shear(); }
  void outputs(const CellState &state, double *o) const override
  {
    if (!drained_)
      o[out::R_U] =
          pore_pressure_ratio(normal_stress(state.stress, plane_), initial_normal_stress_);
  }

 private:
  MixedControl6 simple_shear() const
  {
    return drained_ ? DrainedSimpleShear{plane_, rate_, normal_}.control()
                    : ConstantVolumeSimpleShear{plane_, rate_}.control();
  }
  bool drained_;
  double rate_, normal_ = 0.0;
};

// cyclic_shear PLANE GDOT CSR: cyclic constant-volume simple shear, gamma_dot = +GDOT first,
// reversed each time tau reaches +-CSR sigma_n0; cycles and N_L (cell_control.hpp)
class CyclicShear : public PlaneProgramme {
 public:
  explicit CyclicShear(ArgList &a)
  {
    a.need(3, "cyclic_shear PLANE GDOT CSR");
    plane_ = programme_detail::plane_of(a, "cyclic_shear");
    args_.read(a, "cyclic_shear", "shear rate gamma_dot", "shears towards +tau");
  }
  bool keyword(const std::string &key, ArgList &a) override
  {
    return args_.keyword(key, a, "shear");
  }
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p = PlaneProgramme::profile();
    p.columns.insert(p.columns.end(), {out::R_U, out::CYCLES, out::N_L_RU, out::N_L_GAMMA});
    return p;
  }
  double largest_rate() const override { return args_.rate; }
  std::vector<NamedRate> constant_rates() const override { return {{args_.rate_name, args_.rate}}; }
  std::string held_targets(const Vector6d &) const override { return ""; }
  std::string begin_run(const CellState &state, SettingValues &values) override
  {
    PlaneProgramme::begin_run(state, values);
    require_initial_normal_stress("cyclic_shear");
    cyclic().require_valid();
    // a test that begins with the shear stress beyond the amplitude reverses at once
    const double tau = shear_stress(state.stress, plane_);
    if (state_.reversals == 0 && state_.direction * tau >= cyclic().amplitude())
      return "cyclic_shear: the shear stress when the test begins, tau = " +
          programme_detail::g4(tau) +
          " (tau/sigma_n0 = " + programme_detail::g4(tau / initial_normal_stress_) +
          "), is at the amplitude CSR "
          "sigma_n0 = " +
          programme_detail::g4(cyclic().amplitude()) +
          " already: the first "
          "half cycle ends at its first step; use a CSR above |tau|/sigma_n0";
    return "";
  }
  MixedControl6 control(const CellState &, SettingValues &) override
  {
    return cyclic().control(state_);
  }
  void after_step(const CellState &s) override
  {
    cyclic().update(state_, shear_stress(s.stress, plane_), -s.strain(plane_.component()),
                    normal_stress(s.stress, plane_));
  }
  void outputs(const CellState &state, double *o) const override
  {
    o[out::R_U] = pore_pressure_ratio(normal_stress(state.stress, plane_), initial_normal_stress_);
    o[out::CYCLES] = cyclic().cycles(state_);
    o[out::N_L_RU] = state_.cycles_to_pore_pressure;
    o[out::N_L_GAMMA] = state_.cycles_to_double_amplitude;
  }
  std::vector<double> state() const override
  {
    std::vector<double> s{initial_normal_stress_};
    s.resize(1 + CyclicSimpleShear::State::size);
    state_.to_array(s.data() + 1);
    return s;
  }
  void restore(const std::vector<double> &s) override
  {
    initial_normal_stress_ = s[0];
    state_ = CyclicSimpleShear::State::from_array(s.data() + 1);
  }

 private:
  CyclicSimpleShear cyclic() const
  {
    return {plane_, args_.rate, args_.csr, initial_normal_stress_, args_.criteria};
  }
  CyclicArguments args_;
  CyclicSimpleShear::State state_;
};

// stress_rotation PLANE P Q B ALPHA_DOT: sigma1 = P + (2 - B)Q/3 turning in PLANE at ALPHA_DOT
// degrees per second from the angle `start_angle`, sigma3 in the plane at right angles, sigma2
// along the third axis; all six components stress controlled
class StressRotation : public PlaneProgramme {
 public:
  // the largest turn of the principal direction in a step: a target that turns by more is no
  // stress path the servo, which removes a few per cent of its error per step, can follow
  static constexpr double MAX_DEGREES_PER_STEP = 1.0;
  explicit StressRotation(ArgList &a)
  {
    a.need(5, "stress_rotation PLANE P Q B ALPHA_DOT");
    plane_ = programme_detail::plane_of(a, "stress_rotation");
    r_.i = plane_.direction, r_.j = plane_.normal;
    r_.mean_stress = a.stress("stress_rotation mean stress p");
    r_.deviatoric_stress = a.number_in("stress_rotation Q = sigma1 - sigma3", 0.0, MAX_STRESS, true,
                                       " Pa (Q = 0 is an isotropic stress, which has no "
                                       "direction to turn)");
    r_.b = a.number_in("stress_rotation b", 0.0, 1.0, false);
    r_.rotation_rate_deg = a.number("stress_rotation rate ALPHA_DOT (degrees per second)");
    // sigma_3 = p - (1 + b) Q/3 must stay compressive
    if (!(r_.mean_stress - (1.0 + r_.b) * r_.deviatoric_stress / 3.0 > 0.0))
      throw std::invalid_argument(
          "stress_rotation: Q = " + g_text(r_.deviatoric_stress) +
          " at p = " + g_text(r_.mean_stress) + " and b = " + g_text(r_.b) +
          " puts the minor principal "
          "stress p - (1 + b) Q/3 in tension (a granular cell carries none): use Q < " +
          g_text(3.0 * r_.mean_stress / (1.0 + r_.b)));
  }
  bool keyword(const std::string &key, ArgList &a) override
  {
    if (key != "start_angle") return false;
    r_.initial_angle_deg = a.number_in(key, -360.0, 360.0, false, " degrees");
    return true;
  }
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p = PlaneProgramme::profile();
    p.strains_shear = {true, true, true};
    p.holds_shear_stress = true;
    p.mean_stress = r_.mean_stress;
    return p;
  }
  double largest_rate() const override { return 0.0; }
  std::vector<NamedRate> constant_rates() const override { return {}; }
  std::string held_targets(const Vector6d &s) const override
  {
    return programme_detail::held_mean_stress(s, r_.mean_stress);
  }
  std::string begin_run(const CellState &state, SettingValues &values) override
  {
    PlaneProgramme::begin_run(state, values);
    const double per_step = std::fabs(r_.rotation_rate_deg) * state.dt;
    if (per_step > MAX_DEGREES_PER_STEP)
      throw std::invalid_argument(
          "stress_rotation: ALPHA_DOT = " + g_text(r_.rotation_rate_deg) +
          " degrees per second "
          "turns the principal direction by " +
          programme_detail::g4(per_step) +
          " degrees per "
          "step (timestep " +
          programme_detail::g4(state.dt) + "), more than the " + g_text(MAX_DEGREES_PER_STEP) +
          " a servo can follow: use |ALPHA_DOT| <= " +
          programme_detail::g4(MAX_DEGREES_PER_STEP / state.dt) + " degrees per second");
    return "";
  }
  MixedControl6 control(const CellState &state, SettingValues &) override
  {
    return r_.control(state.time);
  }

 private:
  PrincipalStressRotation r_;
};

// ---------------------------------------------------------------------------------------------
// undrained AXIS RATE: undrained (constant-volume) triaxial test, the lateral axes at -RATE/2
// plus the servo's difference that holds sigma2 = sigma3 (cell_control.hpp)

class UndrainedTriaxialTest : public CellProgramme {
 public:
  explicit UndrainedTriaxialTest(ArgList &a)
  {
    a.need(2, "undrained AXIS RATE");
    axis_ = programme_detail::axis_of(a, "undrained");
    rate_ = programme_detail::nonzero_rate(a, "undrained axial strain rate",
                                           " (> 0 compression, < 0 extension)");
  }
  ProgrammeProfile profile() const override { return {}; }
  std::vector<Setting *> settings() override { return {&rate_}; }
  double largest_rate() const override { return std::fabs(rate_.value); }
  std::vector<NamedRate> constant_rates() const override
  {
    std::vector<NamedRate> r;
    programme_detail::add_constant(r, rate_);
    return r;
  }
  std::string held_targets(const Vector6d &s) const override
  {
    return "sig2 - sig3 = " + programme_detail::g4(s((axis_ + 1) % 3) - s((axis_ + 2) % 3)) +
        ", target 0";
  }
  std::string begin_run(const CellState &, SettingValues &values) override
  {
    if (rate_.is_variable()) values(rate_);
    return "";
  }
  MixedControl6 control(const CellState &, SettingValues &values) override
  {
    return UndrainedTriaxial{axis_, values(rate_)}.control();
  }

 private:
  int axis_;
  Setting rate_;
};

// ---------------------------------------------------------------------------------------------
// The laboratory tests along an axis (docs/theory.md §13): k0 and cyclic_triaxial report the
// axial strain and stress, the radial stress and the signed deviator of their axis, and a
// restart must be on the same axis

class AxialTest : public CellProgramme {
 public:
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p;
    p.columns = out::axial_columns();
    return p;
  }
  void outputs(const CellState &state, double *o) const override
  {
    o[out::EPS_A] = state.strain(axis_);
    o[out::SIG_A] = state.stress(axis_);
    o[out::SIG_R] = radial_stress(state.stress, axis_);
    o[out::Q_A] = axial_deviator(state.stress, axis_);
  }
  std::vector<double> identity() const override { return {double(axis_)}; }
  std::string identity_mismatch() const override
  {
    return std::string("the restart file was written by a run along another axis; this one "
                       "loads ") +
        axis_name(axis_) +
        ": resume it along the same axis, or "
        "define the fix under a new ID";
  }

 protected:
  int axis_ = 2;
};

// k0 AXIS RATE SIGMA_MAX [ocr R]: oedometric compression, the lateral strains and the shears
// held at zero, the axis at RATE until sigma_a reaches SIGMA_MAX, then (ocr R > 1) unloading at
// -RATE until OCR = (largest sigma_a)/sigma_a reaches R; then the cell rests (progress 1)
class OedometerTest : public AxialTest {
 public:
  explicit OedometerTest(ArgList &a)
  {
    a.need(3, "k0 AXIS RATE SIGMA_MAX");
    axis_ = programme_detail::axis_of(a, "k0");
    rate_ = a.number("k0 axial strain rate");
    if (!(rate_ > 0.0))
      throw std::invalid_argument("k0 axial strain rate = " + number_text(rate_) +
                                  " must be "
                                  "positive (loading compresses the axis; the unloading of "
                                  "keyword 'ocr' runs at -RATE)");
    course_.peak = a.stress("k0 largest axial stress SIGMA_MAX");
  }
  bool keyword(const std::string &key, ArgList &a) override
  {
    if (key != "ocr") return false;
    course_.ocr = a.number_in(key, 1.0, 1e6, false,
                              " (SIGMA_MAX/sigma_a at the end of "
                              "unloading; 1: no unloading)");
    return true;
  }
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p = AxialTest::profile();
    p.stiffness_entries = 0u;    // no held stress: no servo
    p.columns.insert(p.columns.end(), {out::K0, out::K0_INC, out::OCR});
    return p;
  }
  double largest_rate() const override { return rate_; }
  std::vector<NamedRate> constant_rates() const override
  {
    return {{"k0 axial strain rate", rate_}};
  }
  std::string held_targets(const Vector6d &) const override { return ""; }
  std::string begin_run(const CellState &state, SettingValues &) override
  {
    if (!std::isnan(state_.axial0)) return "";
    const double axial = state.stress(axis_);
    if (!(axial < course_.peak))
      throw std::invalid_argument(
          "k0: the axial stress sigma_" + std::string(axis_name(axis_)) + " is " +
          programme_detail::g4(axial) + " when the test begins, not below SIGMA_MAX = " +
          programme_detail::g4(course_.peak) + ": give a SIGMA_MAX above it");
    state_ = course_.begin(axial, radial_stress(state.stress, axis_));
    return "";
  }
  MixedControl6 control(const CellState &, SettingValues &) override
  {
    return OedometricCompression{axis_, state_.direction * rate_}.control();
  }
  void after_step(const CellState &s) override { course_.update(state_, s.stress(axis_)); }
  void outputs(const CellState &state, double *o) const override
  {
    constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
    AxialTest::outputs(state, o);
    const double axial = o[out::SIG_A], radial = o[out::SIG_R];
    o[out::K0] = axial > 0.0 ? radial / axial : NaN;
    o[out::K0_INC] = axial != state_.axial0 ? (radial - state_.radial0) / (axial - state_.axial0)
                                            : NaN;
    o[out::OCR] = axial > 0.0 ? std::max(state_.largest, axial) / axial : NaN;
    axial_now_ = axial;
  }
  // the course with this step's sigma_a: 1 at the step that ends it
  double progress() const override
  {
    OedometerCourse::State now = state_;
    if (!std::isnan(axial_now_)) course_.update(now, axial_now_);
    return course_.progress(now);
  }
  std::vector<double> state() const override { return state_.to_vector(); }
  void restore(const std::vector<double> &s) override
  {
    state_ = OedometerCourse::State::from_array(s.data());
  }

 private:
  double rate_;
  OedometerCourse course_{0.0};
  OedometerCourse::State state_;
  mutable double axial_now_ = std::numeric_limits<double>::quiet_NaN();    // of outputs()
};

// cyclic_triaxial AXIS RATE CSR: undrained cyclic triaxial test, eps_v = 0 and sigma_b = sigma_c
// as `undrained`, the axial rate +RATE first (compression), reversed each time q_a reaches
// +2 CSR p0 and -2 CSR p0 (keyword one_way yes: 0); r_u = 1 - p/p0, cycles and N_L
class CyclicTriaxial : public AxialTest {
 public:
  explicit CyclicTriaxial(ArgList &a)
  {
    a.need(3, "cyclic_triaxial AXIS RATE CSR");
    axis_ = programme_detail::axis_of(a, "cyclic_triaxial");
    args_.read(a, "cyclic_triaxial", "axial strain rate", "compresses the axis");
  }
  bool keyword(const std::string &key, ArgList &a) override
  {
    if (key != "one_way") return args_.keyword(key, a, "axial");
    one_way_ = a.yes_no(key);
    return true;
  }
  ProgrammeProfile profile() const override
  {
    ProgrammeProfile p = AxialTest::profile();
    p.stiffness_entries = servo_stiffness_entries(cyclic().control({}));
    p.columns.insert(p.columns.end(), {out::R_U, out::CYCLES, out::N_L_RU, out::N_L_EPS});
    return p;
  }
  double largest_rate() const override { return args_.rate; }
  std::vector<NamedRate> constant_rates() const override { return {{args_.rate_name, args_.rate}}; }
  std::string held_targets(const Vector6d &s) const override
  {
    return "sig2 - sig3 = " + programme_detail::g4(s((axis_ + 1) % 3) - s((axis_ + 2) % 3)) +
        ", target 0";
  }
  std::string begin_run(const CellState &state, SettingValues &) override
  {
    if (std::isnan(p0_)) p0_ = mean_stress(state.stress.head<3>());
    if (!(p0_ > 0.0))
      throw std::invalid_argument("cyclic_triaxial: the mean stress is " +
                                  programme_detail::g4(p0_) +
                                  " when the test begins (p0), so r_u = 1 - p/p0 is undefined: "
                                  "load the specimen first (e.g. fix cell/servo iso P)");
    const double q = axial_deviator(state.stress, axis_);
    if (count_.reversals == 0 && q >= cyclic().amplitude())
      return "cyclic_triaxial: the deviator when the test begins, q_a = " +
          programme_detail::g4(q) +
          ", is at the amplitude 2 CSR p0 = " + programme_detail::g4(cyclic().amplitude()) +
          " already: the first half cycle ends at its first step; use a CSR above "
          "q_a/(2 p0) = " +
          programme_detail::g4(q / (2.0 * p0_));
    return "";
  }
  MixedControl6 control(const CellState &, SettingValues &) override
  {
    return cyclic().control(count_);
  }
  void after_step(const CellState &s) override { cyclic().update(count_, s.stress, s.strain); }
  void outputs(const CellState &state, double *o) const override
  {
    AxialTest::outputs(state, o);
    o[out::R_U] = cyclic().pore_pressure_ratio_of(state.stress);
    o[out::CYCLES] = count_.cycles();
    o[out::N_L_RU] = count_.cycles_to_pore_pressure;
    o[out::N_L_EPS] = count_.cycles_to_double_amplitude;
  }
  std::vector<double> state() const override
  {
    std::vector<double> s{p0_};
    s.resize(1 + CycleCount::size);
    count_.to_array(s.data() + 1);
    return s;
  }
  void restore(const std::vector<double> &s) override
  {
    p0_ = s[0];
    count_ = CycleCount::from_array(s.data() + 1);
  }
  // a redefinition continuing the test along the same axis takes p0 over
  std::vector<double> carried() const override { return {CARRY_TAG + axis_, p0_}; }
  void take_carried(const std::vector<double> &c) override
  {
    if (c.size() == 2 && c[0] == CARRY_TAG + axis_) p0_ = c[1];
  }

 private:
  static constexpr double CARRY_TAG = 100.0;    // (a plane programme carries its component)
  CyclicUndrainedTriaxial cyclic() const
  {
    return {axis_, args_.rate, args_.csr, p0_, one_way_, args_.criteria};
  }
  CyclicArguments args_{LiquefactionCriteria{0.95, 0.05}};
  double p0_ = std::numeric_limits<double>::quiet_NaN();
  bool one_way_ = false;
  CycleCount count_;
};

// ---------------------------------------------------------------------------------------------
// The registry: one row per MODE word

struct ProgrammeKind {
  const char *name;     // the MODE word
  int restart_id;       // its number in restart records: never reused
  const char *usage;    // its arguments
  std::function<std::unique_ptr<CellProgramme>(ArgList &)> parse;
  std::vector<std::string> keywords;    // its own keywords
};

inline const std::vector<ProgrammeKind> &programme_kinds()
{
  using P = std::unique_ptr<CellProgramme>;
  using Path = PiPlanePath::Kind;
  static const std::vector<std::string> path_keywords{"speed", "rotation", "measure",
                                                      "prestrain_leg", "plane_strain"};
  // clang-format off
  static const std::vector<ProgrammeKind> kinds{
      {"iso", 0, "iso P", [](ArgList& a) -> P { return std::make_unique<IsotropicCompression>(a); },
       {"equilibrium", "eq_stress", "eq_unbalanced", "eq_kinetic", "eq_coordination",
        "eq_window"}},
      {"axes", 1, "axes x C V y C V z C V [xy C V] [xz C V] [yz C V]",
       [](ArgList& a) -> P { return std::make_unique<PerComponent>(a); }, {}},
      {"axisym", 2, "axisym AXIS RATE P",
       [](ArgList& a) -> P { return std::make_unique<MajorAxisProgramme>(a, false); }, {}},
      {"constant_b", 3, "constant_b B AXIS RATE P",
       [](ArgList& a) -> P { return std::make_unique<MajorAxisProgramme>(a, true); }, {}},
      {"deviatoric", 4, "deviatoric R1 R2 R3 P",
       [](ArgList& a) -> P { return std::make_unique<DeviatoricStrainRate>(a); }, {}},
      {"circle", 5, "circle PRESTRAIN P",
       [](ArgList& a) -> P { return std::make_unique<PiPlanePath>(a, Path::CIRCLE); },
       {"speed", "rotation", "measure", "prestrain_leg", "sweep"}},
      {"triangle", 5, "triangle PRESTRAIN P",
       [](ArgList& a) -> P { return std::make_unique<PiPlanePath>(a, Path::TRIANGLE); },
       path_keywords},
      {"polygon", 5, "polygon N x1 y1 ... xN yN P",
       [](ArgList& a) -> P { return std::make_unique<PiPlanePath>(a, Path::POLYGON); },
       {"speed", "close", "plane_strain"}},
      {"shear", 6, "shear PLANE GDOT SN",
       [](ArgList& a) -> P { return std::make_unique<SimpleShear>(a, true); }, {}},
      {"shear_cv", 7, "shear_cv PLANE GDOT",
       [](ArgList& a) -> P { return std::make_unique<SimpleShear>(a, false); }, {}},
      {"cyclic_shear", 8, "cyclic_shear PLANE GDOT CSR",
       [](ArgList& a) -> P { return std::make_unique<CyclicShear>(a); },
       {"ru_limit", "da_limit"}},
      {"undrained", 9, "undrained AXIS RATE",
       [](ArgList& a) -> P { return std::make_unique<UndrainedTriaxialTest>(a); }, {}},
      {"stress_rotation", 10, "stress_rotation PLANE P Q B ALPHA_DOT",
       [](ArgList& a) -> P { return std::make_unique<StressRotation>(a); }, {"start_angle"}},
      {"k0", 11, "k0 AXIS RATE SIGMA_MAX",
       [](ArgList& a) -> P { return std::make_unique<OedometerTest>(a); }, {"ocr"}},
      {"cyclic_triaxial", 12, "cyclic_triaxial AXIS RATE CSR",
       [](ArgList& a) -> P { return std::make_unique<CyclicTriaxial>(a); },
       {"ru_limit", "da_limit", "one_way"}},
  };
  // clang-format on
  return kinds;
}

// words that were MODEs or keywords once, and what to write instead
inline std::string renamed(const std::string &word)
{
  if (word == "rotation")
    return "the mode 'rotation PLANE P Q B DEG' is now 'stress_rotation PLANE P Q B ALPHA_DOT' "
           "(ALPHA_DOT: the rate at which sigma1 turns, degrees per second); 'rotation cw|ccw' "
           "is the keyword of a Pi-plane path's sense of travel";
  if (word == "angle")
    return "keyword 'angle' is now 'start_angle' (stress_rotation: the angle of sigma1 when "
           "the test starts, degrees)";
  return "";
}

// the MODE words, separated by `separator`
inline std::string mode_names(const std::string &separator)
{
  std::string names;
  for (const ProgrammeKind &kind : programme_kinds())
    names += (names.empty() ? "" : separator) + std::string(kind.name);
  return names;
}

// the programme of `MODE args` at the front of a (the MODE word read)
inline std::unique_ptr<CellProgramme> parse_programme(ArgList &a)
{
  const std::string mode = a.next("MODE");
  for (const ProgrammeKind &kind : programme_kinds())
    if (mode == kind.name) {
      std::unique_ptr<CellProgramme> p = kind.parse(a);
      p->set_kind(kind.name, kind.restart_id);
      return p;
    }
  const std::string old = renamed(mode);
  if (!old.empty()) throw std::invalid_argument(old);
  throw std::invalid_argument("unknown mode '" + mode + "' (expected " + mode_names(", ") + ")");
}

// the programmes a keyword belongs to ("" if none): for the message of a keyword given to
// another programme
inline std::string owners_of(const std::string &key)
{
  std::vector<std::string> owners;
  for (const ProgrammeKind &kind : programme_kinds())
    for (const std::string &k : kind.keywords)
      if (k == key) owners.push_back(kind.name);
  std::string text;
  for (std::size_t k = 0; k < owners.size(); ++k)
    text += (k == 0 ? "" : k + 1 == owners.size() ? " and " : ", ") + owners[k];
  return text;
}

}    // namespace tycore

#endif
