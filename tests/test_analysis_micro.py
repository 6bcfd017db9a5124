"""tyanalysis micromechanics: names in step with the compute, shares on a synthetic record."""
import os
import re
import subprocess
import sys

import numpy as np
import pytest

from tylmp.analysis import io
from tylmp.analysis import micromechanics as micro


def test_names_follow_the_compute_vector_layout(repo):
    # the offsets of the C++ enum name the same entries as tyanalysis's NAMES
    with open(os.path.join(repo, "plugin/lammps/compute_thornton_yin_micromechanics.h")) as fh:
        text = fh.read()
    offsets = {m.group(1): int(m.group(2)) for m in re.finditer(r"(\w+) = (\d+),", text)}
    expected = {"FABRIC": "phi_xx", "FABRIC_DEVIATOR": "phi_d", "STRESS": "s_xx",
                "STRESS_NORMAL": "s_normal_xx", "STRESS_TANGENTIAL": "s_tangential_xx",
                "STRESS_STRONG": "s_strong_xx", "STRESS_WEAK": "s_weak_xx", "CONTACTS": "contacts"}
    for enum, name in expected.items():
        assert micro.NAMES[offsets[enum]] == name, enum
    assert len(micro.NAMES) == int(re.search(r"N_VECTOR = (\d+)", text).group(1)) == 41


def synthetic(n=20):
    """axisymmetric stress 100 kPa + q rising to 60 kPa; strong 80 % of it and weak 20 %,
    tangential forces 10 % of the deviator and none of the mean"""
    t = np.linspace(0, 1, n)
    total = {"xx": 80e3 - 20e3 * t, "yy": 80e3 - 20e3 * t, "zz": 140e3 + 40e3 * t - 40e3,
             "xy": 0 * t, "xz": 0 * t, "yz": 0 * t}
    p = (total["xx"] + total["yy"] + total["zz"]) / 3
    cols = {"step": np.arange(n) * 100.0, "contacts": 500 + 0 * t,
            "sliding_fraction": 0.1 * t, "mean_normal_force": 1.0 + 0 * t,
            "strong_fraction": 0.35 + 0 * t}
    for c in micro.TENSOR:
        diagonal = {"xx": 1 / 3 - 0.05 * t, "yy": 1 / 3 - 0.05 * t, "zz": 1 / 3 + 0.1 * t}
        cols[f"phi_{c}"] = diagonal.get(c, 0 * t)
    cols["phi_d"] = 0.15 * t
    for c in micro.TENSOR:
        iso = p if c in ("xx", "yy", "zz") else 0
        dev = total[c] - iso
        cols[f"s_{c}"] = total[c]
        cols[f"s_strong_{c}"] = 0.8 * dev + 0.6 * iso
        cols[f"s_weak_{c}"] = 0.2 * dev + 0.4 * iso
        cols[f"s_tangential_{c}"] = 0.1 * dev
        cols[f"s_normal_{c}"] = 0.9 * dev + iso
    return cols


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "tylmp.analysis", *map(str, args)],
                          capture_output=True, text=True)


@pytest.mark.parametrize("indexed", [False, True])
def test_shares_of_a_synthetic_record(tmp_path, indexed):
    cols = synthetic()
    if indexed:    # as fix print writes them: c_m[1] ... c_m[41]
        cols = {"step": cols["step"], **{f"c_m[{k + 1}]": cols[n] for k, n in enumerate(micro.NAMES)}}
    path = tmp_path / "micro.csv"
    io.write_servo_csv(path, cols)
    r = run_cli("micromechanics", path, "--out", tmp_path / "m.png")
    assert r.returncode == 0, r.stderr
    values = dict(kv.split("=") for kv in r.stdout.splitlines()[0].split(": ", 1)[1].split())
    assert float(values["q_strong_share"]) == pytest.approx(0.8, abs=1e-12)
    assert float(values["q_weak_share"]) == pytest.approx(0.2, abs=1e-12)
    assert float(values["q_tangential_share"]) == pytest.approx(0.1, abs=1e-12)
    assert float(values["p_tangential_share"]) == pytest.approx(0.0, abs=1e-12)
    assert float(values["p_strong_share"]) == pytest.approx(0.6, abs=1e-12)
    assert float(values["phi_d"]) == pytest.approx(0.15)
    assert (tmp_path / "m.png").stat().st_size > 10000


def test_record_without_the_compute_columns_is_an_error(tmp_path):
    path = tmp_path / "x.csv"
    io.write_servo_csv(path, {"step": np.arange(3.0), "p": np.ones(3)})
    r = run_cli("micromechanics", path, "--out", tmp_path / "m.png")
    assert r.returncode == 2 and "expected the 41 columns" in r.stderr


def test_fix_ave_time_table_is_read(tmp_path):
    # fix ave/time ... c_micro[*] file F writes a title line, then '# TimeStep c_micro[1] ...'
    cols = synthetic(5)
    path = tmp_path / "micro.txt"
    with open(path, "w") as fh:
        fh.write("# Time-averaged data for fix record\n# TimeStep"
                 + "".join(f" c_micro[{k}]" for k in range(1, 42)) + "\n")
        for i in range(5):
            fh.write(f"{int(cols['step'][i])}" + "".join(f" {cols[n][i]!r}" for n in micro.NAMES)
                     + "\n")
    table = micro.read_record(path)
    values = micro.columns(table)
    np.testing.assert_array_equal(values["phi_d"], cols["phi_d"])
    r = run_cli("micromechanics", path, "--out", tmp_path / "m.png")
    assert r.returncode == 0, r.stderr
