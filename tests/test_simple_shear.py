"""Simple shear of the triclinic periodic cell (fix cell/servo shear, shear_cv, cyclic_shear;
docs/theory.md §10-13) on the decks' quick 500-sphere specimens:

  drained        inputs/simple_shear.in on the dense and the loose specimen: sigma_n held,
                 the dense specimen stronger and dilating, the loose one weaker and dilating
                 less; `tyanalysis shear` draws both
  constant volume  the volume constant to 1e-9 relative (simple_shear.in -var drainage
                 constant_volume and over a cyclic test), and r_u recomputed from the record's
                 own sigma_n
  cyclic         inputs/cyclic_simple_shear.in on the loose specimen with a row every step:
                 the reversals at tau = +-CSR sigma_n0 (the amplitude held to 10 %), the cycle
                 count and N_L by both criteria (r_u >= 0.95, double amplitude 3.75 %)
                 recomputed by an independent state machine; a small amplitude does not
                 liquefy within twice the cycles a large one needs; `tyanalysis cyclic-shear`
                 draws and prints N_L; slow (TYLMP_SLOW=1): N_L falls as CSR grows
  tilt flips     gamma counts across flips, the stress of a flipped cell equals that of the
                 unflipped one, a restart written right after a flip resumes the run, and 1 and
                 2 ranks agree over a short run
  decks          both run by absolute path from any directory; bad options are errors
  analysis       tyanalysis.shear on a hand-made record

The decks run as a user runs them (lmp -in inputs/NAME.in from a directory holding inputs/),
with the specimens prepared once per session (tests/conftest.py's fixture); the flip tests
run decks of their own from the dense specimen (the objectivity tests, the same way:
tests/test_shear_objectivity.py). About 1.5-3 minutes (2 cores); every test passes on LAMMPS
29 Sep 2021 and on 4 Feb 2025 (scripts/lammps2025.sh).
"""
import os
import re

import numpy as np
import pytest

import test_decks
from test_decks import cli, read_csv, run_deck
from lmprun import LOAD_TYLMP, run_ok

REPO = test_decks.REPO
SIGMA_N = 1e5


# ---------------------------------------------------------------------------------------------
# drained simple shear: dense against loose (inputs/simple_shear.in)

# a quick test: to 10 % shear strain at 5e-4 1/s (2.5 times the deck's quick rate)
DRAINED = {"strain": 0.1, "rate": 5e-4}


@pytest.fixture(scope="module")
def drained(tmp_path_factory, specimens):
    runs = {}
    for kind in ("dense", "loose"):
        out = f"shear_{kind}"
        work, text = run_deck(tmp_path_factory, specimens, "simple_shear",
                              dict(DRAINED, specimen=kind, out=out), tag=out)
        runs[kind] = (work, out, text)
    return runs


def test_drained_normal_stress_held(drained):
    """sigma_n = sigma_zz is servo controlled: after the first 0.5 % of strain (the servo's
    start from the isotropic specimen) it stays within 2 % of 100 kPa. Tolerance: at this
    rate the stress of a 500-sphere cell moves by up to about 1 % between steps when a contact
    network rearranges (the axisymmetric deck's p is held to 1 %, test_decks.p_held, at the
    lower rate 1e-4); the servo removes a fraction of the error each step, so the record
    shows the transient of each such event."""
    for kind, (work, out, _) in drained.items():
        t, names = read_csv(work / f"{out}.csv")
        assert {"gamma", "tau", "sig_n", "tau_ratio"} <= set(names) and "r_u" not in names
        after = t["gamma"] > 0.005
        assert after.sum() > 20
        err = np.max(np.abs(t["sig_n"][after] / SIGMA_N - 1.0))
        print(f"{kind}: max |sigma_n/100 kPa - 1| = {err:.3g}")
        assert err < 0.02, kind
        # tau_ratio is tau/sigma_n of the same row
        np.testing.assert_allclose(t["tau_ratio"], t["tau"] / t["sig_n"], rtol=1e-9)


