"""The oracle of the six-component stiffness at the LAMMPS level (docs/theory.md §11.1, §12):
equal Hertz–Mindlin spheres (pair thornton/yin with Γ = 0) on a face-centred cubic lattice built
by LAMMPS (`lattice fcc` + create_atoms) in a triclinic box, touching their 12 neighbours with
the relative overlap x that gives p ≈ 1 MPa. The lattice is frozen (no integrator fix: the atoms
only move with the box, which fix cell/servo `axes` holds at rate 0 on all six components), and
the fix's global array f_ID[I][J], the 6x6 affine stiffness its servo uses, must equal the closed
form of §12,

    C11 = K0 (1 + κ),  C12 = K0 (1 − κ)/2,  C44 = K0 (1 + κ)/2,  K0 = √2 E* √x/(1 − x),
    κ = k_T/k_N = 4G*/E* = 2(1 − ν)/(2 − ν),

to 1e-6 relative (of C11) in every entry, in the cube frame (in a box with zero tilts and in one
whose three tilts are one lattice constant each) and in a frame turned by 45° about z
(`orient x 1 1 0 y -1 1 0`), where the cubic tensor transforms to C'11 = (C11 + C12)/2 + C44,
C'12 = (C11 + C12)/2 − C44, C'66 = (C11 − C12)/2 (the standard rotation of a cubic tensor).
The stress the fix measures is checked against p = (4√2/3) E* x^{3/2}/(1 − x)² as well.
The 1e-6 bound: the lattice positions are exact to round-off (1e-16 of the spacing), i.e. 2e-13
relative in the overlap of 5.8e-4; the tallies are sums of a few thousand like terms. A missing
tangential part (κ) or a missing shear block moves entries by O(1).
"""
import math

import numpy as np
import pytest

from cellspec import E, HEADER, NU, RHO, bisect, effective_modulus
from lmprun import LOAD_TYLMP, run_ok

P_TARGET = 1e6          # Pa
R = 1e-4                # m
N_CELLS = 3             # conventional cells per edge (108 spheres; 4 x 108 in the turned frame)


def relative_overlap(p, e_star):
    """x with (4√2/3) E* x^{3/2}/(1 − x)² = p (theory §12)."""
    return bisect(lambda x: 4.0 * math.sqrt(2.0) / 3.0 * e_star * x ** 1.5 / (1.0 - x) ** 2 - p,
                  1e-12, 0.1)


def closed_form(x, e_star, kappa):
    k0 = math.sqrt(2.0) * e_star * math.sqrt(x) / (1.0 - x)
    c11, c12, c44 = k0 * (1 + kappa), 0.5 * k0 * (1 - kappa), 0.5 * k0 * (1 + kappa)
    return c11, c12, c44


def cubic_voigt(c11, c12, c44):
    C = np.zeros((6, 6))
    C[:3, :3] = c12
    np.fill_diagonal(C[:3, :3], c11)
    C[3, 3] = C[4, 4] = C[5, 5] = c44
    return C


def turned_45_about_z(c11, c12, c44):
    """The cubic tensor in axes turned by 45° about z, Voigt6 xx yy zz xy xz yz with engineering
    shears: C'11 = C'22 = (C11 + C12)/2 + C44, C'12 = (C11 + C12)/2 − C44, C'13 = C'23 = C12,
    C'33 = C11, C'xy = (C11 − C12)/2, C'xz = C'yz = C44."""
    a, b = 0.5 * (c11 + c12) + c44, 0.5 * (c11 + c12) - c44
    C = np.array([[a, b, c12, 0, 0, 0], [b, a, c12, 0, 0, 0], [c12, c12, c11, 0, 0, 0],
                  [0, 0, 0, 0.5 * (c11 - c12), 0, 0], [0, 0, 0, 0, c44, 0],
                  [0, 0, 0, 0, 0, c44]])
    return C


def lattice_deck(spacing, orient, tilt=0):
    lines = "\n".join(f'print "C{i} ' + " ".join(f"$(f_cell[{i}][{j}]:%.17g)" for j in range(1, 7))
                      + '"' for i in range(1, 7))
    return HEADER + f"""lattice fcc {spacing!r} {orient}
region box prism 0 {N_CELLS} 0 {N_CELLS} 0 {N_CELLS} {tilt} {tilt} {tilt} units lattice
create_box 1 box
create_atoms 1 box
set atom * diameter {2 * R!r} density {RHO}
""" + LOAD_TYLMP + f"""pair_style thornton/yin
pair_coeff * * {E} {NU} 0.3 0.0
neighbor 2e-5 bin
timestep 0.02
# frozen: no integrator; the box held at zero rate on all six components
fix cell all cell/servo axes x rate 0 y rate 0 z rate 0 xy rate 0 xz rate 0 yz rate 0
run 1
print "N $(atoms) $(vol:%.17g)"
print "S $(f_cell[7]:%.17g) $(f_cell[8]:%.17g) $(f_cell[9]:%.17g)"
{lines}
"""


