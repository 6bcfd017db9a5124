// The batch entry tycore::advance_batch (contact_batch.hpp) in every build this processor runs
// (scalar, SSE2, AVX2, AVX-512; each forced in turn, those the processor lacks not
// instantiated), all instantiations of the law's one text (contact_law.hpp):
//  * the law: random contact paths (contact_paths.hpp), one a lane of a batch whose other lanes
//    follow further paths (contacts in different states in one batch), through snap-in,
//    peeling, micro-slip loading / unloading / reloading, sliding, tension and break, every
//    step of every build against the scalar build and the scalar entry advance_contact to the
//    last bit, and each against what holds for any step of the law (Coulomb limit, energy
//    balance); a digest of the widest build's outputs, which tests/test_scalar_law_build.py
//    compares with the build configured with -DTYLMP_VECTOR_LAW=OFF;
//  * the rest of the step: viscous damping, the servo's affine-stiffness tally
//    (docs/theory.md §6.1), stored energy, first touch (§1.3) and separation (§1.2, §3.2),
//    against their formulas, and the vector builds against the scalar build to the last bit;
//  * the setup pass's entry forces_without_step (forces with the history kept) against the
//    JKR force, the damping formulas and the Coulomb limit;
//  * the lane-wide cube root against jkr::fast_cbrt (bit for bit) and std::cbrt.
#include "cell_stiffness.hpp"
#include "contact_batch.hpp"
#include "contact_kernel.hpp"
#include "contact_types.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"
#include "simd_math.hpp"

#include "contact_paths.hpp"
#include "glass_pair.hpp"
#include "cube_roots.hpp"
#include "jkr_extra.hpp"

#include <gtest/gtest.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <vector>

