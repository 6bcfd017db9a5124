// Contact-level benchmark of the tycore physics core (issue 5; docs/performance.md,
// "Choosing the strain rate and the timestep"). Pure C++ on plugin/core, no LAMMPS.
//
// Build and run (a few seconds; the timings use the thread's CPU clock, so a busy machine slows
// the run but distorts the ns/call figures less than wall time would):
//   cmake -S . -B build -DTYLMP_BENCH=ON && cmake --build build --target bench_contact_level
//   ./build/bench_contact_level                   # writes bench/results/contact_level.{csv,json}
//   ./build/bench_contact_level --repeats 9 --phases 32 --out cl --no-write
//
// Part 1 - the JKR inversion delta -> a (docs/theory.md §1.4), glass pair E = 70 GPa, nu = 0.3
// (E* = E/(2(1-nu^2))), R* = 0.065 mm (two 0.26 mm spheres), Gamma = 0.6 J/m^2, variants
//   closed       jkr::contact_radius          closed form of the quartic (§1.4a)
//   warm         contact_radius_warm          Newton in sqrt(a) from the previous step's radius
//                                             (below; what pair thornton/yin used before its
//                                             law's Halley iteration)
//   newton_warm  jkr::contact_radius_newton   safeguarded Newton in a, previous radius as guess
//   newton_cold  jkr::contact_radius_newton   safeguarded Newton from the bracket midpoint
// on three overlap paths:
//   qs_slow  delta_f -> 3 delta_100 -> delta_f, 1e5 steps each way (~2e-12 m per step), where
//            delta_100 is the Hertz overlap of the mean contact force at 100 kPa
//            (f = pi d^2 p/(Z phi), Z = 4, phi = 0.63)
//   qs_dem   the same sweep with the per-step increment of a DEM run at inertial number 1e-3:
//            ddelta = eps_dot d dt = I dt/sqrt(rho/p), dt = 0.2 t_R, rho = 2650e12, p = 100 kPa
//            (~9e-11 m per step), cycled to 2e5 calls
//   jump     2e5 independent overlaps delta_f + (3 delta_100 - delta_f) u^3, u uniform: every
//            step a large jump from the previous one
// Reported: ns per call, median over --repeats, the variants timed in alternation, in two modes:
//   throughput  independent calls (the guess of call i is the closed-form radius of step i-1, as
//               read from the contact history in the pair loop); the CPU may overlap calls
//   latency     every call's input depends on the previous call's result (delta + 0*a_prev for
//               all variants, the warm variants also take a_prev as their guess): one call's
//               full latency
// the ratio to the closed form, max |a - a_closed|/a_closed and max |delta(a) - delta|/|delta_f|
// (residual of the JKR relation), and the iterations of the Newton variants (warm: mean, max and
// the number of fallbacks to the closed form, iterations == 0), from an untimed pass in which
// the warm variants are chained to their own previous result exactly as in the pair.
//
// Part 2 - time step as a fraction of the Rayleigh time (docs/theory.md §4.1): head-on collision
// of
// two equal spheres, diameter 0.135 mm (the smallest of the specimen), rho = 2650e12 kg/m^3
// (density scaled by 1e12), E, nu as above; t_R = pi R sqrt(rho/G)/(0.1631 nu + 0.8766).
// Integration exactly as LAMMPS fix nve (v += dt/2 F/m; x += dt v; F(x); v += dt/2 F/m) of both
// spheres in absolute coordinates. Normal force from the core: Gamma = 0, Hertz via
// jkr::contact_radius / jkr::normal_force; Gamma = 0.6, JKR as pair thornton/yin does it:
// contact made at the first step with delta >= 0 (snap-on, closed form for a), a by
// contact_radius_warm from the previous step's radius, contact broken at the first step
// with delta < jkr::break_overlap (force 0 from that step on). The run ends once the contact has
// broken. Each case is run for --phases start phases (the overlap at first touch is
// V dt (1 - phi), phi = (k + 1/2)/phases) and the errors are averaged (mean of |error|) and
// maximised over them. Velocities:
//   V_qs       eps_dot d at inertial number 1e-3, = 1e-3 sqrt(p/rho) (the velocity scale of a
//              quasi-static test with this density; below V_s: an adhesive pair would stick,
//              so Hertz only)
//   V(1e-3R), V(1e-2R), V(5e-2R)  Hertz impacts with delta_max = 1e-3, 1e-2, 5e-2 of the sphere
//              radius (docs/theory.md §3.1), both Gamma
//   1.5 V_s, 3 V_s   adhesive only, V_s = jkr::sticking_velocity(R*, E*, Gamma, m*) (§3.2)
// dt/t_R in {0.05, 0.1, 0.2, 0.3, 0.4, 0.5}. Reported, per case and dt: steps per contact
// (force evaluations with the contact on, phase mean), dt/t_c with t_c the analytic Hertz contact
// duration (§3.1), and
//   Gamma = 0    |KE_after - KE_before|/KE_before (the Hertz law is conservative), mean and max
//                over the phases, C = mean/(dt/t_c)^2.5, and the observed order (least-squares
//                slope of log(mean) against log(dt) over the six dt). Verlet's O(dt^2) energy
//                error during the contact is not what remains after it (the shadow energy equals
//                the true one once the force is zero again); what remains comes from the
//                non-smooth start and end of the Hertz force, F ~ delta^(3/2): O((dt/t_c)^2.5),
//                with a sign and size set by where the touch and release fall inside a step
//   Gamma = 0.6  restitution e = V_after/V (phase mean, bias against the closed form
//                e = sqrt(1 - (V_s/V)^2), max |e - e_exact|), the relative error of the adhesive
//                loss |(1 - e^2)/(V_s/V)^2 - 1| (mean, max, observed order) and V dt/|delta_f|:
//                the force jumps at touch (-8/9 Pc) and break (-5/9 Pc -> 0) make this error
//                O(V dt/|delta_f|), first order, per contact; the phase mean is nearly unbiased
// The warm-Newton iteration mean counts the calls that converged (fallbacks are counted apart).

