"""fix cell/servo on a triclinic cell (docs/theory.md §10-13, docs/fix_cell_servo.md "The
six-component cell"): a principal programme on a triclinic cell with zero tilts is the
orthogonal cell's test (the shears idle, the servo the three-component one), and a held shear
stress gets the shear gains; a tilt flip while the cell stretches leaves the contact forces
alone."""
import numpy as np

from cellspec import read_csv
from lmprun import LOAD_TYLMP, run_deck, run_ok
from test_cell_servo import P0, shear_run, small_deck, specimen  # noqa: F401 (fixture)


def test_principal_programme_on_a_triclinic_cell_is_the_orthogonal_test(specimen, tmp_path):
    """Axisymmetric compression of the 216-sphere specimen, once on its orthogonal box and once
    after `change_box all triclinic` (tilts 0): the shears are idle, so the tilts stay 0, the
    shear strains are exactly 0, and the principal stresses and strains are those of the
    orthogonal test to round-off. (The triclinic box bins and wraps atoms in its own
    coordinates, which changes the order of the force sums; that round-off grows chaotically,
    here from 2e-15 of eps2 at step 30 to 1e-12 at step 40 and 1.5e-6 at step 300, so the
    comparison stops at step 60; under LAMMPS 4 Feb 2025 eps3 jumped from 1e-14 to 2.3e-11 (1.9e-8
    of its largest value) between steps 30 and 35 and then fell back, so the bound is 1e-7 of
    each quantity's largest value.)"""
    fix = f"fix c all cell/servo axisym x 1e-3 {P0} csv c.csv 5"
    ortho, tri = tmp_path / "ortho", tmp_path / "tri"
    ortho.mkdir(), tri.mkdir()
    shear_run(specimen, ortho, fix, 60)
    shear_run(specimen, tri, fix, 60, extra="change_box all triclinic\n")
    a, b = read_csv(ortho / "c.csv"), read_csv(tri / "c.csv")
    assert "gamma_xz" not in a and "gamma_xz" in b    # the record of a triclinic cell
    for k in ("gamma_xy", "gamma_xz", "gamma_yz", "rate_xy", "rate_xz", "rate_yz"):
        assert np.all(b[k] == 0.0), k
    assert np.array_equal(a["step"], b["step"])
    parted = [max(abs(a[k][row] - b[k][row]) / np.abs(a[k]).max() for k in ("sig1", "sig2", "sig3"))
              for row in (0, -1)]
    print(f"orthogonal against triclinic: the stresses differ by {parted[0]:.2g} at step 0, "
          f"{parted[1]:.2g} at step {a['step'][-1] - a['step'][0]:.0f}")
    for k in ("eps1", "eps2", "eps3", "sig1", "sig2", "sig3", "p", "q", "volume"):
        scale = np.abs(a[k]).max()
        assert np.abs(a[k] - b[k]).max() <= 1e-7 * scale, k
    # the principal values of the full stress bracket the axis stresses (a symmetric tensor's
    # diagonal lies within its eigenvalues), and p is the mean of either
    assert np.all(b["sig_major"] >= np.maximum(b["sig1"], np.maximum(b["sig2"], b["sig3"])) - 1e-6)
    assert np.all(b["sig_minor"] <= np.minimum(b["sig1"], np.minimum(b["sig2"], b["sig3"])) + 1e-6)
    assert np.allclose((b["sig_major"] + b["sig_inter"] + b["sig_minor"]) / 3, b["p"], rtol=1e-9)


def test_a_held_shear_stress_with_a_large_gain_is_warned_about(tmp_path):
    deck = small_deck(f"change_box all triclinic\nfix c all cell/servo axes x stress {P0} "
                      f"y stress {P0} z stress {P0} xz stress 0 gain 0.02 integral_gain 5e-5")
    rc, out = run_deck(deck, tmp_path)
    assert rc == 0, out[-2000:]
    # 0.02 is where the shear components start to ring (docs/decks/rotation.md)
    line = next(l for l in out.splitlines() if "WARNING" in l and "cell/servo" in l)
    assert "gain 0.02 on a held shear stress" in line and "use gain <= 0.015" in line, line
    # the default gains do not warn
    rc, out = run_deck(small_deck(f"change_box all triclinic\nfix c all cell/servo axes x "
                                  f"stress {P0} y stress {P0} z stress {P0} xz stress 0"),
                       tmp_path)
    assert rc == 0 and "held shear stress" not in out, out[-2000:]


