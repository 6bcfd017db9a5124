// Stress servo of a deformable orthogonal periodic cell (docs/theory.md §6; paper sections
// 2-5). Plain data in, principal strain rates out; every piece of memory is in ServoMemory.
//
// Conventions: principal axes = box axes (index 0, 1, 2 = x, y, z); stresses (Love-Weber,
// pair virial only) and natural strains eps_i = -ln(L_i/L_i0) are compression positive, and so
// are strain rates (a positive rate shortens the box edge).
//
// Mixed control (docs/theory.md §6.2). Each step the strain rate is
//     deps/dt = r_p + W u / dt,
// where r_p is the prescribed (strain-controlled) part and the columns w_k of W are the m
// strain-rate patterns ("actuators") the servo may use, with amplitudes u (strain per step).
// The servo holds m linear combinations of the principal stresses at targets, A sigma = t
// (rows a_k). With the affine stiffness C (d sigma = C d eps, see affine_stiffness) the
// predicted change of A sigma over one step is A C (r_p dt + W u), and u is chosen so that
//     (A C W) u = g (t - A sigma) + g_I S - A C r_p dt     (proportional + integral,
//     S <- S + (t - A sigma)                                  affine feed-forward)
// i.e. eps_dot = [g (sigma* - sigma) + g_I S]/(K dt) in the one-axis case. The errors, and the
// accumulated error S (kept in stress units), are normalised by the current stiffness, so the
// gains are dimensionless fractions per step and one setting serves every stress level, and
// S keeps its meaning when the stiffness grows by orders of magnitude during compaction. The
// affine estimate exceeds the true (relaxed) stiffness of a granular packing, K = r C with
// r <= 1: the proportional loop then removes a constant error geometrically (factor 1 - r g
// per step) without overshoot and leaves a lag e = d/(r g) behind a steady drift of d per step
// (creep, dilatancy). The integral removes that lag; the closed loop z^2 - (2 - r g - r g_I) z
// + 1 - r g has poles of modulus sqrt(1 - r g) < 1 for every r in (0, 1]. S only accumulates
// while every error lies within integral_band of the stress level (a large approach, e.g.
// preparation from a gas, is proportional only) and is frozen while the cap is active. The
// servo part W u/dt is scaled down as a whole when an axis would exceed max_strain_rate; the
// prescribed part is never altered.
//
// The composite programmes of the paper are mixed controls:
//   isotropic compression to p*      all axes stress-controlled, sigma_i = p*
//   per-axis control                 axis i prescribed rate or sigma_i = sigma_i*
//   constant p, deviatoric rate e'   r_p = e', one actuator w = (1,1,1), a = (1,1,1)/3
//   constant p and b, axis 1 rate    r_p on axis 1, actuators axes 2 and 3, rows p and b
//                                    (equivalent to the targets of constant_b_targets)
#ifndef TYCORE_CELL_SERVO_HPP
#define TYCORE_CELL_SERVO_HPP

#include "affine_stiffness_entries.hpp"
#include "cell_kinematics.hpp"
#include "pi_plane.hpp"
#include "strain_path.hpp"

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