def test_drained_dense_stronger_and_dilates_loose_less(drained):
    """The dense specimen (prepared frictionless) reaches a higher peak tau/sigma_n and dilates
    (eps_v < 0, compression positive); the loose one is weaker and dilates less or contracts."""
    res = {}
    for kind, (work, out, _) in drained.items():
        t, _ = read_csv(work / f"{out}.csv")
        res[kind] = (float(np.max(t["tau_ratio"])), float(t["eps_v"][-1]))
    print("peak tau/sigma_n and eps_v at 10 %:", res)
    (dense_peak, dense_ev), (loose_peak, loose_ev) = res["dense"], res["loose"]
    assert dense_peak > loose_peak + 0.05
    assert dense_ev < -0.005
    assert loose_ev > dense_ev + 0.005


def test_drained_figure_and_printed_command(drained):
    work, out, text = drained["dense"]
    assert f"plot: tyanalysis shear {out}.csv --n 500 --specimen dense --out {out}.png" in text
    loose_work, loose_out, _ = drained["loose"]
    os.replace(loose_work / f"{loose_out}.csv", work / f"{loose_out}.csv")
    printed = cli("shear", f"{out}.csv", f"{loose_out}.csv", "--n", "500", "--specimen",
                  "dense, loose", "--out", f"{out}.png", cwd=work)
    test_decks.assert_png(work / f"{out}.png")
    assert "kind=drained" in printed and "tau_ratio_peak=" in printed


def test_constant_volume_deck(tmp_path_factory, specimens):
    """inputs/simple_shear.in -var drainage constant_volume: no volume change, r_u from the
    record's sigma_n, and the three-panel figure."""
    work, text = run_deck(tmp_path_factory, specimens, "simple_shear",
                          {"drainage": "constant_volume", "strain": 0.02, "rate": 5e-4,
                           "out": "cv"}, tag="simple_shear_cv")
    t, names = read_csv(work / "cv.csv")
    assert "r_u" in names and "cycles" not in names
    assert np.max(np.abs(t["volume"] / t["volume"][0] - 1.0)) < 1e-9
    np.testing.assert_allclose(t["r_u"], 1.0 - t["sig_n"] / t["sig_n"][0], rtol=0, atol=1e-9)
    printed = cli("shear", "cv.csv", "--n", "500", "--specimen", "dense", "--out", "cv.png",
                  cwd=work)
    test_decks.assert_png(work / "cv.png")
    assert "kind=constant_volume" in printed


@pytest.mark.parametrize("deck,variables", [
    ("simple_shear", {"strain": 0.002}),
    ("cyclic_simple_shear", {"specimen": "dense", "cycles": 1, "csr": 0.1})])
def test_decks_run_from_any_directory(tmp_path_factory, specimens, deck, variables):
    """Each deck by its absolute path from an empty directory, the specimens where
    -var specimen_dir says: it reuses them, writes its record here and prints its plot
    command; the -var choices of tylmp.decks are checked (a bad one is an error)."""
    away = tmp_path_factory.mktemp(f"{deck}_elsewhere")
    path = os.path.join(REPO, "inputs", f"{deck}.in")
    rc, out = test_decks._run(path, away, dict(variables, specimen_dir=str(specimens)))
    test_decks._check(rc, out, f"{deck}.in from another directory")
    assert f"reusing specimen {specimens}" in out
    assert (away / f"{deck}.csv").is_file() and not (away / "tylmp_specimens").exists()
    command = "cyclic-shear" if deck.startswith("cyclic") else "shear"
    assert re.search(rf"^plot: tyanalysis {command} {deck}\.csv --n 500 ", out, re.M)
    rc, out = test_decks._run(path, away, dict(variables, specimen_dir=str(specimens),
                                               shear_plane="zx"))
    assert rc != 0 and "ERROR: -var shear_plane zx" in out


