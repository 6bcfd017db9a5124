// The builds of tycore::advance_batch (contact_batch.hpp): the lane loops of
// contact_batch_loops.hpp over the contact law's one text, compiled once per instruction set
// (SSE2, AVX2, AVX-512 on x86-64 with GCC or Clang; none elsewhere, where advance_batch runs
// the scalar build).
#include "contact_batch.hpp"
#include "contact_batch_loops.hpp"

TYCORE_DEFINE_BATCH_BUILDS(tycore::batch_loops::vector_batch)
