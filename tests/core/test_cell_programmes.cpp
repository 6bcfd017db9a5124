// The test programmes of fix cell/servo as objects (plugin/core/cell_programmes.hpp,
// cell_command.hpp, cell_restart.hpp; docs/fix_cell_servo.md): the command parsed with errors
// that name the argument, what each programme asks of the cell (the stiffness entries of
// docs/theory.md §11.2), the cycle count of the cyclic tests run to their end on an elastic
// cell (N cycles are 2N half cycles), the checks of `until`, the outputs of k0, restart records
// and what a continued test takes over.
#include "cell_command.hpp"
#include "cell_restart.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

using tycore::Vector6d;

namespace {

std::vector<std::string> words(const std::string& text)
{
  std::istringstream in(text);
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  return w;
}

tycore::CellCommand parse(const std::string& text, bool triclinic = true)
{
  return tycore::parse_cell_command(words(text), triclinic);
}

// the message of the error that parsing `text` raises ("" if none)
std::string refusal(const std::string& text, bool triclinic = true)
{
  try {
    parse(text, triclinic);
  } catch (std::exception& e) {
    return e.what();
  }
  return "";
}

// settings that are numbers only
struct Numbers : tycore::SettingValues {
  double operator()(tycore::Setting& s) override { return s.value; }
};

}    // namespace

TEST(CellProgrammes, ArgumentsAreNamedInTheErrors)
{
  const std::pair<const char*, const char*> cases[] = {
      {"iso 1e400", "iso mean stress p must be a finite number, got '1e400' (it overflows to "
                    "infinity)"},
      {"iso 0", "target iso mean stress p = 0 must be positive"},
      {"iso 1e300", "target iso mean stress p = 1e300 is above 1e+15 Pa, beyond any granular "
                    "material"},
      {"axes x stress 1e300 y rate 0 z rate 0", "axes x stress = 1e300 is outside the accepted "
                                                "range [-1e+15, 1e+15] Pa"},
      {"constant_b 1.5 x 1e-5 1e5", "constant_b b = 1.5 is outside the accepted range [0, 1]"},
      {"shear xz 1e-4", "expected 3 more argument(s): shear PLANE GDOT SN"},
      {"shear zx 1e-4 1e5", "shear: plane 'zx' is not xy, xz or yz"},
      {"stress_rotation xz 1e5 0 0.5 1", "stress_rotation Q = sigma1 - sigma3 = 0 is outside "
                                         "the accepted range (0, 1e+15] Pa (Q = 0 is an "
                                         "isotropic stress"},
      {"rotation xz 1e5 5e4 0.5 1", "'rotation PLANE P Q B DEG' is now 'stress_rotation"},
      {"iso 1e5 close yes", "keyword 'close' applies only to polygon"},
      {"iso 1e5 speed 1e-5", "keyword 'speed' applies only to circle, triangle and polygon"},
      {"iso 1e5 gain 0.2 gain 0.3", "keyword 'gain' is given twice"},
      {"cyclic_shear xz 1e-4 1e-12", "cyclic_shear CSR = 1e-12 is outside the accepted range "
                                     "[1e-06, 10]"},
      {"circle 0.001 1e5", "a Pi-plane path needs 'speed V'"},
  };
  for (const auto& c : cases) {
    EXPECT_NE(refusal(c.first).find(c.second), std::string::npos)
        << c.first << ": " << refusal(c.first);
  }
  // an empty record name (LAMMPS passes "" as an empty word)
  std::vector<std::string> empty_csv = words("iso 1e5 csv");
  empty_csv.push_back("");
  empty_csv.push_back("10");
  try {
    tycore::parse_cell_command(empty_csv, false);
    ADD_FAILURE() << "csv '' accepted";
  } catch (std::exception& e) {
    EXPECT_STREQ(e.what(), "csv needs a file name, got ''");
  }
  EXPECT_NE(refusal("shear xz 1e-4 1e5", false).find("needs a triclinic box: make the box "
                                                     "triclinic before this fix is defined"),
            std::string::npos);
}

