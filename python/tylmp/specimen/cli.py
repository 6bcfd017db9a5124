"""python3 -m tylmp.specimen: a specimen as a LAMMPS data file from the command line."""

import argparse

from .data_file import write_data
from .packing import generate
from .paper import DENSITY, PHI_PAPER, SCALES
from .sizes import DISTRIBUTIONS, describe_distributions, parse_distribution


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="python3 -m tylmp.specimen",
        description="Random contact-free periodic sphere assembly (Thornton's specimen) "
                    "as a LAMMPS data file (units si, atom_style sphere).")
    ap.add_argument("--n", type=int, default=None,
                    help="number of spheres (default: from --scale; paper 3620)")
    ap.add_argument("--scale", choices=sorted(SCALES), default="paper",
                    help="paper: 3620 spheres; quick: 500 spheres, same distribution")
    ap.add_argument("--out", default="specimen.data", help="data file to write")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--solid-fraction", type=float, default=PHI_PAPER)
    ap.add_argument("--density", type=float, default=DENSITY,
                    help="particle density [kg/m^3] (default 2650e12, paper's scaling)")
    ap.add_argument("--gap", type=float, default=1e-6,
                    help="minimum relative gap between surfaces (default 1e-6)")
    ap.add_argument("--distribution", default=None,
                    help="size distribution: a candidate (" + ", ".join(sorted(DISTRIBUTIONS))
                         + "; default maxent), uniform:D_MIN:D_MAX, lognormal:D50:SIGMA, "
                         "number:FILE or mass:FILE (docs/specimen.md)")
    ap.add_argument("--mean-only", action="store_true",
                    help="max-entropy distribution constrained by the mean diameter only "
                         "(= --distribution mean-only)")
    ap.add_argument("--distributions", action="store_true",
                    help="print the candidate size distributions for n spheres (markdown table) "
                         "and exit")
    args = ap.parse_args(argv)
    n = args.n if args.n is not None else SCALES[args.scale]
    if args.distributions:
        print(describe_distributions(n))
        return 0
    if not 0.0 < args.solid_fraction < 0.6:
        ap.error("--solid-fraction must be in (0, 0.6)")
    if args.mean_only and args.distribution not in (None, "mean-only"):
        ap.error(f"--mean-only contradicts --distribution {args.distribution}")
    try:
        parse_distribution(args.distribution)
    except ValueError as err:
        ap.error(str(err))
    L, diam, pos, info = generate(n, args.solid_fraction, seed=args.seed,
                                  match_cell=not args.mean_only, gap=args.gap,
                                  return_info=True, distribution=args.distribution)
    write_data(args.out, L, diam, pos, density=args.density)
    ds = info["size_diameters"]
    print(f"wrote {args.out}: {n} spheres, cube side {L * 1e3:.6f} mm, "
          f"solid fraction {info['solid_fraction']:.12f}, "
          f"mean diameter {diam.mean() * 1e3:.12f} mm, seed {args.seed}")
    if len(ds) <= 20:
        print("sizes [mm] / counts: " + ", ".join(
            f"{d * 1e3:.6f}:{c}" for d, c in zip(ds, info["counts"])))
    else:
        print(f"{len(ds)} sizes from {diam.min() * 1e3:.6f} to {diam.max() * 1e3:.6f} mm")
    print(f"RSA at solid fraction {info['rsa_solid_fraction']:.3f} "
          f"(side {info['rsa_box_side'] * 1e3:.4f} mm), {info['compress_steps']} "
          f"compression steps, {info['relax_iterations']} relaxation sweeps, "
          f"{info['time']:.2f} s")
    return 0