namespace tycore {

enum class AxisControl { STRAIN_RATE, STRESS };

inline const char *axis_name(int axis)
{
  return axis == 0 ? "x" : axis == 1 ? "y" : "z";
}

// a number in a message: 6 significant digits (std::to_string writes 1e300 in 301 digits)
inline std::string number_text(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// ---------------------------------------------------------------------------------------------
// Input checks; messages name the offending quantity so the fix can pass them on

inline void require_positive_stress(const std::string &name, double value)
{
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::invalid_argument("target stress " + name + " = " + number_text(value) +
                                " must be positive (a granular cell carries no tension)");
}

inline void require_b_in_range(double b)
{
  if (!(b >= 0.0 && b <= 1.0))
    throw std::invalid_argument("b = " + number_text(b) + " is outside [0, 1]");
}

// ---------------------------------------------------------------------------------------------
// Stiffness estimate (docs/theory.md §6.1): affine stiffness C_ij = d sigma_i / d eps_j of a
// homogeneous principal strain, C_ij = (1/V) sum_c l^2 [k_N n_i^2 n_j^2
// + k_T (delta_ij n_i^2 - n_i^2 n_j^2)], l = |branch|, n = branch/l. Its diagonal with k_T = 0
// is K_i = (1/V) sum_c k_N (n_i l_i)^2. The normal part alone already gives the exact affine
// bulk stiffness (the tangential part carries no volume change).

// C from the summed contributions, given as 6 numbers in LAMMPS virial order
// (11, 22, 33, 12, 13, 23), and the cell volume
inline Eigen::Matrix3d affine_stiffness(const double sums[6], double volume)
{
  Eigen::Matrix3d c;
  // clang-format off
  c << sums[0], sums[3], sums[4],
       sums[3], sums[1], sums[5],
       sums[4], sums[5], sums[2];
  // clang-format on
  return c / volume;
}

// one contact's share of V*C, branch = x2 - x1 (image-shifted); sum over contacts, each once
// (the formula: affine_stiffness_entries.hpp)
inline Eigen::Matrix3d affine_stiffness_contribution(const Eigen::Vector3d &branch,
                                                     double normal_stiffness,
                                                     double tangential_stiffness = 0.0)
{
  const double l2 = branch.squaredNorm();
  const Eigen::Vector3d n = branch / std::sqrt(l2);
  double sums[6];
  affine_principal_entries(n(0), n(1), n(2), l2, normal_stiffness, tangential_stiffness,
                           [&sums](int m, double value) {
                             sums[m] = value;
                           });
  return affine_stiffness(sums, 1.0);
}

// strain rate at inertial number I: I = eps_dot d sqrt(rho/p)
// (docs/theory.md §4.2, GDR MiDi 2004)
inline double quasi_static_strain_rate(double inertial_number, double mean_stress,
                                       double mean_diameter, double density)
{
  return inertial_number * std::sqrt(mean_stress / density) / mean_diameter;
}

// ---------------------------------------------------------------------------------------------
// Data the fix exchanges with the servo

// The cell's state and the servo's data, on N controlled components: N = 3 for the principal
// axes of an orthogonal cell, N = 6 for the full stress and strain of a triclinic cell (Voigt6
// order xx yy zz xy xz yz, engineering shears; cell_kinematics.hpp, docs/theory.md §11.2)
template <int N> using VectorN = Eigen::Matrix<double, N, 1>;
template <int N> using MatrixN = Eigen::Matrix<double, N, N>;

template <int N> struct CellMeasurementOf {
  VectorN<N> stress;       // compression positive [Pa]; principal stresses along x, y, z if N = 3
  MatrixN<N> stiffness;    // affine stiffness C [Pa]
  VectorN<N> strain;       // strains from the reference cell, compression positive
};
using CellMeasurement = CellMeasurementOf<3>;

// A principal strain of 1 % in one step is no laboratory test: at a quasi-static inertial
// number (I < 1e-3, docs/theory.md) a step strains a packing by ~1e-6; beyond this the contacts
// of one step overlap by a sizeable fraction of a radius and the cell edges may collapse
constexpr double MAX_STRAIN_PER_STEP = 0.01;

struct ServoSettings {
  // fraction of the stress error removed per step; the error keeps its sign as long as the
  // instantaneous stiffness is below 1/gain = 4 times the estimate
  double gain = 0.25;
  // per step, on the accumulated error; below gain^2/4 the closed-loop poles stay real when
  // the estimate is exact, and the lag behind a steady drift decays in ~gain/integral_gain steps
  double integral_gain = 0.005;
  // the integral accumulates only while every |error| <= integral_band * stress level
  double integral_band = 0.05;
  double max_strain_rate = 0.0;    // cap on each axis' servo rate [1/s]; must be set
};

template <int N> struct ServoMemoryOf {
  VectorN<N> integral = VectorN<N>::Zero();            // S [Pa], one per held stress
  VectorN<N> last_strain_rate = VectorN<N>::Zero();    // rate commanded last step

  static constexpr int size = 2 * N;
  void to_array(double *a) const
  {
    for (int i = 0; i < N; ++i) a[i] = integral(i), a[N + i] = last_strain_rate(i);
  }
  static ServoMemoryOf from_array(const double *a)
  {
    ServoMemoryOf m;
    for (int i = 0; i < N; ++i) m.integral(i) = a[i], m.last_strain_rate(i) = a[N + i];
    return m;
  }
};
using ServoMemory = ServoMemoryOf<3>;

template <int N> struct MixedControlOf {
  VectorN<N> prescribed_strain_rate = VectorN<N>::Zero();    // r_p [1/s]
  int actuator_count = 0;                                    // m
  MatrixN<N> actuators = MatrixN<N>::Zero();                 // columns 0..m-1: w_k
  MatrixN<N> stress_rows = MatrixN<N>::Zero();               // rows 0..m-1: a_k
  VectorN<N> stress_targets = VectorN<N>::Zero();            // t_k [Pa]

  void add(const VectorN<N> &actuator, const VectorN<N> &row, double target)
  {
    if (actuator_count == N)
      throw std::invalid_argument("more held stresses than controlled components");
    actuators.col(actuator_count) = actuator;
    stress_rows.row(actuator_count) = row.transpose();
    stress_targets(actuator_count) = target;
    ++actuator_count;
  }
};
using MixedControl = MixedControlOf<3>;

template <int N> struct ServoCommandOf {
  VectorN<N> strain_rate;       // strain rates for the next step [1/s]
  bool saturated;               // the strain-rate cap limited the servo part
  double stress_error = 0.0;    // largest |target - stress| of the held stresses [Pa]
};
using ServoCommand = ServoCommandOf<3>;

// ---------------------------------------------------------------------------------------------
// Programmes

// sigma3* = (3p - (1+b) sigma1)/(2 - b),  sigma2* = 3p - sigma1 - sigma3*   (docs/theory.md §6.3)
inline Eigen::Vector2d constant_b_targets(double major_stress, double mean_stress, double b)
{
  require_b_in_range(b);
  const double minor = (3.0 * mean_stress - (1.0 + b) * major_stress) / (2.0 - b);
  return {3.0 * mean_stress - major_stress - minor, minor};
}

struct AxisProgramme {
  AxisControl control;
  double value;    // strain rate [1/s] or target stress [Pa]
};

// each component at a prescribed strain rate or a target stress; N = 3: the principal axes
// (targets positive), N = 6: also the shears of a triclinic cell (targets of any sign)
template <std::size_t N = 3>
MixedControlOf<int(N)> per_axis_control(const std::array<AxisProgramme, N> &components)
{
  MixedControlOf<int(N)> c;
  for (int i = 0; i < int(N); ++i) {
    const VectorN<int(N)> unit = VectorN<int(N)>::Unit(i);
    const double value = components[i].value;
    if (components[i].control == AxisControl::STRAIN_RATE) {
      c.prescribed_strain_rate(i) = value;
      continue;
    }
    if (i < 3)
      require_positive_stress(std::string("sigma_") + axis_name(i), value);
    else if (!std::isfinite(value))
      throw std::invalid_argument(std::string("target shear stress sigma_") + voigt_names[i] +
                                  " is not finite");
    c.add(unit, unit, value);
  }
  return c;
}

inline MixedControl isotropic_compression_control(double mean_stress)
{
  const AxisProgramme held{AxisControl::STRESS, mean_stress};
  return per_axis_control({held, held, held});
}

// constant p with a prescribed deviatoric strain rate: deps/dt = e' + (eps_v'/3) 1
inline MixedControl mean_stress_control(double mean_stress,
                                        const Eigen::Vector3d &deviatoric_strain_rate)
{
  require_positive_stress("p", mean_stress);
  MixedControl c;
  c.prescribed_strain_rate = deviator(deviatoric_strain_rate);
  c.add(Eigen::Vector3d::Ones(), Eigen::Vector3d::Constant(1.0 / 3.0), mean_stress);
  return c;
}

// constant p and b with the major axis strain-controlled; the b row is
// (sigma_int - sigma_min) - b (sigma_maj - sigma_min) = 0   (paper eq. 1)
inline MixedControl constant_b_control(double mean_stress, double b, double major_strain_rate,
                                       int major = 0, int intermediate = 1, int minor = 2)
{
  require_positive_stress("p", mean_stress);
  require_b_in_range(b);
  if (major == intermediate || major == minor || intermediate == minor)
    throw std::invalid_argument("constant-b control needs three distinct axes");
  Eigen::Vector3d b_row = Eigen::Vector3d::Zero();
  b_row(major) = -b;
  b_row(intermediate) = 1.0;
  b_row(minor) = -(1.0 - b);
  MixedControl c;
  c.prescribed_strain_rate(major) = major_strain_rate;
  c.add(Eigen::Vector3d::Unit(intermediate), Eigen::Vector3d::Constant(1.0 / 3.0), mean_stress);
  c.add(Eigen::Vector3d::Unit(minor), b_row, 0.0);
  return c;
}

// axisymmetric test at constant p: the axial rate is prescribed (> 0 compression, < 0
// extension), the two lateral stresses are kept equal
inline MixedControl axisymmetric_control(int axis, double axial_strain_rate, double mean_stress)
{
  require_axis_index(axis);
  return constant_b_control(mean_stress, 0.0, axial_strain_rate, axis, (axis + 1) % 3,
                            (axis + 2) % 3);
}

// the free axes must be able to move every held stress combination
template <int N> void require_controllable(const MixedControlOf<N> &c)
{
  const int m = c.actuator_count;
  if (m == 0) return;
  const Eigen::MatrixXd response = c.stress_rows.topRows(m) * c.actuators.leftCols(m);
  if (Eigen::FullPivLU<Eigen::MatrixXd>(response).rank() < m)
    throw std::invalid_argument("the held stresses cannot all be reached with the free axes: "
                                "some stress target has no strain-controlled freedom");
}

inline void require_valid(const ServoSettings &s)
{
  if (!(s.gain > 0.0 && s.gain <= 1.0))
    throw std::invalid_argument("servo gain " + number_text(s.gain) + " is outside (0, 1]");
  if (!(s.integral_gain >= 0.0 && s.integral_gain <= 0.25 * s.gain * s.gain))
    throw std::invalid_argument("servo integral gain " + number_text(s.integral_gain) +
                                " must lie in [0, gain^2/4] (larger values overshoot)");
  if (!(s.integral_band >= 0.0))
    throw std::invalid_argument("servo integral band must not be negative");
  if (!(s.max_strain_rate > 0.0))
    throw std::invalid_argument("servo maximum strain rate " + number_text(s.max_strain_rate) +
                                " must be positive");
}

// ---------------------------------------------------------------------------------------------
// The control law (see the header comment; docs/theory.md §6.2)

namespace detail {

  // The components a control works on: every normal component, and a shear (N = 6) that it
  // prescribes a rate, moves or holds a stress of. A shear outside the programme does not set the
  // scale of the stiffness floor, so that a principal programme is stepped on six components to
  // the same numbers as on three (docs/theory.md §11.2).
  template <int N> std::array<bool, N> used_components(const MixedControlOf<N> &c)
  {
    std::array<bool, N> used;
    for (int j = 0; j < N; ++j)
      used[j] = j < 3 || c.prescribed_strain_rate(j) != 0.0 || c.actuators.row(j).any() ||
          c.stress_rows.col(j).any();
    return used;
  }

  // the largest stiffness, stress and target of the used components: the scale of the floor
  template <int N>
  double floor_scale(const MixedControlOf<N> &control, const CellMeasurementOf<N> &cell)
  {
    const std::array<bool, N> used = used_components(control);
    double scale = control.stress_targets.cwiseAbs().maxCoeff();
    for (int i = 0; i < N; ++i) {
      if (!used[i]) continue;
      scale = std::max(scale, std::abs(cell.stress(i)));
      for (int j = 0; j < N; ++j)
        if (used[j]) scale = std::max(scale, std::abs(cell.stiffness(i, j)));
    }
    return scale;
  }

  // Rate floor (docs/theory.md §6.2): an actuator that moves no held stress, because no
  // contact carries load along it (an axis of a loose specimen that no contact crosses),
  // would be normalised by the stiffness floor alone, and the cap, which scales the servo
  // part as a whole, would freeze every other axis behind it. Such an actuator moves at the
  // cap towards its target (the sign of its error times its row's weight on it), and the
  // loaded actuators are servoed among themselves. Returns the floor's strain rates and marks
  // the unloaded actuators.
  template <int N>
  VectorN<N> unloaded_actuator_rates(const MixedControlOf<N> &control,
                                     const CellMeasurementOf<N> &cell,
                                     const ServoSettings &settings, double floor,
                                     std::array<bool, N> &unloaded)
  {
    const MatrixN<N> raw_response = control.stress_rows * cell.stiffness * control.actuators;
    VectorN<N> floor_rate = VectorN<N>::Zero();
    for (int k = 0; k < control.actuator_count; ++k) {
      unloaded[k] = raw_response.col(k).cwiseAbs().maxCoeff() <= floor;
      const double pull = control.stress_rows.row(k).dot(control.actuators.col(k)) *
          (control.stress_targets(k) - control.stress_rows.row(k).dot(cell.stress));
      if (unloaded[k] && pull != 0.0)
        floor_rate += (pull > 0.0 ? 1.0 : -1.0) * settings.max_strain_rate *
            control.actuators.col(k) / control.actuators.col(k).cwiseAbs().maxCoeff();
    }
    return floor_rate;
  }

  // the loaded actuators' system (A C W) u = g e - A C r_p dt + g_I S, padded to NxN with
  // identity on unused and unloaded actuators so that one fixed-size solve serves all m
  template <int N> struct LoadedServoSystem {
    MatrixN<N> response = MatrixN<N>::Identity();    // A C W
    VectorN<N> error = VectorN<N>::Zero();           // e = t - A sigma
    VectorN<N> feed_forward = VectorN<N>::Zero();    // A C r_p dt
    VectorN<N> held_integral;                        // S of the last step
    double stress_error = 0.0;                       // largest |e| of the held stresses
  };

  // C has the stiffness floor on its diagonal
  template <int N>
  LoadedServoSystem<N> loaded_servo_system(const MixedControlOf<N> &control,
                                           const CellMeasurementOf<N> &cell, double floor,
                                           double dt, const VectorN<N> &integral,
                                           const std::array<bool, N> &unloaded)
  {
    const int m = control.actuator_count;
    const MatrixN<N> C = cell.stiffness + floor * MatrixN<N>::Identity();
    const VectorN<N> prescribed_step = control.prescribed_strain_rate * dt;
    LoadedServoSystem<N> s;
    s.response.topLeftCorner(m, m) =
        control.stress_rows.topRows(m) * C * control.actuators.leftCols(m);
    s.error.head(m) = control.stress_targets.head(m) - control.stress_rows.topRows(m) * cell.stress;
    for (int k = 0; k < m; ++k) s.stress_error = std::max(s.stress_error, std::abs(s.error(k)));
    s.feed_forward.head(m) = control.stress_rows.topRows(m) * C * prescribed_step;
    s.held_integral = integral;
    for (int k = 0; k < m; ++k)
      if (unloaded[k]) {    // out of the loaded actuators' system, like an unused one
        s.response.row(k).setZero();
        s.response.col(k).setZero();
        s.response(k, k) = 1.0;
        s.error(k) = s.feed_forward(k) = s.held_integral(k) = 0.0;
      }
    return s;
  }

  // the amplitudes u (strain per step) of the actuators: proportional, affine feed-forward and
  // integral parts; `integral` is the accumulated error S after this step (it accumulates only
  // near the target)
  template <int N>
  VectorN<N> servo_amplitudes(const LoadedServoSystem<N> &s, const MixedControlOf<N> &control,
                              const CellMeasurementOf<N> &cell, const ServoSettings &settings,
                              VectorN<N> &integral)
  {
    const int m = control.actuator_count;
    const Eigen::FullPivLU<MatrixN<N>> lu(s.response);
    if (!lu.isInvertible())
      throw std::runtime_error("servo: the free axes cannot move the held stresses "
                               "(singular response matrix)");
    const VectorN<N> normalised_error = lu.solve(s.error);
    const double stress_level = std::max(control.stress_targets.head(m).cwiseAbs().maxCoeff(),
                                         std::abs(mean_stress(cell.stress.template head<3>())));
    const bool near_target = s.error.cwiseAbs().maxCoeff() <= settings.integral_band * stress_level;
    integral = s.held_integral + (near_target ? s.error : VectorN<N>::Zero());
    VectorN<N> u = settings.gain * normalised_error - lu.solve(s.feed_forward) +
        settings.integral_gain * lu.solve(integral);
    u.tail(N - m).setZero();
    return u;
  }

}    // namespace detail

template <int N>
ServoCommandOf<N> servo_step(const MixedControlOf<N> &control, const CellMeasurementOf<N> &cell,
                             const ServoSettings &settings, double dt, ServoMemoryOf<N> &memory)
{
  if (!(dt > 0.0)) throw std::invalid_argument("servo time step must be positive");
  const int m = control.actuator_count;
  ServoCommandOf<N> command{control.prescribed_strain_rate, false};
  // stiffness floor so that an empty cell (C = 0) still gets a direction; the cap sets the
  // pace. Nothing held, or nothing to scale by (no stiffness, target or stress): the
  // prescribed rates alone
  const double scale = m == 0 ? 0.0 : detail::floor_scale(control, cell);
  if (scale == 0.0) {
    memory.last_strain_rate = command.strain_rate;
    return command;
  }
  const double floor = 1e-9 * scale;
  std::array<bool, N> unloaded{};
  const VectorN<N> floor_rate =
      detail::unloaded_actuator_rates<N>(control, cell, settings, floor, unloaded);
  const detail::LoadedServoSystem<N> system =
      detail::loaded_servo_system<N>(control, cell, floor, dt, memory.integral, unloaded);
  command.stress_error = system.stress_error;
  VectorN<N> integral;
  const VectorN<N> u = detail::servo_amplitudes(system, control, cell, settings, integral);

  // the cap scales the servo part as a whole, and freezes the integral meanwhile
  VectorN<N> servo_rate = control.actuators * u / dt;
  const double largest = servo_rate.cwiseAbs().maxCoeff();
  if (largest > settings.max_strain_rate) {
    servo_rate *= settings.max_strain_rate / largest;
    command.saturated = true;
  } else {
    memory.integral = integral;
  }
  if (floor_rate != VectorN<N>::Zero()) command.saturated = true;
  command.strain_rate += servo_rate + floor_rate;
  memory.last_strain_rate = command.strain_rate;
  return command;
}

// Multi-axial plane-strain leg (paper section 5: "no strain was permitted in the
// 1-direction"): the fixed axis k has zero total strain rate; the free axes i, j take the
// leg's difference rate (d_i - d_j)/2 (e_i - e_j), and the p servo acts on e_i + e_j only.
// The Pi-plane point then also moves by the volume change of the free axes (dilatancy), which
// a purely deviatoric leg would hide in the fixed axis.
inline MixedControl plane_strain_control(double mean_stress,
                                         const Eigen::Vector3d &deviatoric_strain_rate,
                                         int fixed_axis)
{
  require_positive_stress("p", mean_stress);
  require_axis_index(fixed_axis);
  const int i = (fixed_axis + 1) % 3, j = (fixed_axis + 2) % 3;
  const double half_difference = 0.5 * (deviatoric_strain_rate(i) - deviatoric_strain_rate(j));
  MixedControl c;
  c.prescribed_strain_rate(i) = half_difference;
  c.prescribed_strain_rate(j) = -half_difference;
  Eigen::Vector3d free_axes = Eigen::Vector3d::Ones();
  free_axes(fixed_axis) = 0.0;
  c.add(free_axes, Eigen::Vector3d::Constant(1.0 / 3.0), mean_stress);
  return c;
}

enum class PlaneStrain { TOTAL, DEVIATORIC };

// constant p* while the deviatoric strain follows a Pi-plane path at speed v (|de/dt|): the
// control of the step from the principal strains and the progress s along the path, which it
// advances; on a leg with a zero deviatoric rate along one axis, PlaneStrain::TOTAL also keeps
// that axis' total strain rate at zero (true plane strain), DEVIATORIC lets the p servo act on
// all axes (docs/theory.md §6.3, §7.4)
inline MixedControl path_control(const PiPath &path, double speed, double mean_stress,
                                 const Eigen::Vector3d &strain, double dt, double &path_length,
                                 PlaneStrain plane_strain = PlaneStrain::TOTAL)
{
  const int leg = path.segment_at(std::clamp(path_length, 0.0, path.length()));
  const int fixed_axis =
      plane_strain == PlaneStrain::TOTAL ? plane_strain_axis(path.segments()[leg]) : -1;
  const PathStep step = follow_path(path, path_length, strain, speed, dt);
  path_length = step.path_length;
  return fixed_axis >= 0
      ? plane_strain_control(mean_stress, step.deviatoric_strain_rate, fixed_axis)
      : mean_stress_control(mean_stress, step.deviatoric_strain_rate);
}

// the step of a path's control by the three-component servo
inline ServoCommand path_servo_step(const PiPath &path, double speed, double mean_stress,
                                    const CellMeasurement &cell, const ServoSettings &settings,
                                    double dt, ServoMemory &memory, double &path_length,
                                    PlaneStrain plane_strain = PlaneStrain::TOTAL)
{
  const MixedControl control =
      path_control(path, speed, mean_stress, cell.strain, dt, path_length, plane_strain);
  return servo_step(control, cell, settings, dt, memory);
}

// ---------------------------------------------------------------------------------------------
// Progress of a test that ends when a measure x reaches its target: the fraction of the way
// from where it started, (x - x0)/(target - x0), in [0, 1]; 1 once x has reached the target
// from x0's side (then the test ends)

inline double progress_towards(double start, double now, double target)
{
  if (!(target != start)) return 1.0;
  return std::clamp((now - start) / (target - start), 0.0, 1.0);
}

inline bool reached(double start, double now, double target)
{
  return target >= start ? now >= target : now <= target;
}

// ---------------------------------------------------------------------------------------------
// Quasi-equilibrium for specimen preparation (paper section 2; docs/theory.md §6.4)

struct EquilibriumCriteria {
  double stress_tolerance = 5e-3;              // max_i |sigma_i - sigma_i*| / p*
  double max_unbalanced_force_ratio = 1e-3;    // mean |sum of forces on a grain| / mean |f_c|
  double max_kinetic_energy_ratio = 1e-8;      // E_kin/(p* V) = (phi/2) I^2: 1e-8 <-> I ~ 2e-4
  double coordination_tolerance = 0.01;        // allowed drift of Z over the window
  int window = 10;                             // consecutive samples that must all pass
};

struct EquilibriumSample {
  Eigen::Vector3d stress;
  Eigen::Vector3d target_stress;
  double unbalanced_force_ratio;
  double kinetic_energy_ratio;
  double coordination;
};

struct EquilibriumState {
  double reference_coordination = 0.0;    // Z when the current run of passing samples began
  int passing_samples = 0;                // length of that run

  static constexpr int size = 2;
  void to_array(double *a) const { a[0] = reference_coordination, a[1] = passing_samples; }
  static EquilibriumState from_array(const double *a) { return {a[0], static_cast<int>(a[1])}; }
};

struct EquilibriumCheck {
  bool stress_ok, force_ok, energy_ok, coordination_ok;
  bool reached;    // every criterion held on `window` consecutive samples
};

inline EquilibriumCheck update_equilibrium(EquilibriumState &state, const EquilibriumSample &sample,
                                           const EquilibriumCriteria &criteria)
{
  const double p_target = mean_stress(sample.target_stress);
  EquilibriumCheck check{};
  check.stress_ok = (sample.stress - sample.target_stress).cwiseAbs().maxCoeff() <=
      criteria.stress_tolerance * p_target;
  check.force_ok = sample.unbalanced_force_ratio <= criteria.max_unbalanced_force_ratio;
  check.energy_ok = sample.kinetic_energy_ratio <= criteria.max_kinetic_energy_ratio;
  check.coordination_ok = state.passing_samples == 0 ||
      std::abs(sample.coordination - state.reference_coordination) <=
          criteria.coordination_tolerance;
  if (!(check.stress_ok && check.force_ok && check.energy_ok)) {
    state.passing_samples = 0;
  } else if (state.passing_samples == 0 || !check.coordination_ok) {
    state.reference_coordination = sample.coordination;
    state.passing_samples = 1;
  } else {
    ++state.passing_samples;
  }
  check.reached = state.passing_samples >= criteria.window;
  return check;
}

}    // namespace tycore

#endif
