// Thornton's tangential law (its one text, plugin/core/contact_law.hpp, stepped by the scalar
// instantiation at a prescribed normal force: scalar_contact.hpp) against the exact
// Mindlin-Deresiewicz results of docs/theory.md §2.1 and the Savkoor-Briggs / Thornton (1991)
// relations of §2.2. Expected values are integrated or derived here, not taken from the code.
#include "contact_law.hpp"
#include "contact_types.hpp"
#include "jkr.hpp"

#include "glass_pair.hpp"
#include "scalar_contact.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

using Eigen::Vector3d;

namespace {

using namespace glass_pair;    // docs/theory.md §1.8 glass pair

double hertz_radius(double P) { return std::cbrt(3.0 * kRstar * P / (4.0 * kEstar)); }

// one contact driven step by step at a prescribed normal force (at its overlap), normal along z
// unless given, by the law's scalar instantiation
template <bool Adhesive> struct Driver {
  scalar_contact::Contact<Adhesive> contact;
  tycore::PairCoefficients c;
  tycore::ContactHistory& h;
  double dissipation = 0.0;
  double x = 0.0;    // accumulated tangential displacement along e_x

  explicit Driver(const tycore::PairCoefficients& coef) : contact(coef), c(coef), h(contact.h) {}
  void step(double P, const Vector3d& ds, const Vector3d& n = Vector3d(0, 0, 1), double twist = 0.0)
  {
    dissipation += contact.step_at_load(P, ds, n, twist).dissipation;
  }
  // move along x from the current position to `to` in n equal steps at constant P
  void move_to(double to, int n, double P)
  {
    const double dx = (to - x) / n;
    for (int i = 0; i < n; ++i) step(P, Vector3d(dx, 0, 0));
    x = to;
  }
  Vector3d T() const { return Eigen::Map<const Vector3d>(h.T); }
  double Tx() const { return h.T[0]; }
  // a memory that holds the force T (below the limit mu P) along its direction as one band of
  // uniform traction ratio |T|/(mu P) over the Hertz overlap of P (docs/theory.md §2.3): the
  // state a proportional loading leaves
  void hold(const Vector3d& T, double P)
  {
    const double a = std::cbrt(3.0 * kRstar * P / (4.0 * kEstar));
    Eigen::Map<Vector3d>(h.T) = T;
    Eigen::Map<Vector3d>(h.load_dir) = T.normalized();
    for (int j = 0; j < tycore::memory_bands; ++j)
      h.band_outer[j] = h.band_inner[j] = h.band_depth[j] = 0.0;
    h.band_outer[0] = h.band_inner[0] = T.norm() / (c.mu * P);
    h.band_depth[0] = a * a / kRstar;
  }
};

// exact MD virgin curve at constant P: T = mu P [1 - (1 - x/d)^(3/2)], d = 3 mu P/(16 G* a)
struct Mindlin {
  double muP, d;
  Mindlin(double mu, double P_eff, double a) : muP(mu * P_eff), d(3.0 * mu * P_eff / (16.0 * kGstar * a)) {}
  double f(double x) const
  {
    const double s = x < 0 ? -1.0 : 1.0;
    x = std::abs(x);
    return s * (x >= d ? muP : muP * (1.0 - std::pow(1.0 - x / d, 1.5)));
  }
  double F(double x) const    // integral of f from 0 to x (x in [0, d])
  {
    return muP * (x + 0.4 * d * (std::pow(1.0 - x / d, 2.5) - 1.0));
  }
};

}    // namespace

// §2.1: the first increment from T = 0 is elastic with k_T = 8 G* a, a the Hertz radius of P
TEST(MindlinLoading, InitialStiffnessIs8Ga)
{
  const double P = 1e-3;
  Driver<false> drv(coefficients(0.3, 0.0));
  const double ds = 1e-13;
  drv.step(P, Vector3d::Zero());    // loaded normally first
  drv.step(P, Vector3d(ds, 0, 0));
  // 8 G* a ds to first order: Mindlin's curve bends by ds/(4 kappa delta) ~ 1e-5 here
  EXPECT_NEAR(drv.Tx(), 8.0 * kGstar * hertz_radius(P) * ds, 2e-5 * drv.Tx());
  EXPECT_EQ(drv.h.T[1], 0.0);
  EXPECT_EQ(drv.h.T[2], 0.0);
  EXPECT_EQ(drv.h.sliding, 0.0);
  EXPECT_EQ(drv.h.band_outer[0], 1.0);    // the slip annulus opens at the edge (§2.3)
}

