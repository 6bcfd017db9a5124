// Six-component mixed control (plugin/core/cell_servo.hpp on N = 6, plugin/core/cell_control.hpp,
// docs/theory.md §11.2, §13) against independent expectations: today's principal-axis servo
// as the special case, the partitioned solve written out, closed forms of linear elasticity
// for simple shear, the undrained triaxial constraint and the oedometer, and counted cycles.
#include "cell_control.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tycore::Matrix6d;
using tycore::Vector6d;

namespace {

tycore::ServoSettings settings(double gain = 0.25, double integral_gain = 0.005)
{
  tycore::ServoSettings s;
  s.gain = gain;
  s.integral_gain = integral_gain;
  s.max_strain_rate = 1e6;
  return s;
}

// isotropic linear elasticity in Voigt6 with engineering shears (Lame lambda, mu)
Matrix6d isotropic_stiffness(double lambda, double mu)
{
  Matrix6d c = Matrix6d::Zero();
  c.topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i) c(i, i) += 2 * mu, c(3 + i, 3 + i) = mu;
  return c;
}

Matrix6d random_spd(std::mt19937& rng, double scale)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Matrix6d a;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) a(i, j) = u(rng);
  return scale * (a * a.transpose() + 3.0 * Matrix6d::Identity());
}

// a linear-elastic cell: stress = stress0 + C strain, strain advanced by the commanded rates
struct LinearCell {
  Matrix6d stiffness;
  Vector6d stress0, strain = Vector6d::Zero();

  tycore::CellMeasurementOf<6> measure() const
  {
    return {stress0 + stiffness * strain, stiffness, strain};
  }
  void advance(const Vector6d& rate, double dt) { strain += rate * dt; }
};

}    // namespace

// the present servo is the special case: on a block-diagonal C with the shears held at zero
// rate, the six-component servo commands exactly the three principal rates of N = 3, step
// after step of a cell whose true stiffness is 0.6 C
TEST(CellControl, SixComponentServoReducesToThePrincipalServo)
{
  std::mt19937 rng(1);
  for (bool diagonal : {true, false}) {
    Matrix3d c3 = Vector3d(2e8, 3e8, 1.5e8).asDiagonal();
    if (!diagonal) c3 += Matrix3d::Constant(0.7e8);
    Matrix6d c6 = Matrix6d::Zero();
    c6.topLeftCorner<3, 3>() = c3;
    c6.bottomRightCorner<3, 3>() = 0.9e8 * Matrix3d::Identity();
    const tycore::AxisProgramme rate{tycore::AxisControl::STRAIN_RATE, 0.01};
    const tycore::MixedControl control3 = tycore::per_axis_control(
        {rate, {tycore::AxisControl::STRESS, 1e5}, {tycore::AxisControl::STRESS, 2e5}});
    std::array<tycore::AxisProgramme, 6> components;
    components.fill({tycore::AxisControl::STRAIN_RATE, 0.0});
    for (int k = 0; k < 3; ++k)
      components[k] = {k == 0 ? tycore::AxisControl::STRAIN_RATE : tycore::AxisControl::STRESS,
                       k == 0 ? 0.01 : k * 1e5};
    const tycore::MixedControl6 control6 = tycore::per_axis_control<6>(components);

    Vector3d stress3(0.9e5, 1.2e5, 1.8e5);
    Vector6d stress6 = Vector6d::Zero();
    stress6.head<3>() = stress3;
    tycore::ServoMemory memory3;
    tycore::ServoMemoryOf<6> memory6;
    const double dt = 1e-6;
    for (int step = 0; step < 200; ++step) {
      const tycore::ServoCommand a =
          tycore::servo_step(control3, {stress3, c3, Vector3d::Zero()}, settings(), dt, memory3);
      const tycore::ServoCommandOf<6> b = tycore::servo_step(
          control6, {stress6, c6, Vector6d::Zero()}, settings(), dt, memory6);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(b.strain_rate(k), a.strain_rate(k), 1e-12 * a.strain_rate.norm()) << step;
      EXPECT_EQ(b.strain_rate.tail<3>(), Vector3d::Zero());
      stress3 += 0.6 * c3 * a.strain_rate * dt;
      stress6 += 0.6 * c6 * b.strain_rate * dt;
    }
    EXPECT_NEAR(stress3(1), 1e5, 1e-3 * 1e5);    // the loop has converged but for the lag
  }
}