// the stiffness entries a servo needs (docs/theory.md §11.2): drained simple shear in (i, j)
// holds sigma_jj and strains gamma_ij, so C_jj,jj and C_jj,ij; an orthogonal cell's principal
// programme the principal block; on a triclinic cell the others take all 21
TEST(CellProgrammes, StiffnessEntriesOfTheServo)
{
  using Sums = tycore::AffineStiffnessSums;
  const std::pair<const char*, unsigned> drained[] = {
      {"shear xz 1e-4 1e5", Sums::entry(2, 2) | Sums::entry(2, 4)},
      {"shear xy 1e-4 1e5", Sums::entry(1, 1) | Sums::entry(1, 3)},
      {"shear yz -1e-4 1e5", Sums::entry(2, 2) | Sums::entry(2, 5)}};
  for (const auto& d : drained)
    EXPECT_EQ(tycore::stiffness_entries_of(parse(d.first).programme->profile(), true), d.second)
        << d.first;
  EXPECT_EQ(tycore::stiffness_entries_of(parse("axisym x 1e-5 1e5", false).programme->profile(),
                                         false), Sums::principal_entries);
  EXPECT_EQ(tycore::stiffness_entries_of(parse("undrained x 1e-5").programme->profile(), true),
            Sums::all_entries);
}

// cyclic_shear on an elastic cell (tau = G gamma, sigma_n constant): gamma_dot = +GDOT first;
// `until cycles 3` ends the test at the step the count reaches 3, after the sixth reversal
TEST(CellProgrammes, UntilCyclesNStopsAfterNCycles)
{
  tycore::CellCommand c = parse("cyclic_shear xz 1.0 0.2 until cycles 3");
  tycore::CellProgramme& p = *c.programme;
  const double G = 1e6, dt = 1e-5, sigma_n = 1e5;
  Numbers values;
  tycore::CellState state;
  state.dt = dt;
  state.stress(2) = sigma_n;
  EXPECT_EQ(p.begin_run(state, values), "");
  double gamma = 0.0, out[tycore::out::COUNT];
  int reversals = 0, steps = 0;
  double last_direction = 1.0;
  for (; steps < 100000; ++steps) {
    p.outputs(state, out);
    if (tycore::reached(0.0, out[tycore::out::CYCLES], c.until.value)) break;
    p.after_step(state);
    const double gamma_dot = -p.control(state, values).prescribed_strain_rate(4);
    if (steps == 0) {
      EXPECT_GT(gamma_dot, 0.0);    // the first half cycle towards +tau
    }
    if (gamma_dot * last_direction < 0.0) ++reversals;
    last_direction = gamma_dot;
    gamma += gamma_dot * dt;
    state.strain(4) = -gamma;
    state.stress(4) = -G * gamma;    // tau = -sigma_xz
  }
  EXPECT_EQ(reversals, 6);
  EXPECT_EQ(out[tycore::out::CYCLES], 3.0);
  // the last half cycle ended at -tau_cyc: gamma = -CSR sigma_n/G within a step
  EXPECT_NEAR(gamma, -0.2 * sigma_n / G, 2.0 * dt);
}

TEST(CellProgrammes, UntilTargetsTheTestCannotReachAreRefused)
{
  EXPECT_NE(refusal("shear_cv xz 1e-4 until r_u 1.2").find("r_u = 1 - sigma_n/sigma_n0 cannot "
                                                           "exceed 1"), std::string::npos);
  EXPECT_EQ(refusal("shear_cv xz 1e-4 until r_u 0.9"), "");
  EXPECT_NE(refusal("axisym x 1e-5 1e5 until gamma_xz 0.1").find("axisym does not strain the "
                                                                 "xz shear"), std::string::npos);
  EXPECT_NE(refusal("shear xz 1e-4 1e5 until gamma_xy 0.1").find("shear does not strain the xy "
                                                                 "shear"), std::string::npos);
  EXPECT_EQ(refusal("shear xz 1e-4 1e5 until gamma_xz 0.1"), "");
  EXPECT_NE(refusal("shear xz 1e-4 1e5 until cycles 3").find("shear does not report cycles"),
            std::string::npos);
  EXPECT_NE(refusal("iso 1e5 until tau 3").find("iso does not report tau"), std::string::npos);
}