@pytest.mark.parametrize("name,value,message", [
    ("csr", "0", "must be above 0; csr is the cyclic stress ratio"),
    ("ru_limit", "1.5", "must be below 1; ru_limit is the liquefaction criterion on r_u"),
    ("da_limit", "nan", "not a finite number; da_limit is the liquefaction criterion"),
    ("gamma_max", "-1", "must be above 0; gamma_max is the |gamma| at which a cyclic test ends"),
    ("after_liquefaction", "halt", "unknown value; after_liquefaction is one of continue, stop"),
    ("drainage", "undrained", "unknown value; drainage is one of drained, constant_volume")])
def test_cyclic_deck_bad_option_is_an_error(tmp_path, name, value, message):
    os.symlink(os.path.join(REPO, "inputs"), tmp_path / "inputs")
    rc, out = test_decks._run("inputs/cyclic_simple_shear.in", tmp_path, {name: value})
    assert rc != 0
    assert f"ERROR: -var {name} {value}: {message}" in out
    assert not (tmp_path / "tylmp_specimens").exists()      # nothing prepared


# ---------------------------------------------------------------------------------------------
# cyclic constant-volume simple shear (inputs/cyclic_simple_shear.in)

# The loose specimen (e0 0.671) at a rate low enough for the amplitude to be held: at 1e-4 1/s
# a half cycle at CSR 0.11 lasts some 110-335 steps and tau passes the amplitude by under 1 %
# (at 2e-4, 27-39 steps, by 30 %: the packing's response lags the strain). r_u climbs over the
# first cycles; then the specimen flows at tau below the amplitude, through the double
# amplitude 3.75 %, and its mean stress falls towards zero (docs/decks/cyclic_simple_shear.md:
# N_L = 9.5 by both criteria at the deck's record interval). A flow
# liquefaction need not take r_u to 0.95 (docs/decks/cyclic_triaxial.md finds the same of the
# loose specimen in the triaxial cell), so the test, which needs both detectors to fire to check
# them against the replay, passes the criterion r_u >= 0.8, above everything the small
# amplitude reaches and below the flow's r_u. The small amplitude, CSR 0.055, runs at half the
# rate (the same period at the same stiffness, as a cyclic device runs at one frequency). The
# test's own runs (a row every step; `pytest -s tests/test_simple_shear.py -k cyclic`): CSR 0.11
# liquefies at N_L = 9 by r_u >= 0.8 and 9.5 by the double amplitude, r_u at most 0.984, |tau|
# over the amplitude by 0.6 % at most; CSR 0.055 reaches r_u 0.129 by N = 9.5 and 0.219 after its
# 19 cycles (over 29 cycles the deck page's run reaches 0.314). The monotonic constant-volume
# peak of this specimen is tau/sigma_n0 = 0.174 at 1e-4 (0.117 at 2e-5), so a CSR above it flows
# in the first half cycle (docs/decks/cyclic_simple_shear.md).
CSR_LARGE, RATE_LARGE = 0.11, 1e-4
CSR_SMALL, RATE_SMALL = 0.055, 5e-5
RU_LIMIT, DA_LIMIT = 0.8, 0.0375            # r_u passed (above); double amplitude the deck's
SMALL_MULTIPLE = 2                          # the small amplitude runs 2 x N_L of the large one
OVERSHOOT = 0.10                            # |tau| within 10 % of tau_cyc until liquefaction
CYCLIC = {"specimen": "loose", "csv_every": 1, "after_liquefaction": "stop", "ru_limit": RU_LIMIT}


@pytest.fixture(scope="module")
def cyclic_large(tmp_path_factory, specimens):
    work, text = run_deck(tmp_path_factory, specimens, "cyclic_simple_shear",
                          dict(CYCLIC, csr=CSR_LARGE, rate=RATE_LARGE, cycles=CYCLES_LARGE,
                               out="large"),
                          tag="cyclic_large")
    return work, text


CYCLES_LARGE = 30


