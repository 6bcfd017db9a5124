// The tests of a triclinic periodic cell as six-component mixed controls (docs/theory.md §13):
// which components are strain-rate controlled, which stress controlled, and their rates and
// targets as functions of the state. Each test is a small named piece that a fix consumes
// through control(); the servo law is cell_servo.hpp's servo_step on N = 6 components (Voigt6
// order xx yy zz xy xz yz, engineering shears, compression positive; cell_kinematics.hpp).
//
// Simple shear in the plane (i, j), i < j: the edge along j tilts towards i (L_ij = gamma_dot,
// the only shears an upper-triangular cell carries); j is the normal axis (the specimen's
// height), i the direction of shearing. gamma = int L_ij dt, tau = -sigma_ij (Cauchy),
// sigma_n = sigma_jj, as in cell_kinematics.hpp.
#ifndef TYCORE_CELL_CONTROL_HPP
#define TYCORE_CELL_CONTROL_HPP

#include "cell_kinematics.hpp"
#include "cell_servo.hpp"
#include "pi_plane.hpp"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tycore {

using MixedControl6 = MixedControlOf<6>;

// ---------------------------------------------------------------------------------------------
// The principal programmes in six components (docs/theory.md §11.2): a three-component control
// is the six-component one whose shears are idle (prescribed at zero rate, no held stress or
// actuator touching them). servo_step on six components steps it to the same numbers as the
// three-component servo on the principal block (the shears outside the programme set nothing,
// cell_servo.hpp's used_components), so a principal programme gives the same numbers on any cell.

inline MixedControl6 six_component_control(const MixedControl& c)
{
  MixedControl6 six;
  six.prescribed_strain_rate.head<3>() = c.prescribed_strain_rate;
  six.actuator_count = c.actuator_count;
  six.actuators.topLeftCorner<3, 3>() = c.actuators;
  six.stress_rows.topLeftCorner<3, 3>() = c.stress_rows;
  six.stress_targets.head<3>() = c.stress_targets;
  return six;
}

// ---------------------------------------------------------------------------------------------
// Simple shear

struct ShearPlane {
  int direction = 0;    // i: the axis along which the top moves
  int normal = 2;       // j > i: the specimen's height

  int component() const { return voigt_index(direction, normal); }
};

inline void require_valid(const ShearPlane& plane)
{
  if (!(plane.direction >= 0 && plane.direction < plane.normal && plane.normal <= 2))
    throw std::invalid_argument("simple shear plane (" + std::to_string(plane.direction) + ", "
                                + std::to_string(plane.normal) + ") must be xy, xz or yz: an "
                                "upper-triangular cell only tilts the edge of the larger axis "
                                "towards the smaller");
}

inline void require_finite(const std::string& name, double value)
{
  if (!std::isfinite(value)) throw std::invalid_argument(name + " is not finite");
}

// tau and sigma_n of the plane from the compression-positive Voigt6 stress
inline double shear_stress(const Vector6d& stress, const ShearPlane& plane)
{
  return -stress(plane.component());
}
inline double normal_stress(const Vector6d& stress, const ShearPlane& plane)
{
  return stress(plane.normal);
}

// every component strain-controlled at zero rate except the shear of the plane at gamma_dot
// (the rigid lateral boundaries of a simple-shear device), the normal axis free if asked
inline std::array<AxisProgramme, 6> simple_shear_components(const ShearPlane& plane,
                                                            double shear_rate)
{
  require_valid(plane);
  require_finite("simple shear rate", shear_rate);
  std::array<AxisProgramme, 6> c;
  c.fill({AxisControl::STRAIN_RATE, 0.0});
  c[plane.component()].value = -shear_rate;    // compression-positive engineering shear rate
  return c;
}

// drained simple shear (DSS): eps_ii = 0 for the lateral axes, sigma_n held by the servo,
// gamma_dot prescribed
struct DrainedSimpleShear {
  ShearPlane plane;
  double shear_rate;        // gamma_dot = L_ij [1/s]
  double normal_stress;     // sigma_n [Pa]

  MixedControl6 control() const
  {
    std::array<AxisProgramme, 6> c = simple_shear_components(plane, shear_rate);
    c[plane.normal] = {AxisControl::STRESS, normal_stress};
    return per_axis_control<6>(c);
  }
};

