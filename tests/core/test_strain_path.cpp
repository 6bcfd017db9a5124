#include "strain_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using Eigen::Vector2d;
using Eigen::Vector3d;
using tycore::DeviatoricStrainMeasure;
using tycore::PiPath;
using tycore::Rotation;

namespace {

// integrate the follower exactly as the fix does (natural strain += rate dt) and record every
// state; the isotropic part of the strain is irrelevant to the Pi-plane and is left at zero
struct Trace {
  std::vector<Vector3d> strain, rate;
  std::vector<double> progress;
};

Trace run_path(const PiPath& path, Vector3d strain, double speed, double dt, int max_steps)
{
  Trace t;
  double s = 0.0;
  for (int k = 0; k < max_steps && s < path.length(); ++k) {
    const tycore::PathStep step = tycore::follow_path(path, s, strain, speed, dt);
    strain += step.deviatoric_strain_rate * dt;
    s = step.path_length;
    t.strain.push_back(strain);
    t.rate.push_back(step.deviatoric_strain_rate);
    t.progress.push_back(s);
  }
  return t;
}

// shoelace area in the (x, y) drawing; negative = clockwise
double signed_area(const std::vector<Vector2d>& p)
{
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vector2d& q = p[i];
    const Vector2d& r = p[(i + 1) % p.size()];
    a += q.x() * r.y() - r.x() * q.y();
  }
  return 0.5 * a;
}

}    // namespace

// e_i = sqrt(2/3) cos(theta - 2 pi (i-1)/3) of docs/theory.md §7.2 for a unit radius
TEST(StrainPathDirections, LodeDirectionMatchesCosineFormula)
{
  for (double theta = 0.0; theta < 360.0; theta += 7.5) {
    const Vector3d d = tycore::pi_direction(theta);
    const double t = theta * M_PI / 180.0;
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(d(i), std::sqrt(2.0 / 3.0) * std::cos(t - 2 * M_PI * i / 3), 1e-15);
    EXPECT_NEAR(d.sum(), 0.0, 1e-15);
    EXPECT_NEAR(d.norm(), 1.0, 1e-15);
  }
}

// axisymmetric directions are (2,-1,-1)/sqrt 6 and permutations, with the Lode angles of the
// compression (0, 120, 240) and extension (180, 300, 60) states
TEST(StrainPathDirections, AxisymmetricCompressionAndExtension)
{
  const double extension_lode[] = {180, 300, 60};
  for (int axis = 0; axis < 3; ++axis) {
    Vector3d expected = Vector3d::Constant(-1.0 / std::sqrt(6.0));
    expected(axis) = 2.0 / std::sqrt(6.0);
    const Vector3d c = tycore::axisymmetric_compression_direction(axis);
    const Vector3d e = tycore::axisymmetric_extension_direction(axis);
    EXPECT_LT((c - expected).norm(), 1e-15);
    EXPECT_LT((e + expected).norm(), 1e-15);
    EXPECT_NEAR(tycore::lode_angle_deg(tycore::pi_coordinates(c)), 120.0 * axis, 1e-12);
    EXPECT_NEAR(tycore::lode_angle_deg(tycore::pi_coordinates(e)), extension_lode[axis], 1e-12);
  }
  EXPECT_THROW(tycore::axisymmetric_compression_direction(3), std::invalid_argument);
}

// a user direction is projected on the deviatoric plane and normalised; isotropic is an error
TEST(StrainPathDirections, UserDirectionIsMadeUnitTraceless)
{
  const Vector3d d = tycore::unit_deviatoric_direction(Vector3d(3, 1, 1));
  EXPECT_LT((d - tycore::axisymmetric_compression_direction(0)).norm(), 1e-15);
  EXPECT_THROW(tycore::unit_deviatoric_direction(Vector3d(2, 2, 2)), std::invalid_argument);
  EXPECT_THROW(tycore::unit_deviatoric_direction(Vector3d::Zero()), std::invalid_argument);
}