#include "jkr.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#ifndef TYLMP_BENCH_RESULTS
#define TYLMP_BENCH_RESULTS "bench/results/contact_level"
#endif

namespace {

namespace jkr = tycore::jkr;
constexpr double pi = jkr::pi;

// glass (docs/theory.md §1.8), density scaled by 1e12 as in the paper
constexpr double E_young = 70e9, nu = 0.3, rho = 2650e12, p_mean = 1e5;
const double E_star = E_young / (2.0 * (1.0 - nu * nu));
const double G_shear = E_young / (2.0 * (1.0 + nu));

double rayleigh_time(double R) { return pi * R * std::sqrt(rho / G_shear) / (0.1631 * nu + 0.8766); }

double thread_seconds()
{
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

volatile double sink;    // every timed loop's sum ends here: the calls cannot be dropped

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string fmt(const char* f, double x)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

// ------------------------------------------------------------------------------------------
// Part 1: the JKR inversion
// ------------------------------------------------------------------------------------------

// The warm-started Newton iteration in u = sqrt(a) that pair thornton/yin once used, kept here
// as a variant of this benchmark (the pair's law, plugin/core/contact_law.hpp, now iterates
// the same quartic by Halley steps):
// stable-branch a(delta) warm-started from `guess` (the previous step's radius; <= 0: none):
// Newton on the quartic in u = sqrt(a), f(u) = u^4/R* - c u - delta, c = 2 sqrt(pi Gamma/E*)
// (docs/theory.md §1.4), no root or cube root per iteration. f is convex for u > 0 and increasing
// on the stable branch, so from any start with f'(u) > 0 the iterates are >= the root after the
// first step and decrease monotonically to it. Stop when the quadratic-convergence bound of the
// error of the new iterate, 4 (f''/2f') step^2 = 24 u^2 step^2/(R* f'), is <= rel_tol u (a is
// then good to 2 rel_tol + round-off). No usable guess (f' <= 0 there: below the break radius),
// or no convergence within max_iterations (a large jump): the closed form.
inline double contact_radius_warm(double delta, double R, double E, double Gamma, double guess,
                                  int* iterations = nullptr, double rel_tol = 1e-14,
                                  int max_iterations = 8)
{
  if (iterations) *iterations = 0;
  if (Gamma == 0.0) return std::sqrt(R * std::max(delta, 0.0));
  if (guess > 0.0) {
    const double c = 2.0 * std::sqrt(jkr::pi * Gamma / E);
    const double Rinv = 1.0 / R;
    double u = std::sqrt(guess);
    for (int k = 1; k <= max_iterations; ++k) {
      const double u2 = u * u;
      const double slope = 4.0 * u2 * u * Rinv - c;
      if (!(slope > 0.0)) break;
      const double step = (u2 * u2 * Rinv - c * u - delta) / slope;
      u -= step;
      if (24.0 * u2 * step * step <= rel_tol * u * R * slope) {
        if (iterations) *iterations = k;
        return u * u;
      }
    }
  }
  return jkr::contact_radius(delta, R, E, Gamma);
}

enum Variant { CLOSED = 0, WARM = 1, NEWTON_WARM = 2, NEWTON_COLD = 3, N_VARIANTS = 4 };
const char* variant_name[N_VARIANTS] = {"closed", "warm", "newton_warm", "newton_cold"};

struct Inversion {
  double R, E, Gamma;
};

// one call of variant v; `guess` is ignored by the closed form and the cold Newton
template <int V>
inline double invert(const Inversion& c, double delta, double guess, int* it = nullptr)
{
  if constexpr (V == CLOSED) return jkr::contact_radius(delta, c.R, c.E, c.Gamma);
  if constexpr (V == WARM) return contact_radius_warm(delta, c.R, c.E, c.Gamma, guess, it);
  if constexpr (V == NEWTON_WARM)
    return jkr::contact_radius_newton(delta, c.R, c.E, c.Gamma, guess, it);
  if constexpr (V == NEWTON_COLD)
    return jkr::contact_radius_newton(delta, c.R, c.E, c.Gamma, 0.0, it);
  return 0.0;
}

template <int V>
__attribute__((noinline)) double loop_throughput(const Inversion& c, const double* delta,
                                                 const double* guess, size_t n)
{
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) sum += invert<V>(c, delta[i], guess[i]);
  return sum;
}

template <int V>
__attribute__((noinline)) double loop_latency(const Inversion& c, const double* delta,
                                              double a0, size_t n)
{
  double a = a0, sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    a = invert<V>(c, delta[i] + 0.0 * a, a);    // 0*a: not foldable without -ffast-math
    sum += a;
  }
  return sum;
}

