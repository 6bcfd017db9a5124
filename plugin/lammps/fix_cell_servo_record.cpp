/* ----------------------------------------------------------------------
   fix cell/servo: the checks of its record (keywords csv and extra; docs/fix_cell_servo.md)

   * the record may not be a file LAMMPS itself writes or reads (log and screen files, the
     input script, dump and restart files, the record of another fix cell/servo): compared by
     file identity (tycore::file_identity), so ./c.csv, a symbolic link and ../d/c.csv are seen
     to be c.csv;
   * extra columns name global scalars and vectors of computes and fixes and numeric
     variables; a vector without an index gives one column per element, NAME[i].
------------------------------------------------------------------------- */

#include "fix_cell_servo.h"

#include "comm.h"
#include "compute.h"
#include "dump.h"
#include "error.h"
#include "input.h"
#include "modify.h"
#include "output.h"
#include "universe.h"
#include "variable.h"

#include <cstring>

using namespace LAMMPS_NS;

namespace {

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

// the name of a column: not a built-in column, not a column already taken
void FixCellServo::check_extra_name(const std::string &name, const std::string &ref,
                                    const std::vector<std::pair<std::string, std::string>> &taken)
    const
{
  if (name.empty() || name.find_first_of(",\"' ") != std::string::npos)
    error->all(FLERR, "fix cell/servo {}: extra column name '{}' may not hold commas, quotes or "
               "blanks", id, name);
  if (name == "step")
    error->all(FLERR, "fix cell/servo {}: extra column {} ({}) has the name of the record's "
               "built-in column step: choose another name", id, name, ref);
  for (int k = 0; k < N_OUTPUT; ++k)
    if (name == output_name(k))
      error->all(FLERR, "fix cell/servo {}: extra column {} ({}) has the name of the fix's "
                 "built-in output {} (output {}): choose another name", id, name, ref,
                 output_name(k), k + 1);
  for (const auto &e : taken)
    if (name == e.first)
      error->all(FLERR, "fix cell/servo {}: extra column {} ({}) has the name of extra column "
                 "{} ({}): choose another name", id, name, ref, e.first, e.second);
}

// the columns of `extra N name ref ...`, resolved now that the computes, fixes and variables
// they name exist (init): a global vector without an index gives its elements NAME[1..n]
void FixCellServo::resolve_extra_columns()
{
  const char *accepted = "extra takes global scalars and vectors (c_ID, c_ID[i], f_ID, "
                         "f_ID[i]) and equal-style variables (v_name)";
  extra_columns.clear();
  for (const auto &request : extra_requests) {
    const std::string &name = request.first, &ref = request.second;
    auto add = [&](const std::string &column, const std::string &reference) {
      check_extra_name(column, ref, extra_columns);
      extra_columns.emplace_back(column, reference);
    };
    if (ref.compare(0, 2, "v_") == 0) {
      const int ivar = input->variable->find(ref.c_str() + 2);
      if (ivar < 0)
        error->all(FLERR, "fix cell/servo {}: extra column {}: variable {} does not exist", id,
                   name, ref.substr(2));
      if (!input->variable->equalstyle(ivar))
        error->all(FLERR, "fix cell/servo {}: extra column {}: variable {} is not a number "
                   "each step ({}); {}", id, name, ref.substr(2),
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
    const bool is_compute = ref[0] == 'c';
    const char *kind = nullptr;
    int length = 0;    // elements of an unindexed global vector; 0 for a scalar or an element
    auto inspect = [&](auto *source) {
      kind = global_kind(source, indexed);
      if (!kind && !indexed && !source->scalar_flag) length = source->size_vector;
    };
    if (is_compute) {
      const int i = modify->find_compute(source_id);
      if (i < 0)
        error->all(FLERR, "fix cell/servo {}: extra column {}: compute {} does not exist", id,
                   name, source_id);
      inspect(modify->compute[i]);
    } else {
      const int i = modify->find_fix(source_id);
      if (i < 0)
        error->all(FLERR, "fix cell/servo {}: extra column {}: fix {} does not exist", id, name,
                   source_id);
      inspect(modify->fix[i]);
    }
    if (kind)
      error->all(FLERR, "fix cell/servo {}: extra column {}: {} {} is {}; {} (reduce per-atom "
                 "or local values first, e.g. with compute reduce)", id, name,
                 is_compute ? "compute" : "fix", source_id,
                 std::strcmp(kind, "per-atom") == 0 || std::strcmp(kind, "local") == 0
                     ? fmt::format("{} (not global)", kind) : std::string(kind),
                 accepted);
    if (length == 0) add(name, ref);
    for (int k = 1; k <= length; ++k)
      add(fmt::format("{}[{}]", name, k), fmt::format("{}[{}]", ref, k));
  }
}

// the record may not overwrite a file LAMMPS writes or reads, nor another cell/servo record
// (rank 0: it alone knows the log and screen files)
void FixCellServo::refuse_record_aliases() const
{
  if (csv_path.empty()) return;
  const tycore::FileIdentity record = tycore::file_identity(csv_path);
  auto refuse = [&](const std::string &what) {
    error->one(FLERR, "fix cell/servo {}: csv {} is {}: the record would overwrite it; name "
               "another file", id, csv_path, what);
  };
  const std::pair<FILE *, const char *> streams[] = {
      {lmp->logfile, "the log file of this LAMMPS run"},
      {lmp->screen, "the screen output of this LAMMPS run"},
      {universe->ulogfile, "the log file of this LAMMPS run"},
      {universe->uscreen, "the screen output of this LAMMPS run"},
      {lmp->infile, "the input script LAMMPS is reading"}};
  for (const auto &s : streams)
    if (s.first && tycore::file_identity(s.first) == record) refuse(s.second);
  for (int i = 0; i < lmp->output->ndump; ++i)
    if (lmp->output->dump[i]->filename &&
        tycore::names_file_of(csv_path, lmp->output->dump[i]->filename))
      refuse(fmt::format("the file of dump {}", lmp->output->dump[i]->id));
  const LAMMPS_NS::Output *out = lmp->output;
  for (const char *restart : {out->restart1, out->restart2a, out->restart2b})
    if (restart && tycore::names_file_of(csv_path, restart))
      refuse("a restart file this run writes ('restart' command)");
  for (int i = 0; i < modify->nfix; ++i) {
    auto other = dynamic_cast<FixCellServo *>(modify->fix[i]);
    if (other && other != this && !other->csv_path.empty() &&
        tycore::file_identity(other->csv_path) == record)
      refuse(fmt::format("the record of fix {} (csv {})", other->id, other->csv_path));
  }
}