def replay(t, csr, ru_limit=RU_LIMIT, da_limit=DA_LIMIT):
    """An independent state machine of the cyclic test (docs/theory.md §13) over a record
    with a row every step: each row after the first is the end of a step, at which the rate
    reverses when direction * tau >= CSR sigma_n0, and N_L is recorded. The fix writes a row
    before it updates its state, so the cycle count of row k is the state after row k - 1.
    Returns the reversal rows, the cycle count after each row and (N_L by r_u, N_L by double
    amplitude)."""
    amplitude = csr * t["sig_n"][0]
    direction, reversals, gamma_rev = 1, 0, 0.0
    n_ru = n_da = 0.0
    after = np.zeros(len(t["tau"]))
    turns = []
    for k in range(1, len(t["tau"])):
        if direction * t["tau"][k] >= amplitude:
            direction, reversals, gamma_rev = -direction, reversals + 1, t["gamma"][k]
            turns.append(k)
        # the cycles completed, and the count of the running half cycle (N_L)
        after[k], n = 0.5 * reversals, 0.5 * (reversals + 1)
        if n_ru == 0.0 and 1.0 - t["sig_n"][k] / t["sig_n"][0] >= ru_limit:
            n_ru = n
        if n_da == 0.0 and abs(t["gamma"][k] - gamma_rev) >= da_limit:
            n_da = n
    return np.array(turns), after, (n_ru, n_da)


def test_cyclic_volume_constant_and_r_u(cyclic_large):
    work, _ = cyclic_large
    t, names = read_csv(work / "large.csv")
    assert {"r_u", "cycles", "N_L_ru", "N_L_gamma"} <= set(names)
    v = np.max(np.abs(t["volume"] / t["volume"][0] - 1.0))
    print(f"max |V/V0 - 1| over the cyclic test: {v:.3g}")
    assert v < 1e-9
    np.testing.assert_allclose(t["r_u"], 1.0 - t["sig_n"] / t["sig_n"][0], rtol=0, atol=1e-9)


def half_unit(x, digits=12):
    """Half a unit in the last of `digits` significant digits of each value (0 for 0): how far a
    value printed with %.{digits}g can lie from the number it was printed from."""
    x = np.abs(np.asarray(x, dtype=float))
    exponent = np.floor(np.log10(np.where(x > 0, x, 1.0)))
    return np.where(x > 0, 0.5 * 10.0 ** (exponent - (digits - 1)), 0.0)


def test_cyclic_reversals_cycles_and_liquefaction(cyclic_large):
    work, text = cyclic_large
    t, _ = read_csv(work / "large.csv")
    assert np.all(np.diff(t["step"]) == 1), "the test needs a row every step"
    turns, after, (n_ru, n_da) = replay(t, CSR_LARGE)
    amplitude = CSR_LARGE * t["sig_n"][0]
    assert len(turns) >= 4
    # the reversals at tau = +-amplitude: reached within one step's change of tau
    dtau = np.abs(np.diff(t["tau"]))
    for k in turns:
        assert amplitude <= abs(t["tau"][k]) <= amplitude + dtau[k - 1] + 1e-9 * amplitude
    # gamma_dot = +-rate, turned after each reversal row (the rate the fix chooses at the end
    # of a step moves the cell during the next: the first step, from rest, has none)
    rate = RATE_LARGE
    direction = np.ones(len(t["tau"]))
    for k in turns:
        direction[k + 1:] *= -1
    steps = np.diff(t["gamma"])
    assert steps[0] == 0.0
    # to the CSV's 12 significant digits (%.12g): each printed value is within half a unit of
    # its 12th digit, so a step of gamma is known to the sum of its two ends' half units, and
    # rate * dt to rate times those of the two times (gamma passes 0.1 near liquefaction, where
    # the half units alone reach 1e-12: 7e-7 of a step)
    expected = direction[2:] * rate * np.diff(t["time"])[1:]
    read = half_unit(t["gamma"])
    known = read[2:] + read[1:-1] + rate * (half_unit(t["time"])[2:] + half_unit(t["time"])[1:-1])
    off = np.abs(steps[1:] - expected) - known
    assert np.all(off <= 0), f"step {np.argmax(off) + 1}: off by {np.max(off):.3g} beyond the digits"
    # the fix's cycle count, one row late (written before the update)
    np.testing.assert_array_equal(t["cycles"][1:], after[:-1])
    # N_L by both criteria as the fix reports them at the end
    print(f"CSR {CSR_LARGE}: N_L = {n_ru} (r_u) and {n_da} (double amplitude); reported "
          f"{t['N_L_ru'][-1]}, {t['N_L_gamma'][-1]}; r_u max {np.max(t['r_u']):.3f}")
    assert n_ru > 0 and n_da > 0, "the large amplitude must liquefy within the test"
    assert (t["N_L_ru"][-1], t["N_L_gamma"][-1]) == (n_ru, n_da)
    assert f"N_L = {n_ru:g} (r_u >= {RU_LIMIT:g}) and {n_da:g}" in text
    # the amplitude is held (stress control, not a dynamic overshoot) until liquefaction
    first = min(np.argmax(t["N_L_ru"] > 0), np.argmax(t["N_L_gamma"] > 0))
    over = np.max(np.abs(t["tau"][:first])) / amplitude - 1.0
    print(f"max |tau|/tau_cyc - 1 before liquefaction: {over:.3g}")
    assert over < OVERSHOOT
    # the analysis recomputes the same from the record (the same criteria) and draws the
    # figure
    printed = cli("cyclic-shear", "large.csv", "--n", "500", "--specimen", "loose",
                  "--ru-limit", str(RU_LIMIT), "--out", "large.png", cwd=work)
    test_decks.assert_png(work / "large.png")
    assert f"N_L_ru={n_ru:g} N_L_gamma={n_da:g}" in printed
    assert f"N_L_ru_record={n_ru:g} N_L_gamma_record={n_da:g}" in printed