using ThroughputFn = double (*)(const Inversion&, const double*, const double*, size_t);
using LatencyFn = double (*)(const Inversion&, const double*, double, size_t);
const ThroughputFn throughput_fn[N_VARIANTS] = {loop_throughput<CLOSED>, loop_throughput<WARM>,
                                                loop_throughput<NEWTON_WARM>,
                                                loop_throughput<NEWTON_COLD>};
const LatencyFn latency_fn[N_VARIANTS] = {loop_latency<CLOSED>, loop_latency<WARM>,
                                          loop_latency<NEWTON_WARM>, loop_latency<NEWTON_COLD>};

struct Path {
  std::string name, description;
  std::vector<double> delta;
};

struct InversionRow {
  std::string path, variant;
  double ns_throughput, ns_latency, ratio_throughput, ratio_latency;
  double max_rel_diff, max_residual;
  double iter_mean;
  int iter_max;
  long fallbacks;
};

// deterministic uniform numbers in [0, 1) (splitmix64)
struct Rng {
  std::uint64_t s;
  double next()
  {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return double(z >> 11) * 0x1.0p-53;
  }
};

std::vector<Path> make_paths(const Inversion& c, double& delta_100, double& step_dem)
{
  const double d = 4.0 * c.R;    // R* = R/2 of two equal spheres, d = 2R
  const double f_mean = pi * d * d * p_mean / (4.0 * 0.63);
  delta_100 = std::pow(3.0 * f_mean / (4.0 * c.E * std::sqrt(c.R)), 2.0 / 3.0);
  const double lo = jkr::break_overlap(c.R, c.E, c.Gamma) * (1.0 - 1e-6);    // just above delta_f
  const double hi = 3.0 * delta_100;
  // DEM increment at I = 1e-3 with dt = 0.2 t_R of the smallest sphere (d = 0.135 mm)
  step_dem = 1e-3 * 0.2 * rayleigh_time(0.0675e-3) / std::sqrt(rho / p_mean);

  std::vector<Path> paths;
  {
    Path p{"qs_slow", "", {}};
    const int n = 100000;
    for (int i = 0; i <= n; ++i) p.delta.push_back(lo + (hi - lo) * i / n);
    for (int i = n - 1; i >= 0; --i) p.delta.push_back(lo + (hi - lo) * i / n);
    p.description = "delta_f -> 3 delta_100 -> delta_f, 1e5 steps each way, " +
                    fmt("%.2e", (hi - lo) / n) + " m per step";
    paths.push_back(p);
  }
  {
    Path p{"qs_dem", "", {}};
    const int n = int(std::ceil((hi - lo) / step_dem));
    while (p.delta.size() < 200000) {
      for (int i = 0; i <= n && p.delta.size() < 200000; ++i)
        p.delta.push_back(std::min(lo + step_dem * i, hi));
      for (int i = n - 1; i >= 1 && p.delta.size() < 200000; --i)
        p.delta.push_back(std::min(lo + step_dem * i, hi));
    }
    p.description = "same sweep, DEM increment at I = 1e-3, dt = 0.2 t_R: " +
                    fmt("%.2e", step_dem) + " m per step, " + std::to_string(n) +
                    " steps each way, cycled";
    paths.push_back(p);
  }
  {
    Path p{"jump", "random overlaps delta_f + (3 delta_100 - delta_f) u^3, 2e5 calls", {}};
    Rng rng{12345};
    for (int i = 0; i < 200000; ++i) {
      const double u = rng.next();
      p.delta.push_back(lo + (hi - lo) * u * u * u);
    }
    paths.push_back(p);
  }
  return paths;
}

