// End-to-end tests of one Thornton-Yin contact stepped by the law's scalar instantiation
// (contact_law.hpp through scalar_contact.hpp): JKR normal force (docs/theory.md §1) +
// Thornton's tangential law with adhesion (§2). Expected values are derived here from
// docs/theory.md, not read off a run of the code.
#include "contact_types.hpp"
#include "jkr.hpp"

#include "glass_pair.hpp"
#include "scalar_contact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using Eigen::Vector3d;

namespace {

using namespace glass_pair;    // docs/theory.md §1.8 glass pair
using scalar_contact::Contact;
using scalar_contact::Result;

// JKR scales of docs/theory.md §1.1
struct Jkr {
  double Pc, a0, du;
  explicit Jkr(double Gamma)
      : Pc(3.0 * kPi * Gamma * kRstar), a0(std::cbrt(3.0 * kRstar * Pc / kEstar)), du(a0 * a0 / kRstar) {}
  double P(double ah) const { return Pc * (4.0 * ah * ah * ah - 4.0 * std::pow(ah, 1.5)); }
  double delta(double ah) const { return du * (ah * ah - 2.0 / 3.0 * std::sqrt(ah)); }
  double radius(double d) const    // stable branch by bisection
  {
    double lo = std::pow(6.0, -2.0 / 3.0), hi = 10.0 + std::sqrt(std::abs(d) / du);
    for (int i = 0; i < 200; ++i) {
      const double m = 0.5 * (lo + hi);
      (delta(m) < d ? lo : hi) = m;
    }
    return 0.5 * (lo + hi);    // a^ = a/a0
  }
};

// a deterministic oblique path: overlap (may go tensile for adhesive contacts) and increments
double path_delta(int i, double scale) { return scale * (1.0 + 0.8 * std::sin(0.013 * i)); }
Vector3d path_ds(int i, double scale)
{
  return scale * Vector3d(std::cos(0.011 * i) + 0.3, 0.7 * std::sin(0.017 * i), 0.0);
}

void expect_same_history(const tycore::ContactHistory& a, const tycore::ContactHistory& b, double Tscale,
                         const char* what)
{
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a.T[k], b.T[k], 1e-13 * Tscale) << what << " T" << k;
    EXPECT_NEAR(a.load_dir[k], b.load_dir[k], 1e-13) << what << " dir" << k;
  }
  for (int j = 0; j < tycore::memory_bands; ++j) {
    const double scale = 1e-13 * (a.band_depth[0] + b.band_depth[0]);
    EXPECT_NEAR(a.band_outer[j], b.band_outer[j], 1e-13) << what << " outer slope" << j;
    EXPECT_NEAR(a.band_inner[j], b.band_inner[j], 1e-13) << what << " inner slope" << j;
    EXPECT_NEAR(a.band_depth[j], b.band_depth[j], scale) << what << " depth" << j;
  }
  EXPECT_EQ(a.peeling, b.peeling) << what;
  EXPECT_EQ(a.sliding, b.sliding) << what;
}

}    // namespace

