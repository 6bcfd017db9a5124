// One step of the Thornton-Yin law for a batch of contacts stored as a structure of arrays
// (ContactBatch): geometry and velocities at the contact in; forces, the torque's ingredient,
// the updated history and the per-contact tallies out. Everything the pair style does per
// contact besides finding it, deriving its geometry (contact_geometry.hpp, in the same lanes)
// and scattering its force: first touch (JKR snap-on), separation
// at the break overlap with its energy, the law (contact_law.hpp), viscous damping, the
// servo's affine-stiffness tally (docs/theory.md §6.1) and the stored energy.
//
// Builds of the same entry, all instantiations of the law's one text (contact_law.hpp):
//  * advance_batch<Adhesive, Damped>(b, n, k, p, Isa::scalar): lane after lane through
//    law::scalar_step (contact_kernel.hpp);
//  * Isa::sse2 / avx2 / avx512 (x86-64 with GCC or Clang): the law over the lanes of the batch
//    in SIMD registers (contact_batch_loops.hpp, compiled per instruction set by
//    contact_batch.cpp); best_isa() picks the widest the processor has, once, at run time, so
//    one binary serves every x86-64 processor. Other compilers and architectures, and a build
//    configured with -DTYLMP_VECTOR_LAW=OFF, have the scalar build alone.
// Every build does the same arithmetic operation for operation (no fused multiply-add, the same
// cube root bit for bit: simd_cbrt), so they agree to the last bit;
// tests/core/test_contact_batch.cpp checks this on every ISA the machine has against the
// scalar build and the scalar entry advance_contact, and tests/test_scalar_law_build.py the
// build configured with -DTYLMP_VECTOR_LAW=OFF against this one.
#ifndef TYCORE_CONTACT_BATCH_HPP
#define TYCORE_CONTACT_BATCH_HPP

#include "affine_stiffness_entries.hpp"
#include "contact_kernel.hpp"
#include "contact_types.hpp"
#include "jkr.hpp"
#include "mindlin_deresiewicz.hpp"
#include "simd_math.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <type_traits>

namespace tycore {

// Lanes of one batch. The vector loops always run over all of them (a whole number of
// registers of every width); lanes at and beyond the n given to advance_batch are computed
// on whatever they hold and never read back (start from a value-initialised batch,
// ContactBatch b{}, so that they hold numbers).
inline constexpr int batch_lanes = 16;

// a history field of `values` values as arrays over the lanes: double[values][batch_lanes],
// or double[batch_lanes] for a scalar
template <int values> struct batch_field_type {
  using type = double[values][batch_lanes];
};
template <> struct batch_field_type<1> {
  using type = double[batch_lanes];
};
template <int values> using batch_field = typename batch_field_type<values>::type;

// the lanes of value k of a history field of the batch, scalar (k = 0) or vector alike
template <class X> [[gnu::always_inline]] constexpr auto &batch_value(X &x, int k)
{
  if constexpr (std::rank_v<X> == 2)
    return x[k];
  else
    return x;
}

// in: the contact's geometry and velocities (contact_geometry.hpp, from the spheres' data that
// the engine gathers into the lanes) and its history; out: what the engine scatters
struct ContactBatch {
  // ---- in ----
  alignas(64) double n[3][batch_lanes];      // unit normal, from j to i
  alignas(64) double delta[batch_lanes];     // overlap r_i + r_j - |x_i - x_j| (< 0: a gap)
  alignas(64) double R[batch_lanes];         // R* = r_i r_j / (r_i + r_j)
  alignas(64) double Rinv[batch_lanes];      // 1/R*
  alignas(64) double vn[batch_lanes];        // normal relative velocity of i to j (v_r . n)
  alignas(64) double vt[3][batch_lanes];     // tangential relative velocity of i to j at the
                                             // contact point, spins included (docs/theory.md §5.1)
  alignas(64) double spin_n[batch_lanes];    // (w_i + w_j) . n: the history twists by dt/2 of it
  alignas(64) double m_star[batch_lanes];    // m_i m_j / (m_i + m_j) (Damped only)
  alignas(64) double rsq[batch_lanes];       // |x_i - x_j|^2 (gathered; the geometry's r and
                                             // the affine-stiffness tally)
  bool first_touch[batch_lanes];             // no history yet, delta >= 0: JKR snap-on first

