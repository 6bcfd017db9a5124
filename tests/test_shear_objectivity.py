"""Objectivity of drained simple shear (fix cell/servo shear; docs/theory.md §11-12; issue 28;
docs/validation.md, "Objectivity"): one specimen (a data file of the dense quick specimen,
velocities and contact histories dropped) sheared in xz, and with its axes permuted sheared in
xy and in yz so that the same material plane is sheared in the same sense, gives the same
tau/sigma_n against gamma.

The three runs do the same physics with the same numbers in another order (LAMMPS's neighbour
bins and atom sort, its inverse cell matrix, the cell volume lx ly lz, every contact's
|x_i - x_j|^2), so they agree to round-off at first and part later, when a contact forms or
opens one step earlier in one run than in the other. How soon that happens is measured by a
twin that has no frame difference at all: the xz run with every coordinate of the data file
moved by one unit in the last place. Measured on 2026-12-04 (LAMMPS 29 Sep 2021), first row
at which |delta(tau/sigma_n)|/max(tau/sigma_n) exceeds 1e-8:

  rate 1e-3 1/s:  xy 0.150 %, yz 0.150 %, the one-ulp twin 0.150 %
  rate 1e-4 1/s:  xy 0.629 %, yz 0.988 %, the one-ulp twin 0.629 %, 2 ranks 0.629 %
and on the specimen prepared since commit 9ab3779 (another realisation: the setup pass takes
the law's Halley radius), rate 1e-4 1/s: xy 1.18 %, yz 0.929 %, the twin 1.18 %; on that of the
generator since 34fbc32 (docs/specimen.md, "Reproducibility"; the fixture's runs, one at a time,
at 0daa8df), rate 1e-4 1/s: xy 0.670 %, yz 0.670 %, the twin 0.855 %

so the departure is the assembly's chaos horizon, not a frame dependence. The tests run at
1e-4 1/s: the specimen is closer to quasi-static there (inertial number 2.4e-3 against 2.4e-2;
sigma_n held to 0.05 % against 2.5 %), the contact network rearranges less per unit strain, and
the horizon lies beyond the issue's 0.5 %. Beyond it the curves are different realisations of
the same test (chaos, as between 1 and 2 ranks, docs/validation.md). About 2 minutes on 2 cores
after the specimens' preparation (four runs to 3 % of strain, two at a time).
"""
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

from test_decks import read_csv
from test_simple_shear import SIGMA_N, from_restart, shear_deck, specimen_settings
from lmprun import LOAD_TYLMP, run_ok

RATE = 1e-4
BOUND, GAMMA_BOUND = 1e-8, 0.005     # the bound: 1e-8 relative over 0.5 % of gamma
# the runs go on to where the curves part: the twin's departure depends on the specimen's
# realisation (0.63 % on the specimen of commit a89af1a, 1.18 % on that of 9ab3779, whose
# preparation took the law's Halley radius in the setup pass, 0.855 % on that of the generator
# since 34fbc32), so GAMMA_END leaves room for
# a departure up to GAMMA_END / FACTOR
FACTOR = 2.0
GAMMA_END = 0.03

# shear plane -> permutation of the specimen's axes that puts its (x, z) plane, sheared in xz
# (edge along z towards x), on the plane: xy shears the edge along y towards x (new y = old z),
# yz the edge along z towards y (new y = old x)
PERMUTATIONS = {"xz": (0, 1, 2), "xy": (0, 2, 1), "yz": (1, 0, 2)}
TWIN = "xz_ulp"


def permuted_data(path, source, perm, ulp_seed=None):
    """A data file of the spheres of `source` with the axes permuted: new axis k is the old
    axis perm[k] (positions relative to the box's lower corner; velocities zero). With
    `ulp_seed`, every coordinate is moved by one unit in the last place, up or down at random."""
    from tylmp.analysis import io
    from tylmp import specimen
    lo, hi, ids, diameters, positions = io.read_sphere_data(source)
    assert np.array_equal(ids, np.arange(1, len(ids) + 1))
    x = (positions - lo)[:, list(perm)]
    if ulp_seed is not None:
        up = np.random.default_rng(ulp_seed).random(x.shape) < 0.5
        moved = np.nextafter(x, np.where(up, np.inf, -np.inf))
        assert np.all(moved != x) and np.all(np.abs(moved - x) <= np.spacing(np.abs(x)))
        x = moved
    specimen.write_data(path, (hi - lo)[list(perm)], diameters, x, density=2650e12)