// constant-volume simple shear (the undrained DSS of Dyvik et al. 1987): every axis and the
// other shears strain-controlled at zero rate, so the volume is constant exactly
struct ConstantVolumeSimpleShear {
  ShearPlane plane;
  double shear_rate;

  MixedControl6 control() const { return per_axis_control<6>(simple_shear_components(plane, shear_rate)); }
};

// excess pore pressure ratio of an undrained test: the drop of the effective normal stress
inline double pore_pressure_ratio(double normal_stress, double initial_normal_stress)
{
  return 1.0 - normal_stress / initial_normal_stress;
}

struct LiquefactionCriteria {
  double pore_pressure_ratio = 0.95;          // r_u at liquefaction
  double double_amplitude_strain = 0.0375;    // peak-to-peak gamma at liquefaction
};

// Cyclic constant-volume simple shear with a stress-controlled amplitude: gamma_dot = +rate
// first (tau rises towards +tau_cyc), reversed each time tau reaches +-tau_cyc = +-CSR sigma_n0.
// Half cycles end at the reversals; the cycle count is N = (half cycles completed)/2, 0 during
// the first half cycle, 0.5 from the first reversal on, N once 2N half cycles are over (so that
// a test run until N cycles has made N). The double amplitude strain of the running half cycle
// is |gamma - gamma at the last reversal| (the peak-to-peak swing once it reaches the next
// peak); N_L counts the half cycle in which a criterion first holds, (half cycles completed +
// 1)/2: 0.5 in the first half cycle, N at the end of the 2N-th (0 while it has not held).
struct CyclicSimpleShear {
  ShearPlane plane;
  double shear_rate;                 // |gamma_dot| [1/s]
  double cyclic_stress_ratio;        // CSR = tau_cyc/sigma_n0
  double initial_normal_stress;      // sigma_n0 [Pa]
  LiquefactionCriteria criteria;

  struct State {
    int direction = 1;               // sign of gamma_dot
    int reversals = 0;               // completed half cycles
    double gamma_at_reversal = 0.0;
    double cycles_to_pore_pressure = 0.0;      // N_L by r_u
    double cycles_to_double_amplitude = 0.0;   // N_L by double amplitude gamma

    static constexpr int size = 5;
    void to_array(double* a) const
    {
      a[0] = direction, a[1] = reversals, a[2] = gamma_at_reversal;
      a[3] = cycles_to_pore_pressure, a[4] = cycles_to_double_amplitude;
    }
    static State from_array(const double* a)
    {
      return {static_cast<int>(a[0]), static_cast<int>(a[1]), a[2], a[3], a[4]};
    }
  };

  void require_valid() const
  {
    tycore::require_valid(plane);
    if (!(shear_rate > 0.0) || !std::isfinite(shear_rate))
      throw std::invalid_argument("cyclic simple shear: the shear rate must be positive");
    if (!(cyclic_stress_ratio > 0.0) || !std::isfinite(cyclic_stress_ratio))
      throw std::invalid_argument("cyclic simple shear: CSR must be positive");
    require_positive_stress("sigma_n0", initial_normal_stress);
    if (!(criteria.pore_pressure_ratio > 0.0 && criteria.pore_pressure_ratio <= 1.0))
      throw std::invalid_argument("cyclic simple shear: the r_u criterion must lie in (0, 1]");
    if (!(criteria.double_amplitude_strain > 0.0))
      throw std::invalid_argument("cyclic simple shear: the double amplitude criterion must be "
                                  "positive");
  }

  double amplitude() const { return cyclic_stress_ratio * initial_normal_stress; }
  double cycles(const State& s) const { return 0.5 * s.reversals; }
  double cycles_to_now(const State& s) const { return 0.5 * (s.reversals + 1); }

  // the state after a step ended at (tau, gamma, sigma_n): reverse at the amplitude, record N_L
  void update(State& s, double tau, double gamma, double normal_stress) const
  {
    if (s.direction * tau >= amplitude()) {
      s.direction = -s.direction;
      ++s.reversals;
      s.gamma_at_reversal = gamma;
    }
    if (s.cycles_to_pore_pressure == 0.0
        && pore_pressure_ratio(normal_stress, initial_normal_stress)
               >= criteria.pore_pressure_ratio)
      s.cycles_to_pore_pressure = cycles_to_now(s);
    if (s.cycles_to_double_amplitude == 0.0
        && std::abs(gamma - s.gamma_at_reversal) >= criteria.double_amplitude_strain)
      s.cycles_to_double_amplitude = cycles_to_now(s);
  }