// r_u needs a compressive sigma_n0; a rotation faster than a degree per step is no stress path
TEST(CellProgrammes, ChecksAtTheStartOfARun)
{
  Numbers values;
  tycore::CellState state;
  state.dt = 0.01;
  tycore::CellCommand cv = parse("shear_cv xz 1e-4");
  try {
    cv.programme->begin_run(state, values);    // sigma_zz = 0
    ADD_FAILURE() << "sigma_n0 = 0 accepted";
  } catch (std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("is 0 when the test begins (sigma_n0), so r_u = 1 - "
                                         "sigma_n/sigma_n0 is undefined"), std::string::npos);
  }
  tycore::CellCommand fast = parse("stress_rotation xz 1e5 5e4 0.5 200");
  state.stress.head<3>().setConstant(1e5);
  EXPECT_THROW(fast.programme->begin_run(state, values), std::invalid_argument);    // 2 degrees
  tycore::CellCommand slow = parse("stress_rotation xz 1e5 5e4 0.5 50");
  EXPECT_EQ(slow.programme->begin_run(state, values), "");    // 0.5 degree per step
  // a cyclic test that begins with tau at the amplitude: its first half cycle ends at once
  tycore::CellCommand cyclic = parse("cyclic_shear xz 1e-4 0.01");
  state.stress(4) = -0.02 * state.stress(2);    // tau/sigma_n0 = 0.02 > CSR
  EXPECT_NE(cyclic.programme->begin_run(state, values).find("is at the amplitude CSR sigma_n0 = "
                                                            "1000 already"), std::string::npos);
}

// the restart record: the test and the programme's state read back exactly; a record of
// another plane or programme refused
TEST(CellProgrammes, RestartRecordRoundTrip)
{
  tycore::CellCommand a = parse("cyclic_shear xz 1e-4 0.2");
  Numbers values;
  tycore::CellState state;
  state.stress(2) = 2e5;
  state.stress(4) = -1e5;    // tau at the amplitude: the first half cycle ends
  state.dt = 0.01;
  a.programme->begin_run(state, values);
  a.programme->after_step(state);
  tycore::CellTestState t;
  t.strain.reference_length = Eigen::Vector3d(1.0, 2.0, 3.0);
  t.strain.shear(1) = 0.25;
  t.memory.last_strain_rate(4) = 1e-4;
  t.boundary_work = 3.5, t.elapsed_time = 12.0, t.clock_step = 1200, t.until_start = 0.1;
  const std::vector<double> record = tycore::restart_record(t, *a.programme);
  tycore::CellCommand b = parse("cyclic_shear xz 1e-4 0.2");
  tycore::CellTestState back;
  tycore::read_restart_record(record.data(), back, *b.programme, "c");
  EXPECT_EQ(back.strain.reference_length, t.strain.reference_length);
  EXPECT_EQ(back.strain.shear, t.strain.shear);
  EXPECT_EQ(back.memory.last_strain_rate, t.memory.last_strain_rate);
  EXPECT_EQ(back.clock_step, 1200);
  EXPECT_EQ(b.programme->state(), a.programme->state());    // sigma_n0 and the reversal
  double out[tycore::out::COUNT];
  b.programme->outputs(state, out);
  EXPECT_EQ(out[tycore::out::CYCLES], 0.5);
  tycore::CellCommand other = parse("cyclic_shear yz 1e-4 0.2");
  EXPECT_THROW(tycore::read_restart_record(record.data(), back, *other.programme, "c"),
               std::invalid_argument);
  tycore::CellCommand iso = parse("iso 1e5");
  EXPECT_THROW(tycore::read_restart_record(record.data(), back, *iso.programme, "c"),
               std::invalid_argument);
}

