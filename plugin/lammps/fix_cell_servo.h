/* -*- c++ -*- ----------------------------------------------------------
   fix cell/servo: a stress-controlled, deformable periodic cell (paper sections 2-5;
   docs/theory.md §5, §6, §10-13; docs/fix_cell_servo.md). Each step the fix measures the cell
   (contact stress, affine stiffness, contact counts), asks its test programme for the control
   of the step (plugin/core/cell_programmes.hpp), steps the six-component servo
   (plugin/core/cell_servo.hpp) and moves the box (h <- exp(L dt) h, tilt flips). The physics
   and the parsing are plugin/core's; the record of the test is fix_cell_servo_record.h.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_CELL_SERVO_H
#define LMP_FIX_CELL_SERVO_H

#include "fix.h"

#include "cell_command.hpp"
#include "cell_restart.hpp"
#include "csv_record.hpp"

#include <map>
#include <memory>
#include <string>

namespace LAMMPS_NS {

class FixCellServo : public Fix, private tycore::SettingValues {
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

 private:
  tycore::CellCommand command;
  tycore::CellProgramme &programme() const { return *command.programme; }
  tycore::ProgrammeProfile profile;    // what the programme needs (fixed at construction)
  tycore::CellTestState test;
  bool restored = false, continued = false;
  tycore::FileIdentity continued_csv;
  double origin[tycore::out::COUNT];    // the outputs when the test began (NaN: not known)
  double box_left[6];                   // the box as this test last set it (NaN: not yet)

  // measurements of the last step
  tycore::Vector6d stress;
  tycore::AffineStiffnessSums stiffness_sums;
  unsigned tallied_entries = 0;
  double contacts = 0.0, sliding = 0.0, force_sum = 0.0;
  bigint measured_step = -1, output_step = -1, particle_step = -1;
  double output[tycore::out::COUNT];
  double mean_diameter = 0.0, mean_density = 0.0, solid_volume = 0.0;
  class Compute *pressure = nullptr;
  std::string pressure_id, tally_id;
  class CellTallySource *pair = nullptr;
  std::unique_ptr<class CellRecord> record;
  std::map<std::string, int> variable_index;    // the programme's variables (init)

  // the end of the test ('until'), progress, the cap watch
  double wall_start = 0.0, progress_at_setup = 0.0;
  double until_run_start = 0.0;
  bigint step_start = 0;
  bool until_met = false, until_direction_checked = false;
  tycore::CapWatch cap_watch;
  tycore::TiltFlip pending_flip;
  class Irregular *irregular = nullptr;

  double operator()(tycore::Setting &) override;    // a setting's value now
  tycore::CellState cell_state() const;
  void take_over_replaced_fix();
  void define_named_variables(bool define);
  std::string variable_name(int i) const;

  void measure();
  tycore::CellMeasurementOf<6> cell_measurement() const;
  Eigen::Matrix3d cell_matrix() const;
  void change_box(const tycore::Vector6d &strain_rate);
  void set_box_rate(const tycore::Vector6d &strain_rate, const Eigen::Matrix3d &h);
  void require_box_unchanged();
  void compute_outputs();
  void compute_particle_outputs();
  void write_row();
  void check_until();
  void check_equilibrium();
  void choose_rate_cap();
  void check_rates();
};

}    // namespace LAMMPS_NS

#endif
