"""A LIGGGHTS run's record as tyanalysis reads fix cell/servo's (inputs/liggghts/axisym.in).

LIGGGHTS has no fix cell/servo: its axisymmetric deck prints the raw state of the cell (edges,
the principal stresses of the pair virial, contact counts, the solid volume) with fix print.
`servo_record` turns that into the columns of a fix cell/servo record (io.SERVO_COLUMNS), each
by the definition the fix uses (docs/theory.md §7; docs/fix_cell_servo.md, the output
table), so that every figure and metric of the package reads a LIGGGHTS run as it reads a
LAMMPS one. Axis 1 is x. What LIGGGHTS does not expose (which contacts slide, the unbalanced
force, the inertial number) is NaN. LIGGGHTS 3.8's fix print writes nothing at step 0, so
the deck prints the starting edges on every row.
"""
import math

import numpy as np

from . import invariants as inv
from .io import SERVO_COLUMNS, Table, read_print_table

RAW_COLUMNS = ("step", "time", "lx", "ly", "lz", "sigx", "sigy", "sigz", "contact_ends",
               "n_none", "n_one", "atoms", "solid_volume", "lx0", "ly0", "lz0")


def servo_record(path):
    """The record of inputs/liggghts/axisym.in at `path` as a Table of io.SERVO_COLUMNS."""
    raw = read_print_table(path)
    raw.require(RAW_COLUMNS)
    edges = np.stack([raw["lx"], raw["ly"], raw["lz"]], axis=-1)
    start = np.stack([raw["lx0"], raw["ly0"], raw["lz0"]], axis=-1)    # the cell at step 0
    eps = -np.log(edges / start)                        # natural strains, compression positive
    sig = np.stack([raw["sigx"], raw["sigy"], raw["sigz"]], axis=-1)
    volume = np.prod(edges, axis=-1)
    solid = raw["solid_volume"]
    n, ends, n0, n1 = raw["atoms"], raw["contact_ends"], raw["n_none"], raw["n_one"]
    sx, sy = inv.pi_coordinates(sig)
    ex, ey = inv.pi_coordinates(eps)
    nan = np.full(len(raw), math.nan)
    columns = {
        "step": raw["step"], "time": raw["time"],
        "eps1": eps[:, 0], "eps2": eps[:, 1], "eps3": eps[:, 2],
        "eps_v": inv.volumetric_strain(eps), "eps_q": inv.deviatoric_strain(eps),
        "eps_d13": eps[:, 0] - eps[:, 2],
        "sig1": sig[:, 0], "sig2": sig[:, 1], "sig3": sig[:, 2],
        "p": inv.mean_stress(sig), "q": inv.deviatoric_stress(sig),
        "b": inv.b_value(sig), "lode_deg": inv.lode_angle_of(sig),
        "eta_LD": inv.lade_duncan_eta(sig), "sinphi": inv.sinphi(sig),
        "void_ratio": volume / solid - 1.0, "solid_fraction": solid / volume,
        "Z": ends / n, "Zm": (ends - n1) / (n - n0 - n1),
        "sliding_fraction": nan, "unbalanced": nan, "inertial_number": nan,
        "pi_x": sx, "pi_y": sy, "pi_ex": ex, "pi_ey": ey,
    }
    return Table({k: columns[k] for k in SERVO_COLUMNS}, path)