// §2.1: monotonic loading at constant P follows T = mu P[1 - (1 - 16G*a x/(3 mu P))^(3/2)]
TEST(MindlinLoading, MonotonicFollowsMindlinCurve)
{
  const double P = 1e-3, mu = 0.3;
  const Mindlin md(mu, P, hertz_radius(P));
  Driver<false> drv(coefficients(mu, 0.0));
  const int n = 1000000;    // steps per d (explicit increments: error ~ 1/n)
  for (double frac = 0.05; frac < 0.99; frac += 0.05) {
    drv.move_to(frac * md.d, static_cast<int>(0.05 * n), P);
    EXPECT_NEAR(drv.Tx(), md.f(drv.x), 1e-6 * md.muP) << frac;
    EXPECT_EQ(drv.h.sliding, 0.0) << frac;
  }
}

// §2.1: sliding at T = mu P, reached at x = d; then the dissipation grows by mu P per unit slip.
// Energy at full mobilisation: work = int_0^d f = 0.6 mu P d. The traction is then q = mu p
// (Hertzian shape), whose elastic energy (Johnson's u_x for q0 sqrt(1 - r^2/a^2)) is
// 1.2 (mu P)^2/(2 k_T) = 0.4 mu P d, so D = 0.2 mu P d -- equal to the Masing/Iwan annulus loss
// int_0^d (f - x f') dx = 2 x 0.6 - 1 (mu P d). [Corrected: the earlier 4/15 took |T|^2/(2 k_T)
// as the stored energy, which undercounts it by the factor 1.2.]
TEST(MindlinLoading, GrossSlidingAtMuP)
{
  const double P = 1e-3, mu = 0.3;
  const Mindlin md(mu, P, hertz_radius(P));
  Driver<false> drv(coefficients(mu, 0.0));
  const int n = 200000;
  const double dx = md.d / n;
  int first_slide = -1;
  for (int i = 1; i <= 2 * n; ++i) {
    drv.step(P, Vector3d(dx, 0, 0));
    if (first_slide < 0 && drv.h.sliding != 0.0) first_slide = i;
  }
  ASSERT_GT(first_slide, 0);
  EXPECT_NEAR(first_slide * dx, md.d, 1e-3 * md.d);
  EXPECT_NEAR(drv.T().norm(), mu * P, 1e-14 * mu * P);
  EXPECT_NEAR(drv.T().x(), mu * P, 1e-14 * mu * P);
  EXPECT_EQ(drv.h.sliding, 1.0);
  const double expected = 0.2 * mu * P * md.d + mu * P * (2 * n * dx - md.d);
  EXPECT_NEAR(drv.h.stored_energy, 0.4 * mu * P * md.d, 1e-4 * mu * P * md.d);
  EXPECT_NEAR(drv.dissipation, expected, 1e-4 * expected);
  // one more slip step: dissipation grows by exactly mu P ds
  const double before = drv.dissipation;
  drv.step(P, Vector3d(3 * dx, 0, 0));
  EXPECT_NEAR(drv.dissipation - before, mu * P * 3 * dx, 1e-9 * mu * P * 3 * dx);
}

// §2.1 Masing: unloading from gross sliding follows T* - T = 2 mu P [1 - (1 - (x* - x)/(2d))^(3/2)]
// down to T = -mu P at x* - x = 2d
TEST(MindlinUnloading, MasingCurveFromSliding)
{
  const double P = 2e-3, mu = 0.3;
  const Mindlin md(mu, P, hertz_radius(P));
  Driver<false> drv(coefficients(mu, 0.0));
  const int n = 200000;
  drv.move_to(1.5 * md.d, 3 * n / 2, P);
  ASSERT_EQ(drv.h.sliding, 1.0);
  const double x_star = drv.x, T_star = drv.Tx();
  for (double back = 0.1; back < 1.99; back += 0.1) {
    drv.move_to(x_star - back * md.d, n / 10, P);
    EXPECT_NEAR(drv.Tx(), T_star - 2.0 * md.f(0.5 * back * md.d), 2e-6 * md.muP) << back;
    EXPECT_EQ(drv.h.sliding, 0.0) << back;
  }
  drv.move_to(x_star - 2.2 * md.d, n / 5, P);
  EXPECT_NEAR(drv.Tx(), -mu * P, 1e-12 * mu * P);
  EXPECT_EQ(drv.h.sliding, 1.0);
}

