"""Oedometric (K0) compression and unloading: fix cell/servo k0 (docs/fix_cell_servo.md,
docs/theory.md §12-13) and inputs/k0.in.

  lattice   equal Hertz-Mindlin spheres (pair thornton/yin, Γ = 0, μ = 1000: no slip) on the
            face-centred cubic lattice of tests/test_cell_stiffness_lattice.py at p = 1 MPa,
            frozen (no integrator: the atoms move with the box), loaded oedometrically along a
            cube axis (z) and along a face diagonal (x of the frame turned by 45° about z).
            The ratio of the stress changes the fix reports, K0_inc = Δσ_r/Δσ_a (σ_r the mean
            of the two lateral stresses), must be the closed form of §12: C13/C33 = C12/C11 =
            (1 − κ)/(2(1 + κ)) = 0.0484 along the cube axis and (C'21 + C'31)/(2 C'11) =
            0.0354 along the diagonal (the turned tensor of the lattice test), each with the
            geometric part of §12 (the rotation of the normal forces and the change of volume,
            about 1 % of these small ratios at 1 MPa, computed here from §12's formula) to
            1e-4 (found: 3e-6 and 1.1e-5); K0 = σ_r/σ_a itself follows from the same numbers.
            Without the geometric part the check fails by 1 %, with μ = 0.3 the
            Mindlin-Deresiewicz softening moves it by 1e-3 (at a strain of 1e-3 of the
            overlap): the bound tests the affine response, not the law's slip.
  deck      inputs/k0.in on the quick dense and loose specimens, a row every step: the lateral
            strains stay exactly zero, eps_a moves at +rate, then at -rate from the first row
            with sig_a >= sigma_max, and rests from the first row with OCR >= ocr, where the
            run stops; K0 and OCR recomputed from the record's stresses; K0 falls below 1 in
            loading (lower in the dense specimen) and rises on unloading; `tyanalysis k0`
            prints the same numbers, beside Jaky's 1 - sin φ′ (printed, not a check).

About 5 s of CPU beside the specimens' preparation (once per session: tests/conftest.py).
"""
import math

import re

import numpy as np
import pytest

import test_decks
from cellspec import E, HEADER, NU, RHO, effective_modulus, read_csv
from lmprun import LOAD_TYLMP, run_ok
from test_cell_stiffness_lattice import (N_CELLS, R, closed_form, cubic_voigt, relative_overlap,
                                         turned_45_about_z)
from test_decks import cli, run_deck

P_LATTICE = 1e6
MU_NO_SLIP = 1000.0
STEPS, DT = 20, 0.02
AXIS = {"x": 0, "y": 1, "z": 2}


def nearest_neighbours(frame):
    """The 6 contact directions of an FCC grain (one of each ± pair) in the box frame: the cube
    frame, or the frame of `orient x 1 1 0 y -1 1 0 z 0 0 1`."""
    dirs = np.array([[1, 1, 0], [1, -1, 0], [1, 0, 1], [1, 0, -1], [0, 1, 1], [0, 1, -1]],
                    float) / math.sqrt(2.0)
    if frame == "turned":
        rows = np.array([[1, 1, 0], [-1, 1, 0], [0, 0, 1]], float)
        dirs = dirs @ (rows / np.linalg.norm(rows, axis=1)[:, None]).T
    return dirs


def geometric_response(frame, axis, p):
    """dσ_geo/ε (diagonal, compression positive) of the lattice at rest under the uniaxial
    compression e = ε e_a e_a (docs/theory.md §12): −(1/V) Σ_c P l [(e n) nᵀ + n (e n)ᵀ −
    (n·e n) n nᵀ] + σ tr e, where (1/V) Σ_c P l f(n) = (p/2) Σ over the 6 directions, since
    p = (P d/V_p) Σ n_x² and Σ n_x² = 2."""
    e = np.zeros((3, 3))
    e[axis, axis] = 1.0
    total = np.zeros((3, 3))
    for n in nearest_neighbours(frame):
        en = e @ n
        total += np.outer(en, n) + np.outer(n, en) - (n @ en) * np.outer(n, n)
    return np.diag(-0.5 * p * total + p * np.trace(e) * np.eye(3))


