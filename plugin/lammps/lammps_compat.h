/* -*- c++ -*- ----------------------------------------------------------
   The LAMMPS API differences between the versions tylmp builds against, in one place.

   Tested: LAMMPS 29 Sep 2021 (Debian 12) and 4 Feb 2025 (Debian 13, and a source build with
   PLUGIN: scripts/lammps2025.sh). CMake reads the version of the headers it compiles against
   (src/version.h) and passes it as TYLMP_LAMMPS_VERSION = YYYYMMDD (cmake/Lammps.cmake); the
   switches below are keyed on the release that introduced each change (LAMMPS's
   doc/src/Developer_updating.rst, or the pull request named), so versions in between get the
   API they have, untested.

   The styles call these instead of the version-specific LAMMPS calls:
     tylmp_compat::request_history_list(neighbor, pair, instance_me)
     tylmp_compat::reverse_comm(comm, pair)
     tylmp_compat::PairWithHistory (base class: transfer_history with either signature)
     tylmp_compat::restart_partner_tag(raw) (partner IDs of contact histories in restart files)
------------------------------------------------------------------------- */

#ifndef TYLMP_LAMMPS_COMPAT_H
#define TYLMP_LAMMPS_COMPAT_H

#include "comm.h"
#include "compute.h"
#include "lmptype.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "pair.h"

#ifndef TYLMP_LAMMPS_VERSION
#error "TYLMP_LAMMPS_VERSION (YYYYMMDD of the LAMMPS headers) must be defined: build with CMake"
#endif

// 24 Mar 2022: Neighbor::add_request(requestor, flags) replaces request() + requests[],
// Comm::forward_comm/reverse_comm(Pair *) replace forward_comm_pair/reverse_comm_pair
#define TYLMP_LAMMPS_NEW_REQUEST_AND_COMM (TYLMP_LAMMPS_VERSION >= 20220324)
// GRANULAR refactor (lammps/lammps PR #3512, keyed on its first feature release, 8 Feb 2023):
// Pair::transfer_history gained the types of the pair, (source, target, itype, jtype)
#define TYLMP_LAMMPS_TYPED_TRANSFER_HISTORY (TYLMP_LAMMPS_VERSION >= 20230208)

namespace tylmp_compat {

// a half, size (radius-based cutoff) neighbor list with contact-history bookkeeping, the
// list of granular pair styles
inline void request_history_list(LAMMPS_NS::Neighbor *neighbor, LAMMPS_NS::Pair *pair,
                                 int instance_me)
{
#if TYLMP_LAMMPS_NEW_REQUEST_AND_COMM
  (void) instance_me;
  neighbor->add_request(pair, LAMMPS_NS::NeighConst::REQ_SIZE | LAMMPS_NS::NeighConst::REQ_HISTORY);
#else
  const int irequest = neighbor->request(pair, instance_me);
  neighbor->requests[irequest]->size = 1;
  neighbor->requests[irequest]->history = 1;
#endif
}

// sum the pair's per-ghost reverse-communication buffer into the owners
inline void reverse_comm(LAMMPS_NS::Comm *comm, LAMMPS_NS::Pair *pair)
{
#if TYLMP_LAMMPS_NEW_REQUEST_AND_COMM
  comm->reverse_comm(pair);
#else
  comm->reverse_comm_pair(pair);
#endif
}

// the same for a compute's buffer
inline void reverse_comm(LAMMPS_NS::Comm *comm, LAMMPS_NS::Compute *compute)
{
#if TYLMP_LAMMPS_NEW_REQUEST_AND_COMM
  comm->reverse_comm(compute);
#else
  comm->reverse_comm_compute(compute);
#endif
}

// A pair style with contact history whose transfer between the two sides of a contact
// (FixNeighHistory, with nondefault_history_transfer = 1) is not the default copy. LAMMPS
// calls transfer_history() with the signature of its version; an override of the other
// signature would silently never be called, so the version switch lives here and the style
// implements transfer_contact_history() once.
class PairWithHistory : public LAMMPS_NS::Pair {
 public:
  using LAMMPS_NS::Pair::Pair;

#if TYLMP_LAMMPS_TYPED_TRANSFER_HISTORY
  void transfer_history(double *source, double *target, int /*itype*/, int /*jtype*/) override final
  {
    transfer_contact_history(source, target);
  }
#else
  void transfer_history(double *source, double *target) override final
  {
    transfer_contact_history(source, target);
  }
#endif

 protected:
  // the history of a contact as seen from its partner atom
  virtual void transfer_contact_history(const double *source, double *target) = 0;
};

// The atom ID of a contact partner as FixNeighHistory stores it in restart files: 29 Sep 2021
// writes it as a numeric double (buf = tag), 4 Feb 2025 as a bit pattern (buf = ubuf(tag).d),
// and each reads only its own encoding, so 4 Feb 2025 reading a restart file of 29 Sep 2021
// lost every contact history (docs/lammps_versions.md). The two cannot be confused: with
// smallbig (32-bit tagint) the bit pattern of every double >= 1 exceeds MAXTAGINT, and a
// valid ID as a bit pattern is a double below 1e-300.
inline LAMMPS_NS::tagint restart_partner_tag(double raw)
{
  const int64_t bits = LAMMPS_NS::ubuf(raw).i;
  if (bits >= 1 && bits <= MAXTAGINT) return static_cast<LAMMPS_NS::tagint>(bits);
  return static_cast<LAMMPS_NS::tagint>(raw);
}

}    // namespace tylmp_compat

#endif
