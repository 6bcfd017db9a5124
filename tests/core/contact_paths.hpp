// Long random contact paths that visit every branch of the Thornton-Yin law (peeling, loading /
// unloading / reloading micro-slip, gross sliding, tension, twist, a turning contact normal),
// advanced by the reference law (rotate_history + evaluate_contact, thornton_yin.hpp), and the
// check that another implementation took the same step from the same state. Shared by
// test_contact_kernel.cpp (the fused scalar kernel) and test_contact_batch.cpp (the batch
// entry, scalar and vector builds).
#ifndef TYCORE_TESTS_CONTACT_PATHS_HPP
#define TYCORE_TESTS_CONTACT_PATHS_HPP

#include "contact_types.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"
#include "thornton_yin.hpp"

#include "glass_pair.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace contact_paths {

using Eigen::Vector3d;

struct Visits {
  int peeling = 0, loading = 0, unloading = 0, reloading = 0, sliding = 0, tensile = 0,
      ties = 0;
};

// one step of a path: overlap, contact normal, tangential increment of j relative to i at the
// contact (in the new tangent plane) and twist of the history about the normal
struct Step {
  double delta;
  Vector3d n, ds;
  double twist;
};

// The path of one contact of the glass pair (glass_pair.hpp) with friction mu and interface
// energy Gamma, drawn from `seed`: next() gives step after step.
class RandomPath {
 public:
  RandomPath(double mu, double Gamma, unsigned seed)
      : c(glass_pair::coefficients(mu, Gamma)),
        R(glass_pair::kRstar),
        adhesive(Gamma > 0.0),
        Pc(tycore::jkr::pull_off_force(Gamma, R)),
        delta_scale(2e-3 * R),    // P ~ 4e-5 E* R^2: a contact of a dense assembly
        ds_scale(4e-3 * delta_scale),
        // near P + 2Pc = 0 the law divides by mu (P + 2Pc): differences are measured against
        // the contact's typical force, that at delta_scale (and 1 N when mu = 0)
        force_scale(std::max(mu, 1e-30) *
                    (4.0 / 3.0 * glass_pair::kEstar * std::sqrt(R) * std::pow(delta_scale, 1.5) +
                     2.0 * Pc)),
        delta_f_(adhesive ? tycore::jkr::break_overlap(R, glass_pair::kEstar, Gamma) : 0.0),
        rng_(seed),
        n_(Vector3d(0.3, -0.5, 0.8).normalized()),
        ds_dir_(gauss_(rng_), gauss_(rng_), gauss_(rng_))
  {
  }

  // the history at first touch, at 0.3 delta_scale
  tycore::ContactHistory first_touch() const
  {
    const double delta = 0.3 * delta_scale;
    const double a0 = adhesive ? tycore::jkr::contact_radius(delta, R, c.E_star, c.Gamma)
                               : std::sqrt(R * delta);
    tycore::ContactHistory h;
    tycore::begin_contact(h, tycore::jkr::normal_force(a0, R, c.E_star, c.Gamma), adhesive);
    h.radius = a0;
    return h;
  }

  Step next()
  {
    using glass_pair::kPi;
    Step s;
    // overlap: a slow cycle from just above the break overlap (or a gap, without adhesion) to
    // 3 delta_scale, lingering at the low end, plus noise
    const double lowest = adhesive ? 0.9 * delta_f_ : -0.05 * delta_scale;
    const double x = 0.5 - 0.5 * std::cos(step_ * 2.0 * kPi / 2500.0);
    s.delta = lowest + (3.0 * delta_scale - lowest) *
                           (x * x * x + 2e-3 * (1.0 + std::sin(0.37 * step_))) +
              2e-5 * delta_scale * gauss_(rng_);
    // normal turns a little (a rotation of the history by more than 1e-2 rad now and then);
    // tangential increment with a slowly wandering direction and
    // reversals, sized so that micro-slip, reversals and sliding all occur
    const Vector3d turn(gauss_(rng_), gauss_(rng_), gauss_(rng_));
    n_ = (n_ + ((step_ % 97 == 0) ? 5e-2 : 2e-3) * turn).normalized();    // now and then a jolt
    ds_dir_ = (0.98 * ds_dir_ + 0.2 * Vector3d(gauss_(rng_), gauss_(rng_), gauss_(rng_))).eval();
    // (|ds| stays away from 0: with ds = 0 and dP = 0 the branch choices are ties, decided by
    // round-off differently in the two implementations, both right)
    const double wave = std::sin(step_ * 2.0 * kPi / 700.0);
    const double phase = std::copysign(0.25 + 0.75 * std::abs(wave), wave);
    s.n = n_;
    s.ds = phase * ds_scale * ds_dir_.normalized();
    s.ds -= s.ds.dot(n_) * n_;
    s.twist = (step_ % 5 == 0) ? 5e-3 * gauss_(rng_) : 2e-4 * gauss_(rng_);
    ++step_;
    return s;
  }

