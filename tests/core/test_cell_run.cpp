// What fix cell/servo decides while a test runs, as plain C++ (plugin/core/cell_progress.hpp,
// cell_command.hpp, cell_outputs.hpp, cell_restart.hpp): the progress and ETA outputs, the
// clock and the boundary work of the test, the rates settled at a run's setup, the errors of a
// step that strains the cell too far, of a box changed between runs and of a record a new test
// would overwrite, and the record's header and rows. Every expected value is worked out here
// from the definitions in docs/fix_cell_servo.md and docs/theory.md §5.3, §4.2.
#include "cell_progress.hpp"
#include "cell_restart.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using tycore::Vector6d;
namespace out = tycore::out;

namespace {

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

tycore::CellCommand parse(const std::string &text)
{
  std::istringstream in(text);
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  return tycore::parse_cell_command(w, true);
}

// settings that are numbers only
struct Numbers : tycore::SettingValues {
  double operator()(tycore::Setting &s) override { return s.value; }
};

bool contains(const std::string &text, const std::string &part)
{
  return text.find(part) != std::string::npos;
}

}    // namespace

// progress towards `until`: the fraction of the way from the measure's value when the test
// began to the target; eta at the pace of the progress made in this run
TEST(CellRun, ProgressTowardsTheUntilTarget)
{
  tycore::UntilTarget until;
  until.output = out::EPS1;
  until.value = 0.1;
  tycore::RunProgress run{0, 1000, 100, 0.2};
  double o[out::COUNT];
  o[out::EPS1] = 0.04;    // from 0.02 at the test's start: (0.04 - 0.02)/(0.1 - 0.02) = 0.25
  run.outputs(until, 0.02, NaN, NaN, 150, 30.0, 1e-6, o);
  EXPECT_DOUBLE_EQ(o[out::PROGRESS], 0.25);
  // 0.05 of progress in 30 s: the 0.75 left takes 450 s
  EXPECT_DOUBLE_EQ(o[out::ETA_SECONDS], 450.0);
  // past the target: 1; a measure that has moved back: 0 (and no pace: NaN)
  o[out::EPS1] = 0.2;
  run.outputs(until, 0.02, NaN, NaN, 150, 30.0, 1e-6, o);
  EXPECT_EQ(o[out::PROGRESS], 1.0);
  o[out::EPS1] = 0.0;
  run.outputs(until, 0.02, NaN, NaN, 150, 30.0, 1e-6, o);
  EXPECT_EQ(o[out::PROGRESS], 0.0);
  EXPECT_TRUE(std::isnan(o[out::ETA_SECONDS]));
}

// without `until`: the programme's course, timed by its simulated time left at this run's
// wall time per step, or by the pace of its progress; else the fraction of the run done
TEST(CellRun, ProgressAlongTheCourseOrTheRun)
{
  const tycore::UntilTarget none;
  tycore::RunProgress run{1000, 3000, 1000, 0.1};
  double o[out::COUNT];
  // a strain path: 0.4 done, 2e-3 s of simulated time left at dt 1e-6 = 2000 steps, at
  // 40 s / 500 steps
  run.outputs(none, NaN, 0.4, 2e-3, 1500, 40.0, 1e-6, o);
  EXPECT_DOUBLE_EQ(o[out::PROGRESS], 0.4);
  EXPECT_NEAR(o[out::ETA_SECONDS], 2000 * 40.0 / 500, 1e-9);
  // k0 (no time left known): 0.3 of progress in 40 s, 0.6 left
  run.outputs(none, NaN, 0.4, NaN, 1500, 40.0, 1e-6, o);
  EXPECT_DOUBLE_EQ(o[out::ETA_SECONDS], 40.0 / 0.3 * 0.6);
  // no course: 500 of the run's 2000 steps, 1500 left at 40 s / 500 steps
  run.outputs(none, NaN, NaN, NaN, 1500, 40.0, 1e-6, o);
  EXPECT_DOUBLE_EQ(o[out::PROGRESS], 0.25);
  EXPECT_DOUBLE_EQ(o[out::ETA_SECONDS], 1500 * 40.0 / 500);
  // at the setup: no pace yet; an empty run is done
  run.outputs(none, NaN, NaN, NaN, 1000, 0.0, 1e-6, o);
  EXPECT_EQ(o[out::PROGRESS], 0.0);
  EXPECT_TRUE(std::isnan(o[out::ETA_SECONDS]));
  tycore::RunProgress empty{1000, 1000, 1000, 0.0};
  empty.outputs(none, NaN, NaN, NaN, 1000, 0.0, 1e-6, o);
  EXPECT_EQ(o[out::PROGRESS], 1.0);
}