// Masing from a partial load T* = f(A) < mu P, then reloading: T - T** = 2 mu P[1 - (1 - (x -
// x**)/(2d))^(3/2)], and return-point memory: past x = A the virgin curve f(x) is resumed
TEST(MindlinReloading, MasingReloadAndReturnPointMemory)
{
  const double P = 1e-3, mu = 0.4;
  const Mindlin md(mu, P, hertz_radius(P));
  Driver<false> drv(coefficients(mu, 0.0));
  const int n = 1000000;
  const double A = 0.6 * md.d, B = 0.5 * md.d;
  drv.move_to(A, static_cast<int>(0.6 * n), P);
  const double T_star = md.f(A);
  EXPECT_NEAR(drv.Tx(), T_star, 1e-6 * md.muP);
  for (double u = 0.1; u <= 0.5 + 1e-9; u += 0.1) {    // unloading
    drv.move_to(A - u * md.d, n / 10, P);
    EXPECT_NEAR(drv.Tx(), T_star - 2.0 * md.f(0.5 * u * md.d), 2e-6 * md.muP) << u;
  }
  EXPECT_EQ(drv.h.band_outer[0], -1.0);    // the edge slips backward
  const double x_2star = A - B, T_2star = T_star - 2.0 * md.f(0.5 * B);
  for (double r = 0.1; r <= 0.5 + 1e-9; r += 0.1) {    // reloading back to A
    drv.move_to(x_2star + r * md.d, n / 10, P);
    EXPECT_NEAR(drv.Tx(), T_2star + 2.0 * md.f(0.5 * r * md.d), 2e-6 * md.muP) << r;
  }
  EXPECT_NEAR(drv.Tx(), T_star, 2e-6 * md.muP);    // loop closes at (A, T*)
  for (double x = 0.7; x < 0.99; x += 0.05) {       // virgin curve resumed
    drv.move_to(x * md.d, n / 20, P);
    EXPECT_NEAR(drv.Tx(), md.f(x * md.d), 3e-6 * md.muP) << x;
    EXPECT_EQ(drv.h.band_outer[0], 1.0) << x;
  }
}

// §2.1 energy: a closed symmetric loop +-A without gross sliding dissipates (Masing, exact)
// D = 8F(A) - 4A f(A) = mu P A^3/(2 d^2) + O(A^4): vanishing relative to the stored energy as
// A -> 0 and scaling as A^3 (Mindlin & Deresiewicz)
TEST(MindlinEnergy, SmallLoopHysteresisScalesAsCube)
{
  const double P = 1e-3, mu = 0.3;
  const Mindlin md(mu, P, hertz_radius(P));
  double previous = 0.0;
  for (double frac : {0.4, 0.2, 0.1, 0.05}) {
    const double A = frac * md.d;
    Driver<false> drv(coefficients(mu, 0.0));
    const int n = 40000;
    drv.move_to(A, n, P);
    const double d0 = drv.dissipation, T0 = drv.Tx();
    drv.move_to(-A, 2 * n, P);
    EXPECT_NEAR(drv.Tx(), -md.f(A), 1e-4 * md.f(A)) << frac;
    drv.move_to(A, 2 * n, P);
    EXPECT_NEAR(drv.Tx(), T0, 1e-4 * T0) << frac;
    const double loop = drv.dissipation - d0;
    const double exact = 8.0 * md.F(A) - 4.0 * A * md.f(A);
    EXPECT_NEAR(loop, exact, 2e-3 * exact) << frac;
    EXPECT_NEAR(exact / (md.muP * A * A * A / (2.0 * md.d * md.d)), 1.0, frac) << frac;
    // relative to the elastic energy k A^2/2 (k d = 3 mu P/2) the loss vanishes as (2/3) A/d
    const double k = 8.0 * kGstar * hertz_radius(P);
    EXPECT_NEAR(loop / (0.5 * k * A * A), 2.0 / 3.0 * frac, 0.5 * frac * frac) << frac;
    if (previous > 0.0) {
      EXPECT_NEAR(previous / loop, 8.0, 1.0) << frac;
    }
    previous = loop;
  }
}

