/* -*- c++ -*- ----------------------------------------------------------
   Numbers of tylmp's input commands. utils::numeric turns "1e400" into inf and refuses
   "inf", "nan" and "abc" without saying which argument it was; finite_numeric() refuses all
   of them naming the argument. The one parser of every style of the plugin.
------------------------------------------------------------------------- */

#ifndef LMP_TYLMP_NUMERIC_H
#define LMP_TYLMP_NUMERIC_H

#include "error.h"
#include "lammps.h"
#include "utils.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

namespace tylmp {

// `what` names the argument, e.g. "pair_coeff thornton/yin: Young's modulus E"
inline double finite_numeric(const char *file, int line, const char *text, const std::string &what,
                             LAMMPS_NS::LAMMPS *lmp)
{
  char *end = nullptr;
  const double parsed = std::strtod(text, &end);
  if (end == text || *end != '\0')
    lmp->error->all(file, line, "{} must be a number, got '{}'", what, text);
  if (!std::isfinite(parsed)) {
    const bool overflow = !std::isnan(parsed) && !std::strpbrk(text, "iI");    // not "inf"
    lmp->error->all(file, line, "{} must be a finite number, got '{}'{}", what, text,
                    overflow ? " (it overflows to infinity)" : "");
  }
  return parsed;
}

}    // namespace tylmp

#endif