def lattice_k0_deck(spacing, orient, axis, rate):
    return HEADER + f"""lattice fcc {spacing!r} {orient}
region box block 0 {N_CELLS} 0 {N_CELLS} 0 {N_CELLS} units lattice
create_box 1 box
create_atoms 1 box
set atom * diameter {2 * R!r} density {RHO}
""" + LOAD_TYLMP + f"""pair_style thornton/yin
pair_coeff * * {E} {NU} {MU_NO_SLIP} 0.0
neighbor 2e-5 bin
timestep {DT}
# frozen: no integrator; the lateral strains held at zero, the axis at a constant rate
fix cell all cell/servo k0 {axis} {rate!r} 1e9 csv k0.csv 1
run {STEPS}
"""


@pytest.mark.parametrize("frame,axis", [("cube", "z"), ("turned", "x")])
def test_fcc_lattice_k0_is_the_closed_form(frame, axis, tmp_path):
    e_star = effective_modulus()
    kappa = 2.0 * (1.0 - NU) / (2.0 - NU)
    x = relative_overlap(P_LATTICE, e_star)
    spacing = 2.0 * R * (1.0 - x) * math.sqrt(2.0)
    orient = "" if frame == "cube" else "orient x 1 1 0 orient y -1 1 0 orient z 0 0 1"
    # an axial strain of 1e-4 of the relative overlap over the run: the second-order terms (the
    # Hertz curvature, the tangential forces built up) are below 2e-5 of K0_inc (they scale with
    # the strain: 1.1e-4 at 1e-3 of the overlap)
    rate = 1e-4 * x / (STEPS * DT)
    run_ok(lattice_k0_deck(spacing, orient, axis, rate), tmp_path)
    t = read_csv(tmp_path / "k0.csv")
    a = AXIS[axis]
    b, c = (a + 1) % 3, (a + 2) % 3
    eps = [t[f"eps{k + 1}"] for k in range(3)]
    assert np.all(eps[b] == 0.0) and np.all(eps[c] == 0.0)
    assert eps[a][-1] == pytest.approx(STEPS * rate * DT, rel=0.06)    # the first step is at rest

    c11, c12, c44 = closed_form(x, e_star, kappa)
    C = cubic_voigt(c11, c12, c44) if frame == "cube" else turned_45_about_z(c11, c12, c44)
    geo = geometric_response(frame, a, P_LATTICE)
    affine = 0.5 * (C[b, a] + C[c, a]) / C[a, a]
    expected = 0.5 * (C[b, a] + C[c, a] + geo[b] + geo[c]) / (C[a, a] + geo[a])
    strained = eps[a] > 0.2 * eps[a][-1]     # rows past the stresses' round-off
    k0_inc = t["K0_inc"][strained]
    print(f"{frame} frame, axis {axis}: K0_inc = {k0_inc[-1]:.7f}; closed form C_ra/C_aa = "
          f"{affine:.7f}, with the geometric part {expected:.7f} (relative difference "
          f"{k0_inc[-1] / expected - 1:.2e})")
    assert np.max(np.abs(k0_inc / expected - 1.0)) < 1e-4
    assert abs(affine / expected - 1.0) > 5e-3     # the geometric part matters at this p
    # K0 = sigma_r/sigma_a from the isotropic p and the same increments: 1 - K0 = (1 - K0_inc)
    # d_axial/(p + d_axial), to 1e-4 of it (the linear increments leave out the Hertz
    # curvature, (1/4) eps/x = 2.5e-5 at the end)
    p0 = t["sig1"][0]
    assert p0 == pytest.approx(P_LATTICE, rel=1e-6)
    d_axial = (C[a, a] + geo[a]) * eps[a][strained]
    k0 = (p0 + expected * d_axial) / (p0 + d_axial)
    np.testing.assert_allclose(1.0 - t["K0"][strained], 1.0 - k0, rtol=1e-4, atol=0)
    np.testing.assert_allclose(t["K0"], t["sig_r"] / t["sig_a"], rtol=1e-11)


# ---------------------------------------------------------------------------------------------
# inputs/k0.in on the quick specimens

SIGMA_MAX, OCR, RATE = 1e6, 4.0, 1e-4       # the deck's defaults
SINPHI_CS = 0.375     # sin φ′ at the critical state, docs/validation.md (0.35-0.40): Jaky, printed


@pytest.fixture(scope="module")
def k0_runs(tmp_path_factory, specimens):
    runs = {}
    for kind in ("dense", "loose"):
        work, text = run_deck(tmp_path_factory, specimens, "k0",
                              {"specimen": kind, "csv_every": 1, "out": f"k0_{kind}"},
                              tag=f"k0_{kind}")
        runs[kind] = (work, read_csv(work / f"k0_{kind}.csv"), text)
    return runs