// A principal programme is stepped on six components to the same numbers as on three, bit for
// bit, on a cell whose shears carry stress and whose stiffness couples them to the normal
// components (a triclinic cell's full tally): its shears are outside the programme (cell_servo's
// used_components), so they set neither the step nor the scale of the stiffness floor. The
// principal controls of the paper, on random stiffnesses and stresses, one with an axis so
// soft that the rate floor acts, and at a cap that saturates.
TEST(CellControl, PrincipalProgrammeOnSixComponentsIsBitwiseTheThreeComponentStep)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int steps = 0;
  for (int trial = 0; trial < 600; ++trial) {
    Matrix6d c6 = random_spd(rng, 1e8);
    c6.topLeftCorner<3, 3>() *= trial % 7 == 0 ? 1e-12 : 1.0;
    c6.bottomRightCorner<3, 3>() *= 3.0;    // shear entries above the normal ones
    Vector6d stress6;
    for (int k = 0; k < 6; ++k) stress6(k) = 1e5 * (1.0 + 0.3 * u(rng)) * (k < 3 ? 1.0 : 2.0);
    tycore::ServoSettings s = settings();
    s.max_strain_rate = trial % 3 == 0 ? 1e-9 : 1e-2;
    tycore::MixedControl c3;
    const Vector3d rate(u(rng), u(rng), u(rng));
    switch (trial % 6) {
      case 0: c3 = tycore::isotropic_compression_control(1e5); break;
      case 1: c3 = tycore::axisymmetric_control(trial % 3, 1e-4 * rate(0), 1e5); break;
      case 2: c3 = tycore::constant_b_control(1e5, 0.3, 1e-4, 2, 0, 1); break;
      case 3: c3 = tycore::mean_stress_control(1e5, 1e-4 * rate); break;
      case 4: c3 = tycore::plane_strain_control(1e5, 1e-4 * rate, trial % 3); break;
      default:
        c3 = tycore::per_axis_control({tycore::AxisProgramme{tycore::AxisControl::STRAIN_RATE, 1e-4},
                                       {tycore::AxisControl::STRESS, 1e5},
                                       {tycore::AxisControl::STRESS, 1.2e5}});
    }
    tycore::ServoMemory m3;
    tycore::ServoMemoryOf<6> m6;
    for (int k = 0; k < 3; ++k) m3.integral(k) = m6.integral(k) = 100.0 * u(rng);
    const tycore::MixedControl6 six = tycore::six_component_control(c3);
    for (int step = 0; step < 3; ++step, ++steps) {
      const tycore::ServoCommand a = tycore::servo_step(
          c3, {stress6.head<3>(), c6.topLeftCorner<3, 3>(), Vector3d::Zero()}, s, 1e-6, m3);
      const tycore::ServoCommandOf<6> b =
          tycore::servo_step(six, {stress6, c6, Vector6d::Zero()}, s, 1e-6, m6);
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(b.strain_rate(k), a.strain_rate(k)) << trial << " " << step;
        ASSERT_EQ(m6.integral(k), m3.integral(k)) << trial << " " << step;
      }
      ASSERT_EQ(b.strain_rate.tail<3>(), Vector3d::Zero());
      ASSERT_EQ(b.saturated, a.saturated);
      stress6.head<3>() += 0.5 * c6.topLeftCorner<3, 3>() * a.strain_rate * 1e-6;
    }
  }
  EXPECT_EQ(steps, 1800);
}

