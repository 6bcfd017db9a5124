// Kernel-level benchmark of the contact law (plugin/core/contact_law.hpp): ns per contact-step
// of its scalar entry tycore::advance_contact called contact after contact, and the batch
// entry tycore::advance_batch
// (plugin/core/contact_batch.hpp) in each build this processor runs (scalar, sse2, avx2,
// avx512), its structure-of-arrays batch filled from and written back to the contacts'
// histories as a pair would. Pure C++, no LAMMPS, no memory traffic beyond the contacts' own
// state: it isolates the arithmetic, latency and overlap of the kernel.
//
//   cmake -S . -B build -DTYLMP_BENCH=ON && cmake --build build --target bench_kernel_batch
//   ./build/bench_kernel_batch
//
// 4096 independent contacts of the glass pair (E = 70 GPa, nu = 0.3, mu = 0.3, R* = 0.065 mm)
// at overlaps around 2e-7 m (100 kPa in the paper's specimen), random normals and tangential
// increments of 1e-10 m per step, after 50 warm-up steps; three scenes: Hertz-Mindlin
// (Gamma = 0, contacts in micro-slip), adhesive in micro-slip, adhesive while peeling
// (Gamma = 0.6 J/m^2, the state of contacts formed under adhesion in a static packing). Every
// variant restarts from the same states; median of 201 timings of one sweep over all contacts.
#include "contact_batch.hpp"
#include "contact_kernel.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace tycore;

namespace {

struct Scene {
  const char* name;
  double Gamma;
  bool peeling;
};

constexpr int kContacts = 4096, kRepeats = 201;
constexpr double kR = 6.5e-5;

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

template <bool Adhesive>
void run_scene(const Scene& scene)
{
  const double E = 70e9, nu = 0.3;
  const PairCoefficients c{effective_modulus(E, nu, E, nu), effective_shear_modulus(E, nu, E, nu),
                           0.3, scene.Gamma};
  const PairConstants k = pair_constants(c);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<ContactHistory> start(kContacts);
  std::vector<double> delta(kContacts), n(3 * kContacts), ds(3 * kContacts), twist(kContacts);
  for (int i = 0; i < kContacts; ++i) {
    delta[i] = std::max(2e-7 * (1.0 + 0.5 * g(rng)), 1e-8);
    Eigen::Vector3d nn(g(rng), g(rng), g(rng));
    nn.normalize();
    Eigen::Vector3d s(g(rng), g(rng), g(rng));
    s = 1e-10 * (s - s.dot(nn) * nn);
    for (int d = 0; d < 3; ++d) n[3 * i + d] = nn[d], ds[3 * i + d] = s[d];
    twist[i] = 1e-5 * g(rng);
    const double a = jkr::contact_radius(delta[i], kR, c.E_star, c.Gamma);
    begin_contact(start[i], scene.peeling);
    start[i].radius = a;
    double lost = 0.0;
    for (int step = 0; step < 50; ++step)
      advance_contact<Adhesive>(k, kR, delta[i], &n[3 * i], twist[i], &ds[3 * i], start[i], lost);
  }

  std::vector<ContactHistory> h;
  double sink = 0.0;
  const auto time_sweep = [&](auto&& sweep) {
    std::vector<double> t;
    for (int rep = 0; rep < kRepeats; ++rep) {
      h = start;
      const auto t0 = std::chrono::steady_clock::now();
      sweep();
      const auto t1 = std::chrono::steady_clock::now();
      t.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / kContacts);
    }
    return median(t);
  };

  const double sequential = time_sweep([&] {
    double lost = 0.0;
    for (int i = 0; i < kContacts; ++i)
      sink += advance_contact<Adhesive>(k, kR, delta[i], &n[3 * i], twist[i], &ds[3 * i], h[i],
                                        lost).P;
  });
  std::printf("%-28s fused, one contact at a time %6.1f ns", scene.name, sequential);
  std::printf("\n%-28s", "");
  // the batch entry: dt = 2 makes twist = spin_n and ds = -2 vt exact
  BatchParameters p;
  p.dt = 2.0;
  ContactBatch b{};
  for (Isa isa : {Isa::scalar, Isa::sse2, Isa::avx2, Isa::avx512}) {
    if (!isa_supported(isa)) continue;
    const double entry = time_sweep([&] {
      for (int i0 = 0; i0 < kContacts; i0 += batch_lanes) {
        for (int l = 0; l < batch_lanes; ++l) {
          const int i = i0 + l;
          load_history(b, l, h[i]);
          for (int d = 0; d < 3; ++d) {
            b.n[d][l] = n[3 * i + d];
            b.vt[d][l] = -0.5 * ds[3 * i + d];
          }
          b.delta[l] = delta[i];
          b.R[l] = kR;
          b.Rinv[l] = 1.0 / kR;
          b.spin_n[l] = twist[i];
          b.first_touch[l] = false;
        }
        advance_batch<Adhesive, false>(b, batch_lanes, k, p, isa);
        for (int l = 0; l < batch_lanes; ++l) {
          h[i0 + l] = stored_history(b, l);
          sink += b.force[0][l];
        }
      }
    });
    std::printf("   advance_batch %-6s %6.1f ns", isa_name(isa), entry);
  }
  std::printf("\n");
  if (sink == 42.0) std::printf(" ");
}

}    // namespace

int main()
{
  std::printf("ns per contact-step, median of %d sweeps over %d contacts\n", kRepeats, kContacts);
  run_scene<false>(Scene{"Hertz-Mindlin, micro-slip", 0.0, false});
  run_scene<true>(Scene{"adhesive, micro-slip", 0.6, false});
  run_scene<true>(Scene{"adhesive, peeling", 0.6, true});
  return 0;
}