namespace {

using contact_paths::RandomPath;
using contact_paths::Visits;
using tycore::ContactBatch;
using tycore::Isa;
using tycore::batch_lanes;

std::vector<Isa> supported_isas()
{
  std::vector<Isa> isas;
  for (Isa isa : {Isa::scalar, Isa::sse2, Isa::avx2, Isa::avx512})
    if (tycore::isa_supported(isa)) isas.push_back(isa);
  return isas;
}

// the dt of the batches below: twist = dt spin_n / 2 and ds = -vt dt are then exact
constexpr double kDt = 2.0;

// lane `lane` of b takes step s of a contact with history h (no damping inputs)
void set_lane(ContactBatch& b, int lane, const contact_paths::Step& s, double R,
              const tycore::ContactHistory& h)
{
  tycore::load_history(b, lane, h);
  for (int d = 0; d < 3; ++d) {
    b.n[d][lane] = s.n[d];
    b.vt[d][lane] = -0.5 * s.ds[d];
  }
  b.delta[lane] = s.delta;
  b.R[lane] = R;
  b.Rinv[lane] = 1.0 / R;
  b.vn[lane] = 0.0;
  b.spin_n[lane] = s.twist;
  b.m_star[lane] = 0.0;
  b.rsq[lane] = 0.0;
  b.first_touch[lane] = false;
}

template <bool Adhesive>
void advance(ContactBatch& b, int n, const tycore::PairConstants& k,
             const tycore::BatchParameters& p, Isa isa)
{
  tycore::advance_batch<Adhesive, false>(b, n, k, p, isa);
}

// the scalar kernel's step from the same state, to the last bit
void expect_bitwise_scalar_kernel(const tycore::PairConstants& k, const RandomPath& path,
                                  const contact_paths::Step& s, tycore::ContactHistory h,
                                  const ContactBatch& b, int lane)
{
  const double nv[3] = {s.n.x(), s.n.y(), s.n.z()}, dsv[3] = {s.ds.x(), s.ds.y(), s.ds.z()};
  double lost = 0.0;
  const tycore::KernelResult f =
      path.adhesive ? tycore::advance_contact<true>(k, path.R, s.delta, nv, s.twist, dsv, h, lost)
                    : tycore::advance_contact<false>(k, path.R, s.delta, nv, s.twist, dsv, h, lost);
  ASSERT_EQ(b.P[lane], f.P);
  ASSERT_EQ(b.contact_radius[lane], f.contact_radius);
  ASSERT_EQ(b.dissipation[lane], lost);
  const tycore::ContactHistory g = tycore::stored_history(b, lane);
  const double* x = &g.T[0];
  const double* y = &h.T[0];
  for (int m = 0; m < tycore::history_size; ++m) ASSERT_EQ(x[m], y[m]) << "history value " << m;
  // force on i and the torque's ingredient n x T (no damping here)
  for (int d = 0; d < 3; ++d) ASSERT_EQ(b.force[d][lane], nv[d] * f.P + h.T[d]);
  ASSERT_EQ(b.moment[0][lane], nv[1] * h.T[2] - nv[2] * h.T[1]);
  ASSERT_EQ(b.moment[1][lane], nv[2] * h.T[0] - nv[0] * h.T[2]);
  ASSERT_EQ(b.moment[2][lane], nv[0] * h.T[1] - nv[1] * h.T[0]);
}

// every output of lane `lane` of x and y the same to the last bit
void expect_bitwise_lane(const ContactBatch& x, const ContactBatch& y, int lane)
{
  ASSERT_EQ(x.P[lane], y.P[lane]);
  ASSERT_EQ(x.contact_radius[lane], y.contact_radius[lane]);
  ASSERT_EQ(x.dissipation[lane], y.dissipation[lane]);
  ASSERT_EQ(x.broken[lane], y.broken[lane]);
  ASSERT_EQ(x.break_energy[lane], y.break_energy[lane]);
  ASSERT_EQ(x.slides[lane], y.slides[lane]);
  for (int d = 0; d < 3; ++d) {
    ASSERT_EQ(x.force[d][lane], y.force[d][lane]);
    ASSERT_EQ(x.moment[d][lane], y.moment[d][lane]);
  }
  const tycore::ContactHistory g = tycore::stored_history(x, lane), h = tycore::stored_history(y, lane);
  for (int m = 0; m < tycore::history_size; ++m)
    ASSERT_EQ((&g.T[0])[m], (&h.T[0])[m]) << "history value " << m;
}

// FNV-1a over the bytes of n doubles
void digest_add(std::uint64_t& digest, const double* x, int n)
{
  unsigned char bytes[sizeof(double)];
  for (int i = 0; i < n; ++i) {
    std::memcpy(bytes, &x[i], sizeof(double));
    for (unsigned char c : bytes) digest = (digest ^ c) * 0x100000001b3ULL;
  }
}

// Lane paths[i] follows path i as the pair would: out of contact while the overlap is a gap,
// first touch (JKR snap-in) when it is back at delta >= 0, a step of the law while in contact,
// forgotten where it breaks (below delta_f; a Hertz contact at delta < 0). The contacts in
// contact at a step form the batch's lanes 0 .. m-1; the batch takes the step in build `isa`
// and in the scalar build, and every lane must agree to the last bit with the scalar build,
// with advance_contact from the same history (first touch: begin_contact at the closed-form
// radius), and satisfy expect_law_holds. Returns the digest of the outputs in `digest`.
void compare_batch_on_paths(Isa isa, const std::vector<RandomPath>& paths_in, int steps,
                            std::vector<Visits>& seen, std::uint64_t* digest = nullptr)
{
  std::vector<RandomPath> paths = paths_in;    // a fresh copy of each path's generator
  const int n = static_cast<int>(paths.size());
  ASSERT_LE(n, batch_lanes);
  const tycore::PairConstants k = tycore::pair_constants(paths[0].c);
  const bool adhesive = paths[0].adhesive;
  tycore::BatchParameters p;
  p.dt = kDt;
  auto b = std::make_unique<ContactBatch>(), scalar = std::make_unique<ContactBatch>();
  std::vector<tycore::ContactHistory> h(n);
  std::vector<bool> touching(n, true);
  std::vector<contact_paths::Step> s(n);
  std::vector<int> lane_of(n, -1);
  for (int i = 0; i < n; ++i) h[i] = paths[i].first_touch();
  seen.assign(n, Visits{});
  std::uint64_t sum = 0xcbf29ce484222325ULL;
  for (int step = 0; step < steps; ++step) {
    int m = 0;
    for (int i = 0; i < n; ++i) {
      s[i] = paths[i].next();
      lane_of[i] = -1;
      if (!touching[i] && s[i].delta < 0.0) continue;    // a gap: no contact, no lane
      lane_of[i] = m;
      set_lane(*b, m, s[i], paths[i].R, touching[i] ? h[i] : tycore::ContactHistory{});
      b->first_touch[m] = !touching[i];
      ++m;
    }
    *scalar = *b;
    if (adhesive) {
      advance<true>(*scalar, m, k, p, Isa::scalar);
      advance<true>(*b, m, k, p, isa);
    } else {
      advance<false>(*scalar, m, k, p, Isa::scalar);
      advance<false>(*b, m, k, p, isa);
    }
    for (int i = 0; i < n; ++i) {
      const int lane = lane_of[i];
      if (lane < 0) continue;
      SCOPED_TRACE(::testing::Message() << tycore::isa_name(isa) << " path " << i << " lane "
                                        << lane << " step " << step);
      expect_bitwise_lane(*b, *scalar, lane);
      if (::testing::Test::HasFatalFailure()) return;
      digest_add(sum, &b->P[lane], 1);
      digest_add(sum, &b->dissipation[lane], 1);
      digest_add(sum, &b->break_energy[lane], 1);
      if (b->broken[lane] != 0.0) {    // forgotten: history cleared, no force
        const tycore::ContactHistory gone = tycore::stored_history(*b, lane);
        for (int q = 0; q < tycore::history_size; ++q) ASSERT_EQ((&gone.T[0])[q], 0.0);
        for (int d = 0; d < 3; ++d) ASSERT_EQ(b->force[d][lane], 0.0);
        // the energy lost: the tangential energy and, with adhesion, the JKR energy at a_f
        const double W = adhesive ? tycore::jkr::separation_work(paths[i].R, k.c.E_star, k.c.Gamma)
                                  : 0.0;
        ASSERT_NEAR(b->break_energy[lane], h[i].stored_energy + W,
                    1e-12 * (h[i].stored_energy + W));
        ++seen[i].breaks;
        touching[i] = false;
        continue;
      }
      tycore::ContactHistory before = h[i];
      if (!touching[i]) {    // snap-in: the history begin_contact gives at the closed-form radius
        const double a = adhesive ? tycore::jkr::contact_radius(s[i].delta, paths[i].R, k.c.E_star, k.c.Gamma)
                                  : std::sqrt(paths[i].R * s[i].delta);
        tycore::begin_contact(before, adhesive);
        before.radius = a;
        ++seen[i].snap_ins;
      }
      h[i] = before;
      expect_bitwise_scalar_kernel(k, paths[i], s[i], before, *b, lane);
      if (::testing::Test::HasFatalFailure()) return;
      h[i] = tycore::stored_history(*b, lane);
      digest_add(sum, &h[i].T[0], tycore::history_size);
      contact_paths::expect_law_holds(paths[i], s[i], b->P[lane], before, h[i],
                                      b->dissipation[lane], seen[i]);
      if (::testing::Test::HasFatalFailure()) return;
      touching[i] = true;
    }
  }
  if (digest) *digest = sum;
}

std::vector<RandomPath> paths_of(double mu, double Gamma, const std::vector<unsigned>& seeds,
                                 int breaking_from = batch_lanes)
{
  std::vector<RandomPath> paths;
  paths.reserve(seeds.size());
  for (int i = 0; i < static_cast<int>(seeds.size()); ++i)
    paths.emplace_back(mu, Gamma, seeds[i], i >= breaking_from);
  return paths;
}

// six paths (seeds first .. first + 5) in lanes 0-5, ten more (seeds first + 100 ...) in
// lanes 6-15, of which the last four (adhesive: reaching below delta_f) break and snap in
// again, eight times each
std::vector<unsigned> six_paths_and_ten_more(unsigned first)
{
  std::vector<unsigned> seeds;
  for (unsigned s = first; s < first + 6; ++s) seeds.push_back(s);
  for (unsigned s = first + 100; s < first + 110; ++s) seeds.push_back(s);
  return seeds;
}
constexpr int kFirstBreakingLane = 12;

// the digest of a path test's outputs, for tests/test_scalar_law_build.py: equal in every build
void print_digest(const char* test, Isa isa, std::uint64_t digest)
{
  std::printf("law trajectory digest %s %s %016" PRIx64 "\n", test, tycore::isa_name(isa), digest);
}

class BatchLaw : public ::testing::TestWithParam<Isa> {};

TEST_P(BatchLaw, EveryBuildAsTheScalarEntryWithAdhesion)
{
  std::vector<Visits> seen;
  std::uint64_t digest = 0;
  compare_batch_on_paths(GetParam(), paths_of(0.3, 0.6, six_paths_and_ten_more(1), kFirstBreakingLane),
                         20000, seen, &digest);
  if (HasFatalFailure()) return;
  print_digest("adhesive", GetParam(), digest);
  for (int i = 0; i < batch_lanes; ++i) {
    SCOPED_TRACE(::testing::Message() << "path " << i);
    contact_paths::expect_every_branch(seen[i], true);
    if (i >= kFirstBreakingLane) {
      EXPECT_GE(seen[i].breaks, 5);
      EXPECT_GE(seen[i].snap_ins, 5);
    } else {
      EXPECT_EQ(seen[i].breaks, 0);
    }
  }
}

TEST_P(BatchLaw, EveryBuildAsTheScalarEntryHertzMindlin)
{
  std::vector<Visits> seen;
  std::uint64_t digest = 0;
  compare_batch_on_paths(GetParam(), paths_of(0.3, 0.0, six_paths_and_ten_more(11)), 20000, seen,
                         &digest);
  if (HasFatalFailure()) return;
  print_digest("hertz", GetParam(), digest);
  for (int i = 0; i < batch_lanes; ++i) {
    SCOPED_TRACE(::testing::Message() << "path " << i);
    contact_paths::expect_every_branch(seen[i], false);
    EXPECT_GE(seen[i].breaks, 5);    // a Hertz contact separates at delta < 0
    EXPECT_GE(seen[i].snap_ins, 5);
  }
}

TEST_P(BatchLaw, EveryBuildAsTheScalarEntryFrictionless)
{
  std::vector<unsigned> seeds = {21};
  for (unsigned s = 121; s < 128; ++s) seeds.push_back(s);    // 8 lanes, one partial register
  std::vector<Visits> seen;
  std::uint64_t digest = 0;
  compare_batch_on_paths(GetParam(), paths_of(0.0, 0.6, seeds, 6), 5000, seen, &digest);
  if (HasFatalFailure()) return;
  print_digest("frictionless", GetParam(), digest);
  EXPECT_EQ(seen[0].sliding, 5000);    // mu = 0: every step slides, T = 0
  EXPECT_GE(seen[7].breaks, 1);
}

// mu = 0 without adhesion: the dense specimen's preparation (a batch of the frictionless
// law_stage in the vector builds)
TEST_P(BatchLaw, EveryBuildAsTheScalarEntryFrictionlessHertz)
{
  std::vector<unsigned> seeds;
  for (unsigned s = 31; s < 47; ++s) seeds.push_back(s);
  std::vector<Visits> seen;
  std::uint64_t digest = 0;
  compare_batch_on_paths(GetParam(), paths_of(0.0, 0.0, seeds), 5000, seen, &digest);
  if (HasFatalFailure()) return;
  print_digest("frictionless-hertz", GetParam(), digest);
}

// A contact whose mu has just become 0 (fix adapt) while it carries a tangential force T and a
// stored energy E: the step clears T and its memory, marks the contact sliding and dissipates
// E + T.ds/2, the work of T over the step (docs/theory.md §2.3, §2.4); the same to the bit as
// the scalar kernel, with and without adhesion.
TEST_P(BatchLaw, FrictionlessStepReleasesTheStoredEnergy)
{
  using namespace glass_pair;
  for (const double Gamma : {0.6, 0.0}) {
    SCOPED_TRACE(::testing::Message() << tycore::isa_name(GetParam()) << " Gamma " << Gamma);
    const double R = kRstar, delta = 1e-3 * R;
    const tycore::PairConstants k = tycore::pair_constants(coefficients(0.0, Gamma));
    const double a = Gamma > 0.0 ? tycore::jkr::contact_radius(delta, R, kEstar, Gamma)
                                 : std::sqrt(R * delta);
    const double P = tycore::jkr::normal_force(a, R, kEstar, Gamma);
    tycore::BatchParameters p;
    p.dt = kDt;
    auto b = std::make_unique<ContactBatch>();
    contact_paths::Step s{};
    s.n = Eigen::Vector3d(0.0, 0.0, 1.0);
    s.ds = Eigen::Vector3d(2.0e-9, -1.0e-9, 0.0);    // along T: T does positive work
    s.twist = 0.0;
    s.delta = delta;
    tycore::ContactHistory h;
    tycore::begin_contact(h, Gamma > 0.0);
    h.radius = a;
    h.T[0] = 1e-3 * P;
    h.T[1] = -2e-3 * P;
    h.stored_energy = 3e-15;
    set_lane(*b, 0, s, R, h);
    if (Gamma > 0.0) advance<true>(*b, 1, k, p, GetParam());
    else advance<false>(*b, 1, k, p, GetParam());

    const double work = 0.5 * (h.T[0] * s.ds.x() + h.T[1] * s.ds.y());
    ASSERT_GT(work, 0.0);
    EXPECT_DOUBLE_EQ(b->dissipation[0], h.stored_energy + work);
    EXPECT_EQ(b->sliding[0], 1.0);
    const tycore::ContactHistory after = tycore::stored_history(*b, 0);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(after.T[d], 0.0);
    EXPECT_EQ(after.stored_energy, 0.0);
    EXPECT_NEAR(b->P[0], P, 1e-12 * std::abs(P));
    RandomPath path(0.0, Gamma, 1);
    expect_bitwise_scalar_kernel(k, path, s, h, *b, 0);
  }
}

// the six named paths and ten random ones of a frictional adhesive pair (mu 0.3, Gamma 0.6)
std::vector<RandomPath> frictional_adhesive_paths(unsigned first_seed)
{
  return paths_of(0.3, 0.6, six_paths_and_ten_more(first_seed));
}

// Damping, tallies and energy on the adhesive paths, with relative velocities: the scalar
// build against the formulas, every vector build against the scalar build to the bit.
TEST_P(BatchLaw, DampingTalliesAndEnergyAsTheirFormulas)
{
  const Isa isa = GetParam();
  std::vector<RandomPath> paths = frictional_adhesive_paths(31);
  const int n = static_cast<int>(paths.size());
  const tycore::PairCoefficients& c = paths[0].c;
  const tycore::PairConstants k = tycore::pair_constants(c);
  tycore::BatchParameters p;
  p.dt = kDt;
  p.beta_n = 0.3;
  p.beta_t = 0.2;
  p.tally = p.energy = true;
  auto b = std::make_unique<ContactBatch>(), scalar = std::make_unique<ContactBatch>();
  std::vector<tycore::ContactHistory> h(n);
  for (int i = 0; i < n; ++i) h[i] = paths[i].first_touch();
  std::mt19937_64 rng(5);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double m_star = 0.5 * 2500.0 * 4.0 / 3.0 * glass_pair::kPi * std::pow(1e-4, 3);
  int micro_slip_lanes = 0;
  for (int step = 0; step < 3000; ++step) {
    for (int i = 0; i < n; ++i) {
      const contact_paths::Step s = paths[i].next();
      set_lane(*b, i, s, paths[i].R, h[i]);
      b->vn[i] = 1e-3 * gauss(rng);
      b->m_star[i] = m_star;
      b->rsq[i] = std::pow(2e-4 - s.delta, 2);
    }
    *scalar = *b;
    tycore::advance_batch<true, true>(*scalar, n, k, p, Isa::scalar);
    tycore::advance_batch<true, true>(*b, n, k, p, isa);
    for (int i = 0; i < n; ++i) {
      SCOPED_TRACE(::testing::Message() << tycore::isa_name(isa) << " lane " << i << " step "
                                        << step);
      const double a = scalar->contact_radius[i], P = scalar->P[i], R = scalar->R[i];
      const double n_[3] = {scalar->n[0][i], scalar->n[1][i], scalar->n[2][i]};
      const double vt[3] = {scalar->vt[0][i], scalar->vt[1][i], scalar->vt[2][i]};
      const double vn = scalar->vn[i];
      const tycore::ContactHistory g = tycore::stored_history(*scalar, i);
      // eta = 2 beta sqrt(m* k), k = 2E*a normal, 8G*a tangential
      const double eta_n = 2.0 * p.beta_n * std::sqrt(m_star * 2.0 * c.E_star * a);
      const double eta_t = 2.0 * p.beta_t * std::sqrt(m_star * 8.0 * c.G_star * a);
      const double Fn = P - eta_n * vn;
      double F[3], Ft[3], F2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        Ft[d] = g.T[d] - eta_t * vt[d];
        F[d] = n_[d] * Fn + Ft[d];
        F2 += F[d] * F[d];
        ASSERT_NEAR(scalar->force[d][i], F[d], 1e-13 * std::sqrt(F2) + 1e-30);
      }
      const double tol = 1e-13 * (std::abs(P) + paths[i].Pc);
      ASSERT_NEAR(scalar->moment[0][i], n_[1] * Ft[2] - n_[2] * Ft[1], tol);
      const double vt2 = vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2];
      const double damping = kDt * (eta_n * vn * vn + eta_t * vt2);
      ASSERT_NEAR(scalar->damping_dissipation[i], damping, 1e-13 * damping);
      ASSERT_NEAR(scalar->force_magnitude[i], std::sqrt(F2), 1e-13 * std::sqrt(F2));
      // affine stiffness l^2 [k_N n_a^2 n_b^2 + k_T (d_ab n_a^2 - n_a^2 n_b^2)] (§6.1),
      // k_N = dP/d(delta); k_T = 8G* a_T, a_T^3 = 3R*(P + 2Pc)/(4E*), where the contact was
      // not peeling before the step (a peeled step's k_T has the Savkoor-Briggs radius)
      const double k_N = tycore::jkr::normal_stiffness(a, R, c.E_star, c.Gamma);
      const double k_T =
          8.0 * c.G_star * std::cbrt(3.0 * R * (P + 2.0 * paths[i].Pc) / (4.0 * c.E_star));
      const int ia[6] = {0, 1, 2, 0, 0, 1}, ib[6] = {0, 1, 2, 1, 2, 2};
      if (h[i].peeling == 0.0) {
        ++micro_slip_lanes;
        for (int m = 0; m < 6; ++m) {
          const double na2 = n_[ia[m]] * n_[ia[m]], nn = na2 * n_[ib[m]] * n_[ib[m]];
          const double l2 = scalar->rsq[i];
          ASSERT_NEAR(scalar->affine_stiffness[m][i],
                      l2 * (k_N * nn + k_T * ((m < 3 ? na2 : 0.0) - nn)),
                      1e-12 * l2 * (std::abs(k_N) + k_T));
        }
      }
      ASSERT_NEAR(scalar->energy[i], tycore::contact_stored_energy(c, R, a, P, g),
                  1e-12 * std::abs(scalar->energy[i]) + 1e-30);
      // the vector build: the same to the last bit
      ASSERT_EQ(b->P[i], scalar->P[i]);
      ASSERT_EQ(b->contact_radius[i], scalar->contact_radius[i]);
      ASSERT_EQ(b->dissipation[i], scalar->dissipation[i]);
      ASSERT_EQ(b->damping_dissipation[i], scalar->damping_dissipation[i]);
      ASSERT_EQ(b->force_magnitude[i], scalar->force_magnitude[i]);
      ASSERT_EQ(b->energy[i], scalar->energy[i]);
      for (int d = 0; d < 3; ++d) {
        ASSERT_EQ(b->force[d][i], scalar->force[d][i]);
        ASSERT_EQ(b->moment[d][i], scalar->moment[d][i]);
      }
      for (int m = 0; m < 6; ++m) ASSERT_EQ(b->affine_stiffness[m][i], scalar->affine_stiffness[m][i]);
      ASSERT_EQ(b->normal_stiffness[i], scalar->normal_stiffness[i]);
      ASSERT_EQ(b->tangential_stiffness[i], scalar->tangential_stiffness[i]);
      const tycore::ContactHistory v = tycore::stored_history(*b, i);
      for (int m = 0; m < tycore::history_size; ++m) ASSERT_EQ((&v.T[0])[m], (&g.T[0])[m]);
      h[i] = g;
    }
  }
  EXPECT_GT(micro_slip_lanes, 1000);
}