// one step on a full C: the strain-controlled components take their prescribed increments and
// the stress-controlled ones solve C_SS de_S = g (t_S - sigma_S) - C_SE de_E, so that the
// predicted stress C de removes the fraction g of each held error
TEST(CellControl, PartitionedSolveOnAFullStiffness)
{
  std::mt19937 rng(2);
  const Matrix6d C = random_spd(rng, 1e8);
  const int held[3] = {1, 4, 5}, prescribed[3] = {0, 2, 3};
  std::array<tycore::AxisProgramme, 6> components;
  Vector6d rates, targets = Vector6d::Zero();
  rates << 0.02, 0, -0.01, 0.005, 0, 0;
  for (int k = 0; k < 6; ++k) components[k] = {tycore::AxisControl::STRAIN_RATE, rates(k)};
  targets(1) = 2e5, targets(4) = -3e4, targets(5) = 1e4;
  for (int k : held) components[k] = {tycore::AxisControl::STRESS, targets(k)};
  const tycore::MixedControl6 control = tycore::per_axis_control<6>(components);
  Vector6d stress;
  stress << 1e5, 1.5e5, 1.1e5, 2e3, -1e4, 0.0;
  const double dt = 1e-6, g = 0.3;
  tycore::ServoMemoryOf<6> memory;
  const tycore::ServoCommandOf<6> command =
      tycore::servo_step(control, {stress, C, Vector6d::Zero()}, settings(g, 0.0), dt, memory);
  const Vector6d step = command.strain_rate * dt;

  Eigen::Matrix3d css, cse;
  Vector3d error, de_e;
  for (int a = 0; a < 3; ++a) {
    error(a) = targets(held[a]) - stress(held[a]);
    de_e(a) = rates(prescribed[a]) * dt;
    for (int b = 0; b < 3; ++b) {
      css(a, b) = C(held[a], held[b]);
      cse(a, b) = C(held[a], prescribed[b]);
    }
  }
  const Vector3d de_s = css.lu().solve(g * error - cse * de_e);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(step(prescribed[a]), de_e(a));
    // 1e-8: the servo regularises C by 1e-9 of its largest entry
    EXPECT_NEAR(step(held[a]), de_s(a), 1e-8 * de_s.cwiseAbs().maxCoeff());
    EXPECT_NEAR((C * step)(held[a]), g * error(a), 1e-8 * error.cwiseAbs().maxCoeff());
  }
}

// drained simple shear in xz of an isotropic linear-elastic cell: the lateral axes and the
// other shears do not strain, sigma_zz reaches sigma_n, tau = mu gamma and the lateral stress
// is sigma_0 + lambda eps_zz with eps_zz = (sigma_n - sigma_0)/(lambda + 2 mu)
TEST(CellControl, DrainedSimpleShearOfAnElasticCell)
{
  const double lambda = 4e8, mu = 2.5e8, sigma0 = 1e5, sigma_n = 1.6e5, rate = 0.05, dt = 1e-5;
  const tycore::DrainedSimpleShear test{{0, 2}, rate, sigma_n};
  LinearCell cell{isotropic_stiffness(lambda, mu), Vector6d::Zero()};
  cell.stress0.head<3>().setConstant(sigma0);
  tycore::ServoMemoryOf<6> memory;
  const int steps = 2000;
  for (int s = 0; s < steps; ++s) {
    const tycore::ServoCommandOf<6> c =
        tycore::servo_step(test.control(), cell.measure(), settings(), dt, memory);
    cell.advance(c.strain_rate, dt);
  }
  const Vector6d stress = cell.measure().stress;
  const double gamma = rate * steps * dt;
  EXPECT_EQ(cell.strain(0), 0.0);
  EXPECT_EQ(cell.strain(1), 0.0);
  EXPECT_EQ(cell.strain(3), 0.0);
  EXPECT_EQ(cell.strain(5), 0.0);
  EXPECT_NEAR(-cell.strain(4), gamma, 1e-14);
  EXPECT_NEAR(tycore::normal_stress(stress, test.plane), sigma_n, 1e-9 * sigma_n);
  EXPECT_NEAR(tycore::shear_stress(stress, test.plane), mu * gamma, 1e-9 * mu * gamma);
  const double eps_zz = (sigma_n - sigma0) / (lambda + 2 * mu);
  EXPECT_NEAR(cell.strain(2), eps_zz, 1e-9 * eps_zz);
  EXPECT_NEAR(stress(0), sigma0 + lambda * eps_zz, 1e-9 * sigma0);
}

