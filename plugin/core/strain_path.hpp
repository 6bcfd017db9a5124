// Deviatoric strain programmes on the strain Pi-plane (docs/theory.md §7.4; paper sections 3-5).
//
// Two kinds of generator:
//  * directions: unit traceless principal vectors (axisymmetric compression/extension, radial
//    direction at a Lode angle); the caller scales them by a deviatoric strain rate;
//  * paths: a PiPath is a chain of straight legs and arcs about the origin of the strain
//    Pi-plane, parametrised by arc length s. follow_path() turns the current natural strains
//    and the stored progress s into the deviatoric strain rate for the next step.
//
// Speeds are Pi-plane speeds |de/dt| (Frobenius norm of the deviatoric strain rate, 1/s);
// eps_q rate = sqrt(2/3)|de/dt|, and in axisymmetric compression d(eps1 - eps3)/dt =
// sqrt(3/2)|de/dt|. Axis indices are 0, 1, 2 for the principal (box) axes 1, 2, 3 = x, y, z.
// Rotation::CLOCKWISE is increasing Lode angle (pi_plane.hpp drawing: axis 1 up, axis 2 lower
// right); it is the order of the paper's clockwise triangle (eps1, then eps2, then eps3 fixed).
#ifndef TYCORE_STRAIN_PATH_HPP
#define TYCORE_STRAIN_PATH_HPP

#include "pi_plane.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace tycore {

enum class Rotation { CLOCKWISE, ANTICLOCKWISE };

// which number a "deviatoric strain" magnitude refers to; the paper's 0.285 % pre-strain is
// most plausibly eps1 - eps3 (its Fig. 1 axis), docs/theory.md §7.1
enum class DeviatoricStrainMeasure { STRAIN_DIFFERENCE_13, EPS_Q };

inline void require_axis_index(int axis)
{
  if (axis < 0 || axis > 2)
    throw std::invalid_argument("axis index " + std::to_string(axis) + " is not 0, 1 or 2");
}

// ---------------------------------------------------------------------------------------------
// Directions (unit, traceless)

// direction at Lode angle theta: e_i = sqrt(2/3) cos(theta - 2 pi (i-1)/3)   (docs/theory.md §7.2)
inline Eigen::Vector3d pi_direction(double lode_deg)
{
  return deviator_from_pi(pi_point(1.0, lode_deg));
}

// the given axis shortens most, the other two extend equally (Lode 0, 120, 240 deg)
inline Eigen::Vector3d axisymmetric_compression_direction(int axis)
{
  require_axis_index(axis);
  return pi_direction(120.0 * axis);
}

// the given axis extends, the other two shorten equally (Lode 180, 300, 60 deg)
inline Eigen::Vector3d axisymmetric_extension_direction(int axis)
{
  return -axisymmetric_compression_direction(axis);
}

// deviatoric part of v, normalised; v may come from user variables
inline Eigen::Vector3d unit_deviatoric_direction(const Eigen::Vector3d &v)
{
  const Eigen::Vector3d d = deviator(v);
  const double norm = d.norm();
  if (!std::isfinite(norm) || norm <= 1e-12 * v.norm() || norm == 0.0)
    throw std::invalid_argument("strain-rate direction has no deviatoric part (isotropic or "
                                "zero): cannot define a deviatoric path direction");
  return d / norm;
}

// Pi radius |e| of an axisymmetric compression state of given magnitude:
// e = (d/3)(2,-1,-1) gives eps1 - eps3 = d, eps_q = 2d/3, |e| = d sqrt(2/3)
inline double pi_radius_of_axisymmetric_strain(double magnitude, DeviatoricStrainMeasure measure)
{
  return measure == DeviatoricStrainMeasure::STRAIN_DIFFERENCE_13 ? magnitude * std::sqrt(2.0 / 3.0)
                                                                  : magnitude * std::sqrt(1.5);
}

// ---------------------------------------------------------------------------------------------
// Paths

// a straight leg, or an arc about the Pi-plane origin (angles are Lode angles in degrees;
// sweep > 0 turns clockwise)
struct PiSegment {
  enum class Shape { LINE, ARC };
  Shape shape = Shape::LINE;
  Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();
  double radius = 0.0, start_lode_deg = 0.0, sweep_deg = 0.0;