// A cell with shears (docs/theory.md §11.1): the pair tallies a contact's 21 affine-stiffness
// entries as the batch's 6 principal ones and AffineStiffnessSums::shear_entries from the
// batch's k_N and k_T lanes (pair_thornton_yin.cpp, compute_cell_tally.cpp). These are
// AffineStiffnessSums::add_contact's for the contact (one formula, affine_stiffness_entries.hpp;
// to round-off, since add_contact takes the normal from the branch vector); and k_N, k_T
// are those of the law, dP/d(delta) and 8G* a_T, where the contact was not peeling. Each lane
// has its own branch length and its normal from the path; the steps and the setup pass.
TEST_P(BatchLaw, ShearedCellTallyIsTheAffineStiffnessSums)
{
  const Isa isa = GetParam();
  std::vector<RandomPath> paths = frictional_adhesive_paths(51);
  const int n = static_cast<int>(paths.size());
  const tycore::PairCoefficients& c = paths[0].c;
  const tycore::PairConstants k = tycore::pair_constants(c);
  tycore::BatchParameters p;
  p.dt = kDt;
  p.tally = true;
  auto b = std::make_unique<ContactBatch>();
  std::vector<tycore::ContactHistory> h(n);
  for (int i = 0; i < n; ++i) h[i] = paths[i].first_touch();
  using Sums = tycore::AffineStiffnessSums;
  int checked = 0;
  for (int step = 0; step < 400; ++step) {
    std::vector<Eigen::Vector3d> branch(n);
    for (int i = 0; i < n; ++i) {
      const contact_paths::Step s = paths[i].next();
      set_lane(*b, i, s, paths[i].R, h[i]);
      branch[i] = (2e-4 * (1.0 + 0.05 * i) - s.delta) * s.n;    // x_i - x_j, along n
      b->rsq[i] = branch[i].squaredNorm();
    }
    const bool setup = step % 50 == 7;    // now and then the setup pass (k_T not the law's)
    if (setup) tycore::forces_without_step<true, false>(*b, n, k, p);
    else tycore::advance_batch<true, false>(*b, n, k, p, isa);
    for (int i = 0; i < n; ++i) {
      SCOPED_TRACE(::testing::Message() << tycore::isa_name(isa) << " lane " << i << " step "
                                        << step << (setup ? " (setup)" : ""));
      if (b->broken[i] != 0.0) {
        h[i] = tycore::stored_history(*b, i);
        continue;
      }
      const double k_N = b->normal_stiffness[i], k_T = b->tangential_stiffness[i];
      const double a = b->contact_radius[i], P = b->P[i], R = b->R[i];
      ASSERT_NEAR(k_N, tycore::jkr::normal_stiffness(a, R, c.E_star, c.Gamma),
                  1e-12 * std::abs(k_N));
      if (h[i].peeling == 0.0 || setup) {
        const double a_T = std::cbrt(3.0 * R * (P + 2.0 * paths[i].Pc) / (4.0 * c.E_star));
        ASSERT_NEAR(k_T, 8.0 * c.G_star * a_T, 1e-12 * k_T);
      }
      // the pair's 21 entries of this contact
      Sums pair;
      for (int m = 0; m < Sums::principal_size; ++m) pair.sum[m] = b->affine_stiffness[m][i];
      // the pair's shear entries: from the lane's normal and |branch|^2 (pair_thornton_yin.cpp)
      tycore::affine_shear_entries(b->n[0][i], b->n[1][i], b->n[2][i], b->rsq[i], k_N, k_T,
                                   [&](int m, double v) { pair.sum[Sums::principal_size + m] = v; });
      Sums expected;
      expected.add_contact(branch[i], k_N, k_T);
      const double scale = b->rsq[i] * (std::abs(k_N) + k_T);
      for (int m = 0; m < Sums::principal_size; ++m)
        ASSERT_NEAR(pair.sum[m], expected.sum[m], 1e-14 * scale) << "entry " << m;
      for (int m = Sums::principal_size; m < Sums::size; ++m)
        ASSERT_NEAR(pair.sum[m], expected.sum[m], 1e-14 * scale) << "entry " << m;
      ++checked;
      if (!setup) h[i] = tycore::stored_history(*b, i);
    }
  }
  EXPECT_GT(checked, 4000);
}