// objectivity: an anisotropic cell sheared in xz, and the same cell with its axes relabelled
// (y <-> z: sheared in xy; x <-> y: sheared in yz), give the same tau, sigma_n and normal strain
// histories
TEST(CellControl, SimpleShearIsTheSameInEveryPlaneOfAPermutedCell)
{
  std::mt19937 rng(6);
  const Matrix6d C = random_spd(rng, 1e8);
  const tycore::ShearPlane xz{0, 2};
  auto history = [&](const std::array<int, 3>& axis, const tycore::ShearPlane& plane) {
    Matrix6d P = Matrix6d::Zero();    // Voigt6 component (i, j) -> (axis[i], axis[j])
    for (int I = 0; I < 6; ++I)
      P(tycore::voigt_index(axis[tycore::voigt_pairs[I][0]], axis[tycore::voigt_pairs[I][1]]), I) = 1;
    LinearCell cell{P * C * P.transpose(), Vector6d::Zero()};
    cell.stress0.head<3>().setConstant(1e5);
    const tycore::DrainedSimpleShear test{plane, 0.03, 1.3e5};
    tycore::ServoMemoryOf<6> memory;
    std::vector<Vector3d> out;
    for (int s = 0; s < 400; ++s) {
      cell.advance(tycore::servo_step(test.control(), cell.measure(), settings(), 1e-5, memory)
                       .strain_rate,
                   1e-5);
      const Vector6d stress = cell.measure().stress;
      out.emplace_back(tycore::shear_stress(stress, plane), tycore::normal_stress(stress, plane),
                       cell.strain(plane.normal));
    }
    return out;
  };
  const std::vector<Vector3d> reference = history({0, 1, 2}, xz);
  const std::vector<Vector3d> in_xy = history({0, 2, 1}, {0, 1});
  const std::vector<Vector3d> in_yz = history({1, 0, 2}, {1, 2});
  for (std::size_t k = 0; k < reference.size(); ++k)
    for (int q = 0; q < 3; ++q) {
      const double scale = reference.back().cwiseAbs()(q);
      EXPECT_NEAR(in_xy[k](q), reference[k](q), 1e-10 * scale) << k << " " << q;
      EXPECT_NEAR(in_yz[k](q), reference[k](q), 1e-10 * scale) << k << " " << q;
    }
  EXPECT_GT(std::abs(reference.back()(0)), 1e3);    // it did shear
}

// undrained triaxial on an anisotropic cell: eps_v = 0 to round-off, sigma_2 = sigma_3 held,
// the axial strain at the prescribed rate, the shears unstrained
TEST(CellControl, UndrainedTriaxialHoldsVolumeAndLateralStresses)
{
  std::mt19937 rng(4);
  for (int axis = 0; axis < 3; ++axis) {
    LinearCell cell{random_spd(rng, 1e8), Vector6d::Zero()};
    cell.stress0.head<3>().setConstant(1e5);
    const tycore::UndrainedTriaxial test{axis, -0.02};    // extension
    tycore::ServoMemoryOf<6> memory;
    const double dt = 1e-5;
    for (int s = 0; s < 1000; ++s)
      cell.advance(tycore::servo_step(test.control(), cell.measure(), settings(), dt, memory)
                       .strain_rate,
                   dt);
    const Vector6d stress = cell.measure().stress;
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    EXPECT_NEAR(cell.strain.head<3>().sum(), 0.0, 1e-16);
    EXPECT_NEAR(cell.strain(axis), -0.02 * 1000 * dt, 1e-15);
    EXPECT_NEAR(stress(b), stress(c), 1e-6 * 1e5) << axis;
    EXPECT_EQ(cell.strain.tail<3>(), Vector3d::Zero());
  }
}

