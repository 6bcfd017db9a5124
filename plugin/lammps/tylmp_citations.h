/* ----------------------------------------------------------------------
   The publications behind the styles, for LAMMPS's citation reminder (log.cite and the
   screen notice at the end of a run). One entry per publication; a style registers the ones
   it implements in its constructor.
------------------------------------------------------------------------- */

#ifndef TYLMP_CITATIONS_H
#define TYLMP_CITATIONS_H

#include "citeme.h"
#include "lammps.h"

namespace tylmp {

// the contact law: pair thornton/yin and the computes that evaluate it
constexpr const char *cite_thornton_yin_1991 =
    "pair thornton/yin (tylmp), the contact law: doi:10.1016/0032-5910(91)80178-L\n\n"
    "@Article{Thornton1991,\n"
    " author = {C. Thornton and K. K. Yin},\n"
    " title = {Impact of elastic spheres with and without adhesion},\n"
    " journal = {Powder Technology},\n"
    " year = 1991,\n"
    " volume = 65,\n"
    " pages = {153--166}\n"
    "}\n\n";

// the periodic cell's tests and their micromechanics: fix cell/servo, compute
// thornton/yin/micromechanics
constexpr const char *cite_thornton_2000 =
    "fix cell/servo (tylmp), the periodic-cell tests: doi:10.1680/geot.2000.50.1.43\n\n"
    "@Article{Thornton2000,\n"
    " author = {C. Thornton},\n"
    " title = {Numerical simulations of deviatoric shear deformation of granular media},\n"
    " journal = {G{\\'e}otechnique},\n"
    " year = 2000,\n"
    " volume = 50,\n"
    " number = 1,\n"
    " pages = {43--53}\n"
    "}\n\n";

inline void cite(LAMMPS_NS::LAMMPS *lmp, const char *entry)
{
  if (lmp->citeme) lmp->citeme->add(entry);
}

}    // namespace tylmp

#endif