// §1.6 + §2.1: the non-adhesive specialisation is Hertz-Mindlin: P = 4/3 E* sqrt(R*) delta^1.5,
// a = sqrt(R* delta), normal energy 8/15 E* sqrt(R*) delta^2.5, tangential radius = a,
// first tangential increment 8G*a ds
TEST(ThorntonYinHertz, NormalForceAndInitialShearStiffness)
{
  const auto c = coefficients(0.3, 0.0);
  for (double d : {1e-9, 1e-8, 1e-7}) {
    Contact<false> h(c);
    const double hertz = 4.0 / 3.0 * kEstar * std::sqrt(kRstar) * std::pow(d, 1.5);
    h.step(d, Vector3d::Zero());
    const Vector3d ds(1e-14, 0, 0);
    const auto r = h.step(d, ds);
    EXPECT_NEAR(r.P, hertz, 1e-14 * hertz);
    EXPECT_NEAR(r.contact_radius, std::sqrt(kRstar * d), 1e-15 * r.contact_radius);
    EXPECT_NEAR(r.stiffness, 8.0 * kGstar * r.contact_radius, 1e-14 * 8.0 * kGstar * r.contact_radius);
    EXPECT_NEAR(r.normal_energy, 8.0 / 15.0 * kEstar * std::sqrt(kRstar) * std::pow(d, 2.5),
                1e-14 * hertz * d);
    // Mindlin's loading curve T = mu P [1 - (1 - s/(kappa delta))^(3/2)], kappa = mu E*/(4G*),
    // whose slope at s = 0 is 8 G* a (docs/theory.md §2.1)
    const double kappa_delta = 0.3 * kEstar / (4.0 * kGstar) * d;
    // (to the round-off of mu P: T is a sum of band forces of order mu P)
    EXPECT_NEAR(r.T.x(), -0.3 * hertz * std::expm1(1.5 * std::log1p(-1e-14 / kappa_delta)),
                1e-15 * 0.3 * hertz);
    EXPECT_NEAR(r.T.x(), 8.0 * kGstar * std::sqrt(kRstar * d) * 1e-14, 1e-14 / kappa_delta * r.T.x());
    EXPECT_FALSE(r.peeling);
    EXPECT_FALSE(r.sliding);
  }
}

// Adhesive = true with Gamma = 0 reproduces the Hertz-Mindlin specialisation along an oblique
// path with varying overlap (micro-slip, reversals, loss of contact at delta < 0) to round-off
// (1e-13) up to the first gross sliding.
TEST(ThorntonYinSpecialisation, GammaZeroEqualsAdhesiveTemplate)
{
  const auto c = coefficients(0.3, 0.0);
  Contact<true> ha(c);
  Contact<false> hh(c);
  double max_T = 0.0;
  int strict_steps = 0;
  for (int i = 0; i < 5000; ++i) {
    const double d = path_delta(i, 2e-8) - (i > 4000 ? 3e-8 : 0.0);
    const Vector3d ds = path_ds(i, 5e-13);
    const auto ra = ha.step(d, ds);
    const auto rh = hh.step(d, ds);
    if (ra.sliding || rh.sliding) break;
    ++strict_steps;
    const double Ps = std::max(std::abs(rh.P), 1e-12);
    max_T = std::max(max_T, rh.T.norm());
    ASSERT_NEAR(ra.P, rh.P, 1e-14 * Ps) << i;
    ASSERT_NEAR(ra.contact_radius, rh.contact_radius, 1e-15 * kRstar) << i;
    ASSERT_NEAR(ra.stiffness, rh.stiffness, 1e-15 * 8.0 * kGstar * kRstar) << i;
    ASSERT_NEAR((ra.T - rh.T).norm(), 0.0, 1e-13 * Ps) << i;
    ASSERT_NEAR(ra.normal_energy, rh.normal_energy, 1e-13 * std::abs(rh.normal_energy) + 1e-30) << i;
    // (the memory's energy is a sum of band integrals, each a difference of two terms of the
    // size of the fully mobilised contact's energy (mu P)^2/k_T: round-off of that size)
    const double energy_scale = (0.3 * Ps) * (0.3 * Ps) / rh.stiffness;
    ASSERT_NEAR(ra.tangential_energy, rh.tangential_energy, 1e-13 * energy_scale) << i;
    ASSERT_NEAR(ra.dissipation, rh.dissipation, 1e-10 * std::abs(rh.dissipation) + 1e-24) << i;
    ASSERT_FALSE(ra.peeling) << i;
  }
  EXPECT_GT(max_T, 0.0);
  EXPECT_GT(strict_steps, 1000);
}