// First touch (JKR snap-on: begin_contact at the closed-form radius, docs/theory.md §1.3) and
// separation below the break overlap delta_f (§1.2): the contact is forgotten, its tangential
// energy and the JKR energy at a_f, W = U(a_f) (§3.2), are lost.
TEST_P(BatchLaw, FirstTouchAndSeparation)
{
  using namespace glass_pair;
  const Isa isa = GetParam();
  const double Gamma = 0.6, R = kRstar;
  const tycore::PairCoefficients c = coefficients(0.3, Gamma);
  const tycore::PairConstants k = tycore::pair_constants(c);
  const double delta_f = tycore::jkr::break_overlap(R, kEstar, Gamma);
  tycore::BatchParameters p;
  p.dt = kDt;
  auto b = std::make_unique<ContactBatch>();
  contact_paths::Step s{};
  s.n = Eigen::Vector3d(0.0, 0.0, 1.0);
  s.ds = Eigen::Vector3d::Zero();
  s.twist = 0.0;
  // lane 0: first touch at delta > 0, no tangential motion
  s.delta = 1e-3 * R;
  set_lane(*b, 0, s, R, tycore::ContactHistory{});
  b->first_touch[0] = true;
  // lane 1: a contact with stored tangential energy, pulled below delta_f
  tycore::ContactHistory stretched;
  tycore::begin_contact(stretched, true);
  stretched.T[0] = 1e-6;
  stretched.stored_energy = 3e-15;
  stretched.radius = tycore::jkr::contact_radius(0.5 * delta_f, R, kEstar, Gamma);
  s.delta = 1.01 * delta_f;
  set_lane(*b, 1, s, R, stretched);
  // lane 2: just above delta_f, stays in contact
  s.delta = 0.99 * delta_f;
  set_lane(*b, 2, s, R, stretched);
  tycore::advance_batch<true, false>(*b, 3, k, p, isa);

  const double a_touch = tycore::jkr::contact_radius(1e-3 * R, R, kEstar, Gamma);
  EXPECT_NEAR(b->contact_radius[0], a_touch, 1e-12 * a_touch);
  const double P_touch = tycore::jkr::normal_force(a_touch, R, kEstar, Gamma);
  EXPECT_NEAR(b->P[0], P_touch, 1e-12 * std::abs(P_touch));
  EXPECT_EQ(b->peeling[0], 1.0);
  EXPECT_EQ(b->T[0][0], 0.0);
  EXPECT_EQ(b->dissipation[0], 0.0);
  EXPECT_EQ(b->broken[0], 0.0);

  EXPECT_EQ(b->broken[1], 1.0);
  const double W = tycore::jkr::separation_work(R, kEstar, Gamma);
  EXPECT_NEAR(b->break_energy[1], W + 3e-15, 1e-9 * W);
  const tycore::ContactHistory gone = tycore::stored_history(*b, 1);
  for (int m = 0; m < tycore::history_size; ++m) EXPECT_EQ((&gone.T[0])[m], 0.0);
  for (int d = 0; d < 3; ++d) EXPECT_EQ(b->force[d][1], 0.0);
  EXPECT_EQ(b->P[1], 0.0);

  EXPECT_EQ(b->broken[2], 0.0);
  EXPECT_EQ(b->break_energy[2], 0.0);
  EXPECT_LT(b->P[2], 0.0);    // tensile, near the break
  EXPECT_GT(b->contact_radius[2], tycore::jkr::break_radius(R, kEstar, Gamma));
}

