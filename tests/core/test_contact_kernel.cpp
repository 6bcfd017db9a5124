// The pair style's fused kernel (contact_kernel.hpp: advance_contact) against the reference
// implementation of the same law (rotate_history + evaluate_contact, thornton_yin.hpp, which the
// other core tests check against theory), on long random contact paths that visit every branch:
// peeling, loading / unloading / reloading micro-slip, gross sliding, tension, twist and a
// turning contact normal. Both run side by side from the same first touch.
#include "contact_kernel.hpp"
#include "contact_types.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"
#include "thornton_yin.hpp"

#include "glass_pair.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace {

using namespace glass_pair;
using Eigen::Vector3d;

struct Visits {
  int peeling = 0, loading = 0, unloading = 0, reloading = 0, sliding = 0, tensile = 0,
      ties = 0;
};

// One random path of `steps` steps, advanced by the reference law; at every step the fused kernel
// takes the same step from the same state and must give the same normal force, contact radius,
// tangential force, memory, stored energy and dissipation. Counts in `seen` the branches visited.
void compare_on_random_path(double mu, double Gamma, unsigned seed, int steps, Visits& seen)
{
  const tycore::PairCoefficients c = coefficients(mu, Gamma);
  const tycore::PairConstants k = tycore::pair_constants(c);
  const bool adhesive = Gamma > 0.0;
  const double R = kRstar;
  const double Pc = tycore::jkr::pull_off_force(Gamma, R);
  const double delta_f = adhesive ? tycore::jkr::break_overlap(R, kEstar, Gamma) : 0.0;
  const double delta_scale = 2e-3 * R;    // P ~ 4e-5 E* R^2: a contact of a dense assembly
  const double ds_scale = 4e-3 * delta_scale;
  // near P + 2Pc = 0 the law divides by mu (P + 2Pc): differences are measured against the
  // contact's typical force, that at delta_scale (and 1 N when mu = 0)
  const double force_scale =
      std::max(mu, 1e-30) * (4.0 / 3.0 * kEstar * std::sqrt(R) * std::pow(delta_scale, 1.5) + 2.0 * Pc);

  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);

  Vector3d n = Vector3d(0.3, -0.5, 0.8).normalized();
  double delta = 0.3 * delta_scale;
  Vector3d ds_dir = Vector3d(gauss(rng), gauss(rng), gauss(rng));

  const double a0 = adhesive ? tycore::jkr::contact_radius(delta, R, kEstar, Gamma)
                             : std::sqrt(R * delta);
  tycore::ContactHistory ref, fused;
  tycore::begin_contact(ref, tycore::jkr::normal_force(a0, R, kEstar, Gamma), adhesive);
  ref.radius = a0;
  fused = ref;

  for (int step = 0; step < steps; ++step) {
    // overlap: a slow cycle from just above the break overlap (or a gap, without adhesion) to
    // 3 delta_scale, lingering at the low end, plus noise
    const double lowest = adhesive ? 0.9 * delta_f : -0.05 * delta_scale;
    const double x = 0.5 - 0.5 * std::cos(step * 2.0 * kPi / 2500.0);
    delta = lowest + (3.0 * delta_scale - lowest) * (x * x * x + 2e-3 * (1.0 + std::sin(0.37 * step))) +
            2e-5 * delta_scale * gauss(rng);
    // normal turns a little (a rotation of the history by more than 1e-2 rad now and then);
    // tangential increment with a slowly wandering direction and
    // reversals, sized so that micro-slip, reversals and sliding all occur
    const Vector3d turn(gauss(rng), gauss(rng), gauss(rng));
    n = (n + ((step % 97 == 0) ? 5e-2 : 2e-3) * turn).normalized();    // now and then a jolt
    ds_dir = (0.98 * ds_dir + 0.2 * Vector3d(gauss(rng), gauss(rng), gauss(rng))).eval();
    // (|ds| stays away from 0: with ds = 0 and dP = 0 the branch choices are ties, decided by
    // round-off differently in the two implementations, both right)
    const double wave = std::sin(step * 2.0 * kPi / 700.0);
    const double phase = std::copysign(0.25 + 0.75 * std::abs(wave), wave);
    Vector3d ds = (phase * ds_scale * ds_dir.normalized());
    ds -= ds.dot(n) * n;
    const double twist = (step % 5 == 0) ? 5e-3 * gauss(rng) : 2e-4 * gauss(rng);

    fused = ref;    // one step from the same state
    double diss_ref = 0.0, diss_fused = 0.0;
    tycore::rotate_history(ref, n, twist);
    const tycore::ContactResult r =
        adhesive ? tycore::evaluate_contact<true>(c, R, delta, ds, ref, tycore::RESULT_FORCES)
                 : tycore::evaluate_contact<false>(c, R, delta, ds, ref, tycore::RESULT_FORCES);
    diss_ref += r.dissipation;
    const double nv[3] = {n.x(), n.y(), n.z()}, dsv[3] = {ds.x(), ds.y(), ds.z()};
    const tycore::KernelResult f =
        adhesive ? tycore::advance_contact<true>(k, R, delta, nv, twist, dsv, fused, diss_fused)
                 : tycore::advance_contact<false>(k, R, delta, nv, twist, dsv, fused, diss_fused);

    SCOPED_TRACE(::testing::Message() << "seed " << seed << " step " << step);
    ASSERT_NEAR(f.contact_radius, r.contact_radius, 1e-12 * r.contact_radius + 1e-22);
    ASSERT_NEAR(f.P, r.P, 1e-11 * (std::abs(r.P) + Pc) + 1e-22);
    ASSERT_EQ(fused.P_prev, f.P);
    ASSERT_EQ(fused.radius, f.contact_radius);
    // a contact at the Coulomb limit whose increment stays along T (steady sliding) is a tie of
    // |T| against mu (P + 2Pc) within the law's 4-ulp tolerance, decided by round-off, and
    // differently in the two implementations: both right. Such ties must stay rare.
    const double limit = mu * (r.P + 2.0 * Pc);
    if (fused.sliding != ref.sliding) {
      ASSERT_NEAR(r.T.norm(), limit, 1e-12 * limit) << "sliding differs away from the limit";
      ++seen.ties;
      continue;
    }
    ASSERT_EQ(fused.mode, ref.mode);
    ASSERT_EQ(fused.peeling, ref.peeling);
    // theta = cbrt(theta^3) turns a round-off-sized theta^3 near the limit into ~1e-5: up to
    // 1e-5 of the step's elastic increment, itself < 1e-3 of the typical force
    for (int d = 0; d < 3; ++d) {
      ASSERT_NEAR(fused.T[d], ref.T[d], 1e-9 * force_scale);
      // the direction of a vanishing T is ill-conditioned: weigh it by |T|
      ASSERT_NEAR(fused.load_dir[d] * r.T.norm(), ref.load_dir[d] * r.T.norm(), 1e-9 * force_scale);
    }
    ASSERT_NEAR(fused.T_star, ref.T_star, 1e-9 * force_scale);
    ASSERT_NEAR(fused.T_star2, ref.T_star2, 1e-9 * force_scale);
    const double step_work = force_scale * ds_scale;    // a full-slip step at the typical force
    ASSERT_NEAR(fused.stored_energy, ref.stored_energy, 1e-9 * ref.stored_energy + 1e-8 * step_work);
    ASSERT_NEAR(diss_fused, diss_ref, 1e-8 * step_work);

    seen.peeling += ref.peeling != 0.0;
    seen.sliding += ref.sliding != 0.0;
    seen.tensile += r.P < 0.0;
    seen.loading += ref.mode == tycore::LOADING && ref.sliding == 0.0;
    seen.unloading += ref.mode == tycore::UNLOADING;
    seen.reloading += ref.mode == tycore::RELOADING;
  }
}

// six random paths from consecutive seeds, each visiting every branch of the law
void expect_agreement_on_six_paths(double Gamma, unsigned first_seed)
{
  for (unsigned seed = first_seed; seed < first_seed + 6; ++seed) {
    Visits v;
    compare_on_random_path(0.3, Gamma, seed, 20000, v);
    if (::testing::Test::HasFatalFailure()) return;
    if (Gamma > 0.0) {
      EXPECT_GT(v.peeling, 0);
      EXPECT_GT(v.tensile, 100);
    } else {
      EXPECT_EQ(v.peeling, 0);
    }
    EXPECT_GT(v.loading, 100);
    EXPECT_GT(v.unloading, 100);
    EXPECT_GT(v.reloading, 100);
    EXPECT_GT(v.sliding, 100);
    EXPECT_LT(v.ties, 20);
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
