// The SIMD layer of the contact law, chosen by measurement (docs/performance.md, "Seventh
// round"): the law's one text (plugin/core/contact_law.hpp) instantiated on explicit SIMD lane
// types -- std::experimental::native_simd<double> (bench/simd_layers/stdx_lanes.hpp), xsimd 8
// (xsimd_lanes.hpp) and, where its headers are found, Google Highway 1.0 (hwy_lanes.hpp) -- in
// a batch entry that follows the product's vector build stage for stage
// (bench/simd_layers/layer_batch.hpp), against the product's own builds of
// tycore::advance_batch: the auto-vectorised lane loops of this program's instruction set and
// the scalar build.
//
// One executable per instruction set, the layers' width being the compiler target's:
//   cmake -S . -B build -DTYLMP_BENCH=ON && cmake --build build --target bench_simd_layers
//   ./build/bench_simd_layers_avx512 check          # every layer bit for bit against the product
//   ./build/bench_simd_layers_avx512 time [sweeps]  # ns per contact, median of alternated sweeps
//   ./build/bench_simd_layers_avx2 count VARIANT SCENE SWEEPS   # for callgrind, see below
// (also _avx2, _sse2). count runs SWEEPS sweeps of one variant (auto, scalar, stdx, xsimd,
// highway) on one scene (hertz, adhesive, peeling); the batch steps alone go through
// tybench_batch_step, so that
//   valgrind --tool=callgrind --collect-atstart=no --toggle-collect='tybench_batch_step*' ...
// counts the instructions of the batch entry and nothing else (valgrind has no AVX-512).
//
// Scenes as bench/kernel_batch.cpp: 4096 independent contacts of the glass pair, overlaps
// around 2e-7 m, tangential increments of 1e-10 m per step, after 50 warm-up steps: Hertz-
// Mindlin (Gamma = 0, micro-slip), adhesive in micro-slip and adhesive while peeling
// (Gamma = 0.6 J/m^2). The check runs 40 further steps of every contact with overlaps that go
// up and down, increments that reverse and grow into gross sliding, large twists, and the
// damped law besides the undamped one, and compares every output and history value.
#include "simd_layers/stdx_lanes.hpp"
#include "simd_layers/xsimd_lanes.hpp"
#if __has_include(<hwy/highway.h>) && !defined(TYBENCH_NO_HWY)
#include "simd_layers/hwy_lanes.hpp"
#define TYBENCH_HAVE_HWY 1
#endif
#include "simd_layers/layer_batch.hpp"

#include "contact_kernel.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace tycore;

#ifndef TYBENCH_ISA
#error "TYBENCH_ISA (sse2, avx2 or avx512) names this build's instruction set"
#endif
#define TYBENCH_STR2(x) #x
#define TYBENCH_STR(x) TYBENCH_STR2(x)

using Entry = void (*)(ContactBatch&, int, const PairConstants&, const BatchParameters&);

// the batch steps that count mode measures (callgrind --toggle-collect='tybench_batch_step*':
// the call may go to a clone of it)
extern "C" [[gnu::noinline]] void tybench_batch_step(Entry entry, ContactBatch& b, int n,
                                                     const PairConstants& k,
                                                     const BatchParameters& p)
{
  entry(b, n, k, p);
}

