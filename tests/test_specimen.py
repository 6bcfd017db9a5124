"""Tests of tylmp.specimen: size distribution, exact solid fraction, no overlaps
(including across the periodic faces), determinism, data file read back by LAMMPS.

Run from the repository root: /usr/bin/python3 -m pytest tests/test_specimen.py -q -p no:cacheprovider
"""
import importlib
import math
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np
import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SRC_PY = os.path.join(REPO, "python")


def _import_specimen():
    """tylmp.specimen from sys.path (build/python via conftest, or an install); from the source
    tree if no tylmp with a specimen generator is there."""
    try:
        mod = importlib.import_module("tylmp.specimen")
        if hasattr(mod, "generate") and hasattr(mod, "paper_size_distribution"):
            return mod
    except ImportError:
        pass
    for name in [m for m in sys.modules if m == "tylmp" or m.startswith("tylmp.")]:
        del sys.modules[name]
    sys.path.insert(0, SRC_PY)
    return importlib.import_module("tylmp.specimen")


sp = _import_specimen()
# the directory that holds the package tylmp that sp belongs to
MODULE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(sys.modules["tylmp"].__file__)))

MM = 1e-3
N_QUICK = 500
N_PAPER = 3620
LMP = shutil.which("lmp") or "/usr/bin/lmp"    # the lmp under test (PATH), as elsewhere


def vol_fraction(d, L):
    """Independent Σ π d³/6 / L³."""
    d = np.asarray(d, dtype=np.float64)
    return float(np.sum(math.pi * d ** 3 / 6.0)) / L ** 3


def brute_min_clearance(pos, d, L):
    """min over pairs of |r_ij|_min-image − (r_i + r_j), brute force O(N²), chunked."""
    n = len(d)
    best = np.inf
    for a in range(0, n, 256):
        dv = pos[a:a + 256, None, :] - pos[None, :, :]
        dv -= L * np.round(dv / L)
        dist = np.sqrt(np.sum(dv * dv, axis=-1))
        gap = dist - 0.5 * (d[a:a + 256, None] + d[None, :])
        idx = np.arange(a, min(a + 256, n))
        gap[idx - a, idx] = np.inf          # self
        best = min(best, float(gap.min()))
    return best


def kd_min_clearance(pos, d, L):
    """Same with a periodic KD-tree (scipy) over pairs closer than the largest diameter."""
    try:
        from scipy.spatial import cKDTree
    except ImportError:                     # no scipy: brute force is still fine at N=3620
        return brute_min_clearance(pos, d, L)
    tree = cKDTree(pos, boxsize=L)
    pairs = tree.query_pairs(r=float(d.max()), output_type="ndarray")
    if len(pairs) == 0:
        return np.inf
    i, j = pairs[:, 0], pairs[:, 1]
    dv = pos[j] - pos[i]
    dv -= L * np.round(dv / L)
    dist = np.sqrt(np.sum(dv * dv, axis=1))
    return float(np.min(dist - 0.5 * (d[i] + d[j])))


@pytest.fixture(scope="module")
def quick():
    return sp.generate(N_QUICK, 0.5, seed=1)


@pytest.fixture(scope="module")
def paper():
    t0 = time.perf_counter()
    out = sp.generate(N_PAPER, 0.5, seed=1)
    dt = time.perf_counter() - t0
    print(f"\n[specimen] generation of {N_PAPER} spheres at solid fraction 0.5: {dt:.2f} s, "
          f"cube side {out[0] / MM:.6f} mm")
    assert dt < 60.0
    return out


# ---- size distribution -------------------------------------------------------------

def test_paper_size_distribution():
    d, p = sp.paper_size_distribution()
    assert len(d) == len(p) == 5
    assert d[0] == pytest.approx(0.135 * MM, rel=1e-15)
    assert d[-1] == pytest.approx(0.4 * MM, rel=1e-15)
    assert np.all(np.diff(d) > 0)
    assert np.all(p > 0)
    assert abs(p.sum() - 1.0) < 1e-14
    assert abs(float(p @ d) / MM - 0.26) < 1e-12
    # smooth, single-peaked
    k = int(np.argmax(p))
    assert np.all(np.diff(p[:k + 1]) > 0) and np.all(np.diff(p[k:]) < 0)
    # mean-only variant also has the exact mean
    d1, p1 = sp.paper_size_distribution(match_cell=False)
    assert abs(float(p1 @ d1) / MM - 0.26) < 1e-12


