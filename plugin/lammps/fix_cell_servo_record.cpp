/* ----------------------------------------------------------------------
   The record of a fix cell/servo test (fix_cell_servo_record.h)
------------------------------------------------------------------------- */

#include "fix_cell_servo_record.h"

#include "cell_command.hpp"

#include "comm.h"
#include "compute.h"
#include "dump.h"
#include "error.h"
#include "fix.h"
#include "input.h"
#include "modify.h"
#include "output.h"
#include "universe.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <cstring>

using namespace LAMMPS_NS;

namespace {

// the records of this process's fixes cell/servo, to refuse a second one on the same file
std::vector<std::pair<const LAMMPS *, const CellRecord *>> &live_records()
{
  static std::vector<std::pair<const LAMMPS *, const CellRecord *>> records;
  return records;
}

// what a reference c_ID, c_ID[i], f_ID or f_ID[i] names, for the messages
template <class T> const char *global_kind(const T *source, bool indexed)
{
  if (!indexed && source->scalar_flag) return nullptr;                     // a scalar: fine
  if (source->vector_flag) return nullptr;                                 // a vector: fine
  if (source->array_flag) return "a global array";
  if (source->peratom_flag) return "per-atom";
  if (source->local_flag) return "local";
  return indexed ? "no global vector" : "no global scalar or vector";
}

}    // namespace

CellRecord::CellRecord(LAMMPS *lmp, const std::string &fix_id, const std::string &path,
                       int every, const Columns &extra) :
    Pointers(lmp), fix_id_(fix_id), path_(path), every_(every), requests_(extra)
{
  live_records().emplace_back(lmp, this);
}

CellRecord::~CellRecord()
{
  auto &records = live_records();
  records.erase(std::remove(records.begin(), records.end(), std::make_pair(
                                static_cast<const LAMMPS *>(lmp), static_cast<const CellRecord *>(this))),
                records.end());
}

// a global vector without an index gives its elements NAME[1..n]; an index beyond the
// vector is refused here (LAMMPS would stop on it at the first row without naming the column)
void CellRecord::resolve_extra()
{
  const char *accepted = "extra takes global scalars and vectors (c_ID, c_ID[i], f_ID, "
                         "f_ID[i]) and equal-style variables (v_name)";
  columns_.clear();
  for (const auto &request : requests_) {
    const std::string &name = request.first, &ref = request.second;
    auto add = [&](const std::string &column, const std::string &reference) {
      try {
        tycore::check_extra_column(column, reference, columns_);
      } catch (std::exception &x) {
        error->all(FLERR, "fix cell/servo {}: {}", fix_id_, x.what());
      }
      columns_.emplace_back(column, reference);
    };
    if (ref.compare(0, 2, "v_") == 0) {
      const int ivar = input->variable->find(ref.c_str() + 2);
      if (ivar < 0)
        error->all(FLERR, "fix cell/servo {}: extra column {}: variable {} does not exist",
                   fix_id_, name, ref.substr(2));
      if (!input->variable->equalstyle(ivar))
        error->all(FLERR, "fix cell/servo {}: extra column {}: variable {} is not a number "
                   "each step ({}); {}", fix_id_, name, ref.substr(2),
                   input->variable->atomstyle(ivar) ? "it is per-atom"
                   : input->variable->vectorstyle(ivar) ? "it is vector-style"
                                                        : "it is a string, read as 0",
                   accepted);
      add(name, ref);
      continue;
    }
    // c_ID or f_ID, with or without [i]
    const std::size_t open = ref.find('[');
    const std::string source_id = ref.substr(2, open == std::string::npos ? open : open - 2);
    const bool indexed = open != std::string::npos;
    const int index = indexed ? std::atoi(ref.c_str() + open + 1) : 0;
    const bool is_compute = ref[0] == 'c';
    const char *kind = nullptr;
    int length = 0, size = 0;    // length: the columns of an unindexed vector
    bool variable_size = false;
    auto inspect = [&](auto *source) {
      kind = global_kind(source, indexed);
      size = source->size_vector;
      variable_size = source->size_vector_variable;
      if (!kind && !indexed && !source->scalar_flag) length = size;
    };
    const int i = is_compute ? modify->find_compute(source_id) : modify->find_fix(source_id);
    if (i < 0)
      error->all(FLERR, "fix cell/servo {}: extra column {}: {} {} does not exist", fix_id_, name,
                 is_compute ? "compute" : "fix", source_id);
    if (is_compute) inspect(modify->compute[i]);
    else inspect(modify->fix[i]);
    if (kind)
      error->all(FLERR, "fix cell/servo {}: extra column {}: {} {} is {}; {} (reduce per-atom "
                 "or local values first, e.g. with compute reduce)", fix_id_, name,
                 is_compute ? "compute" : "fix", source_id,
                 std::strcmp(kind, "per-atom") == 0 || std::strcmp(kind, "local") == 0
                     ? fmt::format("{} (not global)", kind) : std::string(kind),
                 accepted);
    if (indexed && !variable_size && (index < 1 || index > size))
      error->all(FLERR, "fix cell/servo {}: extra column {}: {} is out of range: {} {} has a "
                 "global vector of {} values (index 1 to {})", fix_id_, name, ref,
                 is_compute ? "compute" : "fix", source_id, size, size);
    if (length == 0) add(name, ref);
    for (int k = 1; k <= length; ++k)
      add(fmt::format("{}[{}]", name, k), fmt::format("{}[{}]", ref, k));
  }
}

