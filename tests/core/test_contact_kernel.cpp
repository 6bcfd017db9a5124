// The pair style's fused kernel (contact_kernel.hpp: advance_contact) against the reference
// implementation of the same law (rotate_history + evaluate_contact, thornton_yin.hpp, which the
// other core tests check against theory), on long random contact paths that visit every branch:
// peeling, loading / unloading / reloading micro-slip, gross sliding, tension, twist and a
// turning contact normal (contact_paths.hpp). Both run side by side from the same first touch.
#include "contact_kernel.hpp"
#include "contact_types.hpp"

#include "contact_paths.hpp"

#include <gtest/gtest.h>

namespace {

using contact_paths::RandomPath;
using contact_paths::Visits;

// One random path of `steps` steps, advanced by the reference law; at every step the fused kernel
// takes the same step from the same state and must give the same normal force, contact radius,
// tangential force, memory, stored energy and dissipation. Counts in `seen` the branches visited.
void compare_on_random_path(double mu, double Gamma, unsigned seed, int steps, Visits& seen)
{
  RandomPath path(mu, Gamma, seed);
  const tycore::PairConstants k = tycore::pair_constants(path.c);
  tycore::ContactHistory ref = path.first_touch(), fused;
  for (int step = 0; step < steps; ++step) {
    const contact_paths::Step s = path.next();
    fused = ref;    // one step from the same state
    const tycore::ContactResult r = path.reference_step(s, ref);
    const double nv[3] = {s.n.x(), s.n.y(), s.n.z()}, dsv[3] = {s.ds.x(), s.ds.y(), s.ds.z()};
    double diss_fused = 0.0;
    const tycore::KernelResult f =
        path.adhesive
            ? tycore::advance_contact<true>(k, path.R, s.delta, nv, s.twist, dsv, fused, diss_fused)
            : tycore::advance_contact<false>(k, path.R, s.delta, nv, s.twist, dsv, fused, diss_fused);
    SCOPED_TRACE(::testing::Message() << "seed " << seed << " step " << step);
    contact_paths::expect_same_step(path, r, ref, r.dissipation, f.P, f.contact_radius, fused,
                                    diss_fused, seen);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

// six random paths from consecutive seeds, each visiting every branch of the law
void expect_agreement_on_six_paths(double Gamma, unsigned first_seed)
{
  for (unsigned seed = first_seed; seed < first_seed + 6; ++seed) {
    Visits v;
    compare_on_random_path(0.3, Gamma, seed, 20000, v);
    if (::testing::Test::HasFatalFailure()) return;
    contact_paths::expect_every_branch(v, Gamma > 0.0);
  }
}

TEST(ContactKernel, MatchesReferenceLawWithAdhesion) { expect_agreement_on_six_paths(0.6, 1); }

TEST(ContactKernel, MatchesReferenceLawHertzMindlin) { expect_agreement_on_six_paths(0.0, 11); }

TEST(ContactKernel, MatchesReferenceLawFrictionless)
{
  Visits v;
  compare_on_random_path(0.0, 0.6, 21, 5000, v);
  if (HasFatalFailure()) return;
  EXPECT_EQ(v.sliding, 5000);
}

}    // namespace
