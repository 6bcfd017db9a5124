// Long random contact paths that visit every branch of the Thornton-Yin law (snap-in,
// peeling, loading / unloading / reloading micro-slip, gross sliding, tension, break, twist, a
// turning contact normal), the scalar entry's step along them (advance_contact, the law's
// instantiation at V = double), and the checks of each step that hold whatever the
// implementation: the Coulomb limit, T in the tangent plane, the energy balance of §2.4.
// Used by test_contact_batch.cpp, which compares every build of the batch entry with it.
#ifndef TYCORE_TESTS_CONTACT_PATHS_HPP
#define TYCORE_TESTS_CONTACT_PATHS_HPP

#include "contact_kernel.hpp"
#include "contact_types.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"

#include "glass_pair.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace contact_paths {

using Eigen::Vector3d;

struct Visits {
  int peeling = 0, forward = 0, backward = 0, sticking = 0, sliding = 0, tensile = 0,
      snap_ins = 0, breaks = 0;
  // the energy balance over the path (docs/theory.md §2.4): the frictional dissipation booked,
  // and what the stored energy gained beyond the step's work less dissipation (its
  // discretisation: the work is the trapezoid of the force over the step)
  double dissipated = 0.0, excess = 0.0;
};

// one step of a path: overlap, contact normal, tangential increment of j relative to i at the
// contact (in the new tangent plane) and twist of the history about the normal
struct Step {
  double delta;
  Vector3d n, ds;
  double twist;
};

// The path of one contact of the glass pair (glass_pair.hpp) with friction mu and interface
// energy Gamma, drawn from `seed`: next() gives step after step. With `breaking`, an adhesive
// path's overlap cycle reaches below the break overlap delta_f (the contact breaks, and snaps
// in again when the overlap is back at 0); a Hertz path's always reaches gaps.
class RandomPath {
 public:
  RandomPath(double mu, double Gamma, unsigned seed, bool breaking = false)
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
        breaking_(breaking),
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
    tycore::begin_contact(h, adhesive);
    h.radius = a0;
    return h;
  }

  Step next()
  {
    using glass_pair::kPi;
    Step s;
    // overlap: a slow cycle from just above the break overlap (or a gap, without adhesion) to
    // 3 delta_scale, lingering at the low end, plus noise
    const double lowest = adhesive ? (breaking_ ? 1.5 : 0.9) * delta_f_ : -0.05 * delta_scale;
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

  // the step of the scalar entry advance_contact from history h (h advanced; the dissipation
  // of the step in `dissipation`)
  tycore::KernelResult scalar_step(const Step& s, tycore::ContactHistory& h,
                                   double& dissipation) const
  {
    const tycore::PairConstants k = tycore::pair_constants(c);
    const double nv[3] = {s.n.x(), s.n.y(), s.n.z()}, dsv[3] = {s.ds.x(), s.ds.y(), s.ds.z()};
    dissipation = 0.0;
    return adhesive ? tycore::advance_contact<true>(k, R, s.delta, nv, s.twist, dsv, h, dissipation)
                    : tycore::advance_contact<false>(k, R, s.delta, nv, s.twist, dsv, h, dissipation);
  }

  const tycore::PairCoefficients c;
  const double R;
  const bool adhesive;
  const double Pc, delta_scale, ds_scale, force_scale;

 private:
  const double delta_f_;
  const bool breaking_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> gauss_{0.0, 1.0};
  Vector3d n_, ds_dir_;
  int step_ = 0;
};

// What holds for every step of the law from history `before` to `after` with increment s.ds,
// normal force P and frictional dissipation `lost` (fatal gtest failures otherwise): T in the
// tangent plane of s.n, |T| <= mu (P + 2Pc) (the Coulomb cap, within its 4-ulp tolerance),
// the memory's axis a unit vector or zero, the dissipation >= 0, the stored energy >= 0; sums
// the dissipation and the step's departure from the energy balance (docs/theory.md §2.4:
// stored energy after = stored before + tangential work - dissipation, up to the
// discretisation of the work) in `seen`, and counts the state the step ended in.
inline void expect_law_holds(const RandomPath& path, const Step& s, double P,
                             const tycore::ContactHistory& before,
                             const tycore::ContactHistory& after, double lost, Visits& seen)
{
  const double limit = path.c.mu * std::max(P + 2.0 * path.Pc, 0.0);
  const Eigen::Map<const Vector3d> T(after.T), T_old(before.T), dir(after.load_dir);
  ASSERT_LE(T.norm(), limit * (1.0 + 1e-14) + 1e-300);
  ASSERT_LE(std::abs(T.dot(s.n)), 1e-14 * (T.norm() + limit) + 1e-300);
  const double dir2 = dir.squaredNorm();
  // (carried and twisted step after step off the loading branch, it drifts by round-off)
  ASSERT_TRUE(dir2 == 0.0 || std::abs(dir2 - 1.0) < 1e-10) << dir2;
  ASSERT_GE(lost, 0.0);
  ASSERT_GE(after.stored_energy, 0.0);
  for (int j = 0; j < tycore::memory_bands; ++j) {    // the memory: |m| <= 1, depths >= 0
    ASSERT_LE(std::abs(after.band_outer[j]), 1.0) << j;
    ASSERT_LE(std::abs(after.band_inner[j]), 1.0) << j;
    ASSERT_GE(after.band_depth[j], 0.0) << j;
  }
  // the work of T over the step, T_old carried with the contact: onto the new tangent plane
  // (magnitude kept), then turned about n by the twist (Rodrigues)
  Vector3d carried = T_old - T_old.dot(s.n) * s.n;
  if (carried.norm() > 0.0) carried *= T_old.norm() / carried.norm();
  carried = std::cos(s.twist) * carried + std::sin(s.twist) * s.n.cross(carried);
  const double work = 0.5 * (carried + T).dot(s.ds);
  seen.dissipated += lost;
  seen.excess += std::abs(after.stored_energy - (before.stored_energy + work - lost));
  seen.peeling += after.peeling != 0.0;
  seen.sliding += after.sliding != 0.0;
  seen.tensile += P < 0.0;
  // the edge band of the memory (docs/theory.md §2.3): slipping forward or backward along its
  // axis, or sticking, while the contact as a whole does not slide
  // (a turn of the force in the tangent plane raises the slopes by the second order of the
  // turn: an edge within 1e-6 of the limit slips)
  const bool micro = after.peeling == 0.0 && after.sliding == 0.0 && after.band_depth[0] > 0.0;
  const double edge = after.band_outer[0];
  seen.forward += micro && edge >= 1.0 - 1e-6;
  seen.backward += micro && edge <= -1.0 + 1e-6;
  seen.sticking += micro && std::abs(edge) < 1.0 - 1e-6;
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
  EXPECT_GT(v.forward, 100);
  EXPECT_GT(v.backward, 100);
  EXPECT_GT(v.sticking, 100);
  EXPECT_GT(v.sliding, 100);
  // the balance over the path: these paths take steps of up to a fifth of the slip distance,
  // where the trapezoid of the work misses ~1 % of the frictional loss (measured 0.5-2.4 %);
  // docs/theory.md §2.4 shows the defect falling with the step
  EXPECT_GT(v.dissipated, 0.0);
  EXPECT_LT(v.excess, 0.05 * v.dissipated);
}

}    // namespace contact_paths

#endif