@pytest.mark.parametrize("n", [N_QUICK, N_PAPER, 1000, 8000])
def test_size_counts(n):
    d, c = sp.size_counts(n)
    assert int(c.sum()) == n and np.all(c > 0)
    assert d[0] == 0.135 * MM and d[-1] == 0.4 * MM
    assert abs(float(c @ d) / n / MM - 0.26) < 1e-12
    # the interior diameters move by far less than the spacing
    d0, p = sp.paper_size_distribution()
    assert np.max(np.abs(d - d0)) < 0.01 * (d0[1] - d0[0])
    assert np.max(np.abs(c / n - p)) <= 1.0 / n


def test_paper_cell_side_implied():
    """3620 spheres of the chosen distribution at solid fraction 0.5 fill a cube of
    ≈4.3 mm, the paper's cell."""
    d, c = sp.size_counts(N_PAPER)
    L = sp.box_side(np.repeat(d, c), 0.5)
    assert abs(L / (4.3 * MM) - 1.0) < 1e-4
    # the mean-only maximum-entropy distribution would not match the paper's cell
    d1, c1 = sp.size_counts(N_PAPER, match_cell=False)
    L1 = sp.box_side(np.repeat(d1, c1), 0.5)
    assert L1 / (4.3 * MM) > 1.04


# ---- candidate size distributions (docs/specimen.md) --------------------------------------

# the facts each candidate claims to honour exactly: which mean is 0.26 mm, and whether
# 3620 spheres at solid fraction 0.5 fill the paper's 4.3 mm cube
CLAIMS = {"maxent": ("number", True), "geometric": ("number", True),
          "mean-only": ("number", False), "volume-mean": ("volume", False)}


def test_every_candidate_is_listed():
    assert set(sp.DISTRIBUTIONS) == set(CLAIMS)


@pytest.mark.parametrize("name", sorted(CLAIMS))
@pytest.mark.parametrize("n", [N_QUICK, N_PAPER, 8000])
def test_candidate_honours_its_facts(name, n):
    mean_kind, cell = CLAIMS[name]
    d, c = sp.size_counts(n, distribution=name)
    # five sizes from 0.135 to 0.4 mm, every size present, n spheres
    assert len(d) == 5 and np.all(np.diff(d) > 0) and np.all(c > 0) and int(c.sum()) == n
    assert d[0] == 0.135 * MM and d[-1] == 0.4 * MM
    number_mean = float(c @ d) / n                          # Σ c d / n
    volume_mean = float(c @ d ** 4) / float(c @ d ** 3)     # Σ c d^4 / Σ c d^3
    assert abs((number_mean if mean_kind == "number" else volume_mean) / MM - 0.26) < 1e-12
    assert sp.number_mean(d, c) == pytest.approx(number_mean, rel=1e-14)
    assert sp.volume_mean(d, c) == pytest.approx(volume_mean, rel=1e-14)
    # cell side of 3620 spheres at 0.5: L^3 = 3620 (π/6) <d^3> / 0.5
    if n == N_PAPER:
        L = (N_PAPER * math.pi / 6 * float(c @ d ** 3) / n / 0.5) ** (1 / 3)
        if cell:
            assert abs(L / (4.3 * MM) - 1.0) < 1e-4
        else:
            assert abs(L / (4.3 * MM) - 1.0) > 0.04         # documented: 4.53 / 3.51 mm