// the pre-strain magnitude converts to the Pi radius of the state a(2,-1,-1) that has it
TEST(StrainPathDirections, PrestrainMeasuresGiveConsistentRadius)
{
  const double d = 2.85e-3;
  const double r13 = tycore::pi_radius_of_axisymmetric_strain(d,
      DeviatoricStrainMeasure::STRAIN_DIFFERENCE_13);
  const Vector3d a13 = tycore::deviator_from_pi(tycore::pi_point(r13, 0.0));
  EXPECT_NEAR(tycore::strain_difference_13(a13), d, 1e-18);
  const double rq = tycore::pi_radius_of_axisymmetric_strain(d, DeviatoricStrainMeasure::EPS_Q);
  const Vector3d aq = tycore::deviator_from_pi(tycore::pi_point(rq, 0.0));
  EXPECT_NEAR(tycore::deviatoric_strain(aq), d, 1e-18);
}

// circle: every state stays at |e| = rho, the Lode angle grows by v dt/rho per step
// (clockwise) and the path closes after 360 deg
TEST(StrainPathCircle, FollowsCircleAtConstantAngularRate)
{
  const double rho = 2.3e-3, dt = 1e-3, speed = 2 * M_PI * rho / (1000 * dt);
  const Vector3d start = tycore::deviator_from_pi(tycore::pi_point(rho, 0.0));
  const PiPath circle = PiPath::circle_through(tycore::pi_coordinates(start), Rotation::CLOCKWISE);
  const Trace t = run_path(circle, start, speed, dt, 5000);
  ASSERT_EQ(t.strain.size(), 1000u);
  double previous = 0.0;
  for (std::size_t k = 0; k < t.strain.size(); ++k) {
    const Vector2d xy = tycore::pi_coordinates(t.strain[k]);
    EXPECT_NEAR(xy.norm(), rho, 1e-12 * rho);
    const double angle = std::atan2(xy.x(), xy.y());
    double turned = angle - previous;
    if (turned < -M_PI) turned += 2 * M_PI;
    EXPECT_NEAR(turned, speed * dt / rho, 1e-12) << k;
    previous = angle;
  }
  EXPECT_LT((t.strain.back() - start).norm(), 1e-12 * rho);
  EXPECT_NEAR(circle.progress(t.progress[249]).fraction, 0.25, 1e-12);
}

// anticlockwise: the Lode angle decreases; the circle is centred on the origin and starts at
// the current deviatoric strain (Lode 130 deg here)
TEST(StrainPathCircle, AnticlockwiseFromCurrentState)
{
  const Vector3d start = tycore::deviator_from_pi(tycore::pi_point(1e-3, 130.0));
  const PiPath circle = PiPath::circle_through(tycore::pi_coordinates(start),
                                               Rotation::ANTICLOCKWISE, 90.0);
  EXPECT_NEAR(circle.length(), 1e-3 * M_PI / 2, 1e-18);
  const double rho = 1e-3, speed = 1e-3, dt = 1e-3;
  const Trace t = run_path(circle, start, speed, dt, 100000);
  EXPECT_NEAR(tycore::lode_angle_deg(tycore::pi_coordinates(t.strain.back())), 40.0, 1e-9);
  const double turned_deg = 11 * speed * dt / rho * 180 / M_PI;   // after 11 steps
  EXPECT_NEAR(tycore::lode_angle_deg(tycore::pi_coordinates(t.strain[10])), 130.0 - turned_deg,
              1e-9);
}

// a state off the circle (radius 1 % too large) is pulled back: the radius error shrinks by
// v dt per step until it is gone, and no rate exceeds twice the path speed
TEST(StrainPathCircle, RadialCorrectionRemovesDrift)
{
  const double rho = 1e-3, dt = 1.0, speed = 1e-6;
  const PiPath circle = PiPath::circle(rho, 0.0, 360.0);
  const Vector3d start = tycore::deviator_from_pi(tycore::pi_point(1.01 * rho, 0.0));
  const Trace t = run_path(circle, start, speed, dt, 100);
  for (std::size_t k = 0; k < t.rate.size(); ++k)
    EXPECT_LE(t.rate[k].norm(), 2 * speed * (1 + 1e-12));
  EXPECT_NEAR(tycore::pi_coordinates(t.strain[4]).norm(), 1.005 * rho, 1e-3 * speed);
  EXPECT_NEAR(tycore::pi_coordinates(t.strain.back()).norm(), rho, 1e-12 * rho);
}

