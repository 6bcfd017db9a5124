// The law's inputs from the spheres' data (contact_geometry.hpp): gather_contact and
// contact_geometry lane by lane, batch_geometry over a batch in every build this processor
// runs. Against an independent calculation with Eigen of docs/theory.md §5.1: the unit normal
// from j to i, the overlap, R* and 1/R*, the relative velocity of i to j at the contact point
// (contact point at -(r_i - delta/2) n from i and +(r_j - delta/2) n from j, so that the
// spins add n x (l_i w_i + l_j w_j)), its normal and tangential parts, the twist rate
// (w_i + w_j).n, m*, and a deforming cell's affine velocity L (x_i - x_j); and every build
// against the scalar build to the last bit; and the overlap check that comes with it (an
// overlap beyond the smaller radius, or not finite, in a lane in use).
#include "contact_geometry.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using tycore::ContactBatch;
using tycore::Isa;
using tycore::batch_lanes;

struct Sphere {
  Eigen::Vector3d x, v, w;
  double r, m;
};

struct Contact {
  Sphere i, j;
};

// touching spheres with random radii (polydisperse, ratio up to 3), overlaps up to 1 % of the
// smaller radius, velocities and spins of the order of a granular flow's
Contact random_contact(std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0), radius(0.05e-3, 0.15e-3);
  Contact c;
  c.i.r = radius(rng), c.j.r = radius(rng);
  Eigen::Vector3d n(u(rng), u(rng), u(rng));
  n.normalize();
  const double overlap = 0.01 * std::min(c.i.r, c.j.r) * (0.5 + 0.5 * u(rng));
  c.j.x = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1e-3;
  c.i.x = c.j.x + (c.i.r + c.j.r - overlap) * n;
  for (Sphere* s : {&c.i, &c.j}) {
    s->v = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1e-2;
    s->w = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1e2;
    s->m = 2650.0 * 4.0 / 3.0 * M_PI * std::pow(s->r, 3);
  }
  return c;
}

void gather(ContactBatch& b, int l, const Contact& c)
{
  const Eigen::Vector3d del = c.i.x - c.j.x;
  const tycore::SphereState si{c.i.v.data(), c.i.w.data(), c.i.r, c.i.m};
  const tycore::SphereState sj{c.j.v.data(), c.j.w.data(), c.j.r, c.j.m};
  tycore::gather_contact<true>(b, l, del.data(), del.squaredNorm(), si, sj, false);
}

tycore::AffineGradient random_gradient(std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  tycore::AffineGradient g{};
  for (int a = 0; a < 3; ++a)
    for (int c = a; c < 3; ++c) g.L[a][c] = 1e-2 * u(rng);    // upper triangular, as LAMMPS's box
  return g;
}

template <bool Affine>
void run_geometry(ContactBatch& b, int n, const tycore::AffineGradient& g, Isa isa)
{
  tycore::batch_geometry<Affine, true>(b, n, g, isa);
}

std::vector<Isa> supported_isas()
{
  std::vector<Isa> isas;
  for (Isa isa : {Isa::scalar, Isa::sse2, Isa::avx2, Isa::avx512})
    if (tycore::isa_supported(isa)) isas.push_back(isa);
  return isas;
}

// docs/theory.md §5.1 with Eigen, for lane l of b
void expect_geometry(const ContactBatch& b, int l, const Contact& c,
                     const tycore::AffineGradient* g)
{
  const Eigen::Vector3d del = c.i.x - c.j.x;
  const double dist = del.norm();
  const Eigen::Vector3d n = del / dist;
  const double delta = c.i.r + c.j.r - dist;
  const double R = c.i.r * c.j.r / (c.i.r + c.j.r);
  Eigen::Vector3d v = c.i.v - c.j.v;
  if (g) {
    Eigen::Matrix3d L;
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 3; ++k) L(a, k) = g->L[a][k];
    v += L * del;
  }
  // contact point velocities: v_i + w_i x (-l_i n), v_j + w_j x (l_j n)
  const double l_i = c.i.r - 0.5 * delta, l_j = c.j.r - 0.5 * delta;
  const Eigen::Vector3d v_contact = v + c.i.w.cross(-l_i * n) - c.j.w.cross(l_j * n);
  const Eigen::Vector3d vt = v_contact - v_contact.dot(n) * n;
  const double tol = 1e-12;
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(b.n[d][l], n(d), tol);
  EXPECT_NEAR(b.delta[l], delta, 1e-9 * delta);
  EXPECT_NEAR(b.R[l], R, 1e-14 * R);
  EXPECT_NEAR(b.Rinv[l], 1.0 / R, 1e-14 / R);
  EXPECT_NEAR(b.vn[l], v_contact.dot(n), 1e-12 * v_contact.norm());
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(b.vt[d][l], vt(d), 1e-12 * v_contact.norm());
  const double spin = (c.i.w + c.j.w).dot(n);
  EXPECT_NEAR(b.spin_n[l], spin, 1e-12 * (c.i.w.norm() + c.j.w.norm()));
  const double m_star = c.i.m * c.j.m / (c.i.m + c.j.m);
  EXPECT_NEAR(b.m_star[l], m_star, 1e-14 * m_star);
}

