"""The cell's state outputs of fix cell/servo against the specimen's own geometry (issue 29: a
void ratio computed as porosity passed every test before): on the shipped 3620-sphere specimen
the cell volume is the product of the box edges of the data file, the solid volume the sum of
(4/3) pi r^3 over its spheres, and void ratio e = V/V_s - 1, solid fraction V_s/V."""
import numpy as np
import pytest

from conftest import REPO
from lmprun import LOAD_TYLMP, run_deck
from tylmp.analysis.io import read_sphere_data

SPECIMEN = f"{REPO}/bench/data/dense_paper_100kPa.data"


def test_void_ratio_and_solid_fraction_from_cell_and_sphere_volumes(tmp_path):
    rc, out = run_deck(f"""{LOAD_TYLMP}
units si
atom_style sphere
boundary p p p
comm_modify vel yes
read_data {SPECIMEN}
pair_style thornton/yin
pair_coeff * * 70e9 0.3 0.3 0
neighbor 1.35e-5 bin
timestep 0.0144
fix integrate all nve/sphere
fix cell all cell/servo iso 1e5 variables yes
run 0
print "STATE $(v_cell_volume:%.17g) $(v_cell_void_ratio:%.17g) $(v_cell_solid_fraction:%.17g)"
""", tmp_path)
    assert rc == 0, out[-2000:]
    volume, e, phi = map(float, next(l for l in out.splitlines()
                                     if l.startswith("STATE ")).split()[1:])
    lo, hi, _, diameters, _ = read_sphere_data(SPECIMEN)
    cell = float(np.prod(hi - lo))
    solid = float(np.sum(np.pi / 6.0 * diameters ** 3))
    assert volume == pytest.approx(cell, rel=1e-12)
    assert e == pytest.approx(cell / solid - 1.0, rel=1e-12)
    assert phi == pytest.approx(solid / cell, rel=1e-12)
    # porosity n = 1 - phi is not the void ratio: e = n/(1 - n), about 0.52 against 0.34 here
    assert abs(e - (1.0 - phi)) > 0.1