// paper section 5 by hand, a = d/3 for d = eps1 - eps3 = 0.285 %: A = a(2,-1,-1),
// B = 2a(1,1,-2), C = 2a(-2,1,1), D = 2a(1,-2,1); the clockwise path visits A B C D A
// exactly, holds eps1, eps2, eps3, eps1 (deviatoric) fixed on the four legs, and encloses
// the triangle clockwise
TEST(StrainPathPolygon, PaperTriangleClockwise)
{
  const double d = 0.285e-2, a = d / 3;
  const PiPath path = tycore::multiaxial_plane_strain_path(
      d, DeviatoricStrainMeasure::STRAIN_DIFFERENCE_13, Rotation::CLOCKWISE, false);
  const Vector3d A = a * Vector3d(2, -1, -1), B = 2 * a * Vector3d(1, 1, -2),
                 C = 2 * a * Vector3d(-2, 1, 1), D = 2 * a * Vector3d(1, -2, 1);
  const Vector3d expected_vertices[] = {B, C, D, A};
  const int fixed_axis[] = {0, 1, 2, 0};

  const double dt = 1.0, speed = path.length() / 3001.5;
  const Trace t = run_path(path, A, speed, dt, 10000);
  int leg = 0;
  std::vector<Vector2d> corners{tycore::pi_coordinates(A)};
  for (std::size_t k = 0; k < t.strain.size(); ++k) {
    EXPECT_LE(std::abs(t.rate[k](fixed_axis[leg])), 1e-12 * t.rate[k].norm()) << "leg " << leg;
    if (t.progress[k] == path.segment_end(leg)) {
      EXPECT_LT((t.strain[k] - expected_vertices[leg]).norm(), 1e-12 * a) << "vertex " << leg;
      corners.push_back(tycore::pi_coordinates(t.strain[k]));
      ++leg;
    }
  }
  EXPECT_EQ(leg, 4);
  // B: eps1 = eps2; C: eps2 = eps3; D: eps1 = eps3 (axisymmetric extension states)
  EXPECT_NEAR(B(0), B(1), 1e-18);
  EXPECT_NEAR(C(1), C(2), 1e-18);
  EXPECT_NEAR(D(0), D(2), 1e-18);
  corners.pop_back();
  EXPECT_LT(signed_area(corners), 0.0);
  const double lode[] = {0, 60, 180, 300};
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(tycore::lode_angle_deg(corners[i]), lode[i], 1e-9);
}

// anticlockwise: A D C B A with eps1, eps3, eps2, eps1 fixed and positive enclosed area
TEST(StrainPathPolygon, PaperTriangleAnticlockwise)
{
  const double d = 0.285e-2, a = d / 3;
  const PiPath path = tycore::multiaxial_plane_strain_path(
      d, DeviatoricStrainMeasure::STRAIN_DIFFERENCE_13, Rotation::ANTICLOCKWISE, false);
  const Vector3d A = a * Vector3d(2, -1, -1), B = 2 * a * Vector3d(1, 1, -2),
                 C = 2 * a * Vector3d(-2, 1, 1), D = 2 * a * Vector3d(1, -2, 1);
  const Vector3d expected[] = {A, D, C, B};
  const int fixed_axis[] = {0, 2, 1, 0};
  std::vector<Vector2d> corners;
  for (int i = 0; i < 4; ++i) {
    const tycore::PiSegment& leg = path.segments()[i];
    EXPECT_LT((tycore::deviator_from_pi(leg.start) - expected[i]).norm(), 1e-15);
    EXPECT_EQ(tycore::plane_strain_axis(leg), fixed_axis[i]);
    corners.push_back(leg.start);
  }
  EXPECT_GT(signed_area(corners), 0.0);
}