// oedometric loading and unloading of an anisotropic linear cell along each axis: the lateral
// strains and the shears stay zero exactly (no servo: every component is strain controlled);
// the ratio of the stress changes is the elastic K0 of the increments, (C_ba + C_ca)/(2 C_aa);
// loading ends at the first step with sigma_a >= the peak, unloading at the first with
// (largest sigma_a)/sigma_a >= OCR, and then the cell rests; the progress grows from 0 to 1
TEST(CellControl, OedometerHoldsTheLateralStrainsAndGivesTheElasticK0)
{
  std::mt19937 rng(7);
  const double p0 = 1e5, rate = 1.0, dt = 1e-6, peak = 4e5, ocr = 2.0;
  for (int axis = 0; axis < 3; ++axis) {
    LinearCell cell{random_spd(rng, 1e8), Vector6d::Zero()};
    cell.stress0.head<3>().setConstant(p0);
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    const double k0_elastic =
        (cell.stiffness(b, axis) + cell.stiffness(c, axis)) / (2.0 * cell.stiffness(axis, axis));
    const tycore::OedometerCourse course{peak, ocr};
    tycore::OedometerCourse::State s = course.begin(p0, p0);
    tycore::ServoMemoryOf<6> memory;
    double largest = p0, progress = 0.0, last_step = 0.0;
    int phase_changes = 0, last_direction = 1, steps = 0;
    for (; s.direction != 0 && steps < 100000; ++steps) {
      const tycore::MixedControl6 control =
          tycore::OedometricCompression{axis, s.direction * rate}.control();
      EXPECT_EQ(control.actuator_count, 0);
      cell.advance(tycore::servo_step(control, cell.measure(), settings(), dt, memory).strain_rate,
                   dt);
      const Vector6d stress = cell.measure().stress;
      last_step = std::abs(stress(axis) - s.last);
      largest = std::max(largest, stress(axis));
      course.update(s, stress(axis));
      if (s.direction != last_direction) {    // at the first step beyond the bound
        ++phase_changes;
        if (last_direction > 0) {
          EXPECT_GE(stress(axis), peak);
          EXPECT_LT(stress(axis) - last_step, peak);
        } else {
          EXPECT_GE(largest / stress(axis), ocr);
          EXPECT_LT(largest / (stress(axis) + last_step), ocr);
        }
        last_direction = s.direction;
      }
      EXPECT_EQ(cell.strain(b), 0.0);
      EXPECT_EQ(cell.strain(c), 0.0);
      EXPECT_EQ(cell.strain.tail<3>(), Vector6d::Zero().tail<3>());
      const double radial = tycore::radial_stress(stress, axis);
      EXPECT_NEAR((radial - p0) / (stress(axis) - p0), k0_elastic, 1e-9) << axis;
      EXPECT_NEAR(tycore::axial_deviator(stress, axis), stress(axis) - radial, 1e-9 * p0);
      EXPECT_GE(course.progress(s), progress);
      progress = course.progress(s);
    }
    EXPECT_EQ(phase_changes, 2);    // loading -> unloading -> at rest
    EXPECT_EQ(progress, 1.0);
    EXPECT_EQ(s.largest, largest);
    EXPECT_EQ((tycore::OedometricCompression{axis, 0.0}.control().prescribed_strain_rate),
              Vector6d::Zero());
  }
  // without unloading (OCR 1) the course ends at the peak
  const tycore::OedometerCourse loading{peak};
  tycore::OedometerCourse::State s = loading.begin(p0, p0);
  loading.update(s, 0.5 * (p0 + peak));
  EXPECT_DOUBLE_EQ(loading.progress(s), 0.5);
  loading.update(s, peak);
  EXPECT_EQ(s.direction, 0);
}

// undrained cyclic triaxial test on an isotropic linear cell whose mean stress falls by beta
// per unit of axial strain travelled (a contractive model): at eps_v = 0, q_a = 3 mu eps_a, so
// the reversals come at eps_a = +-2 CSR p0/(3 mu) (two-way) or at +2 CSR p0/(3 mu) and 0
// (one-way); eps_v = 0 and sigma_b = sigma_c held; N_L by r_u where the travel 0.95 p0/beta is
// reached; N_L by double amplitude eps_a >= 5 % in the second half cycle (swing 6 %) two-way,
// never one-way (swing 3 %)
TEST(CellControl, CyclicUndrainedTriaxialCountsCyclesToLiquefaction)
{
  const double p0 = 1e5, csr = 0.15, lame = 2e6, mu = 1e6 / 3.0, beta = 3e5, rate = 1.0;
  const double dt = 1e-5;
  const double eps_amplitude = 2.0 * csr * p0 / (3.0 * mu);    // 0.03
  for (bool one_way : {false, true}) {
    const tycore::CyclicUndrainedTriaxial test{2, rate, csr, p0, one_way};
    tycore::CyclicUndrainedTriaxial::State state;
    LinearCell cell{isotropic_stiffness(lame, mu), Vector6d::Zero()};
    cell.stress0.head<3>().setConstant(p0);
    tycore::ServoMemoryOf<6> memory;
    double travel = 0.0;
    int reversals_seen = 0;
    while (travel < 2.0 && state.cycles_to_pore_pressure == 0.0) {
      const tycore::MixedControl6 control = test.control(state);
      const Vector6d rate6 =
          tycore::servo_step(control, cell.measure(), settings(), dt, memory).strain_rate;
      cell.advance(rate6, dt);
      travel += std::abs(rate6(2)) * dt;
      Vector6d stress = cell.measure().stress;
      stress.head<3>().array() -= beta * travel;
      const int before = state.reversals;
      test.update(state, stress, cell.strain);
      EXPECT_NEAR(cell.strain.head<3>().sum(), 0.0, 1e-15);
      EXPECT_NEAR(stress(0), stress(1), 1e-6 * p0);
      if (state.reversals != before) {
        ++reversals_seen;
        const bool at_top = state.direction < 0;    // it turned towards the lower bound
        const double bound = at_top ? eps_amplitude : (one_way ? 0.0 : -eps_amplitude);
        EXPECT_NEAR(cell.strain(2), bound, 2 * rate * dt) << one_way << " " << reversals_seen;
      }
    }
    EXPECT_EQ(reversals_seen, state.reversals);
    EXPECT_EQ(state.cycles(), 0.5 * reversals_seen);
    // half cycle k ends after a travel of eps_amplitude (2k - 1) two-way, k eps_amplitude one-way
    const double travel_at_liquefaction = 0.95 * p0 / beta;
    const int half_cycle =
        one_way ? static_cast<int>(std::ceil(travel_at_liquefaction / eps_amplitude))
                : static_cast<int>(std::ceil((travel_at_liquefaction / eps_amplitude + 1) / 2));
    EXPECT_DOUBLE_EQ(state.cycles_to_pore_pressure, 0.5 * half_cycle) << one_way;
    EXPECT_DOUBLE_EQ(state.cycles_to_double_amplitude, one_way ? 0.0 : 1.0);
  }
}