// The setup pass (tycore::forces_without_step): forces at the overlap with the history kept,
// sliding judged against the Coulomb limit mu (P + 2Pc) of the mu in force (docs/theory.md §2),
// nothing dissipated, a contact below delta_f forgotten without booking a break energy
TEST(BatchForcesWithoutStep, ForcesAtTheOverlapHistoryKept)
{
  using namespace glass_pair;
  const double Gamma = 0.6, R = kRstar, mu = 0.3;
  const tycore::PairConstants k = tycore::pair_constants(coefficients(mu, Gamma));
  const double delta = 1e-3 * R, delta_f = tycore::jkr::break_overlap(R, kEstar, Gamma);
  const double a = tycore::jkr::contact_radius(delta, R, kEstar, Gamma);
  const double P = tycore::jkr::normal_force(a, R, kEstar, Gamma);
  const double limit = mu * (P + 2.0 * tycore::jkr::pull_off_force(Gamma, R));
  tycore::BatchParameters p;
  p.dt = kDt;
  p.beta_n = 0.2;
  p.beta_t = 0.1;
  auto b = std::make_unique<ContactBatch>();
  contact_paths::Step s{};
  s.n = Eigen::Vector3d(0.0, 0.0, 1.0);
  s.ds = Eigen::Vector3d(-2.0e-9, 0.0, 0.0);    // vt = (1e-9, 0, 0)
  s.twist = 0.0;
  s.delta = delta;
  tycore::ContactHistory h[3];
  for (int lane = 0; lane < 3; ++lane) {
    tycore::begin_contact(h[lane], true);
    h[lane].peeling = 0.0;
    h[lane].radius = 1.01 * a;    // a warm start near the answer
    h[lane].stored_energy = 1e-15;
  }
  h[0].T[0] = 0.5 * limit;    // inside the limit
  h[1].T[0] = 1.5 * limit;    // beyond it (a smaller mu since the last step)
  for (int lane = 0; lane < 3; ++lane) {
    set_lane(*b, lane, s, R, h[lane]);
    b->m_star[lane] = 1e-9;
    b->vn[lane] = -1e-6;
  }
  b->delta[2] = 1.01 * delta_f;    // below the break overlap
  tycore::forces_without_step<true, true>(*b, 3, k, p);

  for (int lane = 0; lane < 2; ++lane) {
    EXPECT_NEAR(b->contact_radius[lane], a, 1e-13 * a);
    EXPECT_NEAR(b->P[lane], P, 1e-12 * P);
    const tycore::ContactHistory kept = tycore::stored_history(*b, lane);
    for (int m = 0; m < tycore::history_size; ++m)
      EXPECT_EQ((&kept.T[0])[m], (&h[lane].T[0])[m]) << "lane " << lane << " history " << m;
    EXPECT_EQ(b->dissipation[lane], 0.0);
    EXPECT_EQ(b->damping_dissipation[lane], 0.0);
    EXPECT_EQ(b->break_energy[lane], 0.0);
    // the applied force: P - eta_n vn along n, T - eta_t vt in the plane (damping as a step)
    const double eta_n = 2.0 * 0.2 * std::sqrt(1e-9 * 2.0 * kEstar * b->contact_radius[lane]);
    const double eta_t = 2.0 * 0.1 * std::sqrt(1e-9 * 8.0 * kGstar * b->contact_radius[lane]);
    double Fn, fs[3];
    tycore::force_parts<true>(*b, lane, k.c, p, Fn, fs);
    EXPECT_NEAR(Fn, P + eta_n * 1e-6, 1e-12 * P);
    EXPECT_NEAR(fs[0], h[lane].T[0] - eta_t * 1e-9, 1e-12 * h[lane].T[0]);
    EXPECT_EQ(b->force[2][lane], Fn);
    EXPECT_EQ(b->force[0][lane], fs[0]);
  }
  EXPECT_EQ(b->slides[0], 0.0);
  EXPECT_EQ(b->slides[1], 1.0);
  EXPECT_EQ(b->broken[2], 1.0);
  EXPECT_EQ(b->break_energy[2], 0.0);    // no step: no energy booked
  for (int d = 0; d < 3; ++d) EXPECT_EQ(b->force[d][2], 0.0);
}