std::vector<InversionRow> run_inversion(const Inversion& c, const std::vector<Path>& paths,
                                        int repeats)
{
  std::vector<InversionRow> rows;
  const double delta_f = jkr::break_overlap(c.R, c.E, c.Gamma);
  for (const Path& p : paths) {
    const size_t n = p.delta.size();
    std::vector<double> closed(n), guess(n);
    for (size_t i = 0; i < n; ++i) closed[i] = jkr::contact_radius(p.delta[i], c.R, c.E, c.Gamma);
    guess[0] = closed[0];
    for (size_t i = 1; i < n; ++i) guess[i] = closed[i - 1];

    // accuracy and iterations, warm variants chained to their own previous result as in the pair
    InversionRow r[N_VARIANTS];
    for (int v = 0; v < N_VARIANTS; ++v) {
      double a_prev = closed[0], max_rel = 0.0, max_res = 0.0, it_sum = 0.0;
      int it_max = 0;
      long fallbacks = 0, converged = 0;
      for (size_t i = 0; i < n; ++i) {
        int it = 0;
        double a = 0.0;
        switch (v) {
          case CLOSED: a = invert<CLOSED>(c, p.delta[i], a_prev); break;
          case WARM: a = invert<WARM>(c, p.delta[i], a_prev, &it); break;
          case NEWTON_WARM: a = invert<NEWTON_WARM>(c, p.delta[i], a_prev, &it); break;
          case NEWTON_COLD: a = invert<NEWTON_COLD>(c, p.delta[i], a_prev, &it); break;
        }
        a_prev = a;
        max_rel = std::max(max_rel, std::abs(a - closed[i]) / closed[i]);
        max_res = std::max(max_res, std::abs(jkr::overlap(a, c.R, c.E, c.Gamma) - p.delta[i]) /
                                        std::abs(delta_f));
        it_sum += it;
        it_max = std::max(it_max, it);
        if (it > 0) ++converged;
        if (v == WARM && it == 0) ++fallbacks;
      }
      r[v] = InversionRow{p.name, variant_name[v], 0, 0, 0, 0, max_rel, max_res,
                          converged ? it_sum / double(converged) : 0.0, it_max, fallbacks};
    }

    // timing: the variants in alternation, `repeats` rounds, median
    std::vector<double> t_thr[N_VARIANTS], t_lat[N_VARIANTS];
    double sum = 0.0;
    for (int v = 0; v < N_VARIANTS; ++v) {    // warm-up round, not recorded
      sum += throughput_fn[v](c, p.delta.data(), guess.data(), n);
      sum += latency_fn[v](c, p.delta.data(), closed[0], n);
    }
    for (int rep = 0; rep < repeats; ++rep) {
      for (int k = 0; k < N_VARIANTS; ++k) {
        const int v = (k + rep) % N_VARIANTS;    // rotate the order between rounds
        double t0 = thread_seconds();
        sum += throughput_fn[v](c, p.delta.data(), guess.data(), n);
        double t1 = thread_seconds();
        t_thr[v].push_back((t1 - t0) * 1e9 / double(n));
        t0 = thread_seconds();
        sum += latency_fn[v](c, p.delta.data(), closed[0], n);
        t1 = thread_seconds();
        t_lat[v].push_back((t1 - t0) * 1e9 / double(n));
      }
    }
    sink = sum;
    for (int v = 0; v < N_VARIANTS; ++v) {
      r[v].ns_throughput = median(t_thr[v]);
      r[v].ns_latency = median(t_lat[v]);
    }
    for (int v = 0; v < N_VARIANTS; ++v) {
      r[v].ratio_throughput = r[v].ns_throughput / r[CLOSED].ns_throughput;
      r[v].ratio_latency = r[v].ns_latency / r[CLOSED].ns_latency;
      rows.push_back(r[v]);
    }
  }
  return rows;
}

// ------------------------------------------------------------------------------------------
// Part 2: head-on collision, velocity Verlet as LAMMPS fix nve
// ------------------------------------------------------------------------------------------

struct Sphere {
  double R, m;
};

struct CollisionResult {
  double ke_before, ke_after, e;    // e = relative separation speed / V
  long steps_in_contact;
  bool separated;
  double max_overlap;
};

