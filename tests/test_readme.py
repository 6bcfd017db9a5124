"""README's minimal deck runs as printed, from the repository root, and does what README says
of it: the cell compresses along x while the servo holds the mean stress at 100 kPa, and the
run ends when the deviator strain eps1 - eps3 reaches 0.5 %."""
import re
import shutil
import subprocess

import numpy as np

from conftest import REPO

BLOCK = re.compile(r"## A minimal deck\n.*?```lammps\n(.*?)```", re.S)


def minimal_deck():
    with open(f"{REPO}/README.md", encoding="utf-8") as fh:
        return BLOCK.search(fh.read()).group(1)


def test_readme_minimal_deck_holds_p_and_stops_at_its_strain(tmp_path):
    # the deck reads bench/data/... relative to the repository root: run it from a copy of
    # the tree's layout so that its outputs do not land in the repository
    (tmp_path / "bench").mkdir()
    shutil.copytree(f"{REPO}/bench/data", tmp_path / "bench" / "data")
    (tmp_path / "my_axisym.in").write_text(minimal_deck())
    out = subprocess.run(["lmp", "-in", "my_axisym.in", "-log", "none", "-nocite"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0 and "ERROR" not in out.stdout, out.stdout[-3000:] + out.stderr
    assert "reached the target 0.005" in out.stdout
    rec = np.genfromtxt(tmp_path / "my_axisym.csv", delimiter=",", names=True)
    eps1, eps3 = rec["eps1"], rec["eps3"]
    # compression along x (the major axis), at the prescribed rate 5e-5 1/s of natural strain
    assert eps1[-1] > 0.0 and np.all(np.diff(eps1) >= 0.0)
    rate = (eps1[-1] - eps1[1]) / (rec["time"][-1] - rec["time"][1])
    assert abs(rate / 5e-5 - 1.0) < 1e-6
    assert eps1[-1] - eps3[-1] >= 0.005
    # mean stress held: sigma_ii / 3 within 0.5 % of 100 kPa over the second half of the run
    late = slice(len(rec) // 2, None)
    p = (rec["sig1"] + rec["sig2"] + rec["sig3"])[late] / 3.0
    assert np.all(np.abs(p / 1e5 - 1.0) < 5e-3)
    # a dense specimen resists: the deviator stress has risen well above zero, and the lateral
    # stresses stay equal (axisymmetric) while sig1 grows
    q = (rec["sig1"] - rec["sig3"])[-1]
    assert q > 2e4
    assert abs(rec["sig2"][-1] - rec["sig3"][-1]) < 0.05 * q


SHEAR_BLOCK = re.compile(r"## A simple-shear deck\n.*?```lammps\n(.*?)```", re.S)


def test_readme_simple_shear_deck_holds_sigma_n_and_stops_at_its_gamma(tmp_path):
    """README's second example: drained simple shear of the shipped specimen. The lateral
    edges do not move (eps1 = eps2 = 0 exactly, so eps_v = eps3), gamma grows at the prescribed
    rate to the 'until' target, sigma_n is held at 100 kPa, and the dense specimen mobilises a
    shear stress."""
    (tmp_path / "bench").mkdir()
    shutil.copytree(f"{REPO}/bench/data", tmp_path / "bench" / "data")
    with open(f"{REPO}/README.md", encoding="utf-8") as fh:
        (tmp_path / "my_shear.in").write_text(SHEAR_BLOCK.search(fh.read()).group(1))
    out = subprocess.run(["lmp", "-in", "my_shear.in", "-log", "none", "-nocite"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0 and "ERROR" not in out.stdout, out.stdout[-3000:] + out.stderr
    assert "reached the target 0.002" in out.stdout
    rec = np.genfromtxt(tmp_path / "my_shear.csv", delimiter=",", names=True)
    assert np.all(rec["eps1"] == 0.0) and np.all(rec["eps2"] == 0.0)
    assert np.allclose(rec["eps_v"], rec["eps3"], rtol=1e-12, atol=1e-15)
    # gamma = gamma_dot (t - dt) exactly (a strain-controlled component at 1e-4 1/s; the rate
    # chosen at the end of a step moves the cell in the next, so the first step has none)
    assert np.allclose(rec["gamma"][1:], 1e-4 * (rec["time"][1:] - 0.0144), rtol=1e-9)
    assert rec["gamma"][-1] >= 0.002
    late = slice(len(rec) // 2, None)
    assert np.all(np.abs(rec["sig_n"][late] / 1e5 - 1.0) < 5e-3)
    # tau = -sigma_xz (compression-positive stress), positive and rising in the dense specimen
    assert np.allclose(rec["tau"], -rec["sig_xz"])
    assert rec["tau_ratio"][-1] > 0.2