// leg lengths by hand (r = |A|): AB = sqrt(3) r, BC = CD = 2 sqrt(3) r, DA = sqrt(3) r;
// the pre-strain leg OA (length r) is axisymmetric compression along axis 1
TEST(StrainPathPolygon, ProgressAndRemainingTime)
{
  const double d = 0.285e-2;
  const double r = d * std::sqrt(2.0 / 3.0);
  const PiPath path = tycore::multiaxial_plane_strain_path(
      d, DeviatoricStrainMeasure::STRAIN_DIFFERENCE_13, Rotation::CLOCKWISE, true);
  ASSERT_EQ(path.segment_count(), 5);
  EXPECT_NEAR(path.length(), r + 6 * std::sqrt(3.0) * r, 1e-15);
  const Vector3d oa = tycore::deviator_from_pi(path.segments()[0].end - path.segments()[0].start);
  EXPECT_LT((oa.normalized() - tycore::axisymmetric_compression_direction(0)).norm(), 1e-15);

  const double s = r + std::sqrt(3.0) * r + std::sqrt(3.0) * r;   // halfway along BC
  const tycore::PathProgress p = path.progress(s);
  EXPECT_EQ(p.segment, 2);
  EXPECT_NEAR(p.segment_fraction, 0.5, 1e-12);
  EXPECT_NEAR(p.fraction, s / path.length(), 1e-15);
  EXPECT_FALSE(p.finished);
  EXPECT_TRUE(path.progress(path.length()).finished);
  EXPECT_NEAR(path.remaining_time(s, 1e-5), (path.length() - s) / 1e-5, 1e-9);
}

// circle test path with pre-strain: OA then a full circle of radius |A| starting at Lode 0
TEST(StrainPathPolygon, ConstantDeviatoricStrainPathJoinsPrestrain)
{
  const double d = 0.285e-2;
  const double r = d * std::sqrt(2.0 / 3.0);
  const PiPath path = tycore::constant_deviatoric_strain_path(
      d, DeviatoricStrainMeasure::STRAIN_DIFFERENCE_13, Rotation::CLOCKWISE, true);
  EXPECT_NEAR(path.length(), r + 2 * M_PI * r, 1e-15);
  EXPECT_LT((path.point_at(r) - tycore::pi_point(r, 0.0)).norm(), 1e-18);
  EXPECT_LT((path.point_at(r + M_PI * r / 3) - tycore::pi_point(r, 60.0)).norm(), 1e-15);
}

// restart form: the flattened path rebuilds the same geometry
TEST(StrainPathPolygon, ArrayRoundTrip)
{
  const PiPath path = tycore::constant_deviatoric_strain_path(
      1e-3, DeviatoricStrainMeasure::EPS_Q, Rotation::ANTICLOCKWISE, true);
  const std::vector<double> flat = path.to_array();
  ASSERT_EQ(static_cast<int>(flat.size()), PiPath::array_size(path.segment_count()));
  const PiPath back = PiPath::from_array(flat.data());
  for (double f = 0.0; f <= 1.0; f += 0.01)
    EXPECT_EQ(back.point_at(f * path.length()), path.point_at(f * path.length()));
}

// malformed paths are named errors
TEST(StrainPathPolygon, BadPathsAreRejected)
{
  EXPECT_THROW(PiPath::polygon({{0, 0}}), std::invalid_argument);
  EXPECT_THROW(PiPath::polygon({{0, 0}, {1, 1}, {1, 1}}), std::invalid_argument);
  EXPECT_THROW(PiPath::circle(0.0, 0.0, 360.0), std::invalid_argument);
  EXPECT_THROW(PiPath::polygon({{0, 0}, {1, 0}}).then(PiPath::polygon({{2, 0}, {3, 0}})),
               std::invalid_argument);
  EXPECT_THROW(tycore::multiaxial_plane_strain_path(-1e-3,
      DeviatoricStrainMeasure::EPS_Q, Rotation::CLOCKWISE, true), std::invalid_argument);
  EXPECT_THROW(tycore::follow_path(PiPath(), 0.0, Vector3d::Zero(), 1.0, 1.0),
               std::invalid_argument);
}