// a redefinition continuing the test takes sigma_n0 over on the same plane only
TEST(CellProgrammes, SigmaN0CarriesOverOnTheSamePlane)
{
  Numbers values;
  tycore::CellState state;
  state.stress(2) = 2e5;
  state.stress(1) = 1e5;
  tycore::CellCommand first = parse("shear xz 1e-4 2e5");
  first.programme->begin_run(state, values);
  state.stress(2) = 1.5e5;    // later: sigma_zz has fallen
  tycore::CellCommand same = parse("shear_cv xz 1e-4"), other = parse("shear_cv yz 1e-4");
  tycore::CellCommand iso = parse("iso 1e5");
  iso.programme->take_carried(first.programme->carried());    // passed on through a stage
  same.programme->take_carried(iso.programme->carried());
  other.programme->take_carried(first.programme->carried());
  same.programme->begin_run(state, values);
  other.programme->begin_run(state, values);
  double out[tycore::out::COUNT];
  same.programme->outputs(state, out);
  EXPECT_DOUBLE_EQ(out[tycore::out::R_U], 1.0 - 1.5e5 / 2e5);
  other.programme->outputs(state, out);
  EXPECT_DOUBLE_EQ(out[tycore::out::R_U], 0.0);    // its own sigma_n0 = sigma_zz now
}

// k0 and cyclic_triaxial: errors naming the argument or keyword, the outputs `until` may use
TEST(CellProgrammes, LaboratoryTestsAlongAnAxisRefuseBadInput)
{
  const std::pair<const char*, const char*> cases[] = {
      {"k0 w 1e-5 4e5", "k0: axis 'w' is not x, y or z"},
      {"k0 z -1e-5 4e5", "k0 axial strain rate = -1e-05 must be positive"},
      {"k0 z 1e-5 0", "target k0 largest axial stress SIGMA_MAX = 0 must be positive"},
      {"k0 z 1e-5", "expected 3 more argument(s): k0 AXIS RATE SIGMA_MAX"},
      {"k0 z 1e-5 4e5 ocr 0.5", "ocr = 0.5 is outside the accepted range [1, 1e+06]"},
      {"k0 z 1e-5 4e5 one_way yes", "keyword 'one_way' applies only to cyclic_triaxial"},
      {"k0 z 1e-5 4e5 ru_limit 0.9", "keyword 'ru_limit' applies only to cyclic_shear and "
                                     "cyclic_triaxial"},
      {"iso 1e5 ocr 2", "keyword 'ocr' applies only to k0"},
      {"k0 z 1e-5 4e5 until cycles 2", "until cycles: k0 does not report cycles (cycles: "
                                       "cyclic_shear and cyclic_triaxial)"},
      {"axisym x 1e-5 1e5 until K0 0.5", "until K0: axisym does not report K0 (K0: k0)"},
      {"undrained x 1e-5 until q_a 5e4", "until q_a: undrained does not report q_a (q_a: k0 "
                                         "and cyclic_triaxial)"},
      {"cyclic_triaxial z 1e-4 0", "cyclic_triaxial CSR = 0 is outside the accepted range "
                                   "[1e-06, 10]"},
      {"cyclic_triaxial z -1e-4 0.2", "cyclic_triaxial axial strain rate = -0.0001 must be "
                                      "positive"},
      {"cyclic_triaxial z 1e-4 0.2 one_way maybe", "one_way must be yes or no, got 'maybe'"},
      {"cyclic_triaxial z 1e-4 0.2 da_limit 0", "da_limit = 0 is outside the accepted range "
                                                "(0, 1] (a double-amplitude axial strain)"},
      {"cyclic_triaxial z 1e-4 0.2 until r_u 1.2", "until r_u 1.2: r_u = 1 - p/p0 cannot exceed "
                                                   "1 (a granular cell carries no tension, p >= "
                                                   "0)"},
  };
  for (const auto& c : cases)
    EXPECT_NE(refusal(c.first, false).find(c.second), std::string::npos)
        << c.first << ": " << refusal(c.first, false);
  for (const char* fine : {"k0 x 1e-5 4e5 ocr 4 until ocr 3.9", "k0 y 1e-5 4e5 until K0 0.5",
                           "cyclic_triaxial x 1e-4 0.2 one_way yes until cycles 10",
                           "cyclic_triaxial z 1e-4 0.2 until r_u 0.9"})
    EXPECT_EQ(refusal(fine, false), "") << fine;
}