def test_candidate_spacings_and_the_volume_mean_bound():
    d, _ = sp.paper_size_distribution(distribution="geometric")
    assert np.allclose(d[1:] / d[:-1], (0.4 / 0.135) ** 0.25, rtol=1e-14)
    d, _ = sp.paper_size_distribution(distribution="maxent")
    assert np.allclose(np.diff(d), 0.06625 * MM, rtol=1e-12)
    # D[4,3] >= <d^3>^(1/3) (moment inequality): with the paper's cell <d^3>^(1/3) = 0.2758 mm,
    # so a volume mean of 0.26 mm cannot also fill 4.3 mm at 0.5 -- whatever the fractions
    mean_d3 = 0.5 * (4.3 * MM) ** 3 / (N_PAPER * math.pi / 6)
    assert mean_d3 ** (1 / 3) / MM == pytest.approx(0.27578, abs=1e-5)
    for name in CLAIMS:
        d, p = sp.paper_size_distribution(distribution=name)
        assert sp.volume_mean(d, p) >= float(p @ d ** 3) ** (1 / 3)


def test_default_distribution_unchanged():
    d0, c0 = sp.size_counts(N_PAPER)
    d1, c1 = sp.size_counts(N_PAPER, distribution="maxent")
    assert np.array_equal(c0, [313, 930, 1388, 830, 159]) and np.array_equal(c0, c1)
    assert np.array_equal(d0, d1)
    d2, c2 = sp.size_counts(N_PAPER, match_cell=False)
    d3, c3 = sp.size_counts(N_PAPER, distribution="mean-only")
    assert np.array_equal(c2, c3) and np.array_equal(d2, d3)
    with pytest.raises(ValueError, match="unknown size distribution 'nope'"):
        sp.size_counts(N_PAPER, distribution="nope")


def test_generate_with_candidate():
    L, d, pos = sp.generate(N_QUICK, 0.5, seed=2, distribution="volume-mean")
    sizes, counts = sp.size_counts(N_QUICK, distribution="volume-mean")
    assert np.array_equal(np.sort(d), np.sort(np.repeat(sizes, counts)))
    assert abs(vol_fraction(d, L) - 0.5) < 1e-12
    i, j = sp.find_overlaps(pos, d, L)
    assert len(i) == 0


# ---- generated assemblies ------------------------------------------------------------

def check_assembly(L, d, pos, n, phi):
    assert d.shape == (n,) and pos.shape == (n, 3)
    assert abs(d.mean() / MM - 0.26) < 1e-12
    assert d.min() == 0.135 * MM and d.max() == 0.4 * MM
    assert abs(vol_fraction(d, L) - phi) < 1e-12
    assert abs(sp.solid_fraction(d, L) - phi) < 1e-12
    assert np.all(pos >= 0.0) and np.all(pos < L)
    sizes, counts = sp.size_counts(n)
    got = np.array([np.count_nonzero(d == s) for s in sizes])
    assert np.array_equal(got, counts) and got.sum() == n


def test_quick_assembly(quick):
    L, d, pos = quick
    check_assembly(L, d, pos, N_QUICK, 0.5)
    assert brute_min_clearance(pos, d, L) >= 0.0
    assert len(sp.find_overlaps(pos, d, L)[0]) == 0


def test_paper_assembly(paper):
    L, d, pos = paper
    check_assembly(L, d, pos, N_PAPER, 0.5)
    assert abs(L / (4.3 * MM) - 1.0) < 1e-4
    assert kd_min_clearance(pos, d, L) >= 0.0
    assert len(sp.find_overlaps(pos, d, L)[0]) == 0


def test_rsa_only_low_fraction():
    """Below the RSA threshold the assembly is pure random sequential addition."""
    L, d, pos, info = sp.generate(300, 0.25, seed=7, return_info=True)
    assert info["compress_steps"] == 0
    assert abs(vol_fraction(d, L) - 0.25) < 1e-12
    assert brute_min_clearance(pos, d, L) >= 0.0