TEST(ContactGeometry, AgreesWithTheIndependentCalculation)
{
  std::mt19937_64 rng(20261204);
  for (bool affine : {false, true}) {
    const tycore::AffineGradient g = random_gradient(rng);
    for (int trial = 0; trial < 50; ++trial) {
      ContactBatch b{};
      std::vector<Contact> contacts;
      for (int l = 0; l < batch_lanes; ++l) {
        contacts.push_back(random_contact(rng));
        gather(b, l, contacts.back());
      }
      if (affine) run_geometry<true>(b, batch_lanes, g, Isa::scalar);
      else run_geometry<false>(b, batch_lanes, g, Isa::scalar);
      for (int l = 0; l < batch_lanes; ++l)
        expect_geometry(b, l, contacts[l], affine ? &g : nullptr);
    }
  }
}

// a mistake in the affine part alone (e.g. a lower-triangular L) would pass the test above
// only if L were symmetric: check that the affine velocity is L (x_i - x_j), not its transpose
TEST(ContactGeometry, AffineVelocityIsTheGradientTimesTheBranch)
{
  ContactBatch b{};
  Contact c{};
  c.i = {Eigen::Vector3d(0.0, 1.5e-4, 0.0), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
         1e-4, 1e-8};
  c.j = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 1e-4, 1e-8};
  gather(b, 0, c);
  tycore::AffineGradient g{};
  g.L[0][1] = 2.0;    // simple shear in xy: v_x = 2 y; branch along y
  run_geometry<true>(b, 1, g, Isa::scalar);
  // n = (0, 1, 0), relative velocity (3e-4, 0, 0): all tangential
  EXPECT_DOUBLE_EQ(b.vn[0], 0.0);
  EXPECT_DOUBLE_EQ(b.vt[0][0], 3e-4);
  EXPECT_DOUBLE_EQ(b.vt[0][1], 0.0);
}

TEST(ContactGeometry, EveryBuildAgreesWithTheScalarBuildToTheLastBit)
{
  std::mt19937_64 rng(7);
  const tycore::AffineGradient g = random_gradient(rng);
  for (int trial = 0; trial < 20; ++trial) {
    ContactBatch scalar{};
    const int n = 1 + trial % batch_lanes;
    std::vector<Contact> contacts;
    for (int l = 0; l < n; ++l) {
      contacts.push_back(random_contact(rng));
      gather(scalar, l, contacts.back());
    }
    for (bool affine : {false, true})
      for (Isa isa : supported_isas()) {
        ContactBatch b = scalar, reference = scalar;
        if (affine) {
          run_geometry<true>(b, n, g, isa);
          run_geometry<true>(reference, n, g, Isa::scalar);
        } else {
          run_geometry<false>(b, n, g, isa);
          run_geometry<false>(reference, n, g, Isa::scalar);
        }
        for (int l = 0; l < n; ++l) {
          SCOPED_TRACE(tycore::isa_name(isa));
          for (int d = 0; d < 3; ++d) {
            ASSERT_EQ(b.n[d][l], reference.n[d][l]);
            ASSERT_EQ(b.vt[d][l], reference.vt[d][l]);
          }
          ASSERT_EQ(b.delta[l], reference.delta[l]);
          ASSERT_EQ(b.R[l], reference.R[l]);
          ASSERT_EQ(b.Rinv[l], reference.Rinv[l]);
          ASSERT_EQ(b.vn[l], reference.vn[l]);
          ASSERT_EQ(b.spin_n[l], reference.spin_n[l]);
          ASSERT_EQ(b.m_star[l], reference.m_star[l]);
        }
      }
  }
}