// the two cyclic tests read RATE, CSR and the liquefaction criteria alike (one parser): the
// same checks (docs/fix_cell_servo.md), each message naming its own test, rate and strain
TEST(CellProgrammes, CyclicTestsShareTheirArguments)
{
  const std::pair<const char*, const char*> cases[] = {
      {"cyclic_shear xz 0 0.2", "cyclic_shear shear rate gamma_dot = 0 must be positive (the "
                                "first half cycle shears towards +tau; each reversal turns its "
                                "sign)"},
      {"cyclic_triaxial z 0 0.2", "cyclic_triaxial axial strain rate = 0 must be positive (the "
                                  "first half cycle compresses the axis; each reversal turns "
                                  "its sign)"},
      {"cyclic_shear xz 1e-4 11", "cyclic_shear CSR = 11 is outside the accepted range [1e-06, "
                                  "10] (below, the cyclic amplitude is lost in round-off)"},
      {"cyclic_triaxial z 1e-4 11", "cyclic_triaxial CSR = 11 is outside the accepted range "
                                    "[1e-06, 10] (below, the cyclic amplitude is lost in "
                                    "round-off)"},
      {"cyclic_shear xz 1e-4 0.2 ru_limit 1.5", "ru_limit = 1.5 is outside the accepted range "
                                                "(0, 1]"},
      {"cyclic_triaxial z 1e-4 0.2 ru_limit 0", "ru_limit = 0 is outside the accepted range "
                                                "(0, 1]"},
      {"cyclic_shear xz 1e-4 0.2 da_limit 2", "da_limit = 2 is outside the accepted range (0, "
                                              "1] (a double-amplitude shear strain)"},
      {"cyclic_triaxial z 1e-4 0.2 da_limit 2", "da_limit = 2 is outside the accepted range (0, "
                                                "1] (a double-amplitude axial strain)"},
      {"cyclic_shear xz 1e-4 0.2 one_way yes", "keyword 'one_way' applies only to "
                                               "cyclic_triaxial"},
  };
  for (const auto& c : cases)
    EXPECT_NE(refusal(c.first).find(c.second), std::string::npos)
        << c.first << ": " << refusal(c.first);
  // the rates the cell must resolve carry the same names
  EXPECT_EQ(parse("cyclic_shear xz 2e-4 0.2").programme->constant_rates()[0].what,
            "cyclic_shear shear rate gamma_dot");
  EXPECT_EQ(parse("cyclic_triaxial z 3e-4 0.2").programme->constant_rates()[0].what,
            "cyclic_triaxial axial strain rate");
  EXPECT_EQ(parse("cyclic_triaxial z 3e-4 0.2").programme->constant_rates()[0].rate, 3e-4);
}

// k0 strains every component at a prescribed rate (no stiffness entries); cyclic_triaxial's
// servo holds sigma_b - sigma_c by the traceless actuator e_b - e_c and strains the three axes:
// C_IJ of the rows I = b, c and the columns J = x, y, z
TEST(CellProgrammes, LaboratoryTestsAskForTheEntriesTheirServoUses)
{
  using Sums = tycore::AffineStiffnessSums;
  EXPECT_EQ(tycore::stiffness_entries_of(parse("k0 z 1e-5 4e5", false).programme->profile(),
                                         false), 0u);
  for (int a = 0; a < 3; ++a) {
    const std::string axis = tycore::axis_name(a);
    unsigned expected = 0;
    for (int I : {(a + 1) % 3, (a + 2) % 3})
      for (int J = 0; J < 3; ++J) expected |= Sums::entry(I, J);
    EXPECT_EQ(tycore::stiffness_entries_of(
                  parse("cyclic_triaxial " + axis + " 1e-4 0.2").programme->profile(), true),
              expected) << axis;
  }
}

