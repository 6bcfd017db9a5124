/* -*- c++ -*- ----------------------------------------------------------
   fix cell/servo: a stress-controlled, deformable periodic cell (docs/fix_cell_servo.md;
   docs/theory.md §5, §6, §10-13). Each step it measures the cell, asks its test programme for
   the control (plugin/core/cell_programmes.hpp), steps the servo (cell_servo.hpp) and moves
   the box; its record is fix_cell_servo_record.h.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_CELL_SERVO_H
#define LMP_FIX_CELL_SERVO_H

#include "fix.h"

#include "cell_progress.hpp"
#include "cell_restart.hpp"

#include <array>
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
  // the outputs when the test began (NaN: not known), the box as this test last set it (NaN:
  // not yet)
  std::array<double, tycore::out::COUNT> origin;
  std::array<double, 6> box_left;

  // the cell the outputs are computed from (the stress and contacts of the last measurement,
  // the particles' sizes of init), the last measurement's stiffness and force sum
  tycore::CellSnapshot cell;
  tycore::AffineStiffnessSums stiffness_sums;
  unsigned tallied_entries = 0;
  double force_sum = 0.0;
  bigint measured_step = -1, output_step = -1, particle_step = -1;
  double output[tycore::out::COUNT];
  class Compute *pressure = nullptr;
  std::string pressure_id, tally_id;
  class CellTallySource *pair = nullptr;
  std::unique_ptr<class CellRecord> record;
  std::vector<int> record_columns;              // the fix's columns of the record (setup)
  std::map<std::string, int> variable_index;    // the programme's variables (init)

  // this run: progress, the end of the test ('until'), the cap watch
  tycore::RunProgress run;
  double wall_start = 0.0, until_run_start = 0.0;
  bool until_met = false, until_direction_checked = false;
  tycore::CapWatch cap_watch;
  tycore::TiltFlip pending_flip;
  class Irregular *irregular = nullptr;

  double operator()(tycore::Setting &) override;    // a setting's value now
  tycore::CellState cell_state() const;
  void take_over_replaced_fix();
  void define_named_variables(bool define);

  void measure();
  tycore::CellMeasurementOf<6> cell_measurement() const;
  Eigen::Matrix3d cell_matrix() const;
  void set_box_rate(const tycore::Vector6d &strain_rate, const Eigen::Matrix3d &h);
  void compute_outputs();
  void compute_particle_outputs();
  void write_row();
  void check_until();
  void check_equilibrium();
  void check_rates();
};

}    // namespace LAMMPS_NS

#endif