namespace {

constexpr Isa kIsa = Isa::TYBENCH_ISA;
constexpr int kContacts = 4096;
constexpr double kR = 6.5e-5;

template <bool Adhesive, bool Damped>
void product_vector(ContactBatch& b, int n, const PairConstants& k,
                    const BatchParameters& p)
{
  advance_batch<Adhesive, Damped>(b, n, k, p, kIsa);
}
template <bool Adhesive, bool Damped>
void product_scalar(ContactBatch& b, int n, const PairConstants& k,
                    const BatchParameters& p)
{
  advance_batch<Adhesive, Damped>(b, n, k, p, Isa::scalar);
}

struct Variant {
  const char* name;
  int width;
  Entry entry[2][2];    // [Adhesive][Damped]
};

template <class Layer> Variant layer_variant()
{
  return Variant{Layer::name,
                 Layer::width,
                 {{tybench::layer_batch<Layer, false, false>,
                   tybench::layer_batch<Layer, false, true>},
                  {tybench::layer_batch<Layer, true, false>,
                   tybench::layer_batch<Layer, true, true>}}};
}

std::vector<Variant> variants()
{
  std::vector<Variant> v{
      Variant{"auto", -1, {{product_vector<false, false>, product_vector<false, true>},
                          {product_vector<true, false>, product_vector<true, true>}}},
      Variant{"scalar", 1, {{product_scalar<false, false>, product_scalar<false, true>},
                            {product_scalar<true, false>, product_scalar<true, true>}}},
      layer_variant<tybench::StdxLayer>(), layer_variant<tybench::XsimdLayer>()};
#ifdef TYBENCH_HAVE_HWY
  v.push_back(layer_variant<tybench::HwyLayer>());
#endif
  return v;
}

struct Scene {
  const char* name;
  double Gamma;
  bool peeling;
};
const Scene kScenes[] = {{"hertz", 0.0, false}, {"adhesive", 0.6, false}, {"peeling", 0.6, true}};

// the contacts of a scene after 50 warm-up steps (bench/kernel_batch.cpp)
struct Contacts {
  PairCoefficients c;
  PairConstants k;
  std::vector<ContactHistory> start;
  std::vector<double> delta, n, ds, twist;
};

Contacts make_contacts(const Scene& scene)
{
  const double E = 70e9, nu = 0.3;
  Contacts s;
  s.c = PairCoefficients{effective_modulus(E, nu, E, nu), effective_shear_modulus(E, nu, E, nu),
                         0.3, scene.Gamma};
  s.k = pair_constants(s.c);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g(0.0, 1.0);
  s.start.resize(kContacts);
  s.delta.resize(kContacts), s.n.resize(3 * kContacts), s.ds.resize(3 * kContacts);
  s.twist.resize(kContacts);
  for (int i = 0; i < kContacts; ++i) {
    s.delta[i] = std::max(2e-7 * (1.0 + 0.5 * g(rng)), 1e-8);
    Eigen::Vector3d nn(g(rng), g(rng), g(rng));
    nn.normalize();
    Eigen::Vector3d t(g(rng), g(rng), g(rng));
    t = 1e-10 * (t - t.dot(nn) * nn);
    for (int d = 0; d < 3; ++d) s.n[3 * i + d] = nn[d], s.ds[3 * i + d] = t[d];
    s.twist[i] = 1e-5 * g(rng);
    const double a = jkr::contact_radius(s.delta[i], kR, s.c.E_star, s.c.Gamma);
    begin_contact(s.start[i], jkr::normal_force(a, kR, s.c.E_star, s.c.Gamma), scene.peeling);
    s.start[i].radius = a;
    double lost = 0.0;
    for (int step = 0; step < 50; ++step)
      if (scene.Gamma > 0.0)
        advance_contact<true>(s.k, kR, s.delta[i], &s.n[3 * i], s.twist[i], &s.ds[3 * i],
                              s.start[i], lost);
      else
        advance_contact<false>(s.k, kR, s.delta[i], &s.n[3 * i], s.twist[i], &s.ds[3 * i],
                               s.start[i], lost);
  }
  return s;
}

// one step of every contact through `entry`, 16 lanes a batch, as a pair fills and empties
// the batches (dt = 2: twist = spin_n, ds = -2 vt exactly); `scale` varies the step for the
// check (1: the benchmark's step); `out` (if given) receives every output value of every batch
void sweep(Entry entry, const Contacts& s, std::vector<ContactHistory>& h, const BatchParameters& p,
           ContactBatch& b, double& sink, int step = 0, std::vector<double>* out = nullptr)
{
  for (int i0 = 0; i0 < kContacts; i0 += batch_lanes) {
    for (int l = 0; l < batch_lanes; ++l) {
      const int i = i0 + l;
      load_history(b, l, h[i]);
      double delta = s.delta[i], vt_scale = -0.5, twist = s.twist[i];
      if (step > 0) {    // the check's varied steps
        delta *= 1.0 + 0.3 * std::sin(0.7 * step + i);
        vt_scale *= std::cos(0.45 * step + 0.1 * i) * (1.0 + (step % 7) * (i % 5) * 20.0);
        if ((i + step) % 13 == 0) twist = 2e-3 * std::cos(i + step);
      }
      for (int d = 0; d < 3; ++d) {
        b.n[d][l] = s.n[3 * i + d];
        b.vt[d][l] = vt_scale * s.ds[3 * i + d];
      }
      b.delta[l] = delta;
      b.R[l] = kR;
      b.Rinv[l] = 1.0 / kR;
      b.spin_n[l] = twist;
      b.vn[l] = 1e-3 * std::sin(i + 0.3 * step);
      b.m_star[l] = 1e-9;
      b.first_touch[l] = false;
    }
    tybench_batch_step(entry, b, batch_lanes, s.k, p);
    for (int l = 0; l < batch_lanes; ++l) {
      h[i0 + l] = stored_history(b, l);
      sink += b.force[0][l];
      if (out) {
        const double values[] = {b.force[0][l], b.force[1][l], b.force[2][l], b.moment[0][l],
                                 b.moment[1][l], b.moment[2][l], b.P[l], b.contact_radius[l],
                                 b.dissipation[l], b.damping_dissipation[l], b.slides[l],
                                 b.broken[l], b.break_energy[l]};
        out->insert(out->end(), std::begin(values), std::end(values));
        const ContactHistory& hh = h[i0 + l];
        const double* raw = reinterpret_cast<const double*>(&hh);
        out->insert(out->end(), raw, raw + sizeof(hh) / sizeof(double));
      }
    }
  }
}

std::int64_t ulps(double a, double b)
{
  std::int64_t ia, ib;
  std::memcpy(&ia, &a, 8), std::memcpy(&ib, &b, 8);
  if (ia < 0) ia = INT64_MIN - ia;
  if (ib < 0) ib = INT64_MIN - ib;
  return ia > ib ? ia - ib : ib - ia;
}

// every layer and the scalar build against this ISA's auto-vectorised build, bit for bit
int check()
{
  static_assert(sizeof(ContactHistory) % sizeof(double) == 0, "history of doubles");
  const std::vector<Variant> all = variants();
  int failures = 0;
  for (const Scene& scene : kScenes) {
    const Contacts s = make_contacts(scene);
    const int adhesive = scene.Gamma > 0.0;
    for (int damped = 0; damped < 2; ++damped) {
      BatchParameters p;
      p.dt = 2.0, p.beta_n = damped ? 0.1 : 0.0, p.beta_t = damped ? 0.05 : 0.0;
      std::vector<std::vector<double>> result(all.size());
      long states[5] = {0, 0, 0, 0, 0};
      for (std::size_t v = 0; v < all.size(); ++v) {
        std::vector<ContactHistory> h = s.start;
        ContactBatch b{};
        double sink = 0.0;
        for (int step = 1; step <= 40; ++step) {
          sweep(all[v].entry[adhesive][damped], s, h, p, b, sink, step, &result[v]);
          if (v == 0)    // how much of the law the check goes through
            for (const ContactHistory& x : h)
              ++states[x.sliding != 0.0 ? 0 : x.peeling != 0.0 ? 1 : 2 + int(x.mode)];
        }
      }
      std::printf("%-9s %-8s lane-steps sliding %ld, peeling %ld, in micro-slip loading %ld, "
                  "unloading %ld, reloading %ld\n", scene.name, damped ? "damped" : "undamped",
                  states[0], states[1], states[2 + LOADING], states[2 + UNLOADING],
                  states[2 + RELOADING]);
      for (std::size_t v = 1; v < all.size(); ++v) {
        std::size_t differ = 0;
        std::int64_t worst = 0;
        for (std::size_t j = 0; j < result[0].size(); ++j)
          if (std::memcmp(&result[0][j], &result[v][j], 8) != 0)
            ++differ, worst = std::max(worst, ulps(result[0][j], result[v][j]));
        failures += differ != 0;
        std::printf("%-9s %-8s %-8s vs auto (%s): %zu of %zu values differ (max %lld ulp)\n",
                    scene.name, damped ? "damped" : "undamped", all[v].name,
                    TYBENCH_STR(TYBENCH_ISA),
                    differ, result[0].size(), (long long)worst);
      }
    }
  }
  std::printf(failures ? "check: DIFFERENCES\n" : "check: every layer bit for bit the product\n");
  return failures ? 1 : 0;
}

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// ns per contact-step, every variant's sweeps alternated (one of each in turn)
void time_all(int sweeps)
{
  const std::vector<Variant> all = variants();
  std::printf("ns per contact-step (%s build), median of %d alternated sweeps over %d contacts\n",
              TYBENCH_STR(TYBENCH_ISA), sweeps, kContacts);
  for (const Scene& scene : kScenes) {
    const Contacts s = make_contacts(scene);
    const int adhesive = scene.Gamma > 0.0;
    BatchParameters p;
    p.dt = 2.0;
    std::vector<std::vector<double>> t(all.size());
    std::vector<ContactHistory> h;
    ContactBatch b{};
    double sink = 0.0;
    for (int rep = 0; rep < sweeps; ++rep)
      for (std::size_t v = 0; v < all.size(); ++v) {
        h = s.start;
        const auto t0 = std::chrono::steady_clock::now();
        sweep(all[v].entry[adhesive][0], s, h, p, b, sink);
        const auto t1 = std::chrono::steady_clock::now();
        t[v].push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / kContacts);
      }
    std::printf("%-9s", scene.name);
    for (std::size_t v = 0; v < all.size(); ++v)
      std::printf("  %s %6.1f", all[v].name, median(t[v]));
    std::printf("\n");
    if (sink == 42.0) std::printf(" ");
  }
}

