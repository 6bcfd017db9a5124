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
std::vector<const CellRecord *> &live_records()
{
  static std::vector<const CellRecord *> records;
  return records;
}

}    // namespace

CellRecord::CellRecord(LAMMPS *lmp, const std::string &fix_id, const std::string &path, int every,
                       const Columns &extra) :
    Pointers(lmp),
    fix_id_(fix_id), path_(path), every_(every), requests_(extra)
{
  live_records().push_back(this);
}

CellRecord::~CellRecord()
{
  auto &records = live_records();
  records.erase(std::remove(records.begin(), records.end(), this), records.end());
}

// what each request names (tycore::extra_columns_of): the columns it gives, checked
void CellRecord::resolve_extra()
{
  columns_.clear();
  for (const auto &request : requests_) {
    const tycore::Reference r = tycore::parse_reference(request.second);
    tycore::ReferenceTarget t;
    auto inspect = [&t](auto *source) {
      t.exists = true;
      t.scalar = source->scalar_flag, t.vector = source->vector_flag;
      t.array = source->array_flag, t.peratom = source->peratom_flag;
      t.local = source->local_flag;
      t.size = source->size_vector, t.variable_size = source->size_vector_variable;
    };
    if (r.kind == 'v') {
      const int ivar = input->variable->find(r.id.c_str());
      t.exists = ivar >= 0;
      t.equal_style = t.exists && input->variable->equalstyle(ivar);
      t.atom_style = t.exists && input->variable->atomstyle(ivar);
      t.vector_style = t.exists && input->variable->vectorstyle(ivar);
    } else if (r.kind == 'c' && modify->find_compute(r.id) >= 0) {
      inspect(modify->compute[modify->find_compute(r.id)]);
    } else if (r.kind == 'f' && modify->find_fix(r.id) >= 0) {
      inspect(modify->fix[modify->find_fix(r.id)]);
    }
    try {
      for (const auto &column : tycore::extra_columns_of(request.first, request.second, t)) {
        tycore::check_extra_column(column.first, request.second, columns_);
        columns_.push_back(column);
      }
    } catch (std::exception &x) {
      error->all(FLERR, "fix cell/servo {}: {}", fix_id_, x.what());
    }
  }
}

// a new test starts its record; a continued one appends to it (tycore::CsvRecord: superseded
// rows of a crashed run dropped). Rank 0 alone writes
bool CellRecord::open(const std::string &header, bool resume, bigint step)
{
  if (comm->me == 0 && !csv_.is_open()) {
    refuse_aliases();
    std::string line = header;
    for (const auto &e : columns_) line += "," + e.first;
    try {
      if (resume)
        csv_.resume(path_, line, step);
      else
        csv_.start(path_, line);
    } catch (std::exception &e) {
      error->one(FLERR, "fix cell/servo: {}", e.what());
    }
    if (csv_.dropped_rows() > 0)
      utils::logmesg(lmp,
                     "fix cell/servo: {} continues at step {}: dropped {} row(s) written "
                     "after that step by an earlier run\n",
                     path_, step, csv_.dropped_rows());
  }
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
    error->one(FLERR,
               "fix cell/servo {}: csv {} is {}: the record would overwrite it; name "
               "another file",
               fix_id_, path_, what);
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
  for (const CellRecord *other : live_records())
    if (other->lmp == lmp && other != this && tycore::file_identity(other->path_) == record)
      refuse(fmt::format("the record of fix {} (csv {})", other->fix_id_, other->path_));
}