// §2.1: proportional loading from zero with T/P = c < mu (Hertz normal load growing with
// delta): no micro-slip (theta = 1) and delta_t/delta = c E*/(4 G*)
TEST(MindlinProportional, RatioTangentialToNormal)
{
  const double mu = 0.5, c_ratio = 0.25;
  const double lambda = c_ratio * kEstar / (4.0 * kGstar);    // delta_t/delta
  Driver<false> drv(coefficients(mu, 0.0));
  const double delta_end = 1e-7;
  const int n = 100000;
  for (int i = 1; i <= n; ++i) {
    const double delta = delta_end * i / n;
    const double P = 4.0 / 3.0 * kEstar * std::sqrt(kRstar) * std::pow(delta, 1.5);
    drv.step(P, Vector3d(lambda * delta_end / n, 0, 0));
    EXPECT_EQ(drv.h.sliding, 0.0) << i;
  }
  const double P = 4.0 / 3.0 * kEstar * std::sqrt(kRstar) * std::pow(delta_end, 1.5);
  EXPECT_NEAR(drv.Tx() / P, c_ratio, 1e-4 * c_ratio);
}

// the same no-slip proportional path: theta = 1 throughout (no micro-slip, no sliding), so
// physically nothing is dissipated and the reported dissipation should be ~0
TEST(MindlinProportional, NoSlipPathDissipatesNothing)
{
  const double mu = 0.5, c_ratio = 0.25;
  const double lambda = c_ratio * kEstar / (4.0 * kGstar);
  Driver<false> drv(coefficients(mu, 0.0));
  const double delta_end = 1e-7;
  const int n = 100000;
  double work = 0.0;
  for (int i = 1; i <= n; ++i) {
    const double delta = delta_end * i / n;
    const double P = 4.0 / 3.0 * kEstar * std::sqrt(kRstar) * std::pow(delta, 1.5);
    const double T_old = drv.Tx();
    drv.step(P, Vector3d(lambda * delta_end / n, 0, 0));
    work += 0.5 * (T_old + drv.Tx()) * lambda * delta_end / n;
  }
  const double E_T = drv.h.stored_energy;
  EXPECT_NEAR(drv.dissipation, 0.0, 1e-3 * E_T);
  EXPECT_NEAR(E_T, work, 1e-9 * work);    // all the work is stored
}

// with mu = 0 or a non-adhesive contact at zero load there is no tangential force
TEST(MindlinLimits, FrictionlessAndUnloadedContactCarryNoShear)
{
  Driver<false> drv(coefficients(0.0, 0.0));
  drv.step(1e-3, Vector3d(1e-9, 2e-9, 0));
  EXPECT_EQ(drv.T().norm(), 0.0);
  EXPECT_EQ(drv.h.sliding, 1.0);
  Driver<false> d2(coefficients(0.3, 0.0));
  d2.step(1e-3, Vector3d(1e-9, 0, 0));
  EXPECT_GT(d2.T().norm(), 0.0);
  d2.step(0.0, Vector3d(1e-9, 0, 0));
  EXPECT_EQ(d2.T().norm(), 0.0);
}

// the history carried with the contact: a twist psi about the normal rotates T and the memory's
// axis load_dir by psi (Rodrigues); a step at constant P without increment keeps them so
TEST(MindlinRotation, TwistAboutNormal)
{
  const double P = 1e-2, psi = 0.37;
  const Vector3d n(0, 0, 1), T0(3e-4, -1e-4, 0);
  Driver<false> drv(coefficients(0.3, 0.0));
  drv.step(P, Vector3d::Zero());
  drv.hold(T0, P);
  ASSERT_LT(T0.norm(), 0.3 * P);
  drv.step(P, Vector3d::Zero(), n, psi);
  const Eigen::AngleAxisd Q(psi, n);
  const Vector3d expectT = Q * T0, expectD = Q * T0.normalized();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(drv.h.T[k], expectT[k], 1e-14 * 3e-4);
    EXPECT_NEAR(drv.h.load_dir[k], expectD[k], 1e-14);
  }
}

// tilting the normal about n x T (rigid rotation in the n-T plane) carries T rigidly, magnitude
// kept
TEST(MindlinRotation, TiltOfNormalCarriesT)
{
  const double P = 1e-2;
  Driver<false> drv(coefficients(0.3, 0.0));
  drv.step(P, Vector3d::Zero());
  const Vector3d n(0, 0, 1), T0(2e-4, 0, 0);
  drv.hold(T0, P);
  const Eigen::AngleAxisd Q(0.2, n.cross(T0).normalized());
  drv.step(P, Vector3d::Zero(), Q * n, 0.0);
  const Vector3d T = Eigen::Map<Vector3d>(drv.h.T);
  EXPECT_NEAR((T - Q * T0).norm(), 0.0, 1e-14 * T0.norm());
  EXPECT_NEAR(T.dot(Q * n), 0.0, 1e-14 * T0.norm());
  EXPECT_NEAR(Eigen::Map<Vector3d>(drv.h.load_dir).norm(), 1.0, 1e-15);
}