// the same comparison on a path with repeated gross sliding. The two computations differ only
// by round-off (e.g. 1 ulp in P from a different operation order), so a well-conditioned law
// keeps them within a small multiple of that; 1e-6 mu P is asked for here.
TEST(ThorntonYinSpecialisation, GammaZeroEqualsAdhesiveTemplateWithSliding)
{
  const auto c = coefficients(0.3, 0.0);
  Contact<true> ha(c);
  Contact<false> hh(c);
  double worst = 0.0, worst_norm = 0.0;
  int worst_at = -1, slides = 0;
  for (int i = 0; i < 5000; ++i) {
    const double d = path_delta(i, 2e-8) - (i > 4000 ? 3e-8 : 0.0);
    const Vector3d ds = path_ds(i, 4e-10);
    const auto ra = ha.step(d, ds);
    const auto rh = hh.step(d, ds);
    // (the adhesive template iterates a to 1e-14: P ~ a^3 to a few 1e-14)
    ASSERT_NEAR(ra.P, rh.P, 1e-13 * std::max(std::abs(rh.P), 1e-12)) << i;
    slides += rh.sliding;
    const double scale = c.mu * std::max(std::abs(rh.P), 1e-12);
    const double dev = (ra.T - rh.T).norm() / scale;
    worst_norm = std::max(worst_norm, std::abs(ra.T.norm() - rh.T.norm()) / scale);
    if (dev > worst) worst = dev, worst_at = i;
  }
  EXPECT_GT(slides, 100);
  EXPECT_LE(worst, 1e-6) << "step " << worst_at << ", ||T|| differing by " << worst_norm << " mu P";
}

// stepping the law again with the same overlap and a zero increment changes nothing:
// not the history, not the forces; no dissipation. Checked in micro-slip, peeling and sliding.
TEST(ThorntonYinHistory, ZeroIncrementIsIdempotent)
{
  const Jkr s(0.3);
  struct Case {
    double mu, ds;
    int steps;
  };
  for (const Case& k : {Case{0.3, 2e-11, 40}, Case{0.3, 3e-11, 3}, Case{0.3, 5e-10, 50}}) {
    const auto c = coefficients(k.mu, 0.3);
    Contact<true> h(c);
    const double d = 20.0 * s.du;
    Result r{};
    for (int i = 0; i < k.steps; ++i) r = h.step(d, Vector3d(k.ds, 0.3 * k.ds, 0));
    const tycore::ContactHistory h0 = h.h;
    const Vector3d T0 = r.T;
    for (int rep = 0; rep < 2; ++rep) {
      const auto r2 = h.step(d, Vector3d::Zero());
      expect_same_history(h.h, h0, s.Pc, "repeat");
      EXPECT_NEAR((r2.T - T0).norm(), 0.0, 1e-13 * s.Pc);
      EXPECT_EQ(r2.P, r.P);
      EXPECT_NEAR(r2.dissipation, 0.0, 1e-28);
      EXPECT_EQ(r2.peeling, r.peeling);
      EXPECT_EQ(r2.sliding, r.sliding);
    }
  }
}

// the pair seen from j (history_transfer_sign applied, increment reversed) gives the reaction:
// T_j = -T_i, same P, energies and dissipation; the two histories stay transfer-related
TEST(ThorntonYinSymmetry, ActionReactionBetweenPartners)
{
  const Jkr s(0.3);
  const auto c = coefficients(0.3, 0.3);
  Contact<true> hi(c);
  Contact<true> hj(c);
  for (int i = 0; i < 4000; ++i) {
    const double d = path_delta(i, 5.0 * s.du);
    const Vector3d ds = path_ds(i, 2e-10);
    const auto ri = hi.step(d, ds);
    const auto rj = hj.step(d, -ds);
    ASSERT_EQ(ri.P, rj.P);
    ASSERT_NEAR((ri.T + rj.T).norm(), 0.0, 1e-13 * s.Pc) << i;
    ASSERT_NEAR(ri.dissipation, rj.dissipation, 1e-12 * std::abs(ri.dissipation) + 1e-26) << i;
    ASSERT_NEAR(ri.tangential_energy, rj.tangential_energy, 1e-12 * ri.tangential_energy + 1e-30) << i;
    ASSERT_EQ(ri.sliding, rj.sliding) << i;
    ASSERT_EQ(ri.peeling, rj.peeling) << i;
    const double* a = reinterpret_cast<const double*>(&hi.h);
    const double* b = reinterpret_cast<const double*>(&hj.h);
    for (int k = 0; k < tycore::history_size; ++k)
      ASSERT_NEAR(b[k], tycore::history_transfer_sign[k] * a[k], 1e-13 * std::max(1.0, std::abs(a[k])))
          << i << " " << k;
  }
}

