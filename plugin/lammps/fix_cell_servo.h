/* -*- c++ -*- ----------------------------------------------------------
   fix cell/servo: a stress-controlled, deformable, orthogonal periodic cell that follows
   principal strain-rate programmes and Pi-plane strain paths at a servo-controlled mean
   stress (paper sections 2-5; docs/theory.md §5, §6). See docs/fix_cell_servo.md.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_CELL_SERVO_H
#define LMP_FIX_CELL_SERVO_H

#include "fix.h"

#include "cell_servo.hpp"
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
  void end_of_step() override;
  void post_run() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // indices of the global vector (0-based here, 1-based for users; docs/fix_cell_servo.md)
  enum Output {
    EPS1, EPS2, EPS3, EPS_V, EPS_Q, EPS_D13, SIG1, SIG2, SIG3, P, Q, B, LODE_DEG, ETA_LD,
    SINPHI, VOID_RATIO, SOLID_FRACTION, Z, ZM, SLIDING_FRACTION, UNBALANCED, INERTIAL_NUMBER,
    PI_X, PI_Y, PI_EX, PI_EY,    // the CSV columns end here
    PROGRESS, ETA_SECONDS, EQUILIBRIUM, RATE1, RATE2, RATE3, BOUNDARY_WORK, P_KINETIC, VOLUME,
    TIME, EQ_STRESS_OK, EQ_UNBALANCED_OK, EQ_KINETIC_OK, EQ_COORDINATION_OK, KINETIC_RATIO,
    N_OUTPUT
  };
  static constexpr int N_CSV = PI_EY + 1;
  // what a redefined fix (same ID) takes over from the one it replaces (docs/fix_cell_servo.md)
  struct Continuation {
    double reference_length[3];
    double elapsed_time;
    bigint clock_step;
    double boundary_work;
    double last_strain_rate[3];
    std::string csv_path;
    tycore::FileIdentity csv_identity;    // which file that record is (made by then)
    double origin[N_OUTPUT];              // the outputs when the test began
  };
  static const char *output_name(int i);    // name of output i (0-based)

 protected:
  enum class Mode { ISO, AXES, AXISYM, CONSTANT_B, DEVIATORIC, PATH };
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
  };
  AxisInput axis_input[3];
  AxisInput major_input;           // axisym, constant_b: the major rate, number or variable
  double major_rate_now = 0.0;     // its value at the last evaluation
  double major_strain_rate();
  tycore::PiPath path;
  double path_speed;               // Pi-plane speed |de/dt| [1/s]
  std::string path_kind;           // circle, triangle, polygon (built after the keywords) or empty
  std::vector<Eigen::Vector2d> polygon_vertices;
  bool close_polygon = false;
  double prestrain;                // circle, triangle
  tycore::PlaneStrain plane_strain = tycore::PlaneStrain::TOTAL;
  tycore::ServoSettings settings;
  bool max_rate_given = false;
  double inertial_cap;             // default cap: strain rate at this inertial number

  // equilibrium check (preparation stages)
  int equilibrium_every;
  tycore::EquilibriumCriteria criteria;
  tycore::EquilibriumState equilibrium;
  int equilibrium_reached;

  // state (written to restart files)
  double reference_length[3];      // cell edges when the test started (strain reference)
  double elapsed_time;             // simulated time since the test started [s]
  bigint clock_step;               // step up to which elapsed_time is counted
  tycore::ServoMemory memory;
  double boundary_work;            // int V sigma:deps, compression positive [J]
  int restored;                    // 1 if the state came from a restart file
  int continued;                   // 1 if it came from the fix this one redefines
  int continue_previous;           // keyword continue yes|no
  tycore::FileIdentity continued_csv;    // the record that fix wrote
  double origin[N_OUTPUT];         // the outputs when the test began (NaN: not known)

  // measurements of the last step
  double stress[3], kinetic_stress[3], stiffness_sums[6];
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
  // checks of the programme (fix_cell_servo_input.cpp)
  double number_in(const char *text, const std::string &what, double lo, double hi,
                   bool open_low, const char *unit = "");
  void check_rates_resolvable();
  double stress_level();
  void warn_inertial_number();
  void check_until_direction();
  static constexpr double MIN_STRAIN_PER_STEP = 1e-15;
  static constexpr double UNTIL_DIRECTION_FRACTION = 0.1;    // (the servo's first steps move a strain by ~1e-5 either way)

  void parse_mode(int narg, char **arg, int &iarg);
  void parse_keywords(int narg, char **arg, int iarg);
  AxisInput parse_value(const char *text, tycore::AxisControl control, const std::string &what);
  double evaluate(AxisInput &in);
  tycore::MixedControl current_control();

  void measure();
  tycore::CellMeasurement cell_measurement() const;
  void change_box(const double strain_rate[3]);
  void compute_outputs();
  void compute_particle_outputs();
  static bool is_particle_output(int);
  void write_csv_row();
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
  double current_strain(int axis) const;
};

}    // namespace LAMMPS_NS

#endif