// constant p with a deviatoric rate on six components equals mean_stress_control on three
// when the shears are zero
TEST(CellControl, MeanStressControlOnSixComponents)
{
  const Vector3d deviatoric(0.01, -0.004, -0.006);
  Vector6d rate6 = Vector6d::Zero();
  rate6.head<3>() = deviatoric;
  Matrix6d c6 = isotropic_stiffness(3e8, 2e8);
  const Vector3d stress3(1.1e5, 0.9e5, 0.95e5);
  Vector6d stress6 = Vector6d::Zero();
  stress6.head<3>() = stress3;
  tycore::ServoMemory m3;
  tycore::ServoMemoryOf<6> m6;
  const tycore::ServoCommand a = tycore::servo_step(
      tycore::mean_stress_control(1e5, deviatoric),
      {stress3, Matrix3d(c6.topLeftCorner<3, 3>()), Vector3d::Zero()}, settings(), 1e-6, m3);
  const tycore::ServoCommandOf<6> b = tycore::servo_step(
      tycore::mean_stress_control6(1e5, rate6), {stress6, c6, Vector6d::Zero()}, settings(), 1e-6,
      m6);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(b.strain_rate(k), a.strain_rate(k), 1e-12);
}

// cyclic constant-volume simple shear on a contractive model (tau = G gamma, sigma_n falls by
// beta per unit of shear strain travelled): reversals at gamma = +-tau_cyc/G, N counted in
// half cycles, N_L by r_u where the travel 0.95 sigma_n0/beta is reached, N_L by double
// amplitude in the second half cycle (swing 2 tau_cyc/G >= 3.75 %)
TEST(CellControl, CyclicSimpleShearCountsCyclesToLiquefaction)
{
  const double sigma_n0 = 1e5, csr = 0.2, G = 1e6, beta = 1.5e6, rate = 1.0, dt = 1e-5;
  const tycore::CyclicSimpleShear test{{0, 2}, rate, csr, sigma_n0, {}};
  test.require_valid();
  const double gamma_a = csr * sigma_n0 / G;    // 0.02
  tycore::CyclicSimpleShear::State state;
  double gamma = 0.0, travel = 0.0, extreme = 0.0;
  int reversals_seen = 0;
  while (travel < 1.0 && state.cycles_to_pore_pressure == 0.0) {
    const double gamma_dot = -test.control(state).prescribed_strain_rate(4);
    gamma += gamma_dot * dt;
    travel += std::abs(gamma_dot) * dt;
    const int before = state.reversals;
    test.update(state, G * gamma, gamma, sigma_n0 - beta * travel);
    if (state.reversals != before) {
      ++reversals_seen;
      extreme = gamma;
      EXPECT_NEAR(std::abs(gamma), gamma_a, 2 * rate * dt);
    }
  }
  EXPECT_EQ(reversals_seen, state.reversals);
  EXPECT_EQ(test.cycles(state), 0.5 * reversals_seen);    // cycles completed
  EXPECT_NEAR(std::abs(extreme), gamma_a, 2 * rate * dt);
  // half cycle k ends after a travel of gamma_a (2k - 1)
  const double travel_at_liquefaction = 0.95 * sigma_n0 / beta;
  const int half_cycle = static_cast<int>(std::ceil((travel_at_liquefaction / gamma_a + 1) / 2));
  EXPECT_DOUBLE_EQ(state.cycles_to_pore_pressure, 0.5 * half_cycle);
  EXPECT_DOUBLE_EQ(state.cycles_to_double_amplitude, 1.0);
  // restart array round trip
  double a[tycore::CyclicSimpleShear::State::size];
  state.to_array(a);
  const tycore::CyclicSimpleShear::State back = tycore::CyclicSimpleShear::State::from_array(a);
  EXPECT_EQ(back.reversals, state.reversals);
  EXPECT_EQ(back.direction, state.direction);
  EXPECT_EQ(back.cycles_to_pore_pressure, state.cycles_to_pore_pressure);
}