  // ---- the engine's data of the two spheres, from which contact_geometry
  // (contact_geometry.hpp) derives n, delta, R, Rinv, vn, vt, spin_n and m_star ----
  alignas(64) double del[3][batch_lanes];      // x_i - x_j
  alignas(64) double v_rel[3][batch_lanes];    // v_i - v_j
  alignas(64) double w_i[3][batch_lanes];      // angular velocities
  alignas(64) double w_j[3][batch_lanes];
  alignas(64) double r_i[batch_lanes];    // radii
  alignas(64) double r_j[batch_lanes];
  alignas(64) double m_i[batch_lanes];    // masses (Damped only)
  alignas(64) double m_j[batch_lanes];

  // ---- history, in and out: the fields of TYCORE_HISTORY_FIELDS (contact_types.hpp) as
  // arrays, a vector's value k in name[k][lane] (load_history / store_history) ----
#define TYCORE_BATCH_HISTORY_MEMBER(name, values, carried, from_j, meaning) \
  alignas(64) batch_field<values> name;
  TYCORE_HISTORY_FIELDS(TYCORE_BATCH_HISTORY_MEMBER)
#undef TYCORE_BATCH_HISTORY_MEMBER

  // ---- out ----
  alignas(64) double P[batch_lanes];                 // elastic normal force, > 0 repulsive
  alignas(64) double contact_radius[batch_lanes];    // JKR radius a(delta)
  alignas(64) double force[3][batch_lanes];          // total force on i (damping included)
  alignas(64) double moment[3][batch_lanes];         // n x F_t: torque on i is -(r_i - delta/2)
                                                     // times it, on j -(r_j - delta/2) times it
  alignas(64) double dissipation[batch_lanes];       // frictional dissipation of the step
  alignas(64) double damping_dissipation[batch_lanes];    // dt (eta_n vn^2 + eta_t |vt|^2)
  alignas(64) double broken[batch_lanes];                 // 1: separated at the break overlap this
                                                          // step (history cleared, forces 0)
  alignas(64) double break_energy[batch_lanes];           // elastic energy lost at that separation
  // with BatchParameters::tally: the servo's affine stiffness l^2 [k_N n_a^2 n_b^2 +
  // k_T (d_ab n_a^2 - n_a^2 n_b^2)], ab = xx yy zz xy xz yz (docs/theory.md §6.1), and |F|
  alignas(64) double affine_stiffness[6][batch_lanes];
  alignas(64) double force_magnitude[batch_lanes];
  // with BatchParameters::tally: the k_N and k_T of that tally (zero for a broken lane), for
  // the entries with a shear component (tycore::affine_shear_entries)
  alignas(64) double normal_stiffness[batch_lanes];
  alignas(64) double tangential_stiffness[batch_lanes];
  alignas(64) double energy[batch_lanes];    // with BatchParameters::energy: stored
                                             // elastic energy (contact_stored_energy)
  alignas(64) double slides[batch_lanes];    // 1: at the Coulomb limit in this force
                                             // evaluation (the history's flag after a
                                             // step; slides_without_step without one)
};

struct BatchParameters {
  double dt;              // timestep: ds = -vt dt, twist = dt (w_i + w_j).n / 2
  double beta_n = 0.0;    // viscous damping ratios of the material pair (Damped only):
  double beta_t = 0.0;    // eta = 2 beta sqrt(m* k), k = 2E*a normal, 8G*a tangential
  bool tally = false;     // fill affine_stiffness and force_magnitude
  bool energy = false;    // fill energy
};

// A contact's history into and out of lane `lane`: from and to its slot in LAMMPS's history
// page (history_size doubles, ContactHistory verbatim, slot_index), value by value (no copy
// through the stack); or from and to a ContactHistory (the rare paths: first touch,
// separation, energies)
inline void load_history(ContactBatch &b, int lane, const double *slot)
{
#define TYCORE_LOAD_FIELD(name, values, carried, from_j, meaning) \
  for (int k = 0; k < values; ++k) batch_value(b.name, k)[lane] = slot[slot_index::name + k];
  TYCORE_HISTORY_FIELDS(TYCORE_LOAD_FIELD)
#undef TYCORE_LOAD_FIELD
}

inline void store_history(const ContactBatch &b, int lane, double *slot)
{
#define TYCORE_STORE_FIELD(name, values, carried, from_j, meaning) \
  for (int k = 0; k < values; ++k) slot[slot_index::name + k] = batch_value(b.name, k)[lane];
  TYCORE_HISTORY_FIELDS(TYCORE_STORE_FIELD)
#undef TYCORE_STORE_FIELD
}

inline void load_history(ContactBatch &b, int lane, const ContactHistory &h)
{
  double slot[history_size];
  std::memcpy(slot, &h, sizeof(h));
  load_history(b, lane, slot);
}

inline ContactHistory stored_history(const ContactBatch &b, int lane)
{
  double slot[history_size];
  store_history(b, lane, slot);
  ContactHistory h;
  std::memcpy(&h, slot, sizeof(h));
  return h;
}

// The vector builds of the law exist on x86-64 with GCC or Clang (the instruction sets are
// chosen per function by target attributes and at run time by __builtin_cpu_supports); other
// compilers and architectures, and a build configured with -DTYLMP_VECTOR_LAW=OFF
// (TYCORE_SCALAR_LAW), have the scalar build alone.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(TYCORE_SCALAR_LAW)
#define TYCORE_VECTOR_BUILDS 1
#endif

// instruction sets of the batch entry, narrowest first
enum class Isa { scalar, sse2, avx2, avx512 };

inline const char *isa_name(Isa isa)
{
  switch (isa) {
    case Isa::sse2:
      return "sse2";
    case Isa::avx2:
      return "avx2";
    case Isa::avx512:
      return "avx512";
    default:
      return "scalar";
  }
}

// does this build have `isa` and this processor run it (scalar: always; sse2: every x86-64)
inline bool isa_supported(Isa isa)
{
#ifdef TYCORE_VECTOR_BUILDS
  __builtin_cpu_init();    // idempotent; needed where this runs before main (static init)
  switch (isa) {
    case Isa::avx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
          __builtin_cpu_supports("avx512vl");
    case Isa::avx2:
      return __builtin_cpu_supports("avx2");
    default:
      return true;
  }
#else
  return isa == Isa::scalar;
#endif
}

// the widest build this processor runs, determined once (Isa::scalar where the build has no
// vector builds)
inline Isa best_isa()
{
  static const Isa best = isa_supported(Isa::avx512) ? Isa::avx512
      : isa_supported(Isa::avx2)                     ? Isa::avx2
      : isa_supported(Isa::sse2)                     ? Isa::sse2
                                                     : Isa::scalar;
  return best;
}

namespace detail {