  // the step by the reference law: rotate_history + evaluate_contact
  tycore::ContactResult reference_step(const Step& s, tycore::ContactHistory& h) const
  {
    tycore::rotate_history(h, s.n, s.twist);
    return adhesive ? tycore::evaluate_contact<true>(c, R, s.delta, s.ds, h, tycore::RESULT_FORCES)
                    : tycore::evaluate_contact<false>(c, R, s.delta, s.ds, h, tycore::RESULT_FORCES);
  }

  const tycore::PairCoefficients c;
  const double R;
  const bool adhesive;
  const double Pc, delta_scale, ds_scale, force_scale;

 private:
  const double delta_f_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> gauss_{0.0, 1.0};
  Vector3d n_, ds_dir_;
  int step_ = 0;
};

// The step another implementation took (normal force P, radius a, history h, dissipation) from
// the state the reference started from agrees with the reference's (r, ref, diss_ref): fatal
// gtest failures otherwise. Counts the branch visited in `seen`, or a tie at the sliding limit.
inline void expect_same_step(const RandomPath& path, const tycore::ContactResult& r,
                             const tycore::ContactHistory& ref, double diss_ref, double P,
                             double a, const tycore::ContactHistory& h, double dissipation,
                             Visits& seen)
{
  ASSERT_NEAR(a, r.contact_radius, 1e-12 * r.contact_radius + 1e-22);
  ASSERT_NEAR(P, r.P, 1e-11 * (std::abs(r.P) + path.Pc) + 1e-22);
  ASSERT_EQ(h.P_prev, P);
  ASSERT_EQ(h.radius, a);
  // a contact at the Coulomb limit whose increment stays along T (steady sliding) is a tie of
  // |T| against mu (P + 2Pc) within the law's 4-ulp tolerance, decided by round-off, and
  // differently in the two implementations: both right. Such ties must stay rare.
  const double limit = path.c.mu * (r.P + 2.0 * path.Pc);
  if (h.sliding != ref.sliding) {
    ASSERT_NEAR(r.T.norm(), limit, 1e-12 * limit) << "sliding differs away from the limit";
    ++seen.ties;
    return;
  }
  ASSERT_EQ(h.mode, ref.mode);
  ASSERT_EQ(h.peeling, ref.peeling);
  // theta = cbrt(theta^3) turns a round-off-sized theta^3 near the limit into ~1e-5: up to
  // 1e-5 of the step's elastic increment, itself < 1e-3 of the typical force
  const double force_scale = path.force_scale;
  for (int d = 0; d < 3; ++d) {
    ASSERT_NEAR(h.T[d], ref.T[d], 1e-9 * force_scale);
    // the direction of a vanishing T is ill-conditioned: weigh it by |T|
    ASSERT_NEAR(h.load_dir[d] * r.T.norm(), ref.load_dir[d] * r.T.norm(), 1e-9 * force_scale);
  }
  ASSERT_NEAR(h.T_star, ref.T_star, 1e-9 * force_scale);
  ASSERT_NEAR(h.T_star2, ref.T_star2, 1e-9 * force_scale);
  const double step_work = force_scale * path.ds_scale;    // a full-slip step at the typical force
  ASSERT_NEAR(h.stored_energy, ref.stored_energy, 1e-9 * ref.stored_energy + 1e-8 * step_work);
  ASSERT_NEAR(dissipation, diss_ref, 1e-8 * step_work);

  seen.peeling += ref.peeling != 0.0;
  seen.sliding += ref.sliding != 0.0;
  seen.tensile += r.P < 0.0;
  seen.loading += ref.mode == tycore::LOADING && ref.sliding == 0.0;
  seen.unloading += ref.mode == tycore::UNLOADING;
  seen.reloading += ref.mode == tycore::RELOADING;
}

// every branch of the law visited on one 20000-step path (adhesive: peeling and tension too)
inline void expect_every_branch(const Visits& v, bool adhesive)
{
  if (adhesive) {
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

}    // namespace contact_paths

#endif