@pytest.fixture(scope="module")
def sheared(tmp_path_factory, specimens):
    """Records (rows every step) of xz, xy, yz and the one-ulp twin of xz."""
    work = tmp_path_factory.mktemp("objectivity")
    restart, dt = specimen_settings(specimens)
    run_ok(from_restart(restart) + "write_data spec.data nocoeff\n", work, name="in.data")
    runs = dict(PERMUTATIONS, **{TWIN: PERMUTATIONS["xz"]})
    for name, perm in runs.items():
        permuted_data(work / f"{name}.data", work / "spec.data", perm,
                      ulp_seed=7 if name == TWIN else None)

    def shear(name):
        plane = name[:2]
        start = ("units si\natom_style sphere\natom_modify map array\nboundary p p p\n"
                 f"comm_modify vel yes\nread_data {name}.data\n" + LOAD_TYLMP)
        fix = (f"fix cell all cell/servo shear {plane} {RATE} {SIGMA_N} until gamma {GAMMA_END} "
               f"csv {name}.csv 1")
        steps = int(1.1 * GAMMA_END / (RATE * float(dt)))
        run_ok(shear_deck(start, dt, fix, steps), work, name=f"in.{name}")
        return name, read_csv(work / f"{name}.csv")[0]

    with ThreadPoolExecutor(max_workers=2) as pool:
        records = dict(pool.map(shear, runs))
    for t in records.values():
        assert t["gamma"][-1] >= GAMMA_END
    return records


def departure(t, ref, label):
    """gamma of the first row at which |delta(tau/sigma_n)|/max|tau/sigma_n| exceeds BOUND
    (inf if none), the rows in common and the difference; prints the first crossings of a
    few levels."""
    n = min(len(t["step"]), len(ref["step"]))
    np.testing.assert_array_equal(t["gamma"][:n], ref["gamma"][:n])
    diff = np.abs(t["tau_ratio"][:n] - ref["tau_ratio"][:n]) / np.max(np.abs(ref["tau_ratio"]))
    crossings = {}
    for level in (1e-12, 1e-10, BOUND, 1e-6, 1e-4):
        above = np.flatnonzero(diff > level)
        crossings[level] = ref["gamma"][above[0]] if above.size else np.inf
    print(f"{label} against xz: |delta(tau/sigma_n)|/max first above "
          + ", ".join(f"{level:g} at gamma = {g * 100:.3g} %" if np.isfinite(g)
                      else f"{level:g} not by gamma = {GAMMA_END * 100:g} %"
                      for level, g in crossings.items()))
    return crossings[BOUND], n, diff


def test_permuted_planes_agree_over_half_a_percent(sheared):
    """tau/sigma_n against gamma of xy and yz equals that of xz to 1e-8 of its maximum over the
    first 0.5 % of gamma, and sigma_n (held by the servo on the permuted axis) to 1e-8
    relative; gamma itself is the same number on every row."""
    ref = sheared["xz"]
    for plane in ("xy", "yz"):
        _, n, diff = departure(sheared[plane], ref, plane)
        early = ref["gamma"][:n] <= GAMMA_BOUND
        assert ref["gamma"][:n][early][-1] > 0.99 * GAMMA_BOUND
        assert np.max(diff[early]) < BOUND, plane
        np.testing.assert_allclose(sheared[plane]["sig_n"][:n][early],
                                   ref["sig_n"][:n][early], rtol=BOUND)


def test_the_parting_is_the_chaos_horizon(sheared):
    """The twin (xz again, every coordinate one ulp off: no frame difference, only round-off)
    holds the same bound over 0.5 % and parts from xz within the run; xy and yz part from xz
    at the twin's gamma within a factor FACTOR either way. Were the permutation a frame
    dependence, they would part earlier than the twin; were the twin's parting not chaos, the
    twin would not part at all."""
    ref = sheared["xz"]
    horizon, _, _ = departure(sheared[TWIN], ref, "one-ulp twin (xz)")
    assert GAMMA_BOUND < horizon < GAMMA_END / FACTOR
    for plane in ("xy", "yz"):
        parted, _, _ = departure(sheared[plane], ref, plane)
        print(f"{plane}: parts at {parted / horizon:.3g} times the twin's gamma")
        assert horizon / FACTOR <= parted <= horizon * FACTOR, plane