def parse(out):
    C = np.zeros((6, 6))
    n = volume = None
    sig = None
    for line in out.splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "N" and len(parts) == 3:
            n, volume = int(parts[1]), float(parts[2])
        elif parts[0] == "S" and len(parts) == 4:
            sig = np.array([float(v) for v in parts[1:]])
        elif len(parts) == 7 and parts[0] in {f"C{i}" for i in range(1, 7)}:
            C[int(parts[0][1]) - 1] = [float(v) for v in parts[1:]]
    return n, volume, sig, C


@pytest.mark.parametrize("frame", ["cube", "turned", "tilted"])
def test_fcc_lattice_stiffness_equals_closed_form(frame, tmp_path):
    e_star = effective_modulus()
    kappa = 2.0 * (1.0 - NU) / (2.0 - NU)
    x = relative_overlap(P_TARGET, e_star)
    spacing = 2.0 * R * (1.0 - x) * math.sqrt(2.0)     # cube edge: nearest neighbours at a/√2
    orient = "" if frame == "cube" else "orient x 1 1 0 orient y -1 1 0 orient z 0 0 1"
    # tilted: the cube frame in a box whose tilts xy, xz, yz are one lattice constant each (the
    # same lattice of images): the branch vectors across the tilted boundaries must come out
    # the same
    out = run_ok(lattice_deck(spacing, orient, 1 if frame == "tilted" else 0), tmp_path)
    n, volume, sig, C = parse(out)
    # a complete lattice: 4 grains per conventional cell volume a^3
    assert n == round(4 * volume / spacing ** 3) and n >= 108
    c11, c12, c44 = closed_form(x, e_star, kappa)
    expected = cubic_voigt(c11, c12, c44) if frame == "cube" else turned_45_about_z(c11, c12, c44)
    print(f"{frame}: x = {x:.6g}, C11 = {c11:.6g} Pa, C12 = {c12:.6g}, C44 = {c44:.6g}")
    print("fix array / closed form - 1 (of C11):\n", (C - expected) / c11)
    # the measured stress: isotropic p of §12 (sig1..3 are the fix's outputs 7-9)
    p_closed = 4.0 * math.sqrt(2.0) / 3.0 * e_star * x ** 1.5 / (1.0 - x) ** 2
    assert np.max(np.abs(sig / p_closed - 1.0)) < 1e-6, (sig, p_closed)
    assert np.max(np.abs(C - expected)) / c11 < 1e-6


def test_drained_shear_tallies_the_two_entries_its_servo_uses(tmp_path):
    """Drained simple shear in xz holds sigma_zz alone: its servo inverts C_33 and feeds forward
    C_35 (γ̇_xz), and only these two of the 21 sums are tallied. On the cube lattice they are
    C11 and 0 of the closed form; every other entry of f_ID[I][J] reads NaN (not measured)."""
    e_star = effective_modulus()
    kappa = 2.0 * (1.0 - NU) / (2.0 - NU)
    x = relative_overlap(P_TARGET, e_star)
    spacing = 2.0 * R * (1.0 - x) * math.sqrt(2.0)
    deck = lattice_deck(spacing, "").replace(
        "fix cell all cell/servo axes x rate 0 y rate 0 z rate 0 xy rate 0 xz rate 0 yz rate 0",
        f"fix cell all cell/servo shear xz 1e-9 {P_TARGET!r}")
    assert "shear xz" in deck
    _, _, _, C = parse(run_ok(deck, tmp_path))
    c11 = closed_form(x, e_star, kappa)[0]
    held = {(2, 2), (2, 4), (4, 2)}
    assert abs(C[2, 2] / c11 - 1.0) < 1e-5, C[2, 2]
    assert abs(C[2, 4]) / c11 < 1e-6 and C[4, 2] == C[2, 4]
    assert all(np.isnan(C[i, j]) for i in range(6) for j in range(6) if (i, j) not in held)