  MixedControl6 control(const State& s) const
  {
    return ConstantVolumeSimpleShear{plane, s.direction * shear_rate}.control();
  }
};

// Undrained (constant-volume) triaxial test: axial rate R prescribed (> 0 compression), the
// lateral rates -R/2 + delta and -R/2 - delta, delta the servo's on sigma_b - sigma_c = 0:
// the actuator e_b - e_c is traceless, so eps_v = 0 exactly; the shears stay at zero rate
struct UndrainedTriaxial {
  int axis;
  double axial_strain_rate;

  MixedControl6 control() const
  {
    require_axis_index(axis);
    require_finite("undrained triaxial axial strain rate", axial_strain_rate);
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    MixedControl6 control;
    control.prescribed_strain_rate(axis) = axial_strain_rate;
    control.prescribed_strain_rate(b) = control.prescribed_strain_rate(c) =
        -0.5 * axial_strain_rate;
    const Vector6d lateral_difference = Vector6d::Unit(b) - Vector6d::Unit(c);
    control.add(lateral_difference, lateral_difference, 0.0);
    return control;
  }
};

// Constant p with a prescribed deviatoric strain rate (Voigt6, any shears): the p servo acts
// on the isotropic mode (1, 1, 1, 0, 0, 0), as mean_stress_control on three axes
inline MixedControl6 mean_stress_control6(double mean_stress, const Vector6d& strain_rate)
{
  require_positive_stress("p", mean_stress);
  MixedControl6 c;
  c.prescribed_strain_rate = strain_rate;
  c.prescribed_strain_rate.head<3>() = deviator(strain_rate.head<3>());
  Vector6d isotropic = Vector6d::Zero();
  isotropic.head<3>().setOnes();
  c.add(isotropic, isotropic / 3.0, mean_stress);
  return c;
}

// Principal stress rotation at constant p, q and b (the hollow-cylinder path): the major
// principal stress sigma_1 turns in the plane (i, j) at alpha from axis i towards j, sigma_3 in
// the plane at right angles, sigma_2 along the third axis:
//     sigma = R(alpha) diag(sigma_1, sigma_3) R(alpha)^T in the plane,
// sigma_1 = p + (2 - b) q/3 and (sigma_2, sigma_3) = constant_b_targets. All six components are
// stress controlled, the shears out of the plane at zero.
struct PrincipalStressRotation {
  int i = 0, j = 2;
  double mean_stress, deviatoric_stress, b;
  double initial_angle_deg = 0.0;
  double rotation_rate_deg = 0.0;    // d alpha/dt [degree/s]

  double angle_deg(double time) const { return initial_angle_deg + rotation_rate_deg * time; }

  Vector6d targets(double time) const
  {
    if (!(i >= 0 && i < j && j <= 2))
      throw std::invalid_argument("principal stress rotation plane must be xy, xz or yz");
    require_finite("rotation rate", rotation_rate_deg);
    const double major = mean_stress + (2.0 - b) * deviatoric_stress / 3.0;
    const Eigen::Vector2d intermediate_minor = constant_b_targets(major, mean_stress, b);
    require_positive_stress("sigma_3", intermediate_minor(1));
    const double alpha = angle_deg(time) * piplane::degree;
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    R(i, i) = std::cos(alpha), R(i, j) = -std::sin(alpha);
    R(j, i) = std::sin(alpha), R(j, j) = std::cos(alpha);
    Eigen::Vector3d principal;
    principal(i) = major, principal(j) = intermediate_minor(1);
    principal(3 - i - j) = intermediate_minor(0);
    return stress_from_tensor(R * principal.asDiagonal() * R.transpose());
  }

  MixedControl6 control(double time) const
  {
    const Vector6d t = targets(time);
    std::array<AxisProgramme, 6> c;
    for (int k = 0; k < 6; ++k) c[k] = {AxisControl::STRESS, t(k)};
    return per_axis_control<6>(c);
  }
};

}    // namespace tycore

#endif