def test_cyclic_small_amplitude_does_not_liquefy(tmp_path_factory, specimens, cyclic_large):
    """At CSR 0.055 (half the rate: the same period) the loose specimen does not liquefy, by
    either criterion, within SMALL_MULTIPLE times the cycles CSR 0.11 needs to liquefy by
    both, with its amplitude held as closely."""
    t_large, _ = read_csv(cyclic_large[0] / "large.csv")
    needed = max(t_large["N_L_ru"][-1], t_large["N_L_gamma"][-1])
    assert needed > 0
    work, _ = run_deck(tmp_path_factory, specimens, "cyclic_simple_shear",
                       dict(CYCLIC, csr=CSR_SMALL, rate=RATE_SMALL,
                            cycles=int(np.ceil(SMALL_MULTIPLE * needed)), out="small"),
                       tag="cyclic_small")
    t, _ = read_csv(work / "small.csv")
    assert t["cycles"][-1] >= SMALL_MULTIPLE * needed
    assert t["N_L_ru"][-1] == 0.0 and t["N_L_gamma"][-1] == 0.0
    _, _, (n_ru, n_da) = replay(t, CSR_SMALL)
    assert (n_ru, n_da) == (0.0, 0.0)
    over = np.max(np.abs(t["tau"])) / (CSR_SMALL * t["sig_n"][0]) - 1.0
    at_needed = np.max(t["r_u"][t["cycles"] <= needed])
    print(f"CSR {CSR_SMALL}: r_u max {at_needed:.3f} by N = {needed} (where CSR {CSR_LARGE} "
          f"liquefied), {np.max(t['r_u']):.3f} after {t['cycles'][-1]} cycles; max "
          f"|tau|/tau_cyc - 1 = {over:.3g}")
    assert over < OVERSHOOT
    assert np.max(t["r_u"]) < RU_LIMIT


@pytest.mark.skipif(not os.environ.get("TYLMP_SLOW"), reason="slow (about 3 minutes): set "
                    "TYLMP_SLOW=1")