  // the parts of the step outside the law, shared by both builds

  // First touch (law::snap_on, docs/theory.md §1.3) and separation at the break overlap
  // (law::separates, §1.2: the history cleared, its energy law::break_energy lost). Lanes in
  // neither state are left alone; this runs lane by lane, both are rare.
  template <bool Adhesive>
  inline void touch_or_break(ContactBatch &b, int n, const PairConstants &k)
  {
    const PairCoefficients &c = k.c;
    for (int i = 0; i < n; ++i) {
      b.broken[i] = 0.0;
      b.break_energy[i] = 0.0;
      const double R = b.R[i], delta = b.delta[i];
      if (b.first_touch[i]) {
        load_history(b, i, law::snap_on(c, R, delta, Adhesive));
      } else if (law::separates(c, R, delta, Adhesive)) {
        b.broken[i] = 1.0;
        b.break_energy[i] = law::break_energy(c, R, stored_history(b, i), Adhesive);
        load_history(b, i, ContactHistory{});
      }
    }
  }

  // energy stored in each contact after the step (lane by lane: only when LAMMPS asks)
  inline void stored_energies(ContactBatch &b, int n, const PairConstants &k)
  {
    for (int i = 0; i < n; ++i)
      b.energy[i] = b.broken[i] != 0.0
          ? 0.0
          : contact_stored_energy(k.c, b.R[i], b.contact_radius[i], b.P[i], stored_history(b, i));
  }

