"""The undrained cyclic triaxial test: fix cell/servo cyclic_triaxial (docs/fix_cell_servo.md,
docs/theory.md §13) and inputs/cyclic_triaxial.in on the loose quick specimen, with a row every
step.

  two-way   CSR 0.12: the volume constant to 1e-9 relative, sigma2 = sigma3 held, r_u = 1 - p/p0
            recomputed and rising cycle after cycle, the reversals at q_a = +-2 CSR p0 (the
            amplitude held to 5 % until liquefaction), eps_a at +-rate, and the cycle count and
            N_L by both criteria recomputed by an independent state machine of the test; the
            specimen liquefies within the run by both (with the criteria r_u >= 0.5 and double
            amplitude eps_a >= 2 %, so that the run stops early instead of flowing on to the
            deck's 5 %); `tyanalysis cyclic-triaxial` draws it and prints the same N_L
  one-way   CSR 0.15 between q_a = 0 and +2 CSR p0 for 5 cycles: the reversals at both bounds,
            the volume constant, no liquefaction
  options   the decks' bad -var options are errors naming them

About 6 s of CPU beside the specimens' preparation (once per session: tests/conftest.py).
"""
import os

import numpy as np
import pytest

import test_decks
from cellspec import read_csv
from test_decks import cli, run_deck

REPO = test_decks.REPO
CSR, RATE = 0.15, 1e-4
# two-way: an amplitude the loose quick specimen withstands for several cycles, so that r_u is
# seen rising cycle after cycle and the reversals and the cycle count are exercised before it
# liquefies (test_cyclic_triaxial.py's own run, `pytest -s`: N_L = 10 by r_u >= 0.5 and 10.5 by
# the double amplitude 2 %, r_u at most 0.898; at CSR 0.15 the deck page's run, with its
# criteria, reaches the double amplitude 5 % within 2.5 cycles, too few to exercise the count)
CSR_TWO_WAY = 0.12
RU_LIMIT, DA_LIMIT = 0.5, 0.02
AMPLITUDE_HELD = 0.05        # |q_a| within 5 % of 2 CSR p0 until liquefaction
TWO_WAY = {"specimen": "loose", "csv_every": 1, "csr": CSR_TWO_WAY, "cycles": 40,
           "after_liquefaction": "stop", "ru_limit": RU_LIMIT, "da_limit": DA_LIMIT,
           "eps_max": 0.03, "out": "two_way"}
ONE_WAY = {"specimen": "loose", "csv_every": 1, "csr": CSR, "cycles": 5, "loading": "one_way",
           "out": "one_way"}


@pytest.fixture(scope="module")
def two_way(tmp_path_factory, specimens):
    work, text = run_deck(tmp_path_factory, specimens, "cyclic_triaxial", TWO_WAY, tag="ctx_two")
    return work, read_csv(work / "two_way.csv"), text


@pytest.fixture(scope="module")
def one_way(tmp_path_factory, specimens):
    work, text = run_deck(tmp_path_factory, specimens, "cyclic_triaxial", ONE_WAY, tag="ctx_one")
    return work, read_csv(work / "one_way.csv"), text


def replay(t, csr, one_way=False, ru_limit=0.95, da_limit=0.05):
    """An independent state machine of the test (docs/theory.md §13) over a record with a row
    every step: each row after the first ends a step, at which the axial rate reverses when
    q_a reaches the bound ahead (+2 CSR p0 compressing; -2 CSR p0, or 0 one-way, extending),
    and N_L is recorded. The fix writes a row before it updates its state, so the cycle count
    of row k is the state after row k - 1. Returns the reversal rows, the cycle count after
    each row and (N_L by r_u, N_L by double amplitude eps_a)."""
    p0 = t["p"][0]
    upper = 2.0 * csr * p0
    lower = 0.0 if one_way else -upper
    direction, reversals, eps_rev = 1, 0, 0.0
    n_ru = n_da = 0.0
    after = np.zeros(len(t["q_a"]))
    turns = []
    for k in range(1, len(t["q_a"])):
        q = t["q_a"][k]
        if (direction > 0 and q >= upper) or (direction < 0 and q <= lower):
            direction, reversals, eps_rev = -direction, reversals + 1, t["eps_a"][k]
            turns.append(k)
        after[k], n = 0.5 * reversals, 0.5 * (reversals + 1)
        if n_ru == 0.0 and 1.0 - t["p"][k] / p0 >= ru_limit:
            n_ru = n
        if n_da == 0.0 and abs(t["eps_a"][k] - eps_rev) >= da_limit:
            n_da = n
    return np.array(turns), after, (n_ru, n_da)