@pytest.mark.parametrize("kind", ["dense", "loose"])
def test_k0_deck_holds_the_lateral_strains_and_follows_its_course(k0_runs, kind):
    _, t, text = k0_runs[kind]
    assert np.all(np.diff(t["step"]) == 1), "the test needs a row every step"
    assert np.all(t["eps1"] == 0.0) and np.all(t["eps2"] == 0.0)    # axis z
    np.testing.assert_array_equal(t["eps_a"], t["eps3"])
    # the end of loading: the first row with sig_a >= sigma_max; of unloading: the first with
    # (largest sig_a so far)/sig_a >= ocr, the record's last row (the run stops there)
    top = int(np.argmax(t["sig_a"] >= SIGMA_MAX))
    assert top > 0 and np.all(t["sig_a"][:top] < SIGMA_MAX)
    largest = np.maximum.accumulate(t["sig_a"])
    np.testing.assert_allclose(t["ocr"], largest / t["sig_a"], rtol=1e-10)
    np.testing.assert_allclose(t["K0"], t["sig_r"] / t["sig_a"], rtol=1e-10)
    np.testing.assert_allclose(t["sig_r"], 0.5 * (t["sig1"] + t["sig2"]), rtol=1e-10)
    end = int(np.argmax((np.arange(len(t["ocr"])) > top) & (t["ocr"] >= OCR)))
    assert end == len(t["ocr"]) - 1 and t["progress"][end] == 1.0
    assert np.all(t["progress"][:end] < 1.0)
    # the deck's thermo lines: the wall time left, known once the course has progressed
    # (step, ..., progress, eta_seconds), none at its end
    rows = [line.split() for line in text.splitlines()
            if re.fullmatch(r"\s*\d+(\s+\S+){9}\s*", line)]
    progress, eta = (np.array([float(r[k]) for r in rows]) for k in (8, 9))
    assert len(rows) >= 2 and np.all(np.isfinite(eta[progress > 0])), eta
    assert np.all(eta[progress > 0] >= 0.0) and eta[-1] == 0.0
    # eps_a at +rate, turned after the row that ended loading (the rate chosen at the end of a
    # step moves the cell in the next; the first step, from rest, has none); to the record's
    # 12 digits of eps_a and time
    direction = np.ones(len(t["eps_a"]))
    direction[top + 1:] = -1.0
    steps = np.diff(t["eps_a"])
    assert steps[0] == 0.0
    np.testing.assert_allclose(steps[1:], direction[2:] * RATE * np.diff(t["time"])[1:], rtol=0,
                               atol=1e-12)
    print(f"{kind}: K0 = {t['K0'][top]:.4f} at sigma_a = {t['sig_a'][top] / 1e3:.1f} kPa "
          f"(eps_a {t['eps_a'][top] * 100:.3f} %), K0_inc {t['K0_inc'][top]:.4f}; K0 = "
          f"{t['K0'][end]:.4f} at OCR {t['ocr'][end]:.3f}; Jaky 1 - sin phi' = "
          f"{1 - SINPHI_CS:.3f} (sin phi' {SINPHI_CS})")
    assert f"k0: K0 = {t['K0'][end]:.4f} at OCR {t['ocr'][end]:.3f}" in text


def test_k0_falls_in_loading_and_rises_on_unloading(k0_runs):
    """An isotropic specimen loaded oedometrically far past its preparation stress (100 kPa to
    1 MPa) has K0 well below 1, lower the denser it is; unloading raises K0 with OCR."""
    at_peak = {}
    for kind, (_, t, _) in k0_runs.items():
        top = int(np.argmax(t["sig_a"]))
        at_peak[kind] = t["K0"][top]
        assert 0.2 < t["K0"][top] < 0.9, kind
        half = top + int(np.argmax(t["ocr"][top:] >= 2.0))
        assert t["K0"][top] < t["K0"][half] < t["K0"][-1], kind
    assert at_peak["dense"] < at_peak["loose"]


def test_k0_analysis(k0_runs):
    work, t, _ = k0_runs["dense"]
    printed = cli("k0", "k0_dense.csv", "--n", "500", "--specimen", "dense", "--sinphi",
                  str(SINPHI_CS), "--out", "k0.png", cwd=work)
    test_decks.assert_png(work / "k0.png")
    top = int(np.argmax(t["sig_a"]))
    assert f"K0_loading={t['K0'][top]:.6g}" in printed
    assert f"K0_end={t['K0'][-1]:.6g}" in printed
    assert f"jaky={1 - SINPHI_CS:.6g}" in printed