// two equal spheres on the x axis, sphere 1 at the origin moving +V/2, sphere 2 moving -V/2;
// the first overlap >= 0 is V dt (1 - phase)
CollisionResult collide(const Sphere& s, double Gamma, double V, double dt, double phase,
                        long max_steps)
{
  const double Rs = 0.5 * s.R;    // R* of two equal spheres
  const double delta_break = Gamma > 0.0 ? jkr::break_overlap(Rs, E_star, Gamma) : 0.0;
  double x1 = 0.0, x2 = 2.0 * s.R + V * dt * (2.0 + phase);
  double v1 = 0.5 * V, v2 = -0.5 * V;
  bool touch = false, was_touched = false;
  double radius = 0.0, max_overlap = 0.0;
  long in_contact = 0;

  // force on sphere 2 (+x = away from 1) from the contact law, pair thornton/yin logic
  const auto force = [&]() {
    const double delta = 2.0 * s.R - (x2 - x1);
    if (touch && delta < delta_break) {    // Thornton & Yin: separation at delta_f (0: Hertz)
      touch = false;
      return 0.0;
    }
    if (!touch) {
      if (delta < 0.0 || was_touched) return 0.0;    // one collision: no re-contact counted
      touch = was_touched = true;                    // first touch at delta >= 0: snap-on
      radius = jkr::contact_radius(delta, Rs, E_star, Gamma);
    }
    ++in_contact;
    max_overlap = std::max(max_overlap, delta);
    const double a = Gamma > 0.0 ? contact_radius_warm(delta, Rs, E_star, Gamma, radius)
                                 : jkr::contact_radius(delta, Rs, E_star, Gamma);
    radius = a;
    return jkr::normal_force(a, Rs, E_star, Gamma);
  };

  const double dtf = 0.5 * dt / s.m;
  double F = force();    // LAMMPS setup: forces before the first step
  const double ke_before = 0.5 * s.m * (v1 * v1 + v2 * v2);
  long step = 0;
  for (; step < max_steps; ++step) {
    v1 -= dtf * F;    // initial_integrate
    v2 += dtf * F;
    x1 += dt * v1;
    x2 += dt * v2;
    F = force();      // pair
    v1 -= dtf * F;    // final_integrate
    v2 += dtf * F;
    if (was_touched && !touch) break;    // broken: no force from here on
  }
  CollisionResult r;
  r.ke_before = ke_before;
  r.ke_after = 0.5 * s.m * (v1 * v1 + v2 * v2);
  r.e = (v2 - v1) / V;
  r.steps_in_contact = in_contact;
  r.separated = was_touched && !touch && v2 - v1 > 0.0;
  r.max_overlap = max_overlap;
  return r;
}

struct CollisionRow {
  double Gamma;
  std::string velocity;
  double V, V_over_Vs, dt_over_tR, dt_over_tc, steps_per_contact, max_overlap_over_R;
  double vdt_over_delta_f;                          // per-step overlap increment / |delta_f|
  double energy_err_mean, energy_err_max;           // Gamma = 0
  double e_mean, e_exact, e_err_max, diss_err_mean, diss_err_max;    // Gamma > 0
  double order;    // least-squares slope of log(phase-mean error) vs log(dt), per case
  int separated, phases;
};

// Hertz: impact velocity giving the maximum overlap delta_max (docs/theory.md §3.1)
double hertz_velocity(double delta_max, double R_star, double m_star)
{
  return std::sqrt(16.0 * E_star * std::sqrt(R_star) * std::pow(delta_max, 2.5) / (15.0 * m_star));
}

double hertz_duration(double V, double R_star, double m_star)
{
  return 2.868 * std::pow(m_star * m_star / (E_star * E_star * R_star * V), 0.2);
}

