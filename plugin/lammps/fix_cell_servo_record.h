/* -*- c++ -*- ----------------------------------------------------------
   The record of a fix cell/servo test (keywords csv and extra; docs/fix_cell_servo.md, "The
   record"): a CSV file written and flushed row by row (tycore::CsvRecord), with extra columns
   of computes, fixes and variables. It may not be a file LAMMPS writes or reads, nor the record
   of another fix cell/servo, compared by file identity (./c.csv, a link, ../d/c.csv).
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
  // setup: start the record (`header`: the fix's columns), or continue it (superseded rows
  // dropped, logged); whether it holds a row of `step` already (every rank agrees)
  bool open(const std::string &header, bool resume, bigint step);
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
