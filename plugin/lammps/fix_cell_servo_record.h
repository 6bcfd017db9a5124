/* -*- c++ -*- ----------------------------------------------------------
   The record of a fix cell/servo test (keywords csv and extra; docs/fix_cell_servo.md, "The
   record"): a CSV file written and flushed row by row (tycore::CsvRecord), whose extra columns
   are global scalars and vectors of computes and fixes and equal-style variables. It may not be
   a file LAMMPS itself writes or reads (log and screen files, the input script, dump and restart
   files) nor the record of another fix cell/servo, compared by file identity, so that ./c.csv,
   a symbolic link and ../d/c.csv are seen to be c.csv.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_CELL_SERVO_RECORD_H
#define LMP_FIX_CELL_SERVO_RECORD_H

#include "pointers.h"

#include "csv_record.hpp"

#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

class CellRecord : protected Pointers {
 public:
  using Columns = std::vector<std::pair<std::string, std::string>>;    // name, reference
  // `extra`: the requested columns as given; their names are checked here
  CellRecord(LAMMPS *, const std::string &fix_id, const std::string &path, int every,
             const Columns &extra);
  ~CellRecord() override;

  const std::string &path() const { return path_; }
  bool due(bigint step) const { return step % every_ == 0; }
  // init: the extra columns' references, now that the computes, fixes and variables exist
  void resolve_extra();
  // setup (rank 0): start the record, or continue it (superseded rows dropped, logged)
  void open(const std::string &header, bool resume, bigint step);
  // whether the record holds a row of `step` already (every rank agrees)
  bool holds(bigint step) const;
  std::string extra_header() const;
  // a row: the extra columns are evaluated on every rank, rank 0 writes
  void write(bigint step, const std::vector<double> &values);

 private:
  std::string fix_id_, path_;
  int every_;
  Columns requests_, columns_;
  tycore::CsvRecord csv_;
  void refuse_aliases() const;
};

}    // namespace LAMMPS_NS

#endif