  double length() const
  {
    return shape == Shape::LINE ? (end - start).norm()
                                : radius * std::abs(sweep_deg) * piplane::degree;
  }

  // point at arc length s from the segment start, 0 <= s <= length()
  Eigen::Vector2d point_at(double s) const
  {
    const double L = length();
    if (shape == Shape::LINE) return L > 0.0 ? start + (s / L) * (end - start) : start;
    const double turned = L > 0.0 ? sweep_deg * (s / L) : 0.0;
    return pi_point(radius, start_lode_deg + turned);
  }

  Eigen::Vector2d end_point() const
  {
    return shape == Shape::LINE ? end : pi_point(radius, start_lode_deg + sweep_deg);
  }
  Eigen::Vector2d start_point() const
  {
    return shape == Shape::LINE ? start : pi_point(radius, start_lode_deg);
  }
};

struct PathProgress {
  int segment;                // index of the leg being travelled (last leg once finished)
  double segment_fraction;    // fraction of that leg done
  double fraction;            // fraction of the whole path done (by arc length)
  bool finished;
};

class PiPath {
 public:
  PiPath() = default;

  // polyline through the vertices; close = true adds the leg from the last vertex back to the
  // first (as does repeating the first vertex)
  static PiPath polygon(std::vector<Eigen::Vector2d> vertices, bool close = false)
  {
    if (vertices.size() < 2)
      throw std::invalid_argument("a Pi-plane polygon needs at least two vertices");
    if (close && vertices.back() != vertices.front()) vertices.push_back(vertices.front());
    PiPath path;
    for (std::size_t i = 0; i + 1 < vertices.size(); ++i) {
      PiSegment leg;
      leg.start = vertices[i];
      leg.end = vertices[i + 1];
      if (!(leg.length() > 0.0))
        throw std::invalid_argument("Pi-plane polygon vertices " + std::to_string(i) + " and " +
                                    std::to_string(i + 1) + " coincide (zero-length leg)");
      path.push(leg);
    }
    return path;
  }

  // arc of radius rho about the origin from Lode angle theta0 through sweep (> 0 clockwise)
  static PiPath circle(double radius, double start_lode_deg, double sweep_deg)
  {
    if (!(radius > 0.0))
      throw std::invalid_argument("circle radius " + std::to_string(radius) + " must be positive");
    if (!(sweep_deg != 0.0) || !std::isfinite(sweep_deg))
      throw std::invalid_argument("circle sweep angle must be non-zero and finite");
    PiSegment arc;
    arc.shape = PiSegment::Shape::ARC;
    arc.radius = radius;
    arc.start_lode_deg = start_lode_deg;
    arc.sweep_deg = sweep_deg;
    PiPath path;
    path.push(arc);
    return path;
  }

  // circle about the origin through the given Pi point (e.g. the current deviatoric strain)
  static PiPath circle_through(const Eigen::Vector2d &start, Rotation rotation,
                               double sweep_deg = 360.0)
  {
    const double signed_sweep = rotation == Rotation::CLOCKWISE ? sweep_deg : -sweep_deg;
    return circle(start.norm(), lode_angle_deg(start), signed_sweep);
  }

  // the same path entered from the point `from` (the current strain): a straight lead-in leg
  // from `from` to the first point is put in front, unless it would be shorter than min_leg
  // (a gap the follower closes by itself, at most speed*dt per step)
  PiPath starting_from(const Eigen::Vector2d &from, double min_leg) const
  {
    if (segments_.empty()) return *this;
    const Eigen::Vector2d first = segments_.front().start_point();
    if (!((first - from).norm() >= min_leg)) return *this;
    return polygon({from, first}).then(*this);
  }

  // this path followed by next; next must start where this one ends
  PiPath then(const PiPath &next) const
  {
    PiPath joined = *this;
    if (!segments_.empty() && !next.segments_.empty()) {
      const Eigen::Vector2d gap =
          next.segments_.front().start_point() - segments_.back().end_point();
      const double scale = std::max(length(), next.length());
      if (gap.norm() > 1e-12 * scale)
        throw std::invalid_argument("Pi-plane path pieces do not join: the next piece starts "
                                    "away from the end of the previous one");
    }
    for (const PiSegment &s : next.segments_) joined.push(s);
    return joined;
  }

