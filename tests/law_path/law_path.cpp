// law_path: one contact of the Thornton-Yin law (plugin/core, its scalar entry
// tycore::advance_contact) driven through a prescribed history, for the oracle tests of the
// tangential law (tests/test_tangential_oracle.py, docs/theory.md §2.5).
//
//   law_path E_STAR G_STAR MU GAMMA R < path > forces
//
// Each input line is one step: the overlap delta and the tangential displacement increment
// (ds_y, ds_z) in the tangent plane of the fixed normal n = (1, 0, 0). The contact begins at the
// first line (tycore::begin_contact at zero normal force). Each output line: P, T_y, T_z, the
// sliding and peeling flags, the frictional dissipation of the step and the stored tangential
// energy (docs/theory.md §2.4), all with 17 significant digits.
#include "contact_kernel.hpp"
#include "contact_types.hpp"
#include "mindlin_deresiewicz.hpp"

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv)
{
  if (argc != 6) {
    std::fprintf(stderr, "usage: law_path E_STAR G_STAR MU GAMMA R < path\n");
    return 2;
  }
  const tycore::PairCoefficients c{std::atof(argv[1]), std::atof(argv[2]), std::atof(argv[3]),
                                   std::atof(argv[4])};
  const double R = std::atof(argv[5]);
  const bool adhesive = c.Gamma > 0.0;
  const tycore::PairConstants k = tycore::pair_constants(c);
  tycore::ContactHistory h;
  tycore::begin_contact(h, 0.0, adhesive);
  const double n[3] = {1.0, 0.0, 0.0};
  double delta, dsy, dsz;
  while (std::scanf("%lf %lf %lf", &delta, &dsy, &dsz) == 3) {
    const double ds[3] = {0.0, dsy, dsz};
    double dissipation = 0.0;
    const tycore::KernelResult r =
        adhesive ? tycore::advance_contact<true>(k, R, delta, n, 0.0, ds, h, dissipation)
                 : tycore::advance_contact<false>(k, R, delta, n, 0.0, ds, h, dissipation);
    std::printf("%.17g %.17g %.17g %g %g %.17g %.17g\n", r.P, h.T[1], h.T[2], h.sliding,
                h.peeling, dissipation, h.stored_energy);
  }
  return 0;
}
