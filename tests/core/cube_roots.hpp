// Cube roots y_i = cbrt(x_i), i < n, lane-wide in the build `isa` (tycore::simd_cbrt, which
// the batch law inlines into its lane loops): the vector cube root in each instruction set,
// for its test against jkr::fast_cbrt (test_contact_batch.cpp). Isa::scalar, and every isa in a
// build without the vector builds (TYCORE_VECTOR_BUILDS), runs jkr::fast_cbrt.
#ifndef TYTESTS_CUBE_ROOTS_HPP
#define TYTESTS_CUBE_ROOTS_HPP

#include "contact_batch.hpp"

namespace tytests {

void cube_roots(const double* x, double* y, int n, tycore::Isa isa);

}    // namespace tytests

#endif