int count(const std::string& variant, const std::string& scene_name, int sweeps)
{
  for (const Variant& v : variants())
    for (const Scene& scene : kScenes)
      if (variant == v.name && scene_name == scene.name) {
        const Contacts s = make_contacts(scene);
        BatchParameters p;
        p.dt = 2.0;
        std::vector<ContactHistory> h;
        ContactBatch b{};
        double sink = 0.0;
        for (int rep = 0; rep < sweeps; ++rep) {
          h = s.start;
          sweep(v.entry[scene.Gamma > 0.0][0], s, h, p, b, sink);
        }
        std::printf("%s %s: %d sweeps of %d contacts (%.17g)\n", v.name, scene.name, sweeps,
                    kContacts, sink);
        return 0;
      }
  std::fprintf(stderr, "unknown variant or scene\n");
  return 2;
}

}    // namespace

int main(int argc, char** argv)
{
  const std::string mode = argc > 1 ? argv[1] : "check";
  std::printf("build %s:", TYBENCH_STR(TYBENCH_ISA));
  for (const Variant& v : variants())
    if (v.width > 0) std::printf(" %s (%d lanes)", v.name, v.width);
    else std::printf(" %s (the product's %s build)", v.name, TYBENCH_STR(TYBENCH_ISA));
#ifdef TYBENCH_HAVE_HWY
  std::printf(" [highway target %s]", hwy::TargetName(HWY_STATIC_TARGET));
#endif
  std::printf("\n");
  if (!isa_supported(kIsa)) {
    std::printf("this processor does not run the %s build\n", TYBENCH_STR(TYBENCH_ISA));
    return 0;
  }
  if (mode == "check") return check();
  if (mode == "time") {
    time_all(argc > 2 ? std::atoi(argv[2]) : 101);
    return 0;
  }
  if (mode == "count" && argc == 5) return count(argv[2], argv[3], std::atoi(argv[4]));
  std::fprintf(stderr, "usage: %s check | time [sweeps] | count VARIANT SCENE SWEEPS\n", argv[0]);
  return 2;
}