// §1.2-1.3 normal cycle (no tangential motion): snap-on at delta = 0 with P = -8/9 Pc,
// a = (4/9)^(1/3) a0; compression and retraction on one reversible curve P(delta); minimum
// -Pc at delta = -0.132283 delta_u; at the break delta_f: P = -5/9 Pc, a = 6^(-2/3) a0, and the
// stored normal energy is the separation work 0.25741 Pc delta_u (§3.2)
TEST(ThorntonYinNormalCycle, SnapOnCompressRetractBreak)
{
  const Jkr s(0.3);
  const auto c = coefficients(0.3, 0.3);
  Contact<true> h(c);
  auto r = h.step(0.0, Vector3d::Zero());
  EXPECT_NEAR(r.P, -8.0 / 9.0 * s.Pc, 1e-12 * s.Pc);
  EXPECT_NEAR(r.contact_radius, std::cbrt(4.0 / 9.0) * s.a0, 1e-12 * s.a0);
  EXPECT_NEAR(r.normal_energy, 0.0, 1e-14 * s.Pc * s.du);
  EXPECT_EQ(r.T.norm(), 0.0);

  const int n = 4000;
  const double d_max = 3.0 * s.du, d_f = -std::cbrt(27.0 * kPi * kPi * 0.09 * kRstar / (16.0 * kEstar * kEstar));
  for (int i = 1; i <= n; ++i) {    // compress 0 -> d_max
    const double d = d_max * i / n;
    r = h.step(d, Vector3d::Zero());
    const double ah = s.radius(d);
    EXPECT_NEAR(r.P, s.P(ah), 1e-10 * s.Pc * (1 + ah * ah * ah)) << d / s.du;
  }
  double P_min = 0.0, d_at_min = 0.0, work = 0.0, P_prev = r.P, d_prev = d_max;
  const int m = 200000;
  for (int i = 1; i <= m; ++i) {    // retract d_max -> d_f; same curve, integrate P d(delta)
    const double d = d_max + (d_f - d_max) * i / m;
    r = h.step(d, Vector3d::Zero());
    if (i % 100 == 0) {    // same curve as on compression: no normal hysteresis
      const double ah = s.radius(d);
      EXPECT_NEAR(r.P, s.P(ah), 1e-10 * s.Pc * (1 + ah * ah * ah) + (d < 0.99 * d_f ? 1e-6 * s.Pc : 0.0))
          << d / s.du;
    }
    if (r.P < P_min) P_min = r.P, d_at_min = d;
    work += 0.5 * (r.P + P_prev) * (d - d_prev);
    P_prev = r.P, d_prev = d;
    if (std::abs(d) < 0.5 * std::abs(d_max - d_f) / m) {    // back through delta = 0:
      // slope dP/d(delta) there is k_N = (2/3) E* a_touch = 1.53 Pc/delta_u (§1.5)
      EXPECT_NEAR(r.P, -8.0 / 9.0 * s.Pc, 2.0 * s.Pc * std::abs(d) / s.du + 1e-12 * s.Pc);
    }
  }
  EXPECT_NEAR(P_min, -s.Pc, 1e-8 * s.Pc);
  EXPECT_NEAR(d_at_min / s.du, -0.132283, 2e-5);
  EXPECT_NEAR(r.P, -5.0 / 9.0 * s.Pc, 1e-5 * s.Pc);
  EXPECT_NEAR(r.contact_radius, std::pow(6.0, -2.0 / 3.0) * s.a0, 1e-5 * s.a0);
  EXPECT_NEAR(r.normal_energy, 0.25741 * s.Pc * s.du, 5e-6 * s.Pc * s.du);
  // energy of the path: U(delta_f) - U(d_max) = int_{d_max}^{delta_f} P d(delta); U(d_max) from
  // the closed form of the test, U(a^) = Pc du [1.6 a^5 - 8/3 a^3.5 + 2/3 a^2] - U(touch)
  const auto U = [&](double ah) {
    const auto U0 = [&](double x) { return s.Pc * s.du * (1.6 * std::pow(x, 5) - 8.0 / 3.0 * std::pow(x, 3.5) + 2.0 / 3.0 * x * x); };
    return U0(ah) - U0(std::cbrt(4.0 / 9.0));
  };
  EXPECT_NEAR(r.normal_energy - U(s.radius(d_max)), work, 1e-6 * s.Pc * s.du);
  // docs/theory.md §1.8: delta_f for Gamma = 0.3 J/m^2
  EXPECT_NEAR(d_f, -3.7003e-9, 0.00005e-9);
}