  // The force of lane i split as the contact records keep it: normal part Fn n (elastic P less
  // the normal viscous force) and tangential part fs (elastic T less the tangential viscous
  // force), and the energy the viscous forces take out over the step. Damping stays outside the
  // elastic history: eta = 2 beta sqrt(m* k), k = 2E*a normal, 8G*a tangential (the energy
  // account: docs/theory.md §2.4).
  template <bool Damped>
  [[gnu::always_inline]] inline double
  damped_force(const ContactBatch &b, int i, const PairCoefficients &c, const BatchParameters &p,
               double &Fn, double fs[3])
  {
    const double a = b.contact_radius[i];
    Fn = b.P[i];
    fs[0] = b.T[0][i];
    fs[1] = b.T[1][i];
    fs[2] = b.T[2][i];
    if (!Damped) return 0.0;
    const double vn = b.vn[i], vt1 = b.vt[0][i], vt2 = b.vt[1][i], vt3 = b.vt[2][i];
    const double m_star = b.m_star[i];
    const double eta_n = 2.0 * p.beta_n * std::sqrt(m_star * 2.0 * c.E_star * a);
    const double eta_t = 2.0 * p.beta_t * std::sqrt(m_star * 8.0 * c.G_star * a);
    Fn -= eta_n * vn;
    fs[0] -= eta_t * vt1;
    fs[1] -= eta_t * vt2;
    fs[2] -= eta_t * vt3;
    return p.dt * (eta_n * vn * vn + eta_t * (vt1 * vt1 + vt2 * vt2 + vt3 * vt3));
  }

  // Everything after the law for lane i: viscous damping outside the elastic history, the force
  // on i and the torque's ingredient, with Tally the affine-stiffness tally; a broken lane gets
  // zeros. k_T_law: the tangential stiffness the law used this step, or < 0 where it used none
  // (frictionless or peeled step). Branch-free and reading every input unconditionally, so that
  // it inlines into the vector loop.
  template <bool Adhesive, bool Damped, bool Tally>
  [[gnu::always_inline]] inline void lane_outputs(ContactBatch &b, int i, const PairConstants k,
                                                  const BatchParameters p, double k_T_law)
  {
    const PairCoefficients c = k.c;
    const bool gone = b.broken[i] != 0.0;
    const double nx = b.n[0][i], ny = b.n[1][i], nz = b.n[2][i];
    const double a = b.contact_radius[i], R = b.R[i], P = b.P[i];
    double Fn, fs[3];
    const double lost = damped_force<Damped>(b, i, c, p, Fn, fs);
    b.damping_dissipation[i] = gone ? 0.0 : lost;
    const double fs1 = fs[0], fs2 = fs[1], fs3 = fs[2];
    const double fx = nx * Fn + fs1, fy = ny * Fn + fs2, fz = nz * Fn + fs3;
    b.force[0][i] = gone ? 0.0 : fx;
    b.force[1][i] = gone ? 0.0 : fy;
    b.force[2][i] = gone ? 0.0 : fz;
    b.moment[0][i] = gone ? 0.0 : ny * fs3 - nz * fs2;
    b.moment[1][i] = gone ? 0.0 : nz * fs1 - nx * fs3;
    b.moment[2][i] = gone ? 0.0 : nx * fs2 - ny * fs1;
    if (Tally) {
      // k_N = dP/d(delta) (jkr::normal_stiffness, docs/theory.md §1.5); where the law used no
      // k_T this step (peeling, the setup pass), k_T = 8 G* a_T of the micro-slip radius
      // (law::micro_slip_radius, §2.2)
      const double rsq = b.rsq[i];
      const double k_N = jkr::normal_stiffness(a, R, c.E_star, c.Gamma);
      const law::NormalLoad<double> load = law::normal_load<Adhesive>(k, R, P);
      const double a_T = law::micro_slip_radius<Adhesive>(k, R, a, load);
      const double k_T = k_T_law >= 0.0 ? k_T_law : 8.0 * c.G_star * a_T;
      affine_principal_entries(nx, ny, nz, rsq, k_N, k_T, [&](int m, double entry) {
        b.affine_stiffness[m][i] = gone ? 0.0 : entry;
      });
      b.force_magnitude[i] = gone ? 0.0 : std::sqrt(fx * fx + fy * fy + fz * fz);
      b.normal_stiffness[i] = gone ? 0.0 : k_N;
      b.tangential_stiffness[i] = gone ? 0.0 : k_T;
    }
  }