// cyclic_triaxial on an undrained linear cell (q_a = 3 G eps_a, p constant): compression
// first; `until cycles 3` ends the test after the sixth reversal, at -2 CSR p0 two-way; the
// outputs are those of the axis (sigma_r the mean of the lateral stresses)
TEST(CellProgrammes, CyclicTriaxialUntilCyclesNStopsAfterNCycles)
{
  for (bool one_way : {false, true}) {
    tycore::CellCommand c = parse(std::string("cyclic_triaxial y 1.0 0.2 until cycles 3")
                                  + (one_way ? " one_way yes" : ""), false);
    tycore::CellProgramme& p = *c.programme;
    const double G = 1e6, dt = 1e-5, p0 = 1e5;
    Numbers values;
    tycore::CellState state;
    state.dt = dt;
    state.stress.head<3>().setConstant(p0);
    EXPECT_EQ(p.begin_run(state, values), "");
    double eps = 0.0, out[tycore::out::COUNT];
    int reversals = 0;
    double last_direction = 1.0;
    for (int steps = 0; steps < 100000; ++steps) {
      p.outputs(state, out);
      if (tycore::reached(0.0, out[tycore::out::CYCLES], c.until.value)) break;
      p.after_step(state);
      const Vector6d rate = p.control(state, values).prescribed_strain_rate;
      EXPECT_EQ(rate.head<3>().sum(), 0.0);
      if (steps == 0) {
        EXPECT_GT(rate(1), 0.0);    // the first half cycle compresses y
      }
      if (rate(1) * last_direction < 0.0) ++reversals;
      last_direction = rate(1);
      eps += rate(1) * dt;
      state.strain(1) = eps, state.strain(2) = state.strain(0) = -0.5 * eps;
      state.stress(1) = p0 + 2.0 * G * eps;    // q_a = 3 G eps_a, p = p0
      state.stress(2) = state.stress(0) = p0 - G * eps;
    }
    EXPECT_EQ(reversals, 6) << one_way;
    EXPECT_EQ(out[tycore::out::CYCLES], 3.0);
    EXPECT_NEAR(eps, one_way ? 0.0 : -2.0 * 0.2 * p0 / (3.0 * G), 2.0 * dt);
    EXPECT_DOUBLE_EQ(out[tycore::out::EPS_A], eps);
    EXPECT_DOUBLE_EQ(out[tycore::out::SIG_R], 0.5 * (state.stress(0) + state.stress(2)));
    EXPECT_DOUBLE_EQ(out[tycore::out::Q_A], state.stress(1) - out[tycore::out::SIG_R]);
    EXPECT_NEAR(out[tycore::out::R_U], 0.0, 1e-15);
  }
}

// k0 outputs: K0 = sigma_r/sigma_a, K0_inc from the stresses at the start, OCR from the largest
// sigma_a; a test that begins at or above SIGMA_MAX is refused; cyclic_triaxial needs p0 > 0
// and warns when q_a is at the amplitude already
TEST(CellProgrammes, LaboratoryTestsAtTheStartOfARunAndTheirOutputs)
{
  Numbers values;
  tycore::CellState state;
  state.dt = 0.01;
  state.stress << 1e5, 1e5, 4e5, 0, 0, 0;
  tycore::CellCommand high = parse("k0 z 1e-5 4e5", false);
  try {
    high.programme->begin_run(state, values);
    ADD_FAILURE() << "a k0 test from sigma_a = SIGMA_MAX accepted";
  } catch (std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("k0: the axial stress sigma_z is 4e+05 when the test "
                                         "begins, not below SIGMA_MAX = 4e+05"),
              std::string::npos) << e.what();
  }
  tycore::CellCommand k0 = parse("k0 z 1e-5 8e5 ocr 2", false);
  EXPECT_EQ(k0.programme->begin_run(state, values), "");
  state.stress << 3e5, 1e5, 8e5, 0, 0, 0;
  k0.programme->after_step(state);    // the peak: unloading starts
  state.stress << 2.4e5, 0.8e5, 5e5, 0, 0, 0;
  double out[tycore::out::COUNT];
  k0.programme->outputs(state, out);
  EXPECT_DOUBLE_EQ(out[tycore::out::SIG_R], 1.6e5);
  EXPECT_DOUBLE_EQ(out[tycore::out::K0], 1.6e5 / 5e5);
  EXPECT_DOUBLE_EQ(out[tycore::out::K0_INC], (1.6e5 - 1e5) / (5e5 - 4e5));
  EXPECT_DOUBLE_EQ(out[tycore::out::OCR], 8e5 / 5e5);
  EXPECT_LT(k0.programme->control(state, values).prescribed_strain_rate(2), 0.0);
  // the progress with this step's sigma_a: the loading 4e5 and 3e5 of the unloading, of 8e5
  EXPECT_DOUBLE_EQ(k0.programme->progress(), (4e5 + 3e5) / (4e5 + 4e5));

  tycore::CellCommand cyclic = parse("cyclic_triaxial z 1e-4 0.2", false);
  state.stress.setZero();
  EXPECT_THROW(cyclic.programme->begin_run(state, values), std::invalid_argument);
  tycore::CellCommand at_amplitude = parse("cyclic_triaxial z 1e-4 0.2", false);
  state.stress << 0.8e5, 0.8e5, 1.4e5, 0, 0, 0;    // p0 1e5, q_a 6e4 >= 2 CSR p0 = 4e4
  EXPECT_NE(at_amplitude.programme->begin_run(state, values).find("is at the amplitude 2 CSR "
                                                                  "p0 = 4e+04 already"),
            std::string::npos);
}