def test_cyclic_resistance_curve(tmp_path_factory, specimens, cyclic_large):
    """The cyclic resistance curve of the loose specimen at 1e-4 1/s: N_L by each criterion
    falls as CSR grows (0.09, 0.10 and the CI test's 0.11), and each liquefies by both within
    60 cycles (docs/decks/cyclic_simple_shear.md)."""
    t_large, _ = read_csv(cyclic_large[0] / "large.csv")
    curve = {CSR_LARGE: (t_large["N_L_ru"][-1], t_large["N_L_gamma"][-1])}
    for csr in (0.09, 0.10):
        work, _ = run_deck(tmp_path_factory, specimens, "cyclic_simple_shear",
                           dict(CYCLIC, csr=csr, rate=RATE_LARGE, cycles=60, csv_every=50,
                                out="curve"), tag=f"cyclic_curve_{csr}")
        t, _ = read_csv(work / "curve.csv")
        curve[csr] = (t["N_L_ru"][-1], t["N_L_gamma"][-1])
    print("CSR: (N_L by r_u, N_L by double amplitude)", curve)
    ratios = sorted(curve)
    for k, criterion in enumerate(("r_u", "double amplitude")):
        n = [curve[c][k] for c in ratios]
        assert all(v > 0 for v in n), criterion
        assert all(a > b for a, b in zip(n, n[1:])), criterion


# ---------------------------------------------------------------------------------------------
# decks of their own: the dense quick specimen (a restart, or a data file written from it)

E, NU, MU, GAMMA = 70e9, 0.3, 0.3, 0.6      # materials/glass.in, the decks' shearing stage


def specimen_settings(specimens):
    """The dense quick specimen's restart file and timestep (its cache record)."""
    import json
    with open(os.path.join(specimens, "dense_quick.restart.json")) as fh:
        settings = json.load(fh)["settings"]
    return os.path.join(specimens, "dense_quick.restart"), settings["dt"]


def shear_deck(start, dt, fix, steps, extra="", after="", triclinic=True):
    """A deck that starts from `start` (lines that define the box and atoms), gives it tilt
    factors, the decks' shearing contact law and numerics, then `extra`, and runs `fix` for
    `steps`."""
    return (start + ("change_box all triclinic\n" if triclinic else "")
            + f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} {GAMMA} damping 0 0\n"
            "neighbor 1.35e-5 bin\nneigh_modify every 1 delay 0 check yes\n"
            f"timestep {dt}\nfix integrate all nve/sphere\n{extra}{fix}\n"
            "thermo 1000\n" + f"run {steps}\n" + after)


def from_restart(restart, before=""):
    return before + LOAD_TYLMP + f"read_restart {restart}\ncomm_modify vel yes\n"


# the flips: drained shear to gamma 2.5 at a fast rate (the tilt of the edge along z flips at
# half the edge along x: 2-3 flips on the dense quick specimen, whose cell is nearly cubic)
FLIP_RATE = 0.02
FLIP_GAMMA = 2.5
# a change of the box needs the restart's per-atom data (the contact histories) consumed by a
# run first; the reference run does the same
RUN0 = "run 0 post no\n"
TILT_PRINT = 'fix tilt all print 1 "$(step) $(xz:%.17g) $(lx:%.17g)" file tilt.txt screen no\n'


def flip_fix(csv, until=FLIP_GAMMA):
    return (f"fix cell all cell/servo shear xz {FLIP_RATE} {SIGMA_N} until gamma {until} "
            f"csv {csv} 1")


@pytest.fixture(scope="module")
def flipped(tmp_path_factory, specimens):
    work = tmp_path_factory.mktemp("flips")
    restart, dt = specimen_settings(specimens)
    steps = int(np.ceil(1.1 * FLIP_GAMMA / (FLIP_RATE * float(dt))))
    run_ok(shear_deck(from_restart(restart), dt, flip_fix("a.csv") + "\n" + TILT_PRINT, steps,
                      extra=RUN0), work, name="in.a")
    tilt = np.loadtxt(work / "tilt.txt", comments="#", ndmin=2)
    jumps = np.flatnonzero(np.diff(tilt[:, 1]) < -0.5 * tilt[1:, 2])
    return work, restart, dt, read_csv(work / "a.csv")[0], tilt, tilt[jumps + 1, 0].astype(int)


