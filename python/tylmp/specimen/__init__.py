"""Specimen generator for Thornton's periodic-cell tests (random, contact-free sphere packs).

The paper's assembly: 3620 elastic spheres of five sizes, smallest diameter 0.135 mm,
largest 0.4 mm, number-mean diameter 0.26 mm, randomly generated in a cubic periodic
cell of side 4.3 mm with a solid fraction of ca. 0.5 and no interparticle contacts
(notional density 2650 kg/m^3 scaled by 1e12).  The paper gives no counts per size;
the choice made here (see docs/specimen.md) is the *maximum-entropy* number
distribution on five evenly spaced diameters subject to every number the paper states:
the number mean 0.26 mm and the mean cube of the diameter implied by 3620 spheres at
solid fraction 0.5 in a 4.3 mm cube.

Positions: random sequential addition (RSA, largest spheres first, cell list) in a
box enlarged to a low solid fraction where RSA cannot jam, then an overlap-free
isotropic compression to the target solid fraction (affine shrink steps, each followed
by iterative removal of overlaps).  The result has the exact target solid fraction,
no overlaps (also across the periodic faces) and is deterministic for a given seed.

All lengths are SI (metres); the data file is for ``units si`` / ``atom_style sphere``.

Modules: paper (the paper's numbers), sizes (size distributions), packing (positions,
overlaps), data_file (the LAMMPS data file), cli (the command line); this package holds
their public names.

Python use::

    from tylmp import specimen
    d, frac = specimen.paper_size_distribution()
    L, diam, pos = specimen.generate(3620, 0.5, seed=1)
    specimen.write_data("specimen.data", L, diam, pos)

Command line::

    python3 -m tylmp.specimen --n 3620 --out specimen.data [--seed 1]
        [--solid-fraction 0.5] [--scale quick|paper] [--density 2650e12]
        [--distribution maxent|uniform:D_MIN:D_MAX|lognormal:D50:SIGMA|number:FILE|mass:FILE]
"""

from . import data_file, packing, paper, sizes
from .cli import main
from .data_file import read_data, write_data
from .packing import find_overlaps, generate
from .paper import D_MAX, D_MEAN, D_MIN, DENSITY, L_PAPER, N_PAPER, PHI_PAPER, SCALES
from .sizes import (DISTRIBUTIONS, NAMED, TABLES, SizeDistribution, box_side,
                    describe_distributions, diameters, number_mean, paper_size_distribution,
                    parse_distribution, read_size_table, size_counts, solid_fraction,
                    user_distribution, volume_mean)

__all__ = [
    "D_MIN", "D_MAX", "D_MEAN", "N_PAPER", "L_PAPER", "PHI_PAPER", "DENSITY",
    "SCALES", "DISTRIBUTIONS", "paper_size_distribution", "size_counts", "box_side",
    "solid_fraction", "number_mean", "volume_mean", "describe_distributions",
    "generate", "find_overlaps", "write_data", "read_data", "main",
    "NAMED", "TABLES", "SizeDistribution", "parse_distribution", "user_distribution",
    "read_size_table", "diameters",
]

# the modules whose code makes a specimen (the decks' specimen cache is keyed on it,
# tylmp.decks.cache.prep_key)
GENERATOR_MODULES = (paper, sizes, packing, data_file)