// the rotating targets keep p, q and b and put sigma_1 at alpha in the plane; the servo on an
// elastic cell reaches them, the shears out of the plane at zero
TEST(CellControl, PrincipalStressRotationTargets)
{
  const tycore::PrincipalStressRotation test{0, 2, 2e5, 1.2e5, 0.4, 10.0, 2.0};
  for (double t : {0.0, 5.0, 20.0, 47.5, 80.0}) {
    const Vector6d target = test.targets(t);
    const Matrix3d sigma = tycore::tensor_from_stress(target);
    const tycore::PrincipalAxes axes = tycore::principal_axes(sigma);
    EXPECT_NEAR(axes.values.mean(), 2e5, 1e-9 * 2e5);
    EXPECT_NEAR(axes.values(0) - axes.values(2), 1.2e5, 1e-9 * 2e5);
    EXPECT_NEAR(tycore::b_value(axes.values), 0.4, 1e-9);
    EXPECT_NEAR(std::abs(axes.directions(1, 1)), 1.0, 1e-12);    // sigma_2 along y
    EXPECT_NEAR(tycore::major_angle_in_plane_deg(sigma, 0, 2),
                tycore::axis_angle_deg(10.0 + 2.0 * t), 1e-9);
    EXPECT_EQ(target(3), 0.0);
    EXPECT_EQ(target(5), 0.0);
  }
  LinearCell cell{isotropic_stiffness(3e8, 2e8), Vector6d::Zero()};
  cell.stress0.head<3>().setConstant(2e5);
  tycore::ServoMemoryOf<6> memory;
  for (int s = 0; s < 1000; ++s)    // slow pole 0.978 of g = 0.25, g_I = 0.005 (§6.2)
    cell.advance(
        tycore::servo_step(test.control(5.0), cell.measure(), settings(), 1e-6, memory).strain_rate,
        1e-6);
  EXPECT_LT((cell.measure().stress - test.targets(5.0)).cwiseAbs().maxCoeff(), 1e-6 * 2e5);
}

TEST(CellControl, BadInputIsRejected)
{
  EXPECT_THROW((tycore::DrainedSimpleShear{{2, 0}, 0.1, 1e5}.control()), std::invalid_argument);
  EXPECT_THROW((tycore::DrainedSimpleShear{{0, 2}, NAN, 1e5}.control()), std::invalid_argument);
  EXPECT_THROW((tycore::DrainedSimpleShear{{0, 2}, 0.1, -1e5}.control()), std::invalid_argument);
  EXPECT_THROW((tycore::CyclicSimpleShear{{0, 1}, 1.0, 0.0, 1e5, {}}.require_valid()),
               std::invalid_argument);
  EXPECT_THROW((tycore::CyclicSimpleShear{{0, 1}, 1.0, 0.2, 1e5, {1.5, 0.0375}}.require_valid()),
               std::invalid_argument);
  EXPECT_THROW((tycore::UndrainedTriaxial{3, 0.1}.control()), std::invalid_argument);
  // q so large that sigma_3 would be tensile
  EXPECT_THROW((tycore::PrincipalStressRotation{0, 2, 1e5, 5e5, 0.0, 0.0, 0.0}.targets(0.0)),
               std::invalid_argument);
  std::array<tycore::AxisProgramme, 6> c;
  c.fill({tycore::AxisControl::STRAIN_RATE, 0.0});
  c[4] = {tycore::AxisControl::STRESS, INFINITY};
  EXPECT_THROW(tycore::per_axis_control<6>(c), std::invalid_argument);
  tycore::MixedControl full = tycore::isotropic_compression_control(1e5);
  EXPECT_THROW(full.add(Vector3d::Ones(), Vector3d::Ones(), 1e5), std::invalid_argument);
}