// restart records of both; p0 of cyclic_triaxial taken over by a continued test along the same
// axis only; a record resumed along another axis refused
TEST(CellProgrammes, LaboratoryTestsRestartAndCarryOver)
{
  Numbers values;
  tycore::CellState state;
  state.stress << 1e5, 1e5, 1e5, 0, 0, 0;
  for (const char* text : {"k0 z 1e-5 4e5 ocr 2", "cyclic_triaxial z 1e-4 0.2"}) {
    tycore::CellCommand a = parse(text, false);
    a.programme->begin_run(state, values);
    Vector6d later = state.stress;
    later(2) = 5e5;
    a.programme->after_step({0.0, 0.01, later, Vector6d::Zero()});    // a reversal in both
    tycore::CellTestState t;
    const std::vector<double> record = tycore::restart_record(t, *a.programme);
    tycore::CellCommand b = parse(text, false);
    tycore::read_restart_record(record.data(), t, *b.programme, "c");
    EXPECT_EQ(b.programme->state(), a.programme->state()) << text;
    EXPECT_LT(b.programme->control(state, values).prescribed_strain_rate(2), 0.0) << text;
    tycore::CellCommand other = parse(std::string(text).replace(std::string(text).find(" z "),
                                                                3, " x "), false);
    try {
      tycore::read_restart_record(record.data(), t, *other.programme, "c");
      ADD_FAILURE() << text << " resumed along x";
    } catch (std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("written by a run along another axis; this one loads "
                                           "x"), std::string::npos) << e.what();
    }
  }
  tycore::CellCommand first = parse("cyclic_triaxial z 1e-4 0.2", false);
  first.programme->begin_run(state, values);    // p0 = 1e5
  state.stress << 0.5e5, 0.5e5, 0.5e5, 0, 0, 0;
  tycore::CellCommand iso = parse("iso 1e5", false);
  iso.programme->take_carried(first.programme->carried());    // passed on through a stage
  tycore::CellCommand same = parse("cyclic_triaxial z 1e-4 0.1", false);
  tycore::CellCommand other = parse("cyclic_triaxial x 1e-4 0.1", false);
  same.programme->take_carried(iso.programme->carried());
  other.programme->take_carried(first.programme->carried());
  same.programme->begin_run(state, values);
  other.programme->begin_run(state, values);
  double out[tycore::out::COUNT];
  same.programme->outputs(state, out);
  EXPECT_DOUBLE_EQ(out[tycore::out::R_U], 0.5);
  other.programme->outputs(state, out);
  EXPECT_DOUBLE_EQ(out[tycore::out::R_U], 0.0);    // its own p0 = p now
}
