// What a cell test carries across runs, redefinitions of its fix and restart files
// (docs/fix_cell_servo.md, "Restart"), and its restart record: a list of doubles that starts
// with a tag, the layout's version and its size, so that a record of another programme or of
// another build is refused, not misread. Plain C++, no LAMMPS.
#ifndef TYCORE_CELL_RESTART_HPP
#define TYCORE_CELL_RESTART_HPP

#include "cell_kinematics.hpp"
#include "cell_programme.hpp"
#include "cell_servo.hpp"
#include "csv_record.hpp"

#include <array>
#include <map>

#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace tycore {

struct CellTestState {
  CumulativeStrain strain;       // reference edges and cumulative shears (docs/theory.md §10.4)
  ServoMemoryOf<6> memory;       // integral and the strain rate of the last step
  double boundary_work = 0.0;    // int V sigma:deps [J]
  double elapsed_time = 0.0;     // simulated time since the test began [s]
  long long clock_step = 0;      // the step up to which elapsed_time is counted
  double until_start = std::numeric_limits<double>::quiet_NaN();    // the until measure then

  // the simulated time up to `step` (a step before clock_step, of an earlier run: none)
  void advance_clock(long long step, double dt)
  {
    if (step > clock_step) elapsed_time += double(step - clock_step) * dt;
    clock_step = step;
  }
  // the boundary work V sigma : deps of a step at `rate` (docs/theory.md §5.3; Voigt6 with
  // engineering shears, so that sigma : deps = sum_I sigma_I deps_I over the cell's
  // `components`: 3 orthogonal, 6 triclinic)
  void add_boundary_work(double volume, const Vector6d &stress, const Vector6d &rate, double dt,
                         int components)
  {
    for (int k = 0; k < components; ++k) boundary_work += volume * stress(k) * rate(k) * dt;
  }
};

constexpr double RESTART_TAG = 8462.0;
// 4: the programme's identity and state as counted lists (3: a fixed layout of every mode's
// fields side by side, 2: three-component memory, unversioned before)
constexpr int RESTART_VERSION = 4;

// [tag, version, size, programme number, identity (n, ...), strain (6), memory (12), boundary
//  work, elapsed time, clock step, until start, programme state (n, ...)]
inline std::vector<double> restart_record(const CellTestState &t, const CellProgramme &p)
{
  std::vector<double> list{RESTART_TAG, RESTART_VERSION, 0.0, double(p.restart_id())};
  const std::vector<double> identity = p.identity(), state = p.state();
  list.push_back(double(identity.size()));
  list.insert(list.end(), identity.begin(), identity.end());
  double a[CumulativeStrain::size + ServoMemoryOf<6>::size];
  t.strain.to_array(a);
  t.memory.to_array(a + CumulativeStrain::size);
  list.insert(list.end(), a, a + CumulativeStrain::size + ServoMemoryOf<6>::size);
  list.insert(list.end(), {t.boundary_work, t.elapsed_time, double(t.clock_step), t.until_start});
  list.push_back(double(state.size()));
  list.insert(list.end(), state.begin(), state.end());
  list[2] = double(list.size());
  return list;
}

// the test and the programme's state from a record written by restart_record; `fix` names the
// fix in the messages. Throws std::invalid_argument when the record is not one of this
// programme (another programme, path or plane), of this version, or is damaged
inline void read_restart_record(const double *list, CellTestState &t, CellProgramme &p,
                                const std::string &fix)
{
  if (list[0] != RESTART_TAG)
    throw std::invalid_argument("the restart file's record for fix " + fix +
                                " is not a "
                                "cell/servo record; define the fix under a new ID");
  if (static_cast<int>(list[1]) != RESTART_VERSION)
    throw std::invalid_argument(
        "the restart record of fix " + fix + " has version " + number_text(list[1]) +
        ", this build reads version " + std::to_string(RESTART_VERSION) +
        " (a record of an "
        "earlier build of tylmp): rerun the stage that wrote it, or define the fix under a new "
        "ID, which starts a new test");
  if (static_cast<int>(list[3]) != p.restart_id())
    throw std::invalid_argument("the restart file holds the state of another cell/servo mode; "
                                "use the same mode as the run that wrote it, or a new fix ID");
  const std::size_t size = static_cast<std::size_t>(list[2]);
  const std::vector<double> identity = p.identity();
  constexpr std::size_t fixed = CumulativeStrain::size + ServoMemoryOf<6>::size + 4;
  const auto damaged = [&](std::size_t parts) {
    return std::invalid_argument("the restart record of fix " + fix + " says it holds " +
                                 std::to_string(size) + " numbers, but its parts hold " +
                                 std::to_string(parts) +
                                 ": the file is damaged or was "
                                 "written by another programme");
  };
  if (size < 5 || size < 5 + static_cast<std::size_t>(list[4])) throw damaged(5);
  bool same = static_cast<std::size_t>(list[4]) == identity.size();
  for (std::size_t i = 0; same && i < identity.size(); ++i) same = list[5 + i] == identity[i];
  if (!same) throw std::invalid_argument(p.identity_mismatch());
  std::size_t k = 5 + identity.size();
  if (size < k + fixed + 1) throw damaged(k + fixed + 1);
  const std::size_t parts = k + fixed + 1 + static_cast<std::size_t>(list[k + fixed]);
  if (size != parts) throw damaged(parts);
  t.strain = CumulativeStrain::from_array(list + k);
  k += CumulativeStrain::size;
  t.memory = ServoMemoryOf<6>::from_array(list + k);
  k += ServoMemoryOf<6>::size;
  t.boundary_work = list[k++];
  t.elapsed_time = list[k++];
  t.clock_step = static_cast<long long>(list[k++]);
  t.until_start = list[k++];
  const std::size_t n = static_cast<std::size_t>(list[k++]);
  if (n > 0) p.restore(std::vector<double>(list + k, list + k + n));
}

// What a redefinition of a fix (same ID, `continue yes`) takes over from the fix it replaces:
// the test, the programme's carried state (sigma_n0 of a plane), the record and the box it
// left, the outputs when the test began. LAMMPS deletes the old fix before it constructs the
// new one: the old one leaves this under its key (its LAMMPS instance and ID).
struct TestCarry {
  CellTestState test;
  std::vector<double> programme;
  FileIdentity record;
  std::string record_path;
  std::array<double, 6> box;
  std::array<double, out::COUNT> origin;
};

inline std::map<std::string, TestCarry> &test_carries()
{
  static std::map<std::string, TestCarry> carries;
  return carries;
}

// the error of a redefinition with 'continue no' whose record (`path`) is the one of the test
// it replaces, by file identity (./a.csv, a symbolic link or d/../a.csv name a.csv too)
inline std::string overwritten_record_error(const std::string &path, const TestCarry &c)
{
  if (!(file_identity(path) == c.record)) return "";
  return "'continue no' starts a new test, whose record " + path + " would overwrite " +
      c.record_path + ", the record of the test it replaces: name another file";
}

// a redefinition continuing the test takes over its state; the servo's integral starts afresh
// with the new programme, and so does the measure of its `until`
inline void continue_test(const TestCarry &c, CellTestState &t, CellProgramme &p)
{
  t = c.test;
  t.memory.integral.setZero();
  t.until_start = std::numeric_limits<double>::quiet_NaN();
  p.take_carried(c.programme);
}

}    // namespace tycore

#endif