// at the end of the path the follower holds the end point (zero rate when on it)
TEST(StrainPathPolygon, HoldsEndPoint)
{
  const PiPath path = PiPath::polygon({{0, 0}, {1e-3, 0}});
  const Vector3d end = tycore::deviator_from_pi({1e-3, 0});
  const tycore::PathStep step = tycore::follow_path(path, path.length(), end, 1e-6, 1.0);
  EXPECT_EQ(step.deviatoric_strain_rate.norm(), 0.0);
  EXPECT_EQ(step.path_length, path.length());
}

// a speed that crosses the shortest leg in fewer than MIN_STEPS_PER_LEG steps cannot be
// followed; at the limit the follower reaches every vertex (issue 15: circle ... speed 1e3)
TEST(StrainPathPolygon, MaxFollowableSpeedIsSetByTheShortestLeg)
{
  const PiPath path = PiPath::polygon({{0.0, 0.0}, {0.0, 3e-3}, {1e-3, 3e-3}});
  const double dt = 0.02;
  EXPECT_DOUBLE_EQ(path.shortest_leg(), 1e-3);
  const double v = tycore::max_followable_speed(path, dt);
  EXPECT_DOUBLE_EQ(v, 1e-3 / (tycore::MIN_STEPS_PER_LEG * dt));
  const Trace t = run_path(path, Vector3d::Zero(), v, dt, 1000);
  // the whole path in length/(v dt) steps (each leg may end on a round-off sliver of a step),
  // the shortest leg in MIN_STEPS_PER_LEG
  const int steps = static_cast<int>(t.progress.size());
  EXPECT_GE(steps, 4 * tycore::MIN_STEPS_PER_LEG);
  EXPECT_LE(steps, 4 * tycore::MIN_STEPS_PER_LEG + 2);
  const Vector2d end = tycore::pi_coordinates(t.strain.back());
  EXPECT_NEAR(end.x(), 1e-3, 1e-15);
  EXPECT_NEAR(end.y(), 3e-3, 1e-15);
}

// a polygon starts from the current strain: the leg to its first vertex is travelled first,
// and close = true comes back to the first vertex (issue 14: the first vertex was skipped and
// the polygon never closed)
TEST(StrainPathPolygon, StartsFromTheCurrentStrainAndCloses)
{
  const Vector2d from(0.0, 0.0), v1(0.0, 1e-3), v2(1e-3, 1e-3), v3(1e-3, 0.0);
  const PiPath open = PiPath::polygon({v1, v2, v3});
  const PiPath closed = PiPath::polygon({v1, v2, v3}, true);
  EXPECT_EQ(open.segment_count(), 2);
  EXPECT_EQ(closed.segment_count(), 3);
  EXPECT_NEAR(closed.length(), 2e-3 + std::sqrt(2.0) * 1e-3, 1e-18);
  const PiPath entered = closed.starting_from(from, 1e-6);
  ASSERT_EQ(entered.segment_count(), 4);
  EXPECT_NEAR(entered.length(), 1e-3 + closed.length(), 1e-18);
  // followed from the origin: the strain passes through every vertex and ends on v1
  const double speed = 1e-5, dt = 1.0;
  const Trace t = run_path(entered, Vector3d::Zero(), speed, dt, 100000);
  for (const Vector2d& v : {v1, v2, v3}) {
    double closest = 1.0;
    for (const Vector3d& e : t.strain)
      closest = std::min(closest, (tycore::pi_coordinates(e) - v).norm());
    EXPECT_LT(closest, 1e-15) << v.transpose();
  }
  EXPECT_LT((tycore::pi_coordinates(t.strain.back()) - v1).norm(), 1e-15);
  // already there (closer than min_leg): no lead-in
  EXPECT_EQ(closed.starting_from(v1 + Vector2d(1e-9, 0.0), 1e-6).segment_count(), 3);
}