std::string CellRecord::extra_header() const
{
  std::string header;
  for (const auto &e : columns_) header += "," + e.first;
  return header;
}

// a new test starts its record; a continued one appends to it (tycore::CsvRecord: superseded
// rows of a crashed run dropped)
void CellRecord::open(const std::string &header, bool resume, bigint step)
{
  if (comm->me != 0 || csv_.is_open()) return;
  refuse_aliases();
  try {
    if (resume) csv_.resume(path_, header, step);
    else csv_.start(path_, header);
  } catch (std::exception &e) {
    error->one(FLERR, "fix cell/servo: {}", e.what());
  }
  if (csv_.dropped_rows() > 0)
    utils::logmesg(lmp, "fix cell/servo: {} continues at step {}: dropped {} row(s) written "
                   "after that step by an earlier run\n", path_, step, csv_.dropped_rows());
}

bool CellRecord::holds(bigint step) const
{
  int held = comm->me == 0 && csv_.last_step() >= step;
  MPI_Bcast(&held, 1, MPI_INT, 0, world);
  return held;
}

void CellRecord::write(bigint step, const std::vector<double> &values)
{
  // the extra columns first, on every rank (computes and variables are collective)
  std::vector<double> row = values;
  if (!columns_.empty()) {
    modify->clearstep_compute();
    for (const auto &e : columns_) row.push_back(input->variable->compute_equal(e.second));
    modify->addstep_compute(step + 1);
  }
  if (comm->me != 0 || !csv_.is_open()) return;
  try {
    csv_.write_row(step, row);
  } catch (std::exception &e) {
    error->one(FLERR, "fix cell/servo: {}", e.what());
  }
}

// the record may not overwrite a file LAMMPS writes or reads, nor another cell/servo record
// (rank 0: it alone knows the log and screen files)
void CellRecord::refuse_aliases() const
{
  const tycore::FileIdentity record = tycore::file_identity(path_);
  auto refuse = [&](const std::string &what) {
    error->one(FLERR, "fix cell/servo {}: csv {} is {}: the record would overwrite it; name "
               "another file", fix_id_, path_, what);
  };
  const std::pair<FILE *, const char *> streams[] = {
      {lmp->logfile, "the log file of this LAMMPS run"},
      {lmp->screen, "the screen output of this LAMMPS run"},
      {universe->ulogfile, "the log file of this LAMMPS run"},
      {universe->uscreen, "the screen output of this LAMMPS run"},
      {lmp->infile, "the input script LAMMPS is reading"}};
  for (const auto &s : streams)
    if (s.first && tycore::file_identity(s.first) == record) refuse(s.second);
  const Output *out = lmp->output;
  for (int i = 0; i < out->ndump; ++i)
    if (out->dump[i]->filename && tycore::names_file_of(path_, out->dump[i]->filename))
      refuse(fmt::format("the file of dump {}", out->dump[i]->id));
  for (const char *restart : {out->restart1, out->restart2a, out->restart2b})
    if (restart && tycore::names_file_of(path_, restart))
      refuse("a restart file this run writes ('restart' command)");
  for (const auto &other : live_records())
    if (other.first == lmp && other.second != this &&
        tycore::file_identity(other.second->path_) == record)
      refuse(fmt::format("the record of fix {} (csv {})", other.second->fix_id_,
                         other.second->path_));
}