def test_overlap_across_periodic_faces_detected():
    """The checks see pairs that overlap only through the periodic boundary."""
    L = 1.0 * MM
    d = np.array([0.4, 0.4, 0.135]) * MM
    pos = np.array([[0.01, 0.5, 0.5], [0.99, 0.5, 0.5], [0.5, 0.5, 0.5]]) * MM
    assert brute_min_clearance(pos, d, L) < 0
    assert kd_min_clearance(pos, d, L) < 0
    i, j = sp.find_overlaps(pos, d, L)
    assert list(zip(i, j)) == [(0, 1)]


def test_deterministic(quick):
    L, d, pos = quick
    L2, d2, pos2 = sp.generate(N_QUICK, 0.5, seed=1)
    assert L2 == L and np.array_equal(d2, d) and np.array_equal(pos2, pos)
    L3, d3, pos3 = sp.generate(N_QUICK, 0.5, seed=2)
    assert L3 == L and np.array_equal(d3, d) and not np.array_equal(pos3, pos)


# ---- data file ---------------------------------------------------------------------------

def run_lmp(workdir, data_name):
    deck = (
        "units si\n"
        "atom_style sphere\n"
        "boundary p p p\n"
        f"read_data {data_name}\n"
        "compute m all property/atom mass\n"
        "compute mtot all reduce sum c_m\n"
        "thermo_style custom step atoms c_mtot\n"
        "thermo_modify format float %.16e\n"
        "run 0\n"
        "variable natoms equal atoms\n"
        "variable mtot equal c_mtot\n"
        'print "RESULT ${natoms} ${mtot}"\n'
    )
    with open(os.path.join(workdir, "in.read"), "w") as f:
        f.write(deck)
    r = subprocess.run([LMP, "-in", "in.read", "-log", "none"], cwd=workdir,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    m = re.search(r"^RESULT (\S+) (\S+)", r.stdout, re.M)
    assert m, r.stdout[-2000:]
    return int(float(m.group(1))), float(m.group(2))


def test_write_read_data(tmp_path, quick):
    L, d, pos = quick
    path = tmp_path / "specimen.data"
    sp.write_data(path, L, d, pos)
    assert sorted(os.listdir(tmp_path)) == ["specimen.data"]      # no temp file left
    text = path.read_text()
    assert f"{N_QUICK} atoms" in text and "1 atom types" in text
    assert re.search(r"^0 \S+ xlo xhi$", text, re.M)
    assert "Atoms # sphere" in text
    box, d2, rho, pos2 = sp.read_data(path)
    assert np.all(box == L)
    assert np.array_equal(d2, d) and np.array_equal(pos2, pos)
    assert np.all(rho == 2650e12)
    # first atom line: id type diameter density x y z
    line = text.split("Atoms # sphere")[1].strip().splitlines()[0].split()
    assert len(line) == 7 and line[:2] == ["1", "1"]
    assert float(line[2]) == d[0] and float(line[3]) == 2650e12


@pytest.mark.skipif(LMP is None, reason="lmp not installed")
@pytest.mark.parametrize("density", [2650e12, 2650.0])
def test_lammps_reads_data(tmp_path, paper, density):
    L, d, pos = paper
    sp.write_data(tmp_path / "specimen.data", L, d, pos, density=density)
    natoms, mtot = run_lmp(str(tmp_path), "specimen.data")
    assert natoms == N_PAPER
    expected = float(np.sum(density * math.pi * d ** 3 / 6.0))
    assert mtot == pytest.approx(expected, rel=1e-12)
    # and mass = density × solid fraction × cell volume
    assert mtot == pytest.approx(density * 0.5 * L ** 3, rel=1e-12)


def _package_env():
    """The environment of a child Python that imports this tylmp (the module under test first,
    then the source tree, then the caller's PYTHONPATH)."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(
        [MODULE_DIR, SRC_PY] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
    return env


def test_cli(tmp_path):
    out = tmp_path / "cli.data"
    r = subprocess.run([sys.executable, "-m", "tylmp.specimen", "--scale", "quick",
                        "--seed", "3", "--out", str(out)],
                       capture_output=True, text=True, env=_package_env(), timeout=120)
    assert r.returncode == 0, r.stderr
    assert "500 spheres" in r.stdout
    box, d, rho, pos = sp.read_data(out)
    L, d0, pos0 = sp.generate(N_QUICK, 0.5, seed=3)
    assert np.all(box == L) and np.array_equal(d, d0) and np.array_equal(pos, pos0)
    assert np.all(rho == 2650e12)


def test_cli_distributions_table(capsys):
    assert sp.main(["--distributions"]) == 0
    rows = [r for r in capsys.readouterr().out.splitlines() if r.startswith("| ") and "---" not in r]
    table = {r.split("|")[1].strip(): [c.strip() for c in r.split("|")[2:-1]] for r in rows[1:]}
    assert set(table) == set(CLAIMS)
    for name in CLAIMS:
        d, c = sp.size_counts(N_PAPER, distribution=name)
        assert table[name][1] == ", ".join(map(str, c))
        # φ0 of 3620 spheres in the 4.3 mm cube, recomputed here
        phi = math.pi / 6 * float(c @ d ** 3) / (4.3 * MM) ** 3
        assert float(table[name][6]) == pytest.approx(phi, abs=6e-5)


# ---- a user's size distribution (docs/specimen.md, "Your own size distribution") ----------

def test_uniform_distribution_is_the_midpoint_quantiles():
    """uniform:A:B by number: n diameters A + (B - A)(k + 1/2)/n, mean (A + B)/2."""
    n = 400
    d = sp.diameters(n, "uniform:0.1e-3:0.3e-3")
    expected = 0.1e-3 + 0.2e-3 * (np.arange(n) + 0.5) / n
    assert np.allclose(np.sort(d), expected, rtol=1e-13, atol=0)
    assert d.mean() == pytest.approx(0.2e-3, rel=1e-12)


def test_lognormal_distribution_has_its_median_and_spread():
    """lognormal:D50:SIGMA by number: ln d of the n diameters has median ln D50 and standard
    deviation SIGMA (to the sampling of the tails by n quantiles: 2 % at n = 4000)."""
    d = sp.diameters(4000, "lognormal:0.2e-3:0.3")
    assert np.median(d) == pytest.approx(0.2e-3, rel=1e-3)
    assert np.std(np.log(d)) == pytest.approx(0.3, rel=0.02)
    # a quarter of the spheres lie below the lower quartile exp(ln D50 - 0.6745 SIGMA)
    q1 = 0.2e-3 * math.exp(-0.6744897501960817 * 0.3)
    assert np.count_nonzero(d < q1) == 1000


@pytest.mark.parametrize("basis", ["number", "mass"])
def test_size_table_by_number_or_mass(tmp_path, basis):
    """A table of diameters and fractions: by number the counts are n x the fractions; by mass
    the counts make the mass shares Σ c d³ of each size equal to the fractions."""
    table = tmp_path / "psd.txt"
    table.write_text("# diameter [m]  fraction\n0.1e-3 1\n0.2e-3 3   # the coarse size\n")
    n = 1000
    d = sp.diameters(n, f"{basis}:{table}")
    small = np.count_nonzero(d == 0.1e-3)
    assert small + np.count_nonzero(d == 0.2e-3) == n
    if basis == "number":
        assert small == 250
    else:
        share = small * 1e-12 / (small * 1e-12 + (n - small) * 8e-12)
        assert share == pytest.approx(0.25, abs=1e-3)
        assert small == round(n * (1 / 1) / (1 / 1 + 3 / 8))    # counts ∝ fraction / d³


def test_generate_with_a_users_distribution():
    """The generator places n spheres of a user's distribution without overlap at the target
    solid fraction."""
    L, d, pos = sp.generate(200, 0.5, seed=4, distribution="lognormal:0.2e-3:0.25")
    assert np.array_equal(d, sp.diameters(200, "lognormal:0.2e-3:0.25"))
    assert abs(vol_fraction(d, L) - 0.5) < 1e-12
    assert len(sp.find_overlaps(pos, d, L)[0]) == 0


@pytest.mark.parametrize("spec,message", [
    ("uniform:0.3e-3:0.1e-3", "D_MIN must be below D_MAX"),
    ("lognormal:0.2e-3", "lognormal takes lognormal:D50:SIGMA"),
    ("lognormal:0.2e-3:-1", "SIGMA must be a finite number > 0, got -1"),
    ("uniform:nan:1e-3", "D_MIN must be a finite number > 0, got nan"),
    ("number:/nonexistent/psd.txt", "cannot read /nonexistent/psd.txt"),
    ("weibull:1:2", "unknown size distribution 'weibull:1:2'")])
def test_bad_distribution_is_named(spec, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        sp.parse_distribution(spec)


def test_cli_users_distribution(tmp_path):
    """python3 -m tylmp.specimen --distribution lognormal:...: the data file holds those
    diameters; a bad one is a usage error naming it."""
    out = tmp_path / "ln.data"
    env = _package_env()
    r = subprocess.run([sys.executable, "-m", "tylmp.specimen", "--n", "150", "--distribution",
                        "lognormal:0.2e-3:0.25", "--out", str(out)],
                       capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 0, r.stderr
    _, d, _, _ = sp.read_data(out)
    assert np.array_equal(np.sort(d), np.sort(sp.diameters(150, "lognormal:0.2e-3:0.25")))
    r = subprocess.run([sys.executable, "-m", "tylmp.specimen", "--n", "150", "--distribution",
                        "uniform:1", "--out", str(out)],
                       capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 2 and "uniform takes uniform:D_MIN:D_MAX" in r.stderr


def test_find_overlaps_does_what_its_description_says(tmp_path):
    """find_overlaps returns index arrays i < j of the pairs closer than r_i + r_j across the
    periodic faces, touching pairs excluded, and takes the box as read_data returns it."""
    d = np.array([1e-3, 1e-3, 1e-3, 0.5e-3])
    pos = np.array([[0.1e-3, 1e-3, 1e-3], [4.95e-3, 1e-3, 1e-3],      # 0.15 mm apart across x
                    [2.5e-3, 2.5e-3, 2.5e-3], [2.5e-3, 2.5e-3 + 0.75e-3, 2.5e-3]])  # touching
    i, j = sp.find_overlaps(pos, d, 5e-3)
    assert (i.tolist(), j.tolist()) == ([0], [1])
    path = tmp_path / "four.data"
    sp.write_data(path, 5e-3, d, pos)
    box, diam, _, xyz = sp.read_data(path)
    i, j = sp.find_overlaps(xyz, diam, box)
    assert (i.tolist(), j.tolist()) == ([0], [1])
    with pytest.raises(ValueError, match="the cell must be a cube"):
        sp.find_overlaps(xyz, diam, [5e-3, 5e-3, 6e-3])


@pytest.mark.parametrize("name", ["maxent", "geometric", "mean-only", "volume-mean"])
def test_diameters_are_the_same_bits_under_every_blas_kernel(name):
    """The diameters do not depend on the machine. OpenBLAS picks its kernels at run time by
    the processor (here forced with OPENBLAS_CORETYPE, as an AMD Zen, an Intel Haswell or
    Skylake-X, or a generic x86-64 would choose them), and its kernels sum in different
    orders; the size distribution's solve once went through it, and the interior diameters
    of the paper's 3620 spheres differed in their last bits between an AMD and an Intel
    machine, so every specimen, and every record, differed. Each kernel must give the same
    bits (on a machine without OpenBLAS the variable is ignored and the check still holds)."""
    code = ("from tylmp.specimen import sizes; "
            f"d, c = sizes.size_counts({N_PAPER}, distribution={name!r}); "
            "print(' '.join(x.hex() for x in d), list(c))")
    env = _package_env()
    outputs = {}
    for core in ("Prescott", "Haswell", "SkylakeX", "Zen"):
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           env=dict(env, OPENBLAS_CORETYPE=core), timeout=120)
        assert r.returncode == 0, r.stderr
        outputs[core] = r.stdout
    assert len(set(outputs.values())) == 1, outputs
