"""fix damping/cundall: Cundall's local non-viscous damping F <- F (1 - lambda sign(F v))
(docs/theory.md §8), checked on free spheres where the motion is known in closed form."""
import numpy as np
import pytest

from lmprun import LOAD_TYLMP, run_ok

def one_sphere(x, y, z):
    """A 1 mm glass sphere alone in a 1 cm periodic box, with the styles loaded."""
    return f"""
units si
atom_style sphere
atom_modify map array
boundary p p p
comm_modify vel yes
region box block 0 1e-2 0 1e-2 0 1e-2
create_box 1 box
create_atoms 1 single {x} {y} {z}
set atom 1 diameter 1e-3 density 2650
{LOAD_TYLMP}
pair_style thornton/yin
pair_coeff * * 70e9 0.3 0.3 0.0
"""


FREE_SPHERE = one_sphere(5e-3, 5e-3, 5e-3) + """velocity all set {v0} 0 0
fix push all addforce {force} 0 0
fix nve all nve/sphere
{damping}
timestep 1e-4
variable vx equal vx[1]
run 1000
print "VX ${{vx}}"
"""
MASS = 2650 * np.pi / 6 * 1e-3 ** 3


def final_velocity(tmp_path, v0, force, damping):
    work = tmp_path / f"{v0}_{force}_{'d' if damping else 'n'}"
    work.mkdir()
    deck = FREE_SPHERE.format(v0=v0, force=force,
                              damping="fix damp all damping/cundall 0.3 0.3" if damping else "")
    out = run_ok(deck, work)
    return float([l for l in out.splitlines() if l.startswith("VX ")][-1].split()[1])


@pytest.mark.parametrize("v0, force, factor", [
    (1e-9, 1e-6, 0.7),     # force along the motion: acceleration reduced by (1 - lambda)
    (1.0, -1e-6, 1.3),     # force against the motion: deceleration increased by (1 + lambda)
])
def test_acceleration_is_scaled_by_one_minus_lambda_sign(tmp_path, v0, force, factor):
    t = 1000 * 1e-4
    expected = v0 + factor * force / MASS * t
    undamped = final_velocity(tmp_path, v0, force, False)
    assert undamped == pytest.approx(v0 + force / MASS * t, rel=1e-9)
    assert final_velocity(tmp_path, v0, force, True) == pytest.approx(expected, rel=1e-9)


def test_no_damping_of_the_affine_motion_in_a_deforming_cell(tmp_path):
    """In fix cell/servo the velocities are fluctuations: a sphere carried by the cell's
    homogeneous strain has none, so damping does nothing and the sphere keeps its place in
    box (lamda) coordinates."""
    deck = one_sphere(2e-3, 7e-3, 4e-3) + f"""fix nve all nve/sphere
fix damp all damping/cundall 0.3 0.3
fix cell all cell/servo axes x rate 1.0 y rate -0.5 z rate 0.2
timestep 1e-3
variable sx equal (x[1]-xlo)/lx
variable sy equal (y[1]-ylo)/ly
variable sz equal (z[1]-zlo)/lz
variable speed equal sqrt(vx[1]^2+vy[1]^2+vz[1]^2)
run 200
print "S ${{sx}} ${{sy}} ${{sz}} ${{speed}}"
"""
    out = run_ok(deck, tmp_path)
    sx, sy, sz, speed = map(float, [l for l in out.splitlines() if l.startswith("S ")][-1].split()[1:])
    assert sx == pytest.approx(0.2, abs=1e-12)
    assert sy == pytest.approx(0.7, abs=1e-12)
    assert sz == pytest.approx(0.4, abs=1e-12)
    assert speed == 0.0


@pytest.mark.parametrize("values, argument", [
    ("inf 0.3", "lambda_linear"), ("0.3 nan", "lambda_angular"), ("1e400 0.3", "lambda_linear"),
    ("0.3 -1e400", "lambda_angular"),
])
def test_non_finite_coefficient_is_refused_naming_it(tmp_path, values, argument):
    # utils::numeric alone would turn 1e400 into inf and refuse 'inf' without naming it
    from lmprun import run_deck
    rc, out = run_deck(one_sphere(5e-3, 5e-3, 5e-3) + f"fix damp all damping/cundall {values}\n",
                       tmp_path)
    assert rc != 0 or "ERROR" in out
    assert f"fix damping/cundall: {argument} must be a finite number" in out, out[-2000:]


def test_text_coefficient_is_refused_naming_it(tmp_path):
    from lmprun import run_deck
    rc, out = run_deck(one_sphere(5e-3, 5e-3, 5e-3) + "fix damp all damping/cundall abc 0.3\n",
                       tmp_path)
    assert rc != 0 or "ERROR" in out
    assert "fix damping/cundall: lambda_linear must be a number, got 'abc'" in out, out[-2000:]