// §2.2 end to end: at fixed overlap, the radius a_T of the step's stiffness k_T = 8 G* a_T is
// the Savkoor-Briggs peeled radius of T before the step while peeling (elastic: dT = k_T ds),
// the Hertz radius of P + 2Pc afterwards; gross sliding at mu (P + 2Pc), P = JKR P(delta)
TEST(ThorntonYinOblique, PeelingRadiusThenSlidingLimit)
{
  const Jkr s(0.3);
  const double mu = 0.3;
  const auto c = coefficients(mu, 0.3);
  for (double dd : {0.0, 1.0, 40.0}) {
    const double d = dd * s.du;
    const double P = s.P(s.radius(d));
    const double Peff = P + 2.0 * s.Pc;
    Contact<true> h(c);
    Result r = h.step(d, Vector3d::Zero());
    const double dx = 1e-12;
    bool was_peeling = true;
    int peeled_steps = 0, micro_slip_steps = 0;
    double work = 0.0, diss = 0.0;
    int i = 0;
    for (; i < 400000 && !r.sliding; ++i) {
      const double T_old = r.T.x();
      r = h.step(d, Vector3d(dx, 0, 0));
      work += 0.5 * (T_old + r.T.x()) * dx;
      diss += r.dissipation;
      EXPECT_NEAR(r.P, P, 1e-9 * s.Pc) << dd;
      if (r.peeling) {
        ASSERT_TRUE(was_peeling) << dd;    // peeling never restarts
      }
      if (was_peeling && r.stiffness < 0.0 && !r.sliding) {    // a peeled step: elastic, a_peel(T_old)
        const double root = 4.0 * P * s.Pc + 4.0 * s.Pc * s.Pc - T_old * T_old * kEstar / (4.0 * kGstar);
        const double a_peel = std::cbrt(3.0 * kRstar * (Peff + std::sqrt(std::max(root, 0.0))) / (4.0 * kEstar));
        EXPECT_NEAR((r.T.x() - T_old) / (8.0 * kGstar * dx), a_peel, 1e-9 * a_peel) << dd;
        ++peeled_steps;
      } else if (!was_peeling) {    // micro-slip: the Hertz radius of P + 2Pc
        EXPECT_NEAR(r.stiffness / (8.0 * kGstar), std::cbrt(3.0 * kRstar * Peff / (4.0 * kEstar)), 1e-13 * s.a0) << dd;
        ++micro_slip_steps;
      }
      // while peeling (elastic) the stored energy is the work and nothing is dissipated; once
      // the memory holds the force, its energy (docs/theory.md §2.4) is at least what the work
      // less dissipation gives, the jump at the end of peeling being the two stages' different
      // tractions (peeling at a_peel, micro-slip at a_T)
      if (r.peeling) {
        EXPECT_NEAR(r.tangential_energy, work, 1e-10 * work + 1e-30) << dd;
        EXPECT_EQ(diss, 0.0) << dd;
      } else {
        EXPECT_GE(r.tangential_energy, (work - diss) * (1.0 - 1e-10)) << dd;
      }
      was_peeling = r.peeling;
    }
    ASSERT_TRUE(r.sliding) << dd;
    EXPECT_FALSE(r.peeling) << dd;
    EXPECT_GT(peeled_steps, 10) << dd;
    if (dd == 40.0) {    // P > 33.6 Pc: peeling ends before sliding, micro-slip between
      EXPECT_GT(micro_slip_steps, 10) << dd;
    }
    EXPECT_NEAR(r.T.norm(), mu * Peff, 1e-13 * mu * Peff) << dd;
    // mu P + 2 mu Pc: at delta = 0 (P = -8/9 Pc) the contact still carries 0.3 x 10/9 Pc
    if (dd == 0.0) {
      EXPECT_NEAR(r.T.norm(), mu * 10.0 / 9.0 * s.Pc, 1e-9 * s.Pc);
    }
  }
}

