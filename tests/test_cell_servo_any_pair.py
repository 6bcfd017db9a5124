"""fix cell/servo with LAMMPS's own granular pair styles (issue 29 item 3): it takes the stress
from the pair virial and, where the pair is not thornton/yin, counts the contacts itself and
estimates their stiffness from the contact forces as for a Hertz law (compute CELL_TALLY,
docs/theory.md §6.5). Shown on the shipped 3620-sphere dense specimen at 100 kPa:
the contact counts equal those of pair thornton/yin on the same packing (serial and across
two ranks), and an axisymmetric test holds p with `pair granular` and `gran/hertz/history`."""
import math

import numpy as np
import pytest

from conftest import REPO
from lmprun import LOAD_TYLMP, run_deck

SPECIMEN = f"{REPO}/bench/data/dense_paper_100kPa.data"
# the glass of the paper with Hertz normal contact and Mindlin friction, no damping
LAWS = {    # pair_style, pair_coeff * * ...
    "thornton/yin": ("thornton/yin", "70e9 0.3 0.3 0"),
    "granular": ("granular", "hertz/material 70e9 0.0 0.3 tangential mindlin NULL 0.0 0.3 "
                             "damping tsuji"),
    # Hertz with Kn = 4G/(3(1 - nu)), Kt = 4G/(2 - nu) (LAMMPS's pair gran docs), G = E/2.6
    "gran/hertz/history": ("gran/hertz/history 5.1282e10 6.3291e10 0 0 0.3 0", ""),
}


def deck(law, fix, run):
    style, coeff = LAWS[law]
    return f"""{LOAD_TYLMP}
units           si
atom_style      sphere
boundary        p p p
comm_modify     vel yes
read_data       {SPECIMEN}
pair_style      {style}
pair_coeff      * * {coeff}
neighbor        1.35e-5 bin
timestep        0.0144
fix             integrate all nve/sphere
fix             cell all cell/servo {fix} variables yes
thermo_style    custom step v_cell_Z v_cell_Zm v_cell_p v_cell_sliding_fraction
thermo_modify   format float %.15g
{run}
"""


def first_thermo_row(output):
    lines = output.splitlines()
    head = next(k for k, line in enumerate(lines) if line.split()[:2] == ["Step", "v_cell_Z"])
    return [float(v) for v in lines[head + 1].split()]


@pytest.mark.parametrize("ranks", [1, 2])
def test_contact_counts_of_other_pair_styles_equal_thornton_yins(tmp_path, ranks):
    rows = {}
    for law in ("thornton/yin", "granular"):
        rc, out = run_deck(deck(law, "axisym x 5e-5 1e5", "run 0"), tmp_path,
                           name=f"in.{law.replace('/', '_')}", np_ranks=ranks)
        assert rc == 0, out[-3000:]
        rows[law] = first_thermo_row(out)
    _, z_ty, zm_ty, p_ty, slide_ty = rows["thornton/yin"]
    _, z_gr, zm_gr, p_gr, slide_gr = rows["granular"]
    # the same packing: every touching pair counted once, across ranks too
    assert z_ty > 5.0 and z_gr == pytest.approx(z_ty, rel=1e-12)
    assert zm_gr == pytest.approx(zm_ty, rel=1e-12)
    # both Hertz with the same E*: the virial stress agrees (the fix's specimen file is at
    # 100 kPa) ...
    assert p_gr == pytest.approx(p_ty, rel=2e-3) and p_ty == pytest.approx(1e5, rel=1e-3)
    # ... but which contacts slide is pair state other styles do not expose
    assert slide_ty == 0.0 and math.isnan(slide_gr)


@pytest.mark.parametrize("law", ["granular", "gran/hertz/history"])
def test_axisymmetric_test_holds_p_with_a_stock_pair_style(tmp_path, law):
    rc, out = run_deck(deck(law, "axisym x 5e-5 1e5 until eps_d13 0.003 csv rec.csv 100",
                            "run 100000"), tmp_path)
    assert rc == 0, out[-3000:]
    assert f"WARNING: fix cell/servo with pair_style {law.split()[0]}" in out
    assert "reached the target 0.003" in out
    rec = np.genfromtxt(tmp_path / "rec.csv", delimiter=",", names=True)
    late = slice(len(rec) // 2, None)
    p = (rec["sig1"] + rec["sig2"] + rec["sig3"])[late] / 3.0
    assert np.all(np.abs(p / 1e5 - 1.0) < 5e-3)
    assert rec["sig1"][-1] - rec["sig3"][-1] > 2e4    # the dense packing resists


def test_a_hybrid_pair_is_refused_by_name(tmp_path):
    text = deck("granular", "axisym x 5e-5 1e5", "run 0").replace(
        "pair_style      granular", "pair_style      hybrid granular").replace(
        "pair_coeff      * * hertz", "pair_coeff      * * granular hertz")
    rc, out = run_deck(text, tmp_path)
    assert rc != 0
    assert "cannot estimate the contact stiffness of pair_style hybrid" in out
