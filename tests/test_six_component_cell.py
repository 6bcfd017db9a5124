"""fix cell/servo on a triclinic cell (docs/theory.md §10-13, docs/fix_cell_servo.md "The
six-component cell"): a principal programme on a triclinic cell with zero tilts is the
orthogonal cell's test (the shears idle, the servo the three-component one), and a held shear
stress gets the shear gains."""
import numpy as np

from cellspec import read_csv
from lmprun import run_deck
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
                      f"y stress {P0} z stress {P0} xz stress 0 gain 0.25")
    rc, out = run_deck(deck, tmp_path)
    assert rc == 0, out[-2000:]
    line = next(l for l in out.splitlines() if "WARNING" in l and "cell/servo" in l)
    assert "gain 0.25 on a held shear stress" in line and "use gain <= 0.05" in line, line
    # the default gains do not warn
    rc, out = run_deck(small_deck(f"change_box all triclinic\nfix c all cell/servo axes x "
                                  f"stress {P0} y stress {P0} z stress {P0} xz stress 0"),
                       tmp_path)
    assert rc == 0 and "held shear stress" not in out, out[-2000:]
