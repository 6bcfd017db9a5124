"""Shared pieces of the fix cell/servo tests: deck fragments and the CSV reader.

Conventions of fix cell/servo (docs/fix_cell_servo.md): compression positive stresses and
natural strains eps_i = -ln(L_i/L_i0); the CSV has a header line of comma-separated names.
"""
import numpy as np

from lmprun import LOAD_TYLMP

E, NU, RHO = 70e9, 0.3, 2650e12     # Pa, -, kg/m^3 (density scaled by 1e12, time by 1e6)
DT = 0.02                           # s (scaled), ~0.2 Rayleigh step for R = 0.1 mm

HEADER = """units si
atom_style sphere
atom_modify map array
boundary p p p
comm_modify vel yes
newton on
"""

# 216 spheres, d in [0.2, 0.26] mm, on a loose simple-cubic lattice
LATTICE_SPECIMEN = HEADER + """lattice sc 2.8e-4
region box block 0 6 0 6 0 6
create_box 1 box
create_atoms 1 box
variable d atom 2.0e-4+6e-5*(0.6180339887*id-floor(0.6180339887*id))
set atom * diameter v_d density {rho}
""".format(rho=RHO) + LOAD_TYLMP


def restart_deck(restart, mu=0.3, gamma=0.6):
    """Lines that continue from the prepared specimen with friction mu and surface energy gamma."""
    return (LOAD_TYLMP + f"read_restart {restart}\n"
            "comm_modify vel yes\n"
            "neighbor 2e-5 bin\n"
            f"pair_coeff * * {E} {NU} {mu} {gamma}\n"
            f"timestep {DT}\n"
            "fix nve all nve/sphere\n")


def read_csv(path):
    """The fix's CSV -> dict of column arrays."""
    with open(path) as fh:
        names = fh.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, k] for k, name in enumerate(names)}


# ---- independent closed forms -------------------------------------------------------------

def effective_modulus(E=E, nu=NU):
    """E* of two equal spheres, 1/E* = 2 (1 - nu^2)/E."""
    return E / (2.0 * (1.0 - nu * nu))


def effective_shear_modulus(E=E, nu=NU):
    """G* of two equal spheres, 1/G* = 2 (2 - nu)/G, G = E/(2 (1 + nu))."""
    G = E / (2.0 * (1.0 + nu))
    return G / (2.0 * (2.0 - nu))


def hertz_force(delta, R_star, E_star):
    return 4.0 / 3.0 * E_star * np.sqrt(R_star) * max(delta, 0.0) ** 1.5


def bisect(fun, lo, hi, tol=1e-15, iters=300):
    flo = fun(lo)
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        fmid = fun(mid)
        if (fmid < 0) == (flo < 0):
            lo, flo = mid, fmid
        else:
            hi = mid
        if hi - lo <= tol * abs(hi):
            break
    return 0.5 * (lo + hi)


def pi_coordinates(v1, v2, v3):
    """Pi-plane (x, y) = ((v2 - v3)/sqrt2, (2 v1 - v2 - v3)/sqrt6) (docs/theory.md §7.2)."""
    return (np.asarray(v2) - v3) / np.sqrt(2.0), (2.0 * np.asarray(v1) - v2 - v3) / np.sqrt(6.0)