// A contact found in the setup pass (first touch, no step: spheres that overlap when a run
// begins) is pressed to its overlap without tangential displacement (docs/theory.md §1.3): the
// run's first step is Mindlin-Deresiewicz's first loading at constant P from there (§2.1),
// T = mu P [1 - (1 - s/s_c)^(3/2)] with s_c = 3 mu P/(16 G* a), of initial stiffness 8 G* a.
// A contact that touches within the step takes its whole overlap as entering with the step's
// displacement (§2.3, operation 1): a band of slope s/(kappa delta), T = (2/3) 8 G* a s.
TEST_P(BatchLaw, ContactFoundInSetupIsPressedWithoutTangentialDisplacement)
{
  using namespace glass_pair;
  const Isa isa = GetParam();
  const double R = kRstar, mu = 0.3, delta = 1e-4 * R;
  const tycore::PairConstants k = tycore::pair_constants(coefficients(mu, 0.0));
  tycore::BatchParameters p;
  p.dt = kDt;
  auto b = std::make_unique<ContactBatch>();
  contact_paths::Step s{};
  s.n = Eigen::Vector3d(0.0, 0.0, 1.0);
  s.ds = Eigen::Vector3d::Zero();
  s.twist = 0.0;
  s.delta = delta;
  set_lane(*b, 0, s, R, tycore::ContactHistory{});
  b->first_touch[0] = true;
  tycore::forces_without_step<false, false>(*b, 1, k, p);
  const double a = std::sqrt(R * delta), P = 4.0 / 3.0 * kEstar * a * delta;    // Hertz
  EXPECT_NEAR(b->P[0], P, 1e-12 * P);
  for (int d = 0; d < 3; ++d) EXPECT_EQ(b->force[d][0], d == 2 ? b->P[0] : 0.0);
  EXPECT_EQ(b->dissipation[0], 0.0);
  EXPECT_EQ(b->energy[0], 0.0);

  const double s_c = 3.0 * mu * P / (16.0 * kGstar * a), step = 1e-3 * s_c;
  s.ds = Eigen::Vector3d(step, 0.0, 0.0);
  set_lane(*b, 0, s, R, tycore::stored_history(*b, 0));
  set_lane(*b, 1, s, R, tycore::ContactHistory{});
  b->first_touch[1] = true;
  tycore::advance_batch<false, false>(*b, 2, k, p, isa);
  const double first_loading = -mu * P * std::expm1(1.5 * std::log1p(-step / s_c));
  EXPECT_NEAR(b->T[0][0], first_loading, 1e-9 * first_loading);
  EXPECT_NEAR(b->T[0][0], 8.0 * kGstar * a * step, 1e-3 * first_loading);    // bend: 2.5e-4
  const double entering = 2.0 / 3.0 * 8.0 * kGstar * a * step;
  EXPECT_NEAR(b->T[0][1], entering, 1e-9 * entering);
}