def check_constant_volume(t):
    v = np.max(np.abs(t["volume"] / t["volume"][0] - 1.0))
    print(f"max |V/V0 - 1|: {v:.3g}")
    assert v < 1e-9
    np.testing.assert_allclose(t["r_u"], 1.0 - t["p"] / t["p"][0], rtol=0, atol=1e-9)
    np.testing.assert_array_equal(t["eps_a"], t["eps3"])      # axis z
    np.testing.assert_allclose(t["q_a"], t["sig3"] - 0.5 * (t["sig1"] + t["sig2"]), rtol=1e-9,
                               atol=1e-6 * t["p"][0])


def check_axial_rate(t, turns):
    """eps_a moves at +rate, turned after each reversal row (the rate chosen at the end of a
    step moves the cell in the next; the first step, from rest, has none), to the record's
    12 digits of eps_a and time."""
    direction = np.ones(len(t["eps_a"]))
    for k in turns:
        direction[k + 1:] *= -1
    steps = np.diff(t["eps_a"])
    assert steps[0] == 0.0
    np.testing.assert_allclose(steps[1:], direction[2:] * RATE * np.diff(t["time"])[1:], rtol=0,
                               atol=1e-12)


def test_two_way_volume_lateral_stresses_and_r_u(two_way):
    _, t, _ = two_way
    check_constant_volume(t)
    first = min(np.argmax(t["N_L_ru"] > 0), np.argmax(t["N_L_eps"] > 0))
    # sigma2 = sigma3 held by the servo until the specimen liquefies
    lateral = np.max(np.abs(t["sig1"] - t["sig2"])[10:first]) / t["p"][0]
    print(f"max |sig_x - sig_y|/p0 before liquefaction: {lateral:.3g}")
    assert lateral < 0.01
    # r_u rises cycle after cycle: at the end of each complete cycle (q_a at +2 CSR p0)
    turns, _, _ = replay(t, CSR_TWO_WAY, ru_limit=RU_LIMIT, da_limit=DA_LIMIT)
    at_top = [k for k in turns if t["q_a"][k] > 0 and k < first]
    r_u = t["r_u"][at_top]
    print("r_u at the compression peaks:", np.round(r_u, 3))
    assert len(r_u) >= 4 and np.all(np.diff(r_u[1:]) > 0) and r_u[-1] > 0.1


