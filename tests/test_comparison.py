"""The claims of docs/comparison.md that rest on bench/compare_tangential.py and
bench/compare_assembly.py, at a coarser resolution / shorter strain than the documented runs:

  * tangential loop at fixed overlap: thornton/yin follows Thornton's closed forms (peeling,
    Mindlin-Deresiewicz, Masing), LAMMPS `granular ... tangential mindlin` is a linear spring
    8G*a capped at mu(P + 2Pc) (pair_granular.cpp, 29Sep2021) and therefore misses the
    Mindlin-Deresiewicz curve by ~0.19 mu P on loading and ~0.39 mu P on unloading; both slide
    at mu(P + 2Pc);
  * assembly: under fix deform remap x the built-in styles lack the affine contact velocity
    L (x_i - x_j): their initial deviatoric stiffness is lower than with streaming velocities
    (remap v), while thornton/yin gives the same stiffness both ways.
"""
import os

import numpy as np
import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture(scope="module")
def tangential(bench):
    return bench("compare_tangential")


@pytest.mark.parametrize("key", ["a", "b", "c"])
def test_tangential_loop_against_closed_forms(tmp_path, tangential, key):
    _, _, Gamma, delta = next(c for c in tangential.CASES if c[0] == key)
    c = tangential.Contact(Gamma, delta)
    A = 2 * c.slip
    ty = tangential.run("thornton/yin", c, A, 1000, str(tmp_path), "ty")
    gr = tangential.run("granular", c, A, 1000, str(tmp_path), "gr")
    for d in (ty, gr):
        assert np.allclose(d["P"], c.P, rtol=1e-9)                       # overlap held exactly
        assert set(np.unique(d["leg"])) == {0, 1, 2}
        end_of_loading = np.flatnonzero(d["leg"] == 0)[-1]
        # both slide at mu(P + 2Pc) (Fncrit = |Fne + 2 F_pulloff| in pair_granular.cpp)
        assert d["T"][end_of_loading] == pytest.approx(c.L, rel=1e-9)
        assert d["T"].min() == pytest.approx(-c.L, rel=1e-9)
    ref_ty = c.reference(ty["s"], ty["leg"], A)
    assert np.max(np.abs(ty["T"] - ref_ty)) < 2e-3 * c.L
    assert np.max(np.abs(gr["T"] - c.linear_capped(gr["s"]))) < 2e-3 * c.L
    miss = np.abs(gr["T"] - c.reference(gr["s"], gr["leg"], A)) / c.L
    k_load, k_unload = tangential.initial_stiffness(ty["s"], ty["T"], ty["leg"], c)
    assert k_load == pytest.approx(c.k0, rel=5e-3)                       # 8 G* a (JKR radius)
    assert k_unload == pytest.approx(c.kT, rel=2e-2)                     # 8 G* a_T (Masing)
    if key == "a":                                        # Gamma = 0: documented 0.192 / 0.385
        assert 0.18 < miss[gr["leg"] == 0].max() < 0.20
        assert 0.37 < miss[gr["leg"] >= 1].max() < 0.40
    if key == "c":                                        # peeling ends at T_c before sliding
        k = int(np.argmax(ty["peel"] == 0))
        assert ty["T"][k - 1] < c.Tc <= ty["T"][k] * (1 + 1e-3)
        assert c.Tc < 0.6 * c.L


@pytest.fixture(scope="module")
def dense_specimen(specimens):
    """The decks' dense quick specimen (prepared once per session: tests/conftest.py)."""
    return str(specimens / "dense_quick.restart")


def test_affine_term_sets_the_initial_stiffness_of_the_assembly(tmp_path, dense_specimen, bench):
    assembly = bench("compare_assembly")
    dt = 0.2 * np.pi * 0.0675e-3 * np.sqrt(2650e12 / (70e9 / 2.6)) / (0.1631 * 0.3 + 0.8766)
    rate, eps = 1e-4, 2e-4
    nsteps = int(np.ceil(eps / (rate * dt)))
    stiffness = {}
    for name in ("thornton/yin G=0 remap x", "thornton/yin G=0 remap v",
                 "granular hertz/material+mindlin remap x",
                 "granular hertz/material+mindlin remap v"):
        pair, remap, lateral = assembly.CASES[name]
        deck = assembly.volume_deck(dense_specimen, pair, remap, lateral, rate, nsteps, 5, dt)
        d = assembly.run_deck(deck, name.replace("/", "_").replace(" ", "_"), str(tmp_path))
        stiffness[name] = assembly.secant_modulus(d, 0.9 * eps)
    ty_x, ty_v = stiffness["thornton/yin G=0 remap x"], stiffness["thornton/yin G=0 remap v"]
    gr_x = stiffness["granular hertz/material+mindlin remap x"]
    gr_v = stiffness["granular hertz/material+mindlin remap v"]
    print({k: f"{v / 1e6:.1f} MPa" for k, v in stiffness.items()})
    assert ty_x == pytest.approx(ty_v, rel=0.01)      # affine term = streaming velocities
    assert gr_v == pytest.approx(ty_v, rel=0.03)      # same kinematics: same stiffness
    assert gr_x < 0.9 * gr_v                          # remap x: the affine term is missing