def test_flips_gamma_counts_on(flipped):
    """gamma = gamma_dot (t - dt) on every row (the rate chosen at the end of a step moves the
    cell in the next: the first step, from rest, has none), across every flip."""
    _, _, dt, t, tilt, flips = flipped
    print(f"flips at steps {list(flips)}; gamma at the end {t['gamma'][-1]:.6g}")
    assert len(flips) >= 2
    assert t["gamma"][-1] >= FLIP_GAMMA
    moving = t["time"] > 0
    # (to the CSV's 12 digits)
    np.testing.assert_allclose(t["gamma"][moving], FLIP_RATE * (t["time"][moving] - float(dt)),
                               rtol=1e-11, atol=1e-14)
    # each flip takes one box length off the tilt, and the tilt stays within half of it
    assert np.all(np.abs(tilt[:, 1]) <= 0.5 * tilt[:, 2] * (1 + 1e-12))


STRESS_COLUMNS = ("sig1", "sig2", "sig3", "p", "q", "sig_xy", "sig_xz", "sig_yz", "tau", "sig_n")


def test_flip_leaves_the_stress_alone(flipped):
    """The same specimen described by the equivalent cell whose edge c leans one box length
    back (xz = -lx: the same lattice of images) is flipped by the fix at its first step; every
    stress of its record equals that of the unflipped run to 1e-9 of sigma_n0 over the first
    steps (then the two drift apart at round-off, as any two orders of arithmetic do). The
    flip shifts coordinates by a box length, so each branch vector carries the round-off of
    numbers about twenty contact lengths large, and the stress, a sum of some 10^4 contact
    terms much larger than their mean, carries that: measured, the difference levels at
    4e-11 to 1.0e-10 within five steps on the quick specimen (CSV digits included). A flip
    done wrong (a row of images missed or counted twice) moves the stress by far more."""
    work, restart, dt, ref, _, _ = flipped
    # LAMMPS 29 Sep 2021 refuses a tilt beyond half a box length unless told
    before = 'if "$(version) < 20220324" then "box tilt large"\n'
    extra = RUN0 + "change_box all xz final $(-lx)\n"
    steps = 20
    run_ok(shear_deck(from_restart(restart, before), dt,
                      flip_fix("c.csv") + "\n" + TILT_PRINT.replace("tilt.txt", "tilt_c.txt"),
                      steps, extra=extra), work, name="in.c")
    t = read_csv(work / "c.csv")[0]
    tilt = np.loadtxt(work / "tilt_c.txt", comments="#", ndmin=2)
    # the tilt -lx at the start (fix print's row at setup), flipped to 0 by the first step and
    # growing from then on
    assert tilt[0, 1] == pytest.approx(-tilt[0, 2], rel=1e-12)
    assert abs(tilt[1, 1]) < 1e-9 * tilt[1, 2] and np.all(np.diff(tilt[1:, 1]) > 0)
    assert len(t["step"]) == steps + 1
    scale = ref["sig_n"][0]
    for name in STRESS_COLUMNS:
        diff = np.max(np.abs(t[name] - ref[name][:steps + 1])) / scale
        print(f"{name}: max |flipped - unflipped|/sigma_n0 over {steps} steps = {diff:.2g}")
        assert diff < 1e-9, name



def first_above(diff, levels=(1e-12, 1e-9, 1e-6)):
    return {level: (int(np.flatnonzero(diff > level)[0]) if np.any(diff > level) else None)
            for level in levels}


def stress_difference(t, ref, rows):
    """max over the stress columns of |t - ref|/sigma_n0, row by row (rows of ref)."""
    return np.max([np.abs(t[name] - ref[name][rows]) / ref["sig_n"][0]
                   for name in STRESS_COLUMNS], axis=0)


RESUMED_STEPS = 30