# ---------------------------------------------------------------------------------------------
# A tilt flip while the cell also stretches (docs/theory.md §10.3): the flip replaces h by h M,
# and h_rate, from which the pair reads L = h_rate h^-1 for the affine contact velocity, must
# go to L h M with it. Under simple shear alone (L_xz only) L M^-1 = L, so a stale h_rate is
# invisible; with L_xx != 0 the pair would read L_xz + n L_xx (n the flip count) for the force
# evaluation after the flip.

FLIP_R, FLIP_DELTA0, FLIP_BOX, FLIP_DT = 1e-3, 1e-6, 7e-3, 1e-7     # as tests/test_triclinic_pair.py
FLIP_STEPS = 1000
FLIP_RATE = 0.9          # 1/s: L_xx = L_xz; the contact reaches about half of Mindlin's u*
FLIP_WINDOW = FLIP_RATE * FLIP_STEPS * FLIP_DT     # the change of xz/lx over the run


def stretching_cell(tilt):
    """Two spheres touching along z at the centre of a triclinic cell whose tilt xz starts at
    tilt * lx; no integrator: the atoms move with the cell (L_xx = L_xz = FLIP_RATE)."""
    centre = np.array([0.5 * (FLIP_BOX + tilt * FLIP_BOX), 0.5 * FLIP_BOX, 0.5 * FLIP_BOX])
    half = 0.5 * (2 * FLIP_R - FLIP_DELTA0)
    columns = ["step", "fx[1]", "fy[1]", "fz[1]", "xz", "lx"]
    defs = "".join(f"variable c{k} equal {c}\n" for k, c in enumerate(columns))
    line = " ".join(f"${{c{k}}}" for k in range(len(columns)))
    return f"""units si
atom_style sphere
atom_modify map array
boundary p p p
comm_modify vel yes
region box prism 0 {FLIP_BOX!r} 0 {FLIP_BOX!r} 0 {FLIP_BOX!r} 0 {tilt * FLIP_BOX!r} 0 units box
create_box 1 box
create_atoms 1 single {centre[0]!r} {centre[1]!r} {centre[2] - half!r} units box
create_atoms 1 single {centre[0]!r} {centre[1]!r} {centre[2] + half!r} units box
set atom * diameter {2 * FLIP_R!r} density 2650
{LOAD_TYLMP}pair_style thornton/yin
pair_coeff * * 70e9 0.3 0.3 0.0
neighbor 1e-5 bin
neigh_modify every 1 delay 0 check yes
timestep {FLIP_DT!r}
fix c all cell/servo axes x rate {-FLIP_RATE!r} y rate 0 z rate 0 xz rate {-FLIP_RATE!r}
{defs}fix out all print 1 "{line}" file out.txt screen no
run {FLIP_STEPS}
"""


def test_a_flip_of_a_stretching_cell_changes_no_contact_force(tmp_path):
    """The same contact in two cells that differ only by their tilt: one starts just below half
    a box length and flips half-way through the run, the other starts at -lx/4 and does not.
    The branch vector follows exp(L t) l0 in both, so the contact forces (its tangential force
    is all affine loading) agree to round-off across the flip. (With the refresh of h_rate at
    the flip left out, they part by 1.9e-4 of the force after the flip, and the pair warns that
    h_rate does not explain the box change.)"""
    runs = {}
    for name, tilt in (("flip", 0.5 - 0.5 * FLIP_WINDOW), ("reference", -0.25)):
        work = tmp_path / name
        work.mkdir()
        out = run_ok(stretching_cell(tilt), work)
        warnings = [l for l in out.splitlines()
                    if "WARNING" in l and "No fixes with time integration" not in l]
        assert not warnings, warnings
        runs[name] = np.loadtxt(work / "out.txt", ndmin=2)
    flip, ref = runs["flip"], runs["reference"]
    jumps = np.flatnonzero(np.diff(flip[:, 4]) < -0.5 * flip[1:, 5])
    assert len(jumps) == 1 and 0.3 * FLIP_STEPS < jumps[0] < 0.7 * FLIP_STEPS, jumps
    assert np.all(np.abs(np.diff(ref[:, 4])) < 1e-3 * FLIP_BOX)      # no flip there
    F, F_ref = flip[:, 1:4], ref[:, 1:4]
    tangential = np.abs(F_ref[:, 0]).max()        # the contact along z: x is tangential
    assert tangential > 0.05 * np.abs(F_ref[:, 2]).max()      # well loaded (mu P = 0.3 P)
    difference = np.abs(F - F_ref).max() / np.abs(F_ref).max()
    print(f"flip at step {flip[jumps[0] + 1, 0]:.0f}: |F - F_ref| <= {difference:.2g} |F|")
    assert difference < 1e-9