  double length() const { return cumulative_.empty() ? 0.0 : cumulative_.back(); }
  double shortest_leg() const
  {
    double shortest = length();
    for (const PiSegment &s : segments_) shortest = std::min(shortest, s.length());
    return shortest;
  }
  int segment_count() const { return static_cast<int>(segments_.size()); }
  const std::vector<PiSegment> &segments() const { return segments_; }
  double segment_start(int i) const { return i == 0 ? 0.0 : cumulative_[i - 1]; }
  double segment_end(int i) const { return cumulative_[i]; }

  // leg being travelled at arc length s; at a vertex, the leg that starts there
  int segment_at(double s) const
  {
    const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
    const int i = static_cast<int>(it - cumulative_.begin());
    return std::min(i, segment_count() - 1);
  }

  Eigen::Vector2d point_at(double s) const
  {
    s = std::clamp(s, 0.0, length());
    const int i = segment_at(s);
    return segments_[i].point_at(s - segment_start(i));
  }

  PathProgress progress(double s) const
  {
    const double total = length();
    s = std::clamp(s, 0.0, total);
    const int i = segment_at(s);
    const double leg = segments_[i].length();
    return {i, leg > 0.0 ? (s - segment_start(i)) / leg : 1.0, total > 0.0 ? s / total : 1.0,
            s >= total};
  }

  // simulated time left at Pi-plane speed v
  double remaining_time(double s, double speed) const
  {
    return std::max(0.0, length() - s) / speed;
  }

  // flat form for restart files: [n, then per segment: shape, 5 numbers]
  std::vector<double> to_array() const
  {
    std::vector<double> a{static_cast<double>(segments_.size())};
    for (const PiSegment &s : segments_) {
      if (s.shape == PiSegment::Shape::LINE)
        a.insert(a.end(), {0.0, s.start.x(), s.start.y(), s.end.x(), s.end.y(), 0.0});
      else
        a.insert(a.end(), {1.0, s.radius, s.start_lode_deg, s.sweep_deg, 0.0, 0.0});
    }
    return a;
  }

  static PiPath from_array(const double *a)
  {
    PiPath path;
    const int n = static_cast<int>(a[0]);
    for (int i = 0; i < n; ++i) {
      const double *r = a + 1 + 6 * i;
      PiSegment s;
      if (r[0] == 0.0) {
        s.start = {r[1], r[2]};
        s.end = {r[3], r[4]};
      } else {
        s.shape = PiSegment::Shape::ARC;
        s.radius = r[1];
        s.start_lode_deg = r[2];
        s.sweep_deg = r[3];
      }
      path.push(s);
    }
    return path;
  }
  static int array_size(int segments) { return 1 + 6 * segments; }

 private:
  void push(const PiSegment &s)
  {
    segments_.push_back(s);
    cumulative_.push_back(length() + s.length());
  }

  std::vector<PiSegment> segments_;
  std::vector<double> cumulative_;
};

// axis with zero deviatoric strain rate along a straight leg (plane-strain leg), or -1
inline int plane_strain_axis(const PiSegment &leg)
{
  if (leg.shape != PiSegment::Shape::LINE) return -1;
  const Eigen::Vector3d d = deviator_from_pi(leg.end - leg.start);
  for (int k = 0; k < 3; ++k)
    if (std::abs(d(k)) <= 1e-12 * d.norm()) return k;
  return -1;
}

// ---------------------------------------------------------------------------------------------
// The paper's deviatoric programmes (paper sections 3 and 5)

// axisymmetric compression along axis 1 from the origin to the pre-strain state A
inline PiPath axisymmetric_prestrain_path(double prestrain, DeviatoricStrainMeasure measure)
{
  if (!(prestrain > 0.0))
    throw std::invalid_argument("pre-strain " + std::to_string(prestrain) + " must be positive");
  return PiPath::polygon(
      {{0.0, 0.0}, pi_point(pi_radius_of_axisymmetric_strain(prestrain, measure), 0.0)});
}