def test_two_way_reversals_cycles_and_liquefaction(two_way):
    work, t, text = two_way
    assert np.all(np.diff(t["step"]) == 1), "the test needs a row every step"
    turns, after, (n_ru, n_da) = replay(t, CSR_TWO_WAY, ru_limit=RU_LIMIT, da_limit=DA_LIMIT)
    amplitude = 2.0 * CSR_TWO_WAY * t["p"][0]
    assert len(turns) >= 6
    # each reversal at q_a = +-amplitude, reached within one step's change of q_a
    dq = np.abs(np.diff(t["q_a"]))
    for k in turns:
        assert amplitude <= abs(t["q_a"][k]) <= amplitude + dq[k - 1] + 1e-9 * amplitude
    assert np.all(np.sign(t["q_a"][turns]) == np.resize([1, -1], len(turns)))   # compression first
    check_axial_rate(t, turns)
    np.testing.assert_array_equal(t["cycles"][1:], after[:-1])     # one row late
    print(f"CSR {CSR_TWO_WAY}: N_L = {n_ru} (r_u >= {RU_LIMIT}) and {n_da} (double amplitude eps_a >= "
          f"{DA_LIMIT}); reported {t['N_L_ru'][-1]}, {t['N_L_eps'][-1]}; r_u max "
          f"{np.max(t['r_u']):.3f}")
    assert n_ru > 0 and n_da > 0, "the loose specimen must liquefy within the test"
    assert (t["N_L_ru"][-1], t["N_L_eps"][-1]) == (n_ru, n_da)
    assert f"N_L = {n_ru:g} (r_u >= {RU_LIMIT:g}) and {n_da:g}" in text
    first = min(np.argmax(t["N_L_ru"] > 0), np.argmax(t["N_L_eps"] > 0))
    over = np.max(np.abs(t["q_a"][:first])) / amplitude - 1.0
    print(f"max |q_a|/(2 CSR p0) - 1 before liquefaction: {over:.3g}")
    assert over < AMPLITUDE_HELD
    printed = cli("cyclic-triaxial", "two_way.csv", "--n", "500", "--specimen", "loose",
                  "--ru-limit", str(RU_LIMIT), "--da-limit", str(DA_LIMIT), "--out", "ct.png",
                  cwd=work)
    test_decks.assert_png(work / "ct.png")
    assert f"N_L_ru={n_ru:g} N_L_eps={n_da:g}" in printed
    assert f"N_L_ru_record={n_ru:g} N_L_eps_record={n_da:g}" in printed


def test_one_way_reverses_at_zero_and_the_amplitude(one_way):
    _, t, text = one_way
    check_constant_volume(t)
    turns, after, (n_ru, n_da) = replay(t, CSR, one_way=True)
    amplitude = 2.0 * CSR * t["p"][0]
    dq = np.abs(np.diff(t["q_a"]))
    assert len(turns) == 10 and t["cycles"][-1] == 5.0
    for j, k in enumerate(turns):
        bound = amplitude if j % 2 == 0 else 0.0
        assert abs(t["q_a"][k] - bound) <= dq[k - 1] + 1e-9 * amplitude, (j, t["q_a"][k])
    assert np.min(t["q_a"]) > -0.05 * amplitude
    check_axial_rate(t, turns)
    np.testing.assert_array_equal(t["cycles"][1:], after[:-1])
    assert (n_ru, n_da) == (0.0, 0.0) and t["N_L_ru"][-1] == 0 and t["N_L_eps"][-1] == 0
    print(f"one-way CSR {CSR}: r_u {t['r_u'][-1]:.3f} after 5 cycles")


@pytest.mark.parametrize("deck,name,value,message", [
    ("cyclic_triaxial", "loading", "both", "unknown value; loading is one of two_way, one_way"),
    ("cyclic_triaxial", "axis", "w", "unknown value; axis is one of z, x, y"),
    ("cyclic_triaxial", "csr", "-0.1", "must be above 0; csr is the cyclic stress ratio"),
    ("cyclic_triaxial", "eps_max", "0", "must be above 0; eps_max is the |axial strain|"),
    ("k0", "ocr", "0.5", "must be at least 1; ocr is the overconsolidation ratio"),
    ("k0", "sigma_max", "inf", "not a finite number; sigma_max is the axial stress")])
def test_deck_bad_option_is_an_error(tmp_path, deck, name, value, message):
    os.symlink(os.path.join(REPO, "inputs"), tmp_path / "inputs")
    rc, out = test_decks._run(f"inputs/{deck}.in", tmp_path, {name: value})
    assert rc != 0
    assert f"ERROR: -var {name} {value}: {message}" in out
    assert not (tmp_path / "tylmp_specimens").exists()      # nothing prepared