// objectivity: the whole history (normal, T, load_dir, increments) rotated rigidly by Q gives
// Q times the unrotated tangential force, same magnitude, same memory and dissipation
TEST(MindlinRotation, ObjectivityUnderRigidRotation)
{
  const double mu = 0.3;
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(0.9, Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  Driver<false> a(coefficients(mu, 0.0)), b(coefficients(mu, 0.0));
  const Vector3d n(0, 0, 1);
  for (int i = 0; i < 3000; ++i) {    // micro-slip, reversals, varying P; below gross sliding
    const double P = 1e-3 * (1.0 + 0.5 * std::sin(0.01 * i));
    const Vector3d ds(2e-12 * std::cos(0.004 * i), 1.5e-12 * std::sin(0.007 * i), 0);
    const double twist = 1e-3 * std::sin(0.02 * i);
    a.step(P, ds, n, twist);
    b.step(P, Q * ds, Q * n, twist);
  }
  const Vector3d Ta = a.T(), Tb = b.T();
  ASSERT_GT(Ta.norm(), 0.0);
  EXPECT_NEAR(Tb.norm(), Ta.norm(), 1e-10 * Ta.norm());
  EXPECT_NEAR((Tb - Q * Ta).norm(), 0.0, 1e-10 * Ta.norm());
  double depth = 0.0;
  for (int j = 0; j < tycore::memory_bands; ++j) depth += a.h.band_depth[j];
  for (int j = 0; j < tycore::memory_bands; ++j) {    // the same memory
    EXPECT_NEAR(b.h.band_outer[j], a.h.band_outer[j], 1e-9) << j;
    EXPECT_NEAR(b.h.band_inner[j], a.h.band_inner[j], 1e-9) << j;
    EXPECT_NEAR(b.h.band_depth[j], a.h.band_depth[j], 1e-9 * depth) << j;
  }
  EXPECT_EQ(a.h.sliding, 0.0);
  // (the dissipation is the step's work less the change of the memory's energy: a difference
  // that multiplies the round-off of the rotation)
  EXPECT_NEAR(b.dissipation, a.dissipation, 1e-6 * std::abs(a.dissipation) + 1e-25);
}

// §2.2: T_c = 4 sqrt(Pc (P + Pc) G*/E*) is where the law's Savkoor-Briggs discriminant
// vanishes; for nu = mu = 0.3, T_c(P=0) = 1.815 Pc and sliding precedes the end of peeling for
// P < 33.6 Pc
TEST(MindlinAdhesion, PeelingEndForceAndCrossover)
{
  const auto c = coefficients(0.3, 0.3);
  const tycore::PairConstants k = tycore::pair_constants(c);
  const double Pc = tycore::jkr::pull_off_force(c.Gamma, kRstar);
  for (double p : {-0.5, 0.0, 1.0, 20.0}) {
    const double P = p * Pc;
    const double Tc = 4.0 * std::sqrt(Pc * (P + Pc) * kGstar / kEstar);
    EXPECT_NEAR(tycore::peeling_discriminant(k, P, Pc, Tc * Tc), 0.0, 1e-12 * Pc * Pc) << p;
    EXPECT_NEAR(tycore::peeling_discriminant(k, P, Pc, 0.0), 4.0 * Pc * (P + Pc), 1e-13 * Pc * Pc);
    // E*/(4G*) coefficient of T^2
    EXPECT_NEAR(tycore::peeling_discriminant(k, P, Pc, 0.0) - tycore::peeling_discriminant(k, P, Pc, 1e-8),
                1e-8 * kEstar / (4.0 * kGstar), 1e-12 * Pc * Pc);
  }
  const double Tc0 = 4.0 * std::sqrt(Pc * Pc * kGstar / kEstar);
  EXPECT_NEAR(Tc0 / Pc, 1.815, 5e-4);
  // crossover mu (P + 2Pc) = T_c, solved by bisection in p = P/Pc
  double lo = 0.0, hi = 100.0;
  for (int i = 0; i < 100; ++i) {
    const double p = 0.5 * (lo + hi);
    (0.3 * (p + 2.0) < 4.0 * std::sqrt((p + 1.0) * kGstar / kEstar) ? lo : hi) = p;
  }
  EXPECT_NEAR(lo, 33.6, 0.05);
}

// §2.2 stage A: a peeled step is elastic with k_T = 8 G* a_peel(T), 4E*a_peel^3/(3R*) =
// P + 2Pc + sqrt(4 P Pc + 4 Pc^2 - T^2 E*/(4G*)): at T = 0 the JKR radius of P, shrinking
// monotonically as T grows; once peeling has ended at T_c, micro-slip with the Hertz radius of
// P + 2Pc (mu = 1: no sliding before T_c)
TEST(MindlinAdhesion, PeeledRadiusFromJkrToHertzOfEffectiveLoad)
{
  const auto c = coefficients(1.0, 0.3);
  const double Pc = tycore::jkr::pull_off_force(c.Gamma, kRstar);
  for (double p : {-0.5, 0.0, 3.0, 50.0}) {
    const double P = p * Pc;
    // JKR radius of P from a^ solving 4a^3 - 4a^1.5 = p on the stable branch (bisection)
    const double a0 = std::cbrt(3.0 * kRstar * Pc / kEstar);
    double lo = std::cbrt(0.25), hi = 10.0;
    for (int i = 0; i < 200; ++i) {
      const double m = 0.5 * (lo + hi);
      (4 * m * m * m - 4 * std::pow(m, 1.5) < p ? lo : hi) = m;
    }
    const double a_jkr = lo * a0;
    const double Tc = 4.0 * std::sqrt(Pc * (P + Pc) * kGstar / kEstar);
    const auto a_peel = [&](double T) {
      const double root = std::max(4.0 * P * Pc + 4.0 * Pc * Pc - T * T * kEstar / (4.0 * kGstar), 0.0);
      return std::cbrt(3.0 * kRstar * (P + 2.0 * Pc + std::sqrt(root)) / (4.0 * kEstar));
    };
    ASSERT_NEAR(a_peel(0.0), a_jkr, 1e-12 * a_jkr);
    Driver<true> drv(c);
    const double dx = 0.02 * Tc / (8.0 * kGstar * a_jkr);
    double prev = 2.0 * a_jkr;
    int peeled_steps = 0;
    while (drv.h.peeling != 0.0 && peeled_steps < 1000) {
      const double T_old = drv.Tx();
      drv.step(P, Vector3d(dx, 0, 0));
      const double a = (drv.Tx() - T_old) / (8.0 * kGstar * dx);    // the step's radius
      EXPECT_NEAR(a, a_peel(T_old), 1e-10 * a_jkr) << p << " " << T_old / Tc;
      EXPECT_LT(a, prev) << p << " " << T_old / Tc;
      prev = a;
      ++peeled_steps;
    }
    EXPECT_GT(peeled_steps, 40) << p;
    EXPECT_NEAR(drv.Tx(), Tc, 0.03 * Tc) << p;    // peeling ends within a step of T_c
    EXPECT_EQ(drv.h.sliding, 0.0) << p;
    const double a_T = std::cbrt(3.0 * kRstar * (P + 2.0 * Pc) / (4.0 * kEstar));
    EXPECT_GT(prev, a_T) << p;
    const scalar_contact::Result r = drv.contact.step_at_load(P, Vector3d(dx, 0, 0));
    EXPECT_NEAR(r.stiffness, 8.0 * kGstar * a_T, 1e-13 * 8.0 * kGstar * a_T) << p;
  }
}

// §2.2 stage A below T_c: dT/dx = 8 G* a_peel(T), no micro-slip: first step stiffness is
// 8 G* a_JKR(P); the curve matches an RK4 integration of that ODE; unloading retraces it
// (no hysteresis over a closed loop); the peeling flag stays set
TEST(MindlinAdhesion, PeelingBelowTcIsElasticWithoutMicroSlip)
{
  const auto c = coefficients(0.3, 0.3);
  const double Pc = tycore::jkr::pull_off_force(c.Gamma, kRstar);
  const double P = 50.0 * Pc;    // T_c < mu (P + 2Pc): peeling ends before sliding
  const double Tc = 4.0 * std::sqrt(Pc * (P + Pc) * kGstar / kEstar);
  const auto a_peel = [&](double T) {
    const double root = std::max(4.0 * P * Pc + 4.0 * Pc * Pc - T * T * kEstar / (4.0 * kGstar), 0.0);
    return std::cbrt(3.0 * kRstar * (P + 2.0 * Pc + std::sqrt(root)) / (4.0 * kEstar));
  };
  const auto rhs = [&](double T) { return 8.0 * kGstar * a_peel(T); };
  // reference: RK4 up to x_end with fine steps
  const double x_end = 0.8 * Tc / rhs(0.0);
  double Tref = 0.0;
  const int m = 20000;
  for (int i = 0; i < m; ++i) {
    const double h = x_end / m;
    const double k1 = rhs(Tref), k2 = rhs(Tref + 0.5 * h * k1), k3 = rhs(Tref + 0.5 * h * k2),
                 k4 = rhs(Tref + h * k3);
    Tref += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  ASSERT_LT(Tref, Tc);

  Driver<true> drv(c);
  const double ds0 = 1e-14;
  drv.step(P, Vector3d(ds0, 0, 0));
  EXPECT_NEAR(drv.Tx(), 8.0 * kGstar * a_peel(0.0) * ds0, 1e-10 * drv.Tx());
  EXPECT_EQ(drv.h.peeling, 1.0);
  drv.x = ds0;
  drv.move_to(x_end, 200000, P);
  EXPECT_NEAR(drv.Tx(), Tref, 1e-5 * Tref);
  EXPECT_EQ(drv.h.peeling, 1.0);
  EXPECT_EQ(drv.h.sliding, 0.0);
  const double d0 = drv.dissipation;
  drv.move_to(0.0, 200000, P);
  EXPECT_NEAR(drv.Tx(), 0.0, 1e-5 * Tref);
  drv.move_to(x_end, 200000, P);
  EXPECT_NEAR(drv.Tx(), Tref, 1e-5 * Tref);
  EXPECT_NEAR(drv.dissipation - d0, 0.0, 1e-5 * Tref * x_end);
  EXPECT_EQ(drv.h.peeling, 1.0);
}

// §2.2: peeling ends at T_c; then micro-slip with P -> P + 2Pc: from (x_c, T_c) the MD ODE
// dT/dx = 8G* a_T (1 - T/(mu Peff))^(1/3) gives (1 - T/(mu Peff))^(2/3) = (1 - T_c/(mu Peff))^(2/3)
// - (x - x_c)/d_eff, d_eff = 3 mu Peff/(16 G* a_T); gross sliding at mu (P + 2Pc), not mu P
TEST(MindlinAdhesion, PeelingThenMicroSlipThenSlidingAtMuPPlus2Pc)
{
  const double mu = 0.3;
  const auto c = coefficients(mu, 0.3);
  const double Pc = tycore::jkr::pull_off_force(c.Gamma, kRstar);
  const double P = 50.0 * Pc, Peff = P + 2.0 * Pc;
  const double Tc = 4.0 * std::sqrt(Pc * (P + Pc) * kGstar / kEstar);
  const double a_T = std::cbrt(3.0 * kRstar * Peff / (4.0 * kEstar));
  const double d_eff = 3.0 * mu * Peff / (16.0 * kGstar * a_T);
  Driver<true> drv(c);
  const double dx = d_eff / 200000;
  int steps = 0;
  while (drv.h.peeling != 0.0 && steps < 10000000) {
    drv.step(P, Vector3d(dx, 0, 0));
    ++steps;
  }
  ASSERT_EQ(drv.h.peeling, 0.0);
  EXPECT_EQ(drv.h.sliding, 0.0);
  const double x_c = steps * dx;
  EXPECT_NEAR(drv.Tx(), Tc, 8.0 * kGstar * a_T * dx * 1.0001);    // within one step of T_c
  const double y_c = std::pow(1.0 - Tc / (mu * Peff), 2.0 / 3.0);
  for (double f = 0.1; f < 0.96; f += 0.1) {
    const double target = x_c + f * y_c * d_eff;
    while ((steps + 1) * dx <= target) {
      drv.step(P, Vector3d(dx, 0, 0));
      ++steps;
    }
    const double y = y_c - (steps * dx - x_c) / d_eff;
    EXPECT_NEAR(drv.Tx(), mu * Peff * (1.0 - std::pow(y, 1.5)), 2e-5 * mu * Peff) << f;
    EXPECT_EQ(drv.h.sliding, 0.0) << f;
  }
  for (int i = 0; i < 200000; ++i) drv.step(P, Vector3d(dx, 0, 0));
  EXPECT_EQ(drv.h.sliding, 1.0);
  EXPECT_NEAR(drv.T().norm(), mu * (P + 2.0 * Pc), 1e-13 * mu * Peff);
  EXPECT_GT(drv.T().norm(), mu * P * 1.03);
}

// §2.2 stage C during peeling: for P < 33.6 Pc (mu = 0.3) the contact slides at mu (P + 2Pc)
// while still peeling -- also in tension, P in (-Pc, 0) -- and the slide ends peeling
TEST(MindlinAdhesion, SlidingDuringPeelingAtLowLoad)
{
  const double mu = 0.3;
  const auto c = coefficients(mu, 3.0);
  const double Pc = tycore::jkr::pull_off_force(c.Gamma, kRstar);
  for (double p : {-0.5, 0.0, 5.0}) {
    const double P = p * Pc, limit = mu * (P + 2.0 * Pc);
    Driver<true> drv(c);
    const double k0 = 8.0 * kGstar * hertz_radius(P + 2.0 * Pc);
    const double dx = limit / k0 / 20000;
    int steps = 0;
    while (drv.h.sliding == 0.0 && steps < 1000000) {
      EXPECT_EQ(drv.h.peeling, 1.0) << p;
      drv.step(P, Vector3d(dx, 0, 0));
      ++steps;
    }
    ASSERT_EQ(drv.h.sliding, 1.0) << p;
    EXPECT_NEAR(drv.T().norm(), limit, 1e-13 * limit) << p;
    EXPECT_LT(limit, 4.0 * std::sqrt(Pc * (P + Pc) * kGstar / kEstar)) << p;
    EXPECT_EQ(drv.h.peeling, 0.0) << p;
    // sliding continues at the same limit, dissipating mu (P + 2Pc) per unit slip
    const double before = drv.dissipation;
    drv.step(P, Vector3d(dx, 0, 0));
    EXPECT_NEAR(drv.dissipation - before, limit * dx, 1e-9 * limit * dx) << p;
  }
}

// gross sliding in a new direction: after sliding along x, slip along y at constant P over many
// d. Coulomb (and any 3D Mindlin generalisation) turns T towards the slip direction, |T| = mu P,
// and friction then dissipates mu P per unit slip.
TEST(MindlinSliding, ForceTurnsTowardsNewSlipDirection)
{
  const double P = 1e-3, mu = 0.3;
  const Mindlin md(mu, P, hertz_radius(P));
  Driver<false> drv(coefficients(mu, 0.0));
  drv.move_to(2.0 * md.d, 20000, P);
  ASSERT_EQ(drv.h.sliding, 1.0);
  const double d0 = drv.dissipation;
  const double dy = md.d / 10000;
  for (int i = 0; i < 100000; ++i) drv.step(P, Vector3d(0, dy, 0));    // slip 10 d along y
  const Vector3d T = drv.T();
  EXPECT_NEAR(T.norm(), mu * P, 1e-12 * mu * P);
  const double cos_y = T.y() / T.norm();
  const double lost = drv.dissipation - d0;
  EXPECT_GT(cos_y, 0.9);
  EXPECT_NEAR(lost, mu * P * 10 * md.d, 0.2 * mu * P * 10 * md.d);
}

// §2.3 step 4: an increment across the memory's axis meets the no-slip stiffness 8 G* a, and the
// memory turns with the force: from a sticking memory (uniform ratio below the limit) a sideways
// ds gives T = T0 + 8 G* a ds exactly (magnitude and direction), and the axis follows T
TEST(MindlinTurn, SidewaysIncrementIsElasticAndTurnsTheMemory)
{
  const double P = 1e-2;
  const Vector3d n(0, 0, 1), T0(1e-3, 0, 0);
  Driver<false> drv(coefficients(0.3, 0.0));
  drv.step(P, Vector3d::Zero());
  drv.hold(T0, P);
  const Vector3d ds(0, 2e-10, 0);
  drv.step(P, ds, n);
  const Vector3d expect = T0 + 8.0 * kGstar * hertz_radius(P) * ds;
  EXPECT_NEAR((drv.T() - expect).norm(), 0.0, 1e-12 * expect.norm());
  const Vector3d axis = Eigen::Map<const Vector3d>(drv.h.load_dir);
  EXPECT_NEAR((axis - expect.normalized()).norm(), 0.0, 1e-12);
  // the memory carries |T|: a uniform ratio |T|/(mu P)
  EXPECT_NEAR(drv.h.band_outer[0], expect.norm() / (0.3 * P), 1e-12);
  EXPECT_NEAR(drv.h.band_inner[0], expect.norm() / (0.3 * P), 1e-12);
}