// elapsed time counts the steps since the last count; a step of an earlier run counts none.
// The boundary work V sigma : deps over a step, engineering shears on a triclinic cell
TEST(CellRun, ClockAndBoundaryWork)
{
  tycore::CellTestState t;
  t.clock_step = 100;
  t.advance_clock(150, 2e-6);
  EXPECT_DOUBLE_EQ(t.elapsed_time, 1e-4);
  t.advance_clock(150, 2e-6);
  EXPECT_DOUBLE_EQ(t.elapsed_time, 1e-4);
  t.advance_clock(120, 2e-6);    // a restart from an earlier step: the clock follows it
  EXPECT_DOUBLE_EQ(t.elapsed_time, 1e-4);
  EXPECT_EQ(t.clock_step, 120);

  Vector6d stress, rate;
  stress << 1e5, 2e5, 3e5, 1e4, 2e4, 3e4;
  rate << 1e-3, -2e-3, 0.0, 4e-3, 0.0, -1e-3;
  const double V = 2e-9, dt = 1e-6;
  // orthogonal: 1e5*1e-3 - 2e5*2e-3 = -300 Pa/s; triclinic adds 1e4*4e-3 - 3e4*1e-3 = 10
  t.add_boundary_work(V, stress, rate, dt, 3);
  EXPECT_NEAR(t.boundary_work, V * -300.0 * dt, 1e-24);
  t.boundary_work = 0.0;
  t.add_boundary_work(V, stress, rate, dt, 6);
  EXPECT_NEAR(t.boundary_work, V * -290.0 * dt, 1e-24);
}

// the default cap: the rate at inertial number 1e-3 at the held p (I = eps_dot d sqrt(rho/p),
// docs/theory.md §4.2), at least 4 times the prescribed rate; what the fix is told
TEST(CellRun, RatesSettledAtSetup)
{
  const double d = 1e-3, rho = 2650.0;
  tycore::CellCommand c = parse("axisym x 1e-4 1e5");
  tycore::RateReport r = tycore::settle_rates(c, 1e5, 1e-6, d, rho);
  EXPECT_NEAR(c.settings.max_strain_rate, 1e-3 / (d * std::sqrt(rho / 1e5)), 1e-12);
  EXPECT_TRUE(r.slow_cap.empty() && r.unresolvable.empty() && r.inertial.empty());
  // a cap below the prescribed rate: the free axes cannot follow
  c = parse("axisym x 1e-4 1e5 max_rate 1e-5");
  r = tycore::settle_rates(c, 1e5, 1e-6, d, rho);
  EXPECT_EQ(c.settings.max_strain_rate, 1e-5);
  EXPECT_TRUE(contains(r.slow_cap, "max_rate 1e-05 is below the prescribed strain rate 0.0001"))
      << r.slow_cap;
  // a given cap the cell cannot follow (1e5 * 1e-6 = 0.1 per step, above 0.01)
  c = parse("axisym x 1e-4 1e5 max_rate 1e5");
  r = tycore::settle_rates(c, 1e5, 1e-6, d, rho);
  EXPECT_TRUE(contains(r.unresolvable, "max_rate = 1e+05 1/s strains the cell by 0.1 per step"))
      << r.unresolvable;
  // 20 1/s: I = 20 d sqrt(rho/p) = 3.26e-3 > 1e-3
  c = parse("axisym x 20 1e5");
  r = tycore::settle_rates(c, 1e5, 1e-6, d, rho);
  EXPECT_NEAR(c.settings.max_strain_rate, 80.0, 1e-12);    // 4 x 20 above the I cap
  EXPECT_TRUE(contains(r.inertial, "inertial number I = 0.00326")) << r.inertial;
  // a servo setting refused
  c = parse("axisym x 1e-4 1e5");
  c.settings.gain = 2.0;
  EXPECT_THROW(tycore::settle_rates(c, 1e5, 1e-6, d, rho), std::invalid_argument);
}

// a step's rates must strain the cell by at most 0.01
TEST(CellRun, StepStrainError)
{
  Vector6d rate = Vector6d::Zero();
  rate(4) = -9e3;    // 9e3 * 1e-6 = 0.009: followed
  EXPECT_EQ(tycore::step_strain_error(rate, 1e-6, 7), "");
  rate(1) = 2e4;    // 0.02
  EXPECT_EQ(tycore::step_strain_error(rate, 1e-6, 7),
            "at step 7 the strain rate 2e+04 1/s strains the cell by 0.02 in one step; the cell "
            "cannot follow more than 0.01 per step: use rates <= 1e+04 1/s (or a smaller "
            "timestep)");
}