// constant deviatoric strain: circle about the origin through A at Lode 0 (paper section 5)
inline PiPath constant_deviatoric_strain_path(double prestrain, DeviatoricStrainMeasure measure,
                                              Rotation rotation, bool with_prestrain,
                                              double sweep_deg = 360.0)
{
  const PiPath prestrain_leg = axisymmetric_prestrain_path(prestrain, measure);
  const PiPath circle =
      PiPath::circle_through(prestrain_leg.point_at(prestrain_leg.length()), rotation, sweep_deg);
  return with_prestrain ? prestrain_leg.then(circle) : circle;
}

// Multi-axial plane strain (paper section 5). From A = a(2,-1,-1) (eps2 = eps3) with eps1
// fixed to eps1 = eps2 gives B = 2a(1,1,-2) at Lode 60; eps2 fixed to eps2 = eps3 gives
// C = 2a(-2,1,1) at 180; eps3 fixed to eps1 = eps3 gives D = 2a(1,-2,1) at 300; eps1 fixed
// back to A, the midpoint of DB. Clockwise A-B-C-D-A, anticlockwise A-D-C-B-A. Each leg has
// zero deviatoric rate along the fixed axis; the triangle BCD has circumradius 2|A|.
inline PiPath multiaxial_plane_strain_path(double prestrain, DeviatoricStrainMeasure measure,
                                           Rotation rotation, bool with_prestrain)
{
  const PiPath prestrain_leg = axisymmetric_prestrain_path(prestrain, measure);
  const double r = pi_radius_of_axisymmetric_strain(prestrain, measure);
  const Eigen::Vector2d A = pi_point(r, 0.0), B = pi_point(2 * r, 60.0), C = pi_point(2 * r, 180.0),
                        D = pi_point(2 * r, 300.0);
  const PiPath triangle = rotation == Rotation::CLOCKWISE ? PiPath::polygon({A, B, C, D, A})
                                                          : PiPath::polygon({A, D, C, B, A});
  return with_prestrain ? prestrain_leg.then(triangle) : triangle;
}

// ---------------------------------------------------------------------------------------------
// Following a path

// A leg travelled in fewer steps than this cannot be followed: the follower's pull back onto
// the path is limited to speed*dt per step and the p servo removes a fraction `gain` (0.25) of
// its error per step, so both need several steps per leg (at speed*dt above a whole leg the
// target jumps to its end in one step and the progress runs ahead of the strain)
constexpr int MIN_STEPS_PER_LEG = 10;

// the largest Pi-plane speed at which every leg takes at least MIN_STEPS_PER_LEG steps
inline double max_followable_speed(const PiPath &path, double dt)
{
  return path.shortest_leg() / (MIN_STEPS_PER_LEG * dt);
}

struct PathStep {
  Eigen::Vector3d deviatoric_strain_rate;    // traceless, 1/s
  double path_length;                        // progress s after this step
};

// Rate that carries the current deviatoric strain to the path point one step ahead. The
// target advances by speed*dt but stops exactly at each vertex; the part that pulls the state
// back onto the path (drift of the radius on a circle, round-off, a late start) is limited to
// speed*dt per step, so a rate never exceeds twice the path speed.
inline PathStep follow_path(const PiPath &path, double path_length, const Eigen::Vector3d &strain,
                            double speed, double dt)
{
  if (path.segment_count() == 0) throw std::invalid_argument("the Pi-plane path is empty");
  if (!(speed > 0.0)) throw std::invalid_argument("path speed must be positive");
  if (!(dt > 0.0)) throw std::invalid_argument("time step must be positive");
  const double s = std::clamp(path_length, 0.0, path.length());
  const int leg = path.segment_at(s);
  const double leg_start = path.segment_start(leg);
  const double s_next = std::min(s + speed * dt, path.segment_end(leg));
  const PiSegment &segment = path.segments()[leg];
  const Eigen::Vector2d on_path = segment.point_at(s - leg_start);
  const bool reaches_vertex = s_next == path.segment_end(leg);
  const Eigen::Vector2d ahead = reaches_vertex ? segment.end_point()
                                               : segment.point_at(s_next - leg_start);
  Eigen::Vector2d back_to_path = on_path - pi_coordinates(strain);
  const double max_correction = speed * dt;
  if (back_to_path.norm() > max_correction) back_to_path *= max_correction / back_to_path.norm();
  return {deviator_from_pi(ahead - on_path + back_to_path) / dt, s_next};
}

}    // namespace tycore

#endif
