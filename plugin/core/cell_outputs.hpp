// The outputs of a cell test (fix cell/servo's global vector and the columns of its record;
// docs/fix_cell_servo.md, "Output"): their one list of names, the columns a record carries, and
// the measures computed from the cell's state (docs/theory.md §4.2, §7.1, §10.4-10.5). Plain C++,
// no LAMMPS: the fix gathers the state, this file turns it into numbers.
#ifndef TYCORE_CELL_OUTPUTS_HPP
#define TYCORE_CELL_OUTPUTS_HPP

#include "cell_control.hpp"
#include "cell_kinematics.hpp"
#include "cell_statistics.hpp"
#include "pi_plane.hpp"

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace tycore {

// indices of the outputs (0-based here, 1-based for users)
namespace out {
  // clang-format off
enum Output {
  EPS1, EPS2, EPS3, EPS_V, EPS_Q, EPS_D13, SIG1, SIG2, SIG3, P, Q, B, LODE_DEG, ETA_LD,
  SINPHI, VOID_RATIO, SOLID_FRACTION, Z, ZM, SLIDING_FRACTION, UNBALANCED, INERTIAL_NUMBER,
  PI_X, PI_Y, PI_EX, PI_EY,    // the CSV columns end here
  PROGRESS, ETA_SECONDS, EQUILIBRIUM, RATE1, RATE2, RATE3, BOUNDARY_WORK, P_KINETIC, VOLUME,
  TIME, EQ_STRESS_OK, EQ_UNBALANCED_OK, EQ_KINETIC_OK, EQ_COORDINATION_OK, KINETIC_RATIO,
  // the six-component cell
  SIG_XY, SIG_XZ, SIG_YZ, GAMMA_XY, GAMMA_XZ, GAMMA_YZ, RATE_XY, RATE_XZ, RATE_YZ,
  SIG_MAJOR, SIG_INTER, SIG_MINOR,
  // the plane of a simple-shear or stress-rotation test
  GAMMA, TAU, SIG_N, TAU_RATIO, STRESS_ANGLE, RATE_ANGLE, NONCOAXIALITY,
  // constant-volume (undrained) shear tests
  R_U, CYCLES, N_L_RU, N_L_GAMMA,
  // the tests along an axis (k0, cyclic_triaxial): axial strain and stress, radial stress, the
  // signed deviator; K0, its increments' ratio and OCR (k0); N_L by double amplitude eps_a
  EPS_A, SIG_A, SIG_R, Q_A, K0, K0_INC, OCR, N_L_EPS,
  COUNT
};
  // clang-format on

  inline const char *name(int i)
  {
    // clang-format off
  static const char* const names[COUNT] = {
      "eps1", "eps2", "eps3", "eps_v", "eps_q", "eps_d13", "sig1", "sig2", "sig3", "p", "q", "b",
      "lode_deg", "eta_LD", "sinphi", "void_ratio", "solid_fraction", "Z", "Zm",
      "sliding_fraction", "unbalanced", "inertial_number", "pi_x", "pi_y", "pi_ex", "pi_ey",
      "progress", "eta_seconds", "equilibrium", "rate1", "rate2", "rate3", "boundary_work",
      "p_kinetic", "volume", "time", "eq_stress_ok", "eq_unbalanced_ok", "eq_kinetic_ok",
      "eq_coordination_ok", "kinetic_ratio",
      "sig_xy", "sig_xz", "sig_yz", "gamma_xy", "gamma_xz", "gamma_yz", "rate_xy", "rate_xz",
      "rate_yz", "sig_major", "sig_inter", "sig_minor",
      "gamma", "tau", "sig_n", "tau_ratio", "stress_angle", "rate_angle", "noncoaxiality",
      "r_u", "cycles", "N_L_ru", "N_L_gamma",
      "eps_a", "sig_a", "sig_r", "q_a", "K0", "K0_inc", "ocr", "N_L_eps"};
    // clang-format on
    return names[i];
  }

  // the index of the output `text`, -1 if none
  inline int index(const std::string &text)
  {
    for (int k = 0; k < COUNT; ++k)
      if (text == name(k)) return k;
    return -1;
  }

  // the outputs computed from the particles (a pass over the atoms): only on the steps that
  // record or test them
  inline bool of_particles(int k)
  {
    return k == Z || k == ZM || k == UNBALANCED || k == P_KINETIC || k == KINETIC_RATIO;
  }

  // the columns after `step` of every record, then those of a triclinic cell and of a plane
  inline std::vector<int> record_columns(bool triclinic, const std::vector<int> &programme)
  {
    std::vector<int> c{TIME,
                       EPS1,
                       EPS2,
                       EPS3,
                       EPS_V,
                       EPS_Q,
                       EPS_D13,
                       SIG1,
                       SIG2,
                       SIG3,
                       P,
                       Q,
                       B,
                       LODE_DEG,
                       ETA_LD,
                       SINPHI,
                       VOID_RATIO,
                       SOLID_FRACTION,
                       Z,
                       ZM,
                       SLIDING_FRACTION,
                       UNBALANCED,
                       INERTIAL_NUMBER,
                       PI_X,
                       PI_Y,
                       PI_EX,
                       PI_EY,
                       RATE1,
                       RATE2,
                       RATE3,
                       BOUNDARY_WORK,
                       P_KINETIC,
                       VOLUME,
                       PROGRESS};
    if (triclinic)
      c.insert(c.end(),
               {SIG_XY, SIG_XZ, SIG_YZ, GAMMA_XY, GAMMA_XZ, GAMMA_YZ, RATE_XY, RATE_XZ, RATE_YZ,
                SIG_MAJOR, SIG_INTER, SIG_MINOR});
    c.insert(c.end(), programme.begin(), programme.end());
    return c;
  }

  // the header line of a record with these columns (without the extra ones)
  inline std::string record_header(const std::vector<int> &columns)
  {
    std::string header = "step";
    for (int k : columns) header += std::string(",") + name(k);
    return header;
  }

  // a record's row: the outputs o of these columns
  inline std::vector<double> record_row(const std::vector<int> &columns, const double *o)
  {
    std::vector<double> row;
    for (int k : columns) row.push_back(o[k]);
    return row;
  }

  inline const std::vector<int> &plane_columns()
  {
    static const std::vector<int> c{GAMMA,        TAU,        SIG_N,        TAU_RATIO,
                                    STRESS_ANGLE, RATE_ANGLE, NONCOAXIALITY};
    return c;
  }

  // the outputs of a test along an axis
  inline const std::vector<int> &axial_columns()
  {
    static const std::vector<int> c{EPS_A, SIG_A, SIG_R, Q_A};
    return c;
  }

  // the outputs `until NAME VALUE` may end a test by: strains, stresses, state, time, work,
  // shears (a programme adds its own: the plane's, r_u, cycles)
  inline bool measure_of_a_test(int k)
  {
    return (k >= EPS1 && k <= SINPHI) || k == VOID_RATIO || k == SOLID_FRACTION ||
        (k >= PI_X && k <= PI_EY) || k == TIME || k == BOUNDARY_WORK ||
        (k >= SIG_XY && k <= GAMMA_YZ);
  }
}    // namespace out

// what the outputs are computed from
struct CellSnapshot {
  Vector6d stress = Vector6d::Zero();                  // contact stress [Pa], compression positive
  Eigen::Vector3d strain = Eigen::Vector3d::Zero();    // natural strains of the axes
  Eigen::Vector3d shear = Eigen::Vector3d::Zero();     // gamma_xy, gamma_xz, gamma_yz
  Vector6d last_strain_rate = Vector6d::Zero();        // the rates of the last step [1/s]
  double volume = 0.0, solid_volume = 0.0;
  double contacts = 0.0, sliding = 0.0;
  double mean_diameter = 0.0, mean_density = 0.0;
  std::optional<ShearPlane> plane;    // the test's plane
};

// the principal measures (docs/theory.md §7.1, §4.2): outputs 1-26, the rates and the volume
inline void principal_outputs(const CellSnapshot &s, double *o)
{
  using namespace out;
  constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector3d &eps = s.strain;
  const Eigen::Vector3d sig = s.stress.head<3>();
  o[EPS1] = eps(0), o[EPS2] = eps(1), o[EPS3] = eps(2);
  o[EPS_V] = volumetric_strain(eps);
  o[EPS_Q] = deviatoric_strain(eps);
  o[EPS_D13] = strain_difference_13(eps);
  o[SIG1] = sig(0), o[SIG2] = sig(1), o[SIG3] = sig(2);
  o[P] = mean_stress(sig);
  o[Q] = deviatoric_stress(sig);
  o[B] = b_value(sig);
  const Eigen::Vector2d pi_stress = pi_coordinates(sig);
  const Eigen::Vector2d pi_strain = pi_coordinates(eps);
  o[LODE_DEG] = lode_angle_deg(pi_stress);
  o[ETA_LD] = sig.minCoeff() > 0.0 ? lade_duncan_eta(sig) : NaN;
  o[SINPHI] = sig.maxCoeff() + sig.minCoeff() > 0.0 ? mobilised_sinphi(sig) : NaN;
  o[SOLID_FRACTION] = s.solid_volume / s.volume;
  o[VOID_RATIO] = s.volume / s.solid_volume - 1.0;
  o[SLIDING_FRACTION] = s.contacts > 0.0 ? s.sliding / s.contacts : 0.0;
  const Eigen::Vector3d rate = s.last_strain_rate.head<3>();
  // I = eps_dot_q d sqrt(rho/p), eps_dot_q = sqrt(2/3 e':e') (docs/theory.md §4.2), the
  // tensor's shears gamma_dot/2 included
  const double shear_rate = std::sqrt(2.0 / 3.0) *
      std::sqrt(deviator(rate).squaredNorm() + 0.5 * s.last_strain_rate.tail<3>().squaredNorm());
  o[INERTIAL_NUMBER] = o[P] > 0.0 ? shear_rate * s.mean_diameter * std::sqrt(s.mean_density / o[P])
                                  : NaN;
  o[PI_X] = pi_stress.x(), o[PI_Y] = pi_stress.y();
  o[PI_EX] = pi_strain.x(), o[PI_EY] = pi_strain.y();
  o[RATE1] = rate(0), o[RATE2] = rate(1), o[RATE3] = rate(2);
  o[VOLUME] = s.volume;
}

// the six-component outputs (docs/theory.md §10.4-10.5, §13): shears in the tilt sense
// (gamma_ij = int L_ij dt, rate_ij = L_ij), tau = -sigma_ij and sigma_n = sigma_jj of the
// plane (i, j), principal directions and the non-coaxiality angle in that plane, both tensors
// compression positive
inline void cell_outputs(const CellSnapshot &s, double *o)
{
  using namespace out;
  constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
  const Vector6d &rate = s.last_strain_rate;
  for (int k = 0; k < 3; ++k) {
    o[SIG_XY + k] = s.stress(3 + k);
    o[GAMMA_XY + k] = s.shear(k);
    o[RATE_XY + k] = -rate(3 + k);
  }
  const Eigen::Matrix3d sigma = tensor_from_stress(s.stress);
  const PrincipalAxes principal = principal_axes(sigma);
  o[SIG_MAJOR] = principal.values(0);
  o[SIG_INTER] = principal.values(1);
  o[SIG_MINOR] = principal.values(2);
  if (!s.plane) return;
  const ShearPlane &plane = *s.plane;
  const int i = plane.direction, j = plane.normal;
  const Eigen::Matrix3d strain_rate = tensor_from_strain(rate);
  o[GAMMA] = s.shear(plane.component() - 3);
  o[TAU] = shear_stress(s.stress, plane);
  o[SIG_N] = normal_stress(s.stress, plane);
  o[TAU_RATIO] = o[SIG_N] > 0.0 ? o[TAU] / o[SIG_N] : NaN;
  o[STRESS_ANGLE] = major_angle_in_plane_deg(sigma, i, j);
  o[RATE_ANGLE] = rate.norm() > 0.0 ? major_angle_in_plane_deg(strain_rate, i, j) : NaN;
  o[NONCOAXIALITY] = rate.norm() > 0.0 ? non_coaxiality_deg(sigma, strain_rate, i, j) : NaN;
}

// the outputs from the particles (cell_statistics.hpp)
inline void particle_outputs(const ParticleStatistics &st, double *o)
{
  o[out::Z] = st.Z;
  o[out::ZM] = st.Zm;
  o[out::UNBALANCED] = st.unbalanced;
  o[out::P_KINETIC] = st.p_kinetic;
  o[out::KINETIC_RATIO] = st.kinetic_ratio;
}

// the quasi-equilibrium sample of a preparation holding `mean_stress` on its axes, from the
// step's outputs (docs/theory.md §6.4)
inline EquilibriumSample equilibrium_sample(const Vector6d &stress, double mean_stress,
                                            const double *o)
{
  EquilibriumSample sample;
  sample.stress = stress.head<3>();
  sample.target_stress = Eigen::Vector3d::Constant(mean_stress);
  sample.unbalanced_force_ratio = o[out::UNBALANCED];
  sample.kinetic_energy_ratio = o[out::KINETIC_RATIO];
  sample.coordination = o[out::Z];
  return sample;
}

// the quasi-equilibrium outputs of a check (docs/theory.md §6.4)
inline void equilibrium_outputs(const EquilibriumCheck &check, double *o)
{
  o[out::EQUILIBRIUM] = check.reached;
  o[out::EQ_STRESS_OK] = check.stress_ok;
  o[out::EQ_UNBALANCED_OK] = check.force_ok;
  o[out::EQ_KINETIC_OK] = check.energy_ok;
  o[out::EQ_COORDINATION_OK] = check.coordination_ok;
}

// the components of a box (LAMMPS's layout lx ly lz yz xz xy) that differ between two, as
// text ("" if none): a box changed behind a test's back
inline std::string box_changes(const double before[6], const double now[6])
{
  static const char *const names[6] = {"lx", "ly", "lz", "yz", "xz", "xy"};
  std::string text;
  for (int k = 0; k < 6; ++k)
    if (before[k] != now[k]) {
      char item[96];
      std::snprintf(item, sizeof item, "%s%s %.10g -> %.10g", text.empty() ? "" : ", ", names[k],
                    before[k], now[k]);
      text += item;
    }
  return text;
}

// the error of a box changed between runs by another command (change_box): the test's strains
// and shears would not count the change ("" if the box is as the test left it, or the test has
// not set it yet: NaN)
inline std::string box_changed_error(const double left[6], const double now[6])
{
  if (std::isnan(left[0])) return "";
  const std::string changed = box_changes(left, now);
  if (changed.empty()) return "";
  return "the box was changed between runs (" + changed +
      ") by another command (change_box?): the test's strains and shears would not count the "
      "change; start a new test from the changed box ('continue no', or unfix the fix first) or "
      "leave the box to the fix";
}

}    // namespace tycore

#endif