// energy bookkeeping (docs/theory.md §2.4): the stored energy is the memory's elastic energy,
// the dissipation of a step its work less the change of that energy (>= 0), the work the
// trapezoid of the force over the step: over a smooth oblique path at fixed overlap with
// micro-slip, reversals and sliding the balance holds to round-off, at two step sizes
double balance_defect(int refine, double& dissipated)
{
  const auto c = coefficients(0.3, 0.0);
  Contact<false> h(c);
  const double d = 2e-8;
  auto r = h.step(d, Vector3d::Zero());
  double work = 0.0, diss = 0.0;
  const double E0 = r.tangential_energy;
  bool slid = false;
  for (int i = 0; i < 4000 * refine; ++i) {
    const double t = double(i) / refine;
    const Vector3d ds = Vector3d(2e-11 * std::cos(0.002 * t), 1e-11 * std::sin(0.003 * t), 0) / refine;
    const Vector3d T_old = r.T;
    r = h.step(d, ds);
    work += 0.5 * (T_old + r.T).dot(ds);
    diss += r.dissipation;
    slid = slid || r.sliding;
  }
  EXPECT_TRUE(slid);
  dissipated = diss;
  return std::abs(diss + (r.tangential_energy - E0) - work);
}

TEST(ThorntonYinEnergy, DissipationBalancesTangentialWork)
{
  double coarse_loss = 0.0, fine_loss = 0.0;
  const double coarse = balance_defect(1, coarse_loss), fine = balance_defect(2, fine_loss);
  EXPECT_GT(coarse_loss, 0.0);
  EXPECT_LT(coarse, 1e-12 * coarse_loss);
  EXPECT_LT(fine, 1e-12 * fine_loss);
  std::printf("balance defect / dissipation: %.3g (steps as given), %.3g (halved)\n",
              coarse / coarse_loss, fine / fine_loss);
}

// §2.2 stage A is elastic ("no micro-slip"): monotonic peeling below T_c dissipates nothing,
// so the reported cumulative dissipation should be ~0 (and never negative)
TEST(ThorntonYinEnergy, PeelingLoadingDissipatesNothing)
{
  const Jkr s(0.3);
  const auto c = coefficients(1.0, 0.3);    // mu (P + 2Pc) > T_c: no sliding during peeling
  const double d = 0.0, P = -8.0 / 9.0 * s.Pc;
  const double Tc = 4.0 * std::sqrt(s.Pc * (P + s.Pc) * kGstar / kEstar);
  ASSERT_LT(Tc, c.mu * (P + 2.0 * s.Pc));
  Contact<true> h(c);
  auto r = h.step(d, Vector3d::Zero());
  double work = 0.0, diss = 0.0;
  const double dx = 1e-14;
  while (r.T.norm() < 0.9 * Tc) {
    const Vector3d T_old = r.T;
    r = h.step(d, Vector3d(dx, 0, 0));
    ASSERT_TRUE(r.peeling);
    ASSERT_FALSE(r.sliding);
    work += 0.5 * (T_old.x() + r.T.x()) * dx;
    diss += r.dissipation;
  }
  EXPECT_NEAR(diss, 0.0, 1e-3 * work);
}
