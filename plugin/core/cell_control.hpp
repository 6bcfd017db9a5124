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

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace tycore {

using MixedControl6 = MixedControlOf<6>;

// ---------------------------------------------------------------------------------------------
// The principal programmes in six components (docs/theory.md §11.2): a three-component control
// is the six-component one whose shears are idle (prescribed at zero rate, no held stress or
// actuator touching them). servo_step on six components steps it to the same numbers as the
// three-component servo on the principal block (the shears outside the programme set nothing,
// cell_servo.hpp's used_components), so a principal programme gives the same numbers on any cell.

inline MixedControl6 six_component_control(const MixedControl &c)
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

inline void require_valid(const ShearPlane &plane)
{
  if (!(plane.direction >= 0 && plane.direction < plane.normal && plane.normal <= 2))
    throw std::invalid_argument("simple shear plane (" + std::to_string(plane.direction) + ", " +
                                std::to_string(plane.normal) +
                                ") must be xy, xz or yz: an "
                                "upper-triangular cell only tilts the edge of the larger axis "
                                "towards the smaller");
}

inline void require_finite(const std::string &name, double value)
{
  if (!std::isfinite(value)) throw std::invalid_argument(name + " is not finite");
}

// tau and sigma_n of the plane from the compression-positive Voigt6 stress
inline double shear_stress(const Vector6d &stress, const ShearPlane &plane)
{
  return -stress(plane.component());
}
inline double normal_stress(const Vector6d &stress, const ShearPlane &plane)
{
  return stress(plane.normal);
}

// every component strain-controlled at zero rate except the shear of the plane at gamma_dot
// (the rigid lateral boundaries of a simple-shear device), the normal axis free if asked
inline std::array<AxisProgramme, 6> simple_shear_components(const ShearPlane &plane,
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
  double shear_rate;       // gamma_dot = L_ij [1/s]
  double normal_stress;    // sigma_n [Pa]

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

  MixedControl6 control() const
  {
    return per_axis_control<6>(simple_shear_components(plane, shear_rate));
  }
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

// The count of a cyclic test whose load reverses at two bounds (docs/theory.md §13): tau of
// cyclic simple shear between -+CSR sigma_n0, the deviator of a cyclic triaxial test between
// -+2 CSR p0 (or 0 and +2 CSR p0, one way). The cycled stress s is driven towards the upper
// bound first (direction +1), and the direction turns at the step that ends with s at or beyond
// the bound ahead. Half cycles end at the reversals; the cycle count is N = (half cycles
// completed)/2, 0 during the first half cycle, 0.5 from the first reversal on, N once 2N half
// cycles are over (so that a test run until N cycles has made N). The double amplitude strain
// of the running half cycle is |strain - strain at the last reversal| (the peak-to-peak swing
// once it reaches the next peak); N_L counts the half cycle in which a criterion first holds,
// (half cycles completed + 1)/2: 0.5 in the first half cycle, N at the end of the 2N-th (0
// while it has not held).
struct CycleCount {
  int direction = 1;    // +1 towards the upper bound, -1 towards the lower
  int reversals = 0;    // completed half cycles
  double strain_at_reversal = 0.0;
  double cycles_to_pore_pressure = 0.0;       // N_L by r_u
  double cycles_to_double_amplitude = 0.0;    // N_L by double amplitude strain

  static constexpr int size = 5;
  void to_array(double *a) const
  {
    a[0] = direction, a[1] = reversals, a[2] = strain_at_reversal;
    a[3] = cycles_to_pore_pressure, a[4] = cycles_to_double_amplitude;
  }
  static CycleCount from_array(const double *a)
  {
    return {static_cast<int>(a[0]), static_cast<int>(a[1]), a[2], a[3], a[4]};
  }
  double cycles() const { return 0.5 * reversals; }
  double cycles_to_now() const { return 0.5 * (reversals + 1); }

  // after a step that ended at the cycled stress s, the strain of the cycle and r_u
  void update(double s, double lower, double upper, double strain, double r_u,
              const LiquefactionCriteria &criteria)
  {
    if (direction > 0 ? s >= upper : s <= lower) {
      direction = -direction;
      ++reversals;
      strain_at_reversal = strain;
    }
    if (cycles_to_pore_pressure == 0.0 && r_u >= criteria.pore_pressure_ratio)
      cycles_to_pore_pressure = cycles_to_now();
    if (cycles_to_double_amplitude == 0.0 &&
        std::abs(strain - strain_at_reversal) >= criteria.double_amplitude_strain)
      cycles_to_double_amplitude = cycles_to_now();
  }
};

// Cyclic constant-volume simple shear with a stress-controlled amplitude: gamma_dot = +rate
// first (tau rises towards +tau_cyc), reversed each time tau reaches +-tau_cyc = +-CSR sigma_n0;
// cycles, the double amplitude gamma and N_L as CycleCount counts them.
struct CyclicSimpleShear {
  ShearPlane plane;
  double shear_rate;               // |gamma_dot| [1/s]
  double cyclic_stress_ratio;      // CSR = tau_cyc/sigma_n0
  double initial_normal_stress;    // sigma_n0 [Pa]
  LiquefactionCriteria criteria;

  using State = CycleCount;    // its direction is the sign of gamma_dot

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
  double cycles(const State &s) const { return s.cycles(); }

  // the state after a step ended at (tau, gamma, sigma_n): reverse at the amplitude, record N_L
  void update(State &s, double tau, double gamma, double normal_stress) const
  {
    s.update(tau, -amplitude(), amplitude(), gamma,
             pore_pressure_ratio(normal_stress, initial_normal_stress), criteria);
  }

  MixedControl6 control(const State &s) const
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

// ---------------------------------------------------------------------------------------------
// Tests along an axis a (docs/theory.md §13): the axial stress sigma_a, the radial stress
// sigma_r = (sigma_b + sigma_c)/2 (the mean of the two lateral stresses) and the signed deviator
// q_a = sigma_a - sigma_r (> 0 in compression, sigma1 - sigma3 while sigma_b = sigma_c)

inline double radial_stress(const Vector6d &stress, int axis)
{
  return 0.5 * (stress((axis + 1) % 3) + stress((axis + 2) % 3));
}
inline double axial_deviator(const Vector6d &stress, int axis)
{
  return stress(axis) - radial_stress(stress, axis);
}

// Oedometric (K0) compression and unloading: the axial rate direction * R (R > 0; direction
// +1 loading, -1 unloading, 0 at rest), the lateral axes and the shears at zero strain rate, so
// that the lateral strains stay zero exactly; every component is strain controlled
struct OedometricCompression {
  int axis;
  double axial_strain_rate;

  MixedControl6 control() const
  {
    require_axis_index(axis);
    require_finite("oedometric axial strain rate", axial_strain_rate);
    std::array<AxisProgramme, 6> c;
    c.fill({AxisControl::STRAIN_RATE, 0.0});
    c[axis].value = axial_strain_rate;
    return per_axis_control<6>(c);
  }
};

// The course of an oedometer test: loading until sigma_a reaches the peak stress, then, for an
// overconsolidation ratio R > 1, unloading until sigma_a = (largest sigma_a)/R, then at rest.
// OCR = (largest sigma_a)/sigma_a; K0 = sigma_r/sigma_a; the ratio of the stress changes since
// the test began, (sigma_r - sigma_r0)/(sigma_a - sigma_a0), is the K0 of the increments (the
// elastic C_ba/C_aa of the stiffness at small strain, docs/theory.md §12).
struct OedometerCourse {
  double peak;         // sigma_a at which loading ends [Pa]
  double ocr = 1.0;    // the overconsolidation ratio at the end of unloading (1: no unloading)

  struct State {
    int direction = 1;                                           // +1 loading, -1 unloading, 0 done
    double axial0 = std::numeric_limits<double>::quiet_NaN();    // sigma_a0 (NaN: not begun)
    double radial0 = 0.0, largest = 0.0, last = 0.0;             // sigma_r0, max sigma_a, sigma_a

    static constexpr int size = 5;
    std::vector<double> to_vector() const
    {
      return {double(direction), axial0, radial0, largest, last};
    }
    static State from_array(const double *a) { return {int(a[0]), a[1], a[2], a[3], a[4]}; }
  };

  State begin(double axial, double radial) const { return {1, axial, radial, axial, axial}; }

  // the state after a step that ended at sigma_a
  void update(State &s, double axial) const
  {
    s.largest = std::max(s.largest, axial);
    s.last = axial;
    if (s.direction > 0 && axial >= peak)
      s.direction = ocr > 1.0 ? -1 : 0;
    else if (s.direction < 0 && axial * ocr <= s.largest)
      s.direction = 0;
  }

  // the fraction of the stress path sigma_a0 -> peak -> (largest sigma_a)/R done (the largest
  // sigma_a is the peak until loading ends); 1 only once the course is over
  double progress(const State &s) const
  {
    if (s.direction == 0) return 1.0;
    const double top = s.direction > 0 ? peak : s.largest;
    const double loading = peak - s.axial0, total = loading + (top - top / ocr);
    const double done = s.direction > 0 ? s.last - s.axial0 : loading + (s.largest - s.last);
    return std::clamp(done / total, 0.0, std::nextafter(1.0, 0.0));
  }
};

// Undrained cyclic triaxial test (the liquefaction test of the triaxial cell): the undrained
// triaxial control (eps_v = 0 exactly, sigma_b = sigma_c) at the axial rate +-R, compression
// first, reversed each time q_a reaches +2 CSR p0 or, on the way back, -2 CSR p0 (two-way) or 0
// (one-way); p0 the mean stress when the test began, r_u = 1 - p/p0, the cycle count and N_L
// by r_u and by the double amplitude axial strain as CycleCount counts them
struct CyclicUndrainedTriaxial {
  int axis;
  double axial_strain_rate;      // R > 0 [1/s]
  double cyclic_stress_ratio;    // CSR = q_cyc/(2 p0)
  double initial_mean_stress;    // p0 [Pa]
  bool one_way = false;
  LiquefactionCriteria criteria{0.95, 0.05};

  using State = CycleCount;    // its direction is the sign of the axial rate

  double amplitude() const { return 2.0 * cyclic_stress_ratio * initial_mean_stress; }
  double lower_bound() const { return one_way ? 0.0 : -amplitude(); }
  double pore_pressure_ratio_of(const Vector6d &stress) const
  {
    return pore_pressure_ratio(mean_stress(stress.head<3>()), initial_mean_stress);
  }

  void update(State &s, const Vector6d &stress, const Vector6d &strain) const
  {
    s.update(axial_deviator(stress, axis), lower_bound(), amplitude(), strain(axis),
             pore_pressure_ratio_of(stress), criteria);
  }

  MixedControl6 control(const State &s) const
  {
    return UndrainedTriaxial{axis, s.direction * axial_strain_rate}.control();
  }
};

// Constant p with a prescribed deviatoric strain rate (Voigt6, any shears): the p servo acts
// on the isotropic mode (1, 1, 1, 0, 0, 0), as mean_stress_control on three axes
inline MixedControl6 mean_stress_control6(double mean_stress, const Vector6d &strain_rate)
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
