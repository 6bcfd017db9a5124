// The progress of a cell test and the wall time it has left (fix cell/servo's outputs progress
// and eta_seconds; docs/fix_cell_servo.md, "Output"). Plain C++, no LAMMPS: the fix gives the
// steps and the wall-clock time, this file the two outputs.
#ifndef TYCORE_CELL_PROGRESS_HPP
#define TYCORE_CELL_PROGRESS_HPP

#include "cell_command.hpp"

#include <cmath>
#include <limits>

namespace tycore {

// A run of a test as the fix counts it, fixed at the run's setup: its first and last step, the
// step of the setup and the progress then
struct RunProgress {
  long long begin_step = 0, end_step = 0;
  long long setup_step = 0;
  double progress_at_setup = 0.0;

  // progress: towards the `until` target (the measure was `until_start` when the test began),
  // else along the programme's course (`course`, NaN if it has none), else through this run.
  // eta_seconds, the wall time left: a course that knows its simulated time left
  // (`course_time`, a strain path) at this run's wall time per step, else at the pace of the
  // progress made in this run; NaN until there is a pace. `wall`: seconds since the setup;
  // o: the step's outputs
  void outputs(const UntilTarget &until, double until_start, double course, double course_time,
               long long step, double wall, double dt, double *o) const
  {
    constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
    const double wall_per_step = step > setup_step ? wall / double(step - setup_step) : NaN;
    double &progress = o[out::PROGRESS], &eta = o[out::ETA_SECONDS];
    const auto eta_from_progress = [&]() {
      const double gained = progress - progress_at_setup;
      return gained > 0.0 ? wall / gained * (1.0 - progress) : NaN;
    };
    if (until.output >= 0) {
      progress = progress_towards(until_start, o[until.output], until.value);
      eta = eta_from_progress();
    } else if (!std::isnan(course)) {
      progress = course;
      eta = std::isnan(course_time) ? eta_from_progress() : course_time / dt * wall_per_step;
    } else {
      const long long span = end_step - begin_step;
      progress = span > 0 ? double(step - begin_step) / double(span) : 1.0;
      eta = double(end_step - step) * wall_per_step;
    }
  }
};

}    // namespace tycore

#endif