std::vector<CollisionRow> run_collisions(int phases, double& t_R, double& V_s, Sphere& s)
{
  s.R = 0.5 * 0.135e-3;
  s.m = 4.0 / 3.0 * pi * s.R * s.R * s.R * rho;
  const double Rs = 0.5 * s.R, ms = 0.5 * s.m, Gamma = 0.6;
  t_R = rayleigh_time(s.R);
  V_s = jkr::sticking_velocity(Rs, E_star, Gamma, ms);
  const double fractions[] = {0.05, 0.1, 0.2, 0.3, 0.4, 0.5};

  struct Case {
    double Gamma;
    std::string label;
    double V;
  };
  std::vector<Case> cases;
  const double V_qs = 1e-3 * std::sqrt(p_mean / rho);
  const double V3 = hertz_velocity(1e-3 * s.R, Rs, ms), V2 = hertz_velocity(1e-2 * s.R, Rs, ms),
               V5 = hertz_velocity(5e-2 * s.R, Rs, ms);
  cases.push_back({0.0, "V_qs(I=1e-3)", V_qs});
  cases.push_back({0.0, "V(1e-3R)", V3});
  cases.push_back({0.0, "V(1e-2R)", V2});
  cases.push_back({0.0, "V(5e-2R)", V5});
  cases.push_back({Gamma, "1.5V_s", 1.5 * V_s});
  cases.push_back({Gamma, "3V_s", 3.0 * V_s});
  cases.push_back({Gamma, "V(1e-3R)", V3});
  cases.push_back({Gamma, "V(1e-2R)", V2});
  cases.push_back({Gamma, "V(5e-2R)", V5});

  std::vector<CollisionRow> rows;
  for (const Case& cs : cases) {
    const double t_c = hertz_duration(cs.V, Rs, ms);
    const double e_exact = cs.Gamma > 0.0 ? jkr::restitution(cs.V, V_s) : 1.0;
    const size_t first = rows.size();
    for (double frac : fractions) {
      const double dt = frac * t_R;
      // generous cap: approach + contact + (adhesive) tensile phase, many times t_c
      const long max_steps = long(200.0 * t_c / dt) + 1000;
      CollisionRow r{};
      r.Gamma = cs.Gamma;
      r.velocity = cs.label;
      r.V = cs.V;
      r.V_over_Vs = cs.V / V_s;
      r.dt_over_tR = frac;
      r.dt_over_tc = dt / t_c;
      r.vdt_over_delta_f = cs.Gamma > 0.0 ? cs.V * dt / -jkr::break_overlap(Rs, E_star, cs.Gamma)
                                          : NAN;
      r.e_exact = e_exact;
      r.phases = phases;
      double steps = 0.0, max_ov = 0.0;
      for (int k = 0; k < phases; ++k) {
        const CollisionResult c = collide(s, cs.Gamma, cs.V, dt, (k + 0.5) / phases, max_steps);
        steps += double(c.steps_in_contact) / phases;
        max_ov = std::max(max_ov, c.max_overlap);
        r.separated += c.separated ? 1 : 0;
        const double err = std::abs(c.ke_after - c.ke_before) / c.ke_before;
        r.energy_err_mean += err / phases;
        r.energy_err_max = std::max(r.energy_err_max, err);
        r.e_mean += c.e / phases;
        r.e_err_max = std::max(r.e_err_max, std::abs(c.e - e_exact));
        if (cs.Gamma > 0.0) {
          const double diss = 1.0 - c.e * c.e, diss_exact = (V_s / cs.V) * (V_s / cs.V);
          const double derr = std::abs(diss / diss_exact - 1.0);
          r.diss_err_mean += derr / phases;
          r.diss_err_max = std::max(r.diss_err_max, derr);
        }
      }
      r.steps_per_contact = steps;
      r.max_overlap_over_R = max_ov / s.R;
      rows.push_back(r);
    }
    // observed order: least-squares slope over the dt of this case
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double nf = double(rows.size() - first);
    for (size_t i = first; i < rows.size(); ++i) {
      const double x = std::log(rows[i].dt_over_tR);
      const double y = std::log(cs.Gamma > 0.0 ? rows[i].diss_err_mean : rows[i].energy_err_mean);
      sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double order = (nf * sxy - sx * sy) / (nf * sxx - sx * sx);
    for (size_t i = first; i < rows.size(); ++i) rows[i].order = order;
  }
  return rows;
}

// ------------------------------------------------------------------------------------------
// output
// ------------------------------------------------------------------------------------------

std::string num(double x)
{
  if (std::isnan(x)) return "";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

std::string jnum(double x) { return std::isnan(x) ? "null" : num(x); }

std::string read_loadavg()
{
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return a + " " + b + " " + c;
}

}    // namespace

int main(int argc, char** argv)
{
  int repeats = 7, phases = 16;
  bool write = true;
  std::string out = TYLMP_BENCH_RESULTS;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeats" && i + 1 < argc) repeats = std::max(1, std::atoi(argv[++i]));
    else if (arg == "--phases" && i + 1 < argc) phases = std::max(1, std::atoi(argv[++i]));
    else if (arg == "--out" && i + 1 < argc) out = argv[++i];
    else if (arg == "--no-write") write = false;
    else {
      std::printf("usage: %s [--repeats N (7)] [--phases N (16)] [--out PREFIX (%s)] "
                  "[--no-write]\n", argv[0], TYLMP_BENCH_RESULTS);
      return arg == "--help" || arg == "-h" ? 0 : 1;
    }
  }
  const std::string load_start = read_loadavg();

  // ---- part 1 ----
  const Inversion inv{0.065e-3, E_star, 0.6};
  double delta_100 = 0.0, step_dem = 0.0;
  const std::vector<Path> paths = make_paths(inv, delta_100, step_dem);
  const std::vector<InversionRow> irows = run_inversion(inv, paths, repeats);
  const double delta_f = jkr::break_overlap(inv.R, inv.E, inv.Gamma);

  std::printf("Part 1: JKR inversion delta -> a, R* = %.3g m, E* = %.4g Pa, Gamma = %.2g J/m^2\n"
              "  delta_f = %.4g m, delta_100 (Hertz, 100 kPa) = %.4g m; ns/call = median of %d "
              "(thread CPU time)\n", inv.R, inv.E, inv.Gamma, delta_f, delta_100, repeats);
  for (const Path& p : paths) std::printf("  %-8s %s\n", p.name.c_str(), p.description.c_str());
  std::printf("\n%-8s %-12s %9s %7s %9s %7s %10s %10s %6s %4s %9s\n", "path", "variant",
              "ns(thr)", "ratio", "ns(lat)", "ratio", "max|da|/a", "max resid", "it.mean",
              "max", "fallback");
  for (const InversionRow& r : irows)
    std::printf("%-8s %-12s %9.2f %7.3f %9.2f %7.3f %10.2e %10.2e %6.2f %4d %9ld\n",
                r.path.c_str(), r.variant.c_str(), r.ns_throughput, r.ratio_throughput,
                r.ns_latency, r.ratio_latency, r.max_rel_diff, r.max_residual, r.iter_mean,
                r.iter_max, r.fallbacks);

  // ---- part 2 ----
  double t_R = 0.0, V_s = 0.0;
  Sphere s{};
  const std::vector<CollisionRow> crows = run_collisions(phases, t_R, V_s, s);
  std::printf("\nPart 2: head-on collision, d = %.4g m, rho = %.4g kg/m^3, m = %.4g kg, "
              "t_R = %.4g s, V_s(Gamma=0.6) = %.4g m/s\n"
              "  fix nve velocity Verlet; %d start phases per case (mean and max over them)\n",
              2.0 * s.R, rho, s.m, t_R, V_s, phases);
  std::printf("\nGamma = 0 (Hertz, conservative): |dE|/E = |KE_after - KE_before|/KE_before, "
              "mean and max over the phases;\n  C = mean/(dt/t_c)^2.5; order = least-squares "
              "slope of log(mean) against log(dt) over the six dt of the case\n");
  std::printf("\n%-13s %9s %9s %6s %7s %8s %9s %9s %7s %6s\n", "velocity", "V(m/s)", "dmax/R",
              "dt/tR", "dt/t_c", "steps/c", "|dE|/E", "max", "C", "order");
  for (const CollisionRow& r : crows) {
    if (r.Gamma > 0.0) continue;
    std::printf("%-13s %9.3e %9.2e %6.2f %7.4f %8.1f %9.2e %9.2e %7.2f %6.2f%s\n",
                r.velocity.c_str(), r.V, r.max_overlap_over_R, r.dt_over_tR, r.dt_over_tc,
                r.steps_per_contact, r.energy_err_mean, r.energy_err_max,
                r.energy_err_mean / std::pow(r.dt_over_tc, 2.5), r.order,
                r.separated == r.phases ? "" : "  (not all phases separated)");
  }
  std::printf("\nGamma = 0.6 (JKR, break at delta_f): e = V_after/V, phase mean; bias = mean - exact;"
              "\n  diss err = |(1 - e^2)/(V_s/V)^2 - 1| (error of the adhesive loss), mean and max;"
              "\n  Vdt/|d_f| = overlap increment per step over |delta_f|; order of the mean diss err\n");
  std::printf("\n%-10s %9s %7s %6s %8s %9s %8s %8s %9s %9s %9s %9s %6s\n", "velocity", "V(m/s)",
              "V/V_s", "dt/tR", "steps/c", "Vdt/|d_f|", "e", "e exact", "bias", "max|de|",
              "diss err", "max", "order");
  for (const CollisionRow& r : crows) {
    if (!(r.Gamma > 0.0)) continue;
    std::printf("%-10s %9.3e %7.3g %6.2f %8.1f %9.3f %8.5f %8.5f %9.1e %9.2e %9.2e %9.2e %6.2f%s\n",
                r.velocity.c_str(), r.V, r.V_over_Vs, r.dt_over_tR, r.steps_per_contact,
                r.vdt_over_delta_f, r.e_mean, r.e_exact, r.e_mean - r.e_exact, r.e_err_max,
                r.diss_err_mean, r.diss_err_max, r.order,
                r.separated == r.phases ? "" : "  (not all phases separated)");
  }

  if (!write) return 0;
  // ---- CSV: one row per measurement, columns of the other part left empty ----
  {
    std::ofstream f(out + ".csv");
    f << "part,path,variant,ns_throughput,ratio_throughput,ns_latency,ratio_latency,"
         "max_rel_diff_a,max_residual_over_delta_f,iter_mean,iter_max,warm_fallbacks,"
         "Gamma,velocity,V,V_over_Vs,dt_over_tR,dt_over_tc,steps_per_contact,"
         "max_overlap_over_R,vdt_over_delta_f,energy_err_mean,energy_err_max,fit_order,e_mean,"
         "e_exact,e_err_max,"
         "diss_err_mean,diss_err_max,phases_separated\n";
    for (const InversionRow& r : irows)
      f << "inversion," << r.path << ',' << r.variant << ',' << num(r.ns_throughput) << ','
        << num(r.ratio_throughput) << ',' << num(r.ns_latency) << ',' << num(r.ratio_latency)
        << ',' << num(r.max_rel_diff) << ',' << num(r.max_residual) << ','
        << num(r.iter_mean) << ',' << r.iter_max << ',' << r.fallbacks
        << ",,,,,,,,,,,,,,,,,,\n";
    for (const CollisionRow& r : crows) {
      const bool adh = r.Gamma > 0.0;
      f << "collision,,,,,,,,,,,," << num(r.Gamma) << ',' << r.velocity << ',' << num(r.V)
        << ',' << num(r.V_over_Vs) << ',' << num(r.dt_over_tR) << ',' << num(r.dt_over_tc)
        << ',' << num(r.steps_per_contact) << ',' << num(r.max_overlap_over_R) << ','
        << num(r.vdt_over_delta_f) << ',' << (adh ? "" : num(r.energy_err_mean)) << ','
        << (adh ? "" : num(r.energy_err_max)) << ',' << num(r.order) << ','
        << num(r.e_mean) << ',' << num(r.e_exact) << ',' << num(r.e_err_max) << ','
        << (adh ? num(r.diss_err_mean) : "") << ',' << (adh ? num(r.diss_err_max) : "") << ','
        << r.separated << '/' << r.phases << '\n';
    }
  }
  // ---- JSON ----
  {
    std::ostringstream j;
    j << "{\n  \"benchmark\": \"bench/contact_level.cpp\",\n"
      << "  \"timer\": \"CLOCK_THREAD_CPUTIME_ID, median of " << repeats
      << " rounds, variants in alternation\",\n"
      << "  \"loadavg_at_start\": \"" << load_start << "\",\n"
      << "  \"material\": {\"E\": " << jnum(E_young) << ", \"nu\": " << jnum(nu)
      << ", \"E_star\": " << jnum(E_star) << ", \"G\": " << jnum(G_shear)
      << ", \"rho\": " << jnum(rho) << "},\n"
      << "  \"inversion\": {\n    \"R_star\": " << jnum(inv.R) << ", \"Gamma\": "
      << jnum(inv.Gamma) << ", \"delta_f\": " << jnum(delta_f) << ", \"delta_100kPa\": "
      << jnum(delta_100) << ", \"dem_step_I1e-3\": " << jnum(step_dem) << ",\n    \"paths\": {";
    for (size_t i = 0; i < paths.size(); ++i)
      j << (i ? ", " : "") << '"' << paths[i].name << "\": \"" << paths[i].description << '"';
    j << "},\n    \"rows\": [\n";
    for (size_t i = 0; i < irows.size(); ++i) {
      const InversionRow& r = irows[i];
      j << "      {\"path\": \"" << r.path << "\", \"variant\": \"" << r.variant
        << "\", \"ns_throughput\": " << jnum(r.ns_throughput)
        << ", \"ratio_throughput\": " << jnum(r.ratio_throughput)
        << ", \"ns_latency\": " << jnum(r.ns_latency)
        << ", \"ratio_latency\": " << jnum(r.ratio_latency)
        << ", \"max_rel_diff_a\": " << jnum(r.max_rel_diff)
        << ", \"max_residual_over_delta_f\": " << jnum(r.max_residual)
        << ", \"iter_mean\": " << jnum(r.iter_mean) << ", \"iter_max\": " << r.iter_max
        << ", \"warm_fallbacks\": " << r.fallbacks << '}' << (i + 1 < irows.size() ? "," : "")
        << '\n';
    }
    j << "    ]\n  },\n  \"collision\": {\n    \"diameter\": " << jnum(2.0 * s.R)
      << ", \"mass\": " << jnum(s.m) << ", \"t_R\": " << jnum(t_R)
      << ", \"V_s_Gamma0.6\": " << jnum(V_s) << ", \"phases\": " << phases
      << ",\n    \"rows\": [\n";
    for (size_t i = 0; i < crows.size(); ++i) {
      const CollisionRow& r = crows[i];
      const bool adh = r.Gamma > 0.0;
      j << "      {\"Gamma\": " << jnum(r.Gamma) << ", \"velocity\": \"" << r.velocity
        << "\", \"V\": " << jnum(r.V) << ", \"V_over_Vs\": " << jnum(r.V_over_Vs)
        << ", \"dt_over_tR\": " << jnum(r.dt_over_tR) << ", \"dt_over_tc\": "
        << jnum(r.dt_over_tc) << ", \"steps_per_contact\": " << jnum(r.steps_per_contact)
        << ", \"max_overlap_over_R\": " << jnum(r.max_overlap_over_R)
        << ", \"vdt_over_delta_f\": " << jnum(r.vdt_over_delta_f)
        << ", \"energy_err_mean\": " << jnum(adh ? NAN : r.energy_err_mean)
        << ", \"energy_err_max\": " << jnum(adh ? NAN : r.energy_err_max) << ", \"fit_order\": "
        << jnum(r.order) << ", \"e_mean\": " << jnum(r.e_mean) << ", \"e_exact\": "
        << jnum(r.e_exact) << ", \"e_err_max\": " << jnum(r.e_err_max)
        << ", \"diss_err_mean\": " << jnum(adh ? r.diss_err_mean : NAN)
        << ", \"diss_err_max\": " << jnum(adh ? r.diss_err_max : NAN)
        << ", \"phases_separated\": " << r.separated << '}'
        << (i + 1 < crows.size() ? "," : "") << '\n';
    }
    j << "    ]\n  }\n}\n";
    std::ofstream(out + ".json") << j.str();
  }
  std::printf("\nwrote %s.csv and %s.json\n", out.c_str(), out.c_str());
  return 0;
}
