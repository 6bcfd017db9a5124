// Benchmark build of the plugin (target tylmp_plumbing, -DTYLMP_BENCH=ON; docs/performance.md):
// tycore::advance_batch's law replaced by a Hertz normal force, the history read and written,
// everything around the law kept (first touch and separation, damping, tallies, energies), to
// measure what the plumbing costs. Its forces are not the Thornton-Yin law. It takes the place
// of plugin/core/contact_batch.cpp in the plugin's sources; the product has no such build.
#include "contact_batch.hpp"
#include "contact_batch_loops.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {

template <bool Adhesive, bool Damped>
void plumbing_only(tycore::ContactBatch& b, int n, const tycore::PairConstants& k,
                   const tycore::BatchParameters& p)
{
  using namespace tycore::detail;
  touch_or_break<Adhesive>(b, n, k);
  for (int i = 0; i < n; ++i) {
    const double delta = std::max(b.delta[i], 0.0);
    const double a = std::sqrt(b.R[i] * delta);
    b.contact_radius[i] = a;
    b.P[i] = (4.0 / 3.0) * k.c.E_star * a * delta;
    b.T[0][i] += 1e-30 * -b.vt[0][i] * p.dt;
    b.dissipation[i] = 0.0;
    if (p.tally) lane_outputs<Adhesive, Damped, true>(b, i, k.c, p, -1.0);
    else lane_outputs<Adhesive, Damped, false>(b, i, k.c, p, -1.0);
  }
  if (p.energy) stored_energies(b, n, k);
}

// said once when LAMMPS loads the plugin
const bool announced = std::fprintf(stderr, "tylmp benchmark build (bench/plumbing_batch.cpp): "
                                    "the contact law is replaced by a Hertz normal force, the "
                                    "results are not the Thornton-Yin law\n") > 0;

}    // namespace

TYCORE_DEFINE_BATCH_BUILDS(plumbing_only)
