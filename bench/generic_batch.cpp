// Benchmark build of the plugin (target tylmp_generic, -DTYLMP_BENCH=ON; docs/performance.md):
// the adhesive, damped build of the law (plugin/core/contact_batch_loops.hpp) for every scene,
// to measure what the pair's specialisations on Gamma = 0 and no damping gain. It takes the
// place of plugin/core/contact_batch.cpp in the plugin's sources; the product has no such build.
#include "contact_batch.hpp"
#include "contact_batch_loops.hpp"

#include <cstdio>

namespace {

template <bool Adhesive, bool Damped>
void every_scene(tycore::ContactBatch& b, int n, const tycore::PairConstants& k,
                 const tycore::BatchParameters& p)
{
  tycore::batch_loops::vector_batch<true, true>(b, n, k, p);
}

// said once when LAMMPS loads the plugin
const bool announced = std::fprintf(stderr, "tylmp benchmark build (bench/generic_batch.cpp): the "
                                    "adhesive, damped contact law runs for every scene\n") > 0;

}    // namespace

TYCORE_DEFINE_BATCH_BUILDS(every_scene)