  // lane i of the batch as the law's lanes (contact_law.hpp)
  [[gnu::always_inline]] inline law::History<double> lane_history(const ContactBatch &b, int i)
  {
    law::History<double> h;
#define TYCORE_LANE_FIELD(name, values, carried, from_j, meaning) \
  for (int k = 0; k < values; ++k) history::value(h.name, k) = batch_value(b.name, k)[i];
    TYCORE_HISTORY_FIELDS(TYCORE_LANE_FIELD)
#undef TYCORE_LANE_FIELD
    return h;
  }

  // the law's step back into lane i: its new history and outputs, or where the lane separated at
  // the break overlap this step (touch_or_break) a cleared history and zeros
  [[gnu::always_inline]] inline void store_lane(ContactBatch &b, int i,
                                                const law::History<double> &h,
                                                const law::Outputs<double> &out, bool gone)
  {
#define TYCORE_STORE_LANE_FIELD(name, values, carried, from_j, meaning) \
  for (int k = 0; k < values; ++k)                                      \
    batch_value(b.name, k)[i] = gone ? 0.0 : history::value(h.name, k);
    TYCORE_HISTORY_FIELDS(TYCORE_STORE_LANE_FIELD)
#undef TYCORE_STORE_LANE_FIELD
    b.P[i] = gone ? 0.0 : out.P;
    b.contact_radius[i] = gone ? 0.0 : out.a;
    b.dissipation[i] = gone ? 0.0 : out.dissipation;
  }