// A batch of valid contacts in lanes 0 .. n-1 and one out of the law's domain: in use (lane 2)
// or not (lane n), in every build.
TEST(ContactGeometry, OverlapCheckNamesLanesInUseOnly)
{
  std::mt19937_64 rng(11);
  const int n = 5;
  ContactBatch valid{};
  for (int l = 0; l < batch_lanes; ++l) gather(valid, l, random_contact(rng));
  const auto with_lane = [&](int lane, double scale, double shift) {
    ContactBatch b = valid;
    // x_i - x_j scaled: 0.3 brings the centres within the smaller radius (an overlap above it);
    // a shift of inf or NaN makes the distance infinite or NaN
    for (int d = 0; d < 3; ++d) b.del[d][lane] = b.del[d][lane] * scale + shift;
    b.rsq[lane] = b.del[0][lane] * b.del[0][lane] + b.del[1][lane] * b.del[1][lane] +
                  b.del[2][lane] * b.del[2][lane];
    return b;
  };
  const tycore::AffineGradient g{};
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(tycore::isa_name(isa));
    ContactBatch b = valid;
    EXPECT_TRUE((tycore::batch_geometry<false, false>(b, n, g, isa)));
    for (const auto& [scale, shift] : {std::pair{0.3, 0.0}, {1.0, inf}, {1.0, nan}}) {
      b = with_lane(2, scale, shift);
      EXPECT_FALSE((tycore::batch_geometry<false, false>(b, n, g, isa))) << scale << " " << shift;
      EXPECT_FALSE(tycore::overlap_valid(b, 2));
      b = with_lane(n, scale, shift);    // a lane not in use: ignored
      EXPECT_TRUE((tycore::batch_geometry<false, false>(b, n, g, isa))) << scale << " " << shift;
    }
  }
}

// The bound is the SMALLER radius (contact_geometry.hpp, overlap_valid): with unlike radii
// r_small = 0.1 mm and r_large = 0.3 mm, an overlap between the two (0.15, 0.2, 0.29 mm) is out
// of the law's domain, whichever sphere of the pair is the small one, in every build; overlaps
// just below r_small (and the small ones of a packing) are in it. A check against the larger
// radius, or the sum, would pass the overlaps between the radii.
TEST(ContactGeometry, OverlapBetweenTheSmallerAndTheLargerRadiusIsRejected)
{
  constexpr double r_small = 0.1e-3, r_large = 0.3e-3;
  const Eigen::Vector3d n = Eigen::Vector3d(1.0, 2.0, -2.0) / 3.0;
  const auto pair_with_overlap = [&](double overlap, bool i_is_small) {
    Contact c;
    c.i.r = i_is_small ? r_small : r_large;
    c.j.r = i_is_small ? r_large : r_small;
    c.j.x = Eigen::Vector3d(0.2e-3, -0.1e-3, 0.3e-3);
    c.i.x = c.j.x + (c.i.r + c.j.r - overlap) * n;
    for (Sphere* s : {&c.i, &c.j}) {
      s->v = s->w = Eigen::Vector3d::Zero();
      s->m = 2650.0 * 4.0 / 3.0 * M_PI * std::pow(s->r, 3);
    }
    return c;
  };
  const tycore::AffineGradient g{};
  for (const bool i_is_small : {true, false})
    for (const auto& [overlap, valid] :
         {std::pair{1e-6, true}, {0.99 * r_small, true}, {1.5 * r_small, false},
          {2.0 * r_small, false}, {0.97 * r_large, false}}) {
      SCOPED_TRACE(std::to_string(overlap) + (i_is_small ? " i small" : " j small"));
      ASSERT_GT(overlap, 0.0);
      ASSERT_EQ(valid, overlap < r_small);    // the cases: below r_small, or between the radii
      ASSERT_LT(overlap, r_large);
      for (Isa isa : supported_isas()) {
        SCOPED_TRACE(tycore::isa_name(isa));
        ContactBatch b{};
        for (int l = 0; l < batch_lanes; ++l) gather(b, l, pair_with_overlap(1e-6, true));
        gather(b, 1, pair_with_overlap(overlap, i_is_small));
        EXPECT_EQ((tycore::batch_geometry<false, false>(b, 3, g, isa)), valid);
        EXPECT_NEAR(b.delta[1], overlap, 1e-12 * r_large);
        EXPECT_EQ(tycore::overlap_valid(b, 1), valid);
      }
    }
}

}    // namespace