def test_restart_right_after_a_flip_resumes_the_run(flipped):
    """A run stopped at the step of the first flip writes a restart file; a new LAMMPS reads it,
    defines the same fix again and goes on: its rows equal the uninterrupted run's to 1e-9 of
    sigma_n0 over RESUMED_STEPS steps. The resumed run builds its neighbour lists afresh, so it
    sums the forces in another order: round-off at first, then chaos (printed)."""
    work, restart, dt, ref, _, flips = flipped
    first = int(ref["step"][0])
    to_flip = int(flips[0]) - first
    run_ok(shear_deck(from_restart(restart), dt, flip_fix("b.csv"), to_flip, extra=RUN0,
                      after="write_restart flip.restart\n"), work, name="in.b")
    run_ok(shear_deck(from_restart("flip.restart"), dt, flip_fix("b.csv"), 2000,
                      triclinic=False), work, name="in.b2")
    t = read_csv(work / "b.csv")[0]
    assert np.array_equal(t["step"], ref["step"][:len(t["step"])])
    rows = np.arange(len(t["step"]))
    diff = stress_difference(t, ref, rows)
    # the record up to the flip is the same run: bit for bit
    assert np.all(diff[:to_flip + 1] == 0)
    after = diff[to_flip + 1:]
    print("resumed after the flip at step", flips[0], ": difference first above",
          {k: (v + 1 if v is not None else None) for k, v in first_above(after).items()},
          "steps after the restart")
    np.testing.assert_array_equal(t["gamma"], ref["gamma"][rows])
    assert np.max(after[:RESUMED_STEPS]) < 1e-9


TWO_RANK_STEPS = 300
TWO_RANK_RUN = 3000     # run on, to print where the records part


def test_one_and_two_ranks_agree_over_a_short_run(flipped):
    """The flip run on 2 ranks: over its first TWO_RANK_STEPS steps the stresses agree with 1
    rank to 1e-9 of sigma_n0 (docs/validation.md: round-off, then chaos; where the records part
    is printed over TWO_RANK_RUN steps)."""
    work, restart, dt, ref, _, _ = flipped
    run_ok(shear_deck(from_restart(restart), dt, flip_fix("np2.csv"), TWO_RANK_RUN,
                      extra=RUN0), work, name="in.np2", np_ranks=2)
    t = read_csv(work / "np2.csv")[0]
    rows = np.arange(len(t["step"]))
    assert len(rows) == TWO_RANK_RUN + 1
    diff = stress_difference(t, ref, rows)
    print("2 ranks against 1: difference first above", first_above(diff), "steps")
    assert np.max(diff[:TWO_RANK_STEPS + 1]) < 1e-9


def test_analysis_of_a_hand_made_cyclic_record():
    """tyanalysis.shear on a record written by hand: three half cycles of 4 rows, the count
    growing at the rows after the reversals; the double amplitude is measured from gamma at the
    last row of the half cycle before, and r_u's first crossing gives its half cycle's count
    (its cycles completed + 0.5)."""
    from tylmp.analysis import io, shear
    gamma = [0.0, 0.01, 0.02, 0.03, 0.02, 0.0, -0.01, -0.02, -0.01, 0.0, 0.02, 0.04]
    cycles = [0.0] * 4 + [0.5] * 4 + [1.0] * 4
    r_u = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.96, 0.9, 0.97, 0.99]
    t = io.Table({"time": np.arange(12.0), "gamma": gamma, "cycles": cycles, "r_u": r_u,
                  "tau": np.zeros(12), "sig_n": np.ones(12), "tau_ratio": np.zeros(12)})
    assert shear.kind(t) == "cyclic"
    assert list(shear.half_cycle_starts(t)) == [4, 8]
    # |gamma - gamma_rev|: 0.03 at row 3 (< 0.0375), 0.04 at row 6 (gamma_rev = 0.03), and
    # with the limit 0.06 first at row 11 (0.04 - (-0.02), gamma_rev = gamma of row 7)
    assert shear.liquefaction_rows(t) == (8, 6)
    assert shear.liquefaction_from_record(t) == (1.5, 1.0)
    assert shear.liquefaction_from_record(t, ru_limit=0.45, da_limit=0.06) == (1.0, 1.5)
    n = shear.continuous_cycles(t)
    assert n[0] == 0.0 and n[4] == 0.5 and n[8] == 1.0 and n[-1] == 1.5
    assert np.all(np.diff(n) > 0)
    assert shear.shear_rate(t) == pytest.approx(0.01)