  // the scalar build of the law: law::scalar_step lane after lane; returns the k_T the law used,
  // or -1
  template <bool Adhesive>
  inline double scalar_lane(ContactBatch &b, int i, const PairConstants &k, double dt)
  {
    law::History<double> h = lane_history(b, i);
    const double n[3] = {b.n[0][i], b.n[1][i], b.n[2][i]};
    const double ds[3] = {-b.vt[0][i] * dt, -b.vt[1][i] * dt, -b.vt[2][i] * dt};
    const law::Outputs<double> out = law::scalar_step<Adhesive>(k, b.R[i], b.Rinv[i], b.delta[i], n,
                                                                0.5 * dt * b.spin_n[i], ds, h);
    store_lane(b, i, h, out, b.broken[i] != 0.0);
    return out.stiffness;
  }

#ifdef TYCORE_VECTOR_BUILDS
// the vector builds, contact_batch.cpp (declared with the instruction set they are built for)
#define TYCORE_AVX512 "avx512f,avx512dq,avx512vl"
  template <bool Adhesive, bool Damped>    // the x86-64 baseline, SSE2
  void advance_batch_sse2(ContactBatch &, int, const PairConstants &, const BatchParameters &);
  template <bool Adhesive, bool Damped>
  __attribute__((target("avx2"))) void
  advance_batch_avx2(ContactBatch &, int, const PairConstants &, const BatchParameters &);
  template <bool Adhesive, bool Damped>
  __attribute__((target(TYCORE_AVX512))) void
  advance_batch_avx512(ContactBatch &, int, const PairConstants &, const BatchParameters &);
#endif

}    // namespace detail

// One step of contacts 0 .. n-1 of the batch (n <= batch_lanes), all of the material pair k:
// inputs and history as documented in ContactBatch, outputs filled. Lanes with first_touch
// start their history here; lanes that separate come back with broken = 1 and a cleared
// history (the caller forgets the contact). `isa` chooses the build (default: the widest this
// processor runs).
template <bool Adhesive, bool Damped>
inline void advance_batch(ContactBatch &b, int n, const PairConstants &k, const BatchParameters &p,
                          Isa isa = best_isa())
{
  switch (isa) {
#ifdef TYCORE_VECTOR_BUILDS
    case Isa::avx512:
      detail::advance_batch_avx512<Adhesive, Damped>(b, n, k, p);
      break;
    case Isa::avx2:
      detail::advance_batch_avx2<Adhesive, Damped>(b, n, k, p);
      break;
    case Isa::sse2:
      detail::advance_batch_sse2<Adhesive, Damped>(b, n, k, p);
      break;
#endif
    default:    // Isa::scalar, and every isa in a build without the vector builds
      detail::touch_or_break<Adhesive>(b, n, k);
      for (int i = 0; i < n; ++i) {
        const double k_T = detail::scalar_lane<Adhesive>(b, i, k, p.dt);
        if (p.tally)
          detail::lane_outputs<Adhesive, Damped, true>(b, i, k, p, k_T);
        else
          detail::lane_outputs<Adhesive, Damped, false>(b, i, k, p, k_T);
      }
      if (p.energy) detail::stored_energies(b, n, k);
      break;
  }
  for (int i = 0; i < n; ++i) b.slides[i] = b.sliding[i];
}

// The forces of contacts 0 .. n-1 without a step of their history: the setup pass of a run,
// which recomputes the forces at unchanged positions. First touch and separation as in
// advance_batch (touch_or_break); a contact touched here for the first time is there at its
// overlap before the run's first step, pressed without tangential displacement
// (docs/theory.md §1.3): the law's step onto that overlap with ds = 0 lays its memory over the
// overlap at slope 0 (§2.3), so that the first step finds the springs in contact (stiffness
// 8G*a) rather than taking the whole overlap as entering with that step's displacement. It adds
// no force and dissipates nothing. Otherwise the history is kept: P and a at the overlap by the
// law (normal_contact: its iteration warm-started from the kept radius), the kept T, damping and
// tallies as after a step, sliding judged under the mu in force now (slides_without_step,
// docs/theory.md §2). Nothing is dissipated (dissipation, damping_dissipation and break_energy are
// 0). Scalar only, once per run.
template <bool Adhesive, bool Damped>
inline void forces_without_step(ContactBatch &b, int n, const PairConstants &k,
                                const BatchParameters &p)
{
  detail::touch_or_break<Adhesive>(b, n, k);
  for (int i = 0; i < n; ++i) {
    ContactHistory h = stored_history(b, i);
    const double R = b.R[i], delta = b.delta[i];
    double a = 0.0, P = 0.0;
    if (b.broken[i] == 0.0 && b.first_touch[i]) {
      const double normal_dir[3] = {b.n[0][i], b.n[1][i], b.n[2][i]}, none[3] = {0.0, 0.0, 0.0};
      double dissipation = 0.0;    // stays 0: no tangential displacement, no stored energy
      const KernelResult normal =
          advance_contact<Adhesive>(k, R, delta, normal_dir, 0.0, none, h, dissipation);
      load_history(b, i, h);
      a = normal.contact_radius;
      P = normal.P;
    } else if (b.broken[i] == 0.0) {
      const KernelResult normal = normal_contact<Adhesive>(k, R, delta, h.radius);
      a = normal.contact_radius;
      P = normal.P;
    }
    b.contact_radius[i] = a;
    b.P[i] = P;
    b.slides[i] = b.broken[i] == 0.0 && slides_without_step(k, R, P, h) ? 1.0 : 0.0;
    b.dissipation[i] = 0.0;
    if (p.tally)
      detail::lane_outputs<Adhesive, Damped, true>(b, i, k, p, -1.0);
    else
      detail::lane_outputs<Adhesive, Damped, false>(b, i, k, p, -1.0);
    b.damping_dissipation[i] = 0.0;
    b.break_energy[i] = 0.0;
  }
  if (p.energy) detail::stored_energies(b, n, k);
}

// The normal part Fn (along n) and tangential part fs of the force lane `lane` applied in
// the last advance_batch or forces_without_step, viscous damping included (for the contact
// records of the computes; advance_batch keeps only their sum)
template <bool Damped>
inline void force_parts(const ContactBatch &b, int lane, const PairCoefficients &c,
                        const BatchParameters &p, double &Fn, double fs[3])
{
  detail::damped_force<Damped>(b, lane, c, p, Fn, fs);
}

}    // namespace tycore

#endif
