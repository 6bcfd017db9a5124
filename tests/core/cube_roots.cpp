// tytests::cube_roots (cube_roots.hpp): the lane loop of simd_cbrt once per instruction set,
// compiled with the lane loops' options (CMakeLists.txt) so that it vectorises as the law's
// loops do.
#include "cube_roots.hpp"

#include "jkr.hpp"
#include "simd_math.hpp"

namespace {

[[gnu::always_inline]] inline void lane_cube_roots(const double* x, double* y, int n)
{
  for (int i = 0; i < n; ++i) y[i] = tycore::simd_cbrt(x[i]);
}

#ifdef TYCORE_VECTOR_BUILDS
void cube_roots_sse2(const double* x, double* y, int n) { lane_cube_roots(x, y, n); }
__attribute__((target("avx2"))) void cube_roots_avx2(const double* x, double* y, int n)
{
  lane_cube_roots(x, y, n);
}
__attribute__((target(TYCORE_AVX512))) void cube_roots_avx512(const double* x, double* y, int n)
{
  lane_cube_roots(x, y, n);
}
#endif

}    // namespace

void tytests::cube_roots(const double* x, double* y, int n, tycore::Isa isa)
{
  using tycore::Isa;
#ifdef TYCORE_VECTOR_BUILDS
  switch (isa) {
    case Isa::avx512: cube_roots_avx512(x, y, n); return;
    case Isa::avx2: cube_roots_avx2(x, y, n); return;
    case Isa::sse2: cube_roots_sse2(x, y, n); return;
    case Isa::scalar: break;
  }
#endif
  for (int i = 0; i < n; ++i) y[i] = tycore::jkr::fast_cbrt(x[i]);
}