TEST(CellRun, UntilReachedAndBoxChanged)
{
  tycore::CellCommand c = parse("axisym x 1e-4 1e5 until eps_d13 0.003");
  EXPECT_EQ(c.until.reached_message(0.0030004, 1234),
            "eps_d13 = 0.0030004 reached the target 0.003 at step 1234: the run stops");
  const double left[6] = {1.0, 2.0, 3.0, 0.0, 0.1, 0.0};
  double now[6] = {1.0, 2.0, 3.0, 0.0, 0.1, 0.0};
  EXPECT_EQ(tycore::box_changed_error(left, now), "");
  now[4] = 0.2;
  EXPECT_TRUE(contains(tycore::box_changed_error(left, now),
                       "the box was changed between runs (xz 0.1 -> 0.2) by another command"));
  const double unset[6] = {NaN, NaN, NaN, NaN, NaN, NaN};
  EXPECT_EQ(tycore::box_changed_error(unset, now), "");
}

// a redefinition that continues a test: its state, with the servo's integral and the until
// measure afresh; 'continue no' may not overwrite the old record, by file identity
TEST(CellRun, ContinuedTestAndItsRecord)
{
  tycore::CellCommand old_fix = parse("shear_cv xz 1e-4");
  Numbers numbers;
  old_fix.programme->begin_run(
      {0.0, 1e-6, (Vector6d() << 1, 2, 3e5, 0, -1, 0).finished(), Vector6d::Zero()}, numbers);
  tycore::TestCarry carry;
  carry.test.elapsed_time = 0.5;
  carry.test.boundary_work = 7.0;
  carry.test.memory.integral.setConstant(3.0);
  carry.test.until_start = 0.01;
  carry.programme = old_fix.programme->carried();
  tycore::CellTestState t;
  tycore::CellCommand next = parse("shear_cv xz 1e-4");
  tycore::continue_test(carry, t, *next.programme);
  EXPECT_EQ(t.elapsed_time, 0.5);
  EXPECT_EQ(t.boundary_work, 7.0);
  EXPECT_TRUE(t.memory.integral.isZero());
  EXPECT_TRUE(std::isnan(t.until_start));
  EXPECT_EQ(next.programme->carried(), carry.programme);    // sigma_n0 = sigma_zz = 3e5

  const std::string path = testing::TempDir() + "cell_run_record.csv";
  std::ofstream(path) << "step\n";
  carry.record = tycore::file_identity(path);
  carry.record_path = path;
  EXPECT_EQ(tycore::overwritten_record_error(testing::TempDir() + "./cell_run_record.csv", carry),
            "'continue no' starts a new test, whose record " + testing::TempDir() +
                "./cell_run_record.csv would overwrite " + path +
                ", the record of the test it replaces: name another file");
  EXPECT_EQ(tycore::overwritten_record_error(path + ".other", carry), "");
  std::remove(path.c_str());
}

// the record: `step`, then the outputs of its columns; the row their values in that order
TEST(CellRun, RecordHeaderAndRow)
{
  const std::vector<int> columns{out::TIME, out::P, out::Q, out::R_U};
  EXPECT_EQ(out::record_header(columns), "step,time,p,q,r_u");
  double o[out::COUNT];
  o[out::TIME] = 1.5, o[out::P] = 1e5, o[out::Q] = 2e4, o[out::R_U] = 0.25;
  EXPECT_EQ(out::record_row(columns, o), (std::vector<double>{1.5, 1e5, 2e4, 0.25}));
  // every record starts with time and the principal strains
  const std::vector<int> all = out::record_columns(false, {out::R_U});
  EXPECT_EQ(out::record_header(all).rfind("step,time,eps1,eps2,eps3,", 0), 0u);
  EXPECT_EQ(all.back(), out::R_U);
}

// the quasi-equilibrium sample of a preparation from the step's outputs
TEST(CellRun, EquilibriumSampleFromTheOutputs)
{
  double o[out::COUNT];
  o[out::UNBALANCED] = 1e-3, o[out::KINETIC_RATIO] = 2e-8, o[out::Z] = 4.5;
  Vector6d stress;
  stress << 1e5, 1.01e5, 0.99e5, 5.0, 6.0, 7.0;
  const tycore::EquilibriumSample s = tycore::equilibrium_sample(stress, 1e5, o);
  EXPECT_EQ(s.stress, Eigen::Vector3d(1e5, 1.01e5, 0.99e5));
  EXPECT_EQ(s.target_stress, Eigen::Vector3d::Constant(1e5));
  EXPECT_EQ(s.unbalanced_force_ratio, 1e-3);
  EXPECT_EQ(s.kinetic_energy_ratio, 2e-8);
  EXPECT_EQ(s.coordination, 4.5);
}