INSTANTIATE_TEST_SUITE_P(EveryIsaOfThisProcessor, BatchLaw, ::testing::ValuesIn(supported_isas()),
                         [](const ::testing::TestParamInfo<Isa>& info) {
                           return std::string(tycore::isa_name(info.param));
                         });

TEST(BatchDispatch, ChoosesTheWidestBuildThisProcessorRuns)
{
  const std::vector<Isa> isas = supported_isas();
  EXPECT_TRUE(tycore::isa_supported(tycore::best_isa()));
#ifdef TYCORE_SCALAR_LAW
  EXPECT_EQ(tycore::best_isa(), Isa::scalar);    // -DTYLMP_VECTOR_LAW=OFF
#else
  EXPECT_EQ(tycore::best_isa(), isas.back());
#endif
  std::printf("builds run by this processor:");
  for (Isa isa : isas) std::printf(" %s", tycore::isa_name(isa));
  std::printf("; advance_batch uses %s\n", tycore::isa_name(tycore::best_isa()));
}

// the lane-wide cube root: bit for bit jkr::fast_cbrt on zero and positive normal numbers,
// within 1e-15 of std::cbrt on subnormals, +inf to +inf, in every build
TEST(SimdCbrt, BitForBitFastCbrtInEveryBuild)
{
  std::mt19937_64 gen(12345);
  std::uniform_real_distribution<double> exponent(-307.0, 307.0), unit(0.0, 1.0);
  constexpr int n = 1 << 16;
  std::vector<double> x(n), y(n);
  for (int i = 0; i < n; ++i) x[i] = i % 2 ? std::pow(10.0, exponent(gen)) : unit(gen);
  x[0] = 0.0;
  x[1] = std::numeric_limits<double>::min();
  x[2] = 1e307;
  x[3] = 1.0;
  // near the largest double, where 2 y^3 of the Halley steps overflowed (both scale x down)
  x[4] = std::numeric_limits<double>::max();
  x[5] = std::nextafter(0x1p1020, 0.0);
  x[6] = 0x1p1020;
  x[7] = 0.6 * std::numeric_limits<double>::max();
  for (Isa isa : supported_isas()) {
    tytests::cube_roots(x.data(), y.data(), n, isa);
    for (int i = 0; i < n; ++i)
      ASSERT_EQ(y[i], tycore::jkr::fast_cbrt(x[i])) << tycore::isa_name(isa) << " x = " << x[i];
    for (int i = 4; i < 8; ++i)
      EXPECT_NEAR(y[i], std::cbrt(x[i]), 1e-15 * std::cbrt(x[i])) << tycore::isa_name(isa);
    std::vector<double> special = {std::numeric_limits<double>::denorm_min(),
                                   1e3 * std::numeric_limits<double>::denorm_min(), 1e-310,
                                   std::numeric_limits<double>::infinity()};
    std::vector<double> root(special.size());
    tytests::cube_roots(special.data(), root.data(), static_cast<int>(special.size()), isa);
    for (std::size_t i = 0; i + 1 < special.size(); ++i)
      EXPECT_NEAR(root[i], std::cbrt(special[i]), 1e-15 * std::cbrt(special[i]));
    EXPECT_EQ(root.back(), std::numeric_limits<double>::infinity());
  }
}

TEST(SimdCbrt, DivisionByThreeOfTheBits)
{
  std::mt19937_64 gen(7);
  for (int i = 0; i < 1000000; ++i) {
    const std::uint64_t b = gen() >> 1;
    ASSERT_EQ(tycore::detail::divide_by_3(b), b / 3) << b;
  }
  for (std::uint64_t b : {0ull, 1ull, 2ull, 3ull, (1ull << 63) - 1, (1ull << 63) - 2})
    EXPECT_EQ(tycore::detail::divide_by_3(b), b / 3);
}

}    // namespace
