/* -*- c++ -*- ----------------------------------------------------------
   fix cell/servo: a stress-controlled, deformable periodic cell: principal strain-rate
   programmes and Pi-plane strain paths at a servo-controlled mean stress on an orthogonal or
   triclinic box (paper sections 2-5; docs/theory.md §5, §6), and on a triclinic box any mix of
   stress and strain-rate control of all six components: simple shear, constant-volume and
   cyclic simple shear, undrained triaxial tests, principal stress rotation (docs/theory.md
   §10-13). See docs/fix_cell_servo.md.
   Files: fix_cell_servo.cpp (set-up, the step, restart), fix_cell_servo_modes.cpp (the test
   programmes), fix_cell_servo_cell.cpp (the cell: measurement, deformation, tilt flips),
   fix_cell_servo_outputs.cpp (outputs), fix_cell_servo_input.cpp (checks that need the run),
   fix_cell_servo_record.cpp (the record's checks).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_CELL_SERVO_H
#define LMP_FIX_CELL_SERVO_H

#include "fix.h"

#include "cell_control.hpp"
#include "cell_kinematics.hpp"
#include "cell_servo.hpp"
#include "cell_stiffness.hpp"
#include "csv_record.hpp"

#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

class FixCellServo : public Fix {
 public:
  FixCellServo(class LAMMPS *, int, char **);
  ~FixCellServo() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_integrate() override;
  void pre_exchange() override;
  void end_of_step() override;
  void post_run() override;
  double compute_vector(int) override;
  double compute_array(int, int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // indices of the global vector (0-based here, 1-based for users; docs/fix_cell_servo.md)
  enum Output {
    EPS1, EPS2, EPS3, EPS_V, EPS_Q, EPS_D13, SIG1, SIG2, SIG3, P, Q, B, LODE_DEG, ETA_LD,
    SINPHI, VOID_RATIO, SOLID_FRACTION, Z, ZM, SLIDING_FRACTION, UNBALANCED, INERTIAL_NUMBER,
    PI_X, PI_Y, PI_EX, PI_EY,    // the CSV columns end here
    PROGRESS, ETA_SECONDS, EQUILIBRIUM, RATE1, RATE2, RATE3, BOUNDARY_WORK, P_KINETIC, VOLUME,
    TIME, EQ_STRESS_OK, EQ_UNBALANCED_OK, EQ_KINETIC_OK, EQ_COORDINATION_OK, KINETIC_RATIO,
    // the six-component cell (docs/fix_cell_servo.md, "Outputs of a triclinic cell")
    SIG_XY, SIG_XZ, SIG_YZ, GAMMA_XY, GAMMA_XZ, GAMMA_YZ, RATE_XY, RATE_XZ, RATE_YZ,
    SIG_MAJOR, SIG_INTER, SIG_MINOR,
    // the plane of a simple-shear or rotation test
    GAMMA, TAU, SIG_N, TAU_RATIO, STRESS_ANGLE, RATE_ANGLE, NONCOAXIALITY,
    // constant-volume (undrained) tests
    R_U, CYCLES, N_L_RU, N_L_GAMMA,
    N_OUTPUT
  };
  // what a redefined fix (same ID) takes over from the one it replaces (docs/fix_cell_servo.md)
  struct Continuation {
    tycore::CumulativeStrain strain;
    double elapsed_time;
    bigint clock_step;
    double boundary_work;
    tycore::Vector6d last_strain_rate;
    double initial_normal_stress;
    std::string csv_path;
    tycore::FileIdentity csv_identity;    // which file that record is (made by then)
    double origin[N_OUTPUT];              // the outputs when the test began
  };
  static const char *output_name(int i);    // name of output i (0-based)

 protected:
  enum class Mode {
    ISO, AXES, AXISYM, CONSTANT_B, DEVIATORIC, PATH,           // principal programmes
    SHEAR, SHEAR_CV, CYCLIC_SHEAR, UNDRAINED, ROTATION          // the six-component cell
  };
  Mode mode;

  // control programme
  double target_p;                 // servo-held mean stress [Pa]
  int major_axis;                  // axisym, constant_b
  double major_rate;               // axisym, constant_b [1/s], compression positive
  double b_target;                 // constant_b
  struct AxisInput {               // axes, deviatoric: a number or an equal-style variable
    tycore::AxisControl control;
    double value;
    std::string variable;
    int ivar;
    std::string what;              // the argument, for error messages
    bool positive = true;          // a target stress must be compressive (not a shear's)
  };
  AxisInput axis_input[6];        // axes: xx yy zz xy xz yz (Voigt6; shears engineering,
                                   // compression positive as the servo's)
  AxisInput major_input;           // axisym, constant_b: the major rate, number or variable
  double major_rate_now = 0.0;     // its value at the last evaluation
  double major_strain_rate();
  // simple shear (shear, shear_cv, cyclic_shear) and principal stress rotation
  tycore::ShearPlane plane;
  bool has_plane = false;          // the test has a plane: gamma, tau, angles are output
  double shear_rate = 0.0;         // gamma_dot [1/s]
  double normal_target = 0.0;      // shear: sigma_n [Pa]
  double cyclic_stress_ratio = 0.0;            // cyclic_shear: CSR
  tycore::LiquefactionCriteria liquefaction;   // cyclic_shear: r_u and double amplitude
  tycore::CyclicSimpleShear::State cyclic;     // cyclic_shear state (restart)
  double initial_normal_stress;                // sigma_n0 of r_u, when the test began (restart)
  tycore::PrincipalStressRotation stress_rotation;    // rotation
  tycore::CyclicSimpleShear cyclic_programme() const;
  tycore::PiPath path;
  double path_speed;               // Pi-plane speed |de/dt| [1/s]
  std::string path_kind;           // circle, triangle, polygon (built after the keywords) or empty
  std::vector<Eigen::Vector2d> polygon_vertices;
  bool close_polygon = false;
  double prestrain;                // circle, triangle
  tycore::PlaneStrain plane_strain = tycore::PlaneStrain::TOTAL;
  tycore::ServoSettings settings;
  bool max_rate_given = false;
  bool gains_given = false;        // gain or integral_gain given
  bool holds_shear_stress() const; // a shear component is stress controlled
  void choose_shear_gains();
  static constexpr double SHEAR_GAIN = 0.02, SHEAR_INTEGRAL_GAIN = 3e-5, MAX_SHEAR_GAIN = 0.05;
  double inertial_cap;             // default cap: strain rate at this inertial number

  // equilibrium check (preparation stages)
  int equilibrium_every;
  tycore::EquilibriumCriteria criteria;
  tycore::EquilibriumState equilibrium;
  int equilibrium_reached;

  // state (written to restart files)
  tycore::CumulativeStrain strain; // reference edges and cumulative shears (docs/theory.md §10.4)
  double elapsed_time;             // simulated time since the test started [s]
  bigint clock_step;               // step up to which elapsed_time is counted
  tycore::ServoMemoryOf<6> memory;
  double boundary_work;            // int V sigma:deps, compression positive [J]
  int restored;                    // 1 if the state came from a restart file
  int continued;                   // 1 if it came from the fix this one redefines
  int continue_previous;           // keyword continue yes|no
  tycore::FileIdentity continued_csv;    // the record that fix wrote
  double origin[N_OUTPUT];         // the outputs when the test began (NaN: not known)
  void take_over_replaced_fix();   // the state of the fix this one redefines
  void lead_into_path();           // the leg from the current strain to the path

  // measurements of the last step
  tycore::Vector6d stress;         // contact stress, compression positive (Voigt6) [Pa]
  double stiffness_sums[tycore::AffineStiffnessSums::size];   // V C (cell_stiffness.hpp)
  unsigned tallied_entries;        // the entries of stiffness_sums the tallies make (cell_tally.h)
  double contacts, sliding, force_sum;
  bigint measured_step;
  double output[N_OUTPUT];
  bigint output_step;
  bigint particle_step;            // step of the per-particle outputs (Z, Zm, unbalanced, p_kin)

  // particle statistics fixed at init
  double mean_diameter, mean_density, solid_volume;

  class Compute *pressure;
  std::string pressure_id;
  std::string tally_id;            // compute CELL_TALLY, for pair styles other than thornton/yin
  class CellTallySource *pair;    // pair thornton/yin, or compute CELL_TALLY (cell_tally.h)

  // CSV
  std::string csv_path;
  int csv_every;
  tycore::CsvRecord csv;
  std::string csv_header() const;
  std::vector<std::pair<std::string, std::string>> extra_requests;  // name, reference as given
  std::vector<std::pair<std::string, std::string>> extra_columns;   // resolved (init)
  // the checks of the record: fix_cell_servo_record.cpp
  void check_extra_name(const std::string &name, const std::string &ref,
                        const std::vector<std::pair<std::string, std::string>> &taken) const;
  void resolve_extra_columns();
  void refuse_record_aliases() const;

  // progress / ETA; 'until NAME VALUE': the test ends when output NAME reaches VALUE
  double wall_start;
  bigint step_start;
  double progress_at_setup = 0.0;
  int until_output = -1;
  double until_value = 0.0;
  double until_start = std::numeric_limits<double>::quiet_NaN();   // NAME when the test began
  int until_met = 0;
  bool until_direction_checked = false;
  double until_run_start = std::numeric_limits<double>::quiet_NaN();   // NAME at this run's setup
  double finite_number(const char *text, const std::string &what);
  int positive_integer(const char *text, const std::string &what);
  // checks of the programme (fix_cell_servo_input.cpp)
  double number_in(const char *text, const std::string &what, double lo, double hi,
                   bool open_low, const char *unit = "");
  void check_rates_resolvable();
  double stress_level();
  void warn_inertial_number();
  void check_until_direction();
  static constexpr double MIN_STRAIN_PER_STEP = 1e-15;
  static constexpr double UNTIL_DIRECTION_FRACTION = 0.1;    // (the servo's first steps move a strain by ~1e-5 either way)

  // the programmes (fix_cell_servo_modes.cpp)
  void parse_mode(int narg, char **arg, int &iarg);
  class ModeArgs;                  // a mode's arguments, read in turn
  void parse_principal_mode(const std::string &name, int narg, char **arg, int &iarg);
  void parse_constant_b(ModeArgs &a);
  void parse_polygon(ModeArgs &a);
  void parse_axes(int narg, char **arg, int &iarg);
  void parse_axial_rate(const std::string &name, const char *text);
  void parse_cell_mode(const std::string &name, int narg, char **arg, int &iarg);
  bool needs_triclinic() const;    // the programme moves or holds a shear component
  void require_controllable();
  // the keywords (fix_cell_servo.cpp), in groups: each returns how many arguments the
  // keyword at hand took, 0 if it is not one of its own
  class KeywordArgs;
  struct PathOptions;
  void parse_keywords(int narg, char **arg, int iarg);
  int path_keyword(const KeywordArgs &k, PathOptions &options);
  int servo_keyword(const KeywordArgs &k);
  int record_keyword(const KeywordArgs &k);
  int parse_extra(const KeywordArgs &k);
  void parse_until(const std::string &name, const char *target);
  int equilibrium_keyword(const KeywordArgs &k);
  int cell_mode_keyword(const KeywordArgs &k);
  void build_path(const PathOptions &options);
  void check_keyword_combinations();
  AxisInput parse_value(const char *text, tycore::AxisControl control, const std::string &what);
  double evaluate(AxisInput &in);
  tycore::MixedControl6 current_control();
  tycore::ServoCommandOf<6> servo_command(const tycore::CellMeasurementOf<6> &cell);
  void after_step();               // a programme's state after the step (cyclic reversals)

  // the cell (fix_cell_servo_cell.cpp)
  void measure();
  tycore::CellMeasurementOf<6> cell_measurement() const;
  unsigned stiffness_entries() const;    // the stiffness entries the programme's servo uses
  Eigen::Matrix3d cell_matrix() const;
  double cell_volume() const;
  void change_box(const tycore::Vector6d &strain_rate);
  void set_box_rate(const tycore::Vector6d &strain_rate, const Eigen::Matrix3d &h);
  tycore::TiltFlip pending_flip;   // found after a step's deformation, made in pre_exchange
  class Irregular *irregular = nullptr;
  void compute_outputs();
  void compute_cell_outputs();     // the six-component outputs (fix_cell_servo_outputs.cpp)
  std::vector<int> csv_columns() const;
  void compute_particle_outputs();
  static bool is_particle_output(int);
  void write_csv_row();
  // the pieces of end_of_step (fix_cell_servo.cpp)
  void write_record_rows();
  tycore::ServoCommandOf<6> next_command(const tycore::CellMeasurementOf<6> &cell);
  void check_equilibrium(const tycore::CellMeasurementOf<6> &cell);
  void watch_rate_cap(const tycore::ServoCommandOf<6> &command);
  void require_followable(const tycore::ServoCommandOf<6> &command);
  void add_boundary_work(const tycore::ServoCommandOf<6> &command);
  void open_csv();
  void advance_clock();
  std::vector<double> restart_record() const;
  std::vector<double> programme_path;   // the user's path, without the lead-in leg
  double default_max_rate() const;
  void choose_rate_cap();
  double prescribed_rate() const;
  std::string held_targets() const;
  bigint saturated_steps;
  double saturated_error;         // the stress error when the servo reached its cap
  bool saturation_warned;         // the cap warning has been given in this run
  bool cap_warning;               // keyword cap_warning yes|no
  bool named_variables;           // keyword variables yes|no: v_ID_NAME for every output
  std::string output_variable(int i) const;    // ID_NAME of output i (0-based)
  void define_named_variables();
  void delete_named_variables();
  static constexpr int SATURATION_WARN_STEPS = 1000;
  Eigen::Vector3d principal_strain() const;
};

}    // namespace LAMMPS_NS

#endif
