"""pair thornton/yin in a triclinic periodic box sheared by LAMMPS's own `fix deform ... remap x`:
the affine relative velocity L (x_i - x_j) of a contact across a periodic boundary, tilts
included (docs/theory.md §5.1, §10.1), and the contact's history across tilt flips (§10.3).

Two touching Hertz-Mindlin spheres (Gamma = 0) and no time integration: the atoms ride the box
(remap x) and carry no velocity, so every tangential force comes from the affine term. The
expected force is computed here from the box alone: the atoms and the partner's image sit at
fixed fractional coordinates, so the branch vector is l = h s (h the printed box matrix, s its
fractional difference) and the tangential displacement the contact has taken is h s - h0 s;
the force must follow Mindlin's initial loading for it (docs/theory.md §2.1)."""
import math

import numpy as np
import pytest

from lmprun import LOAD_TYLMP, read_table, run_ok

E, NU, RHO = 70e9, 0.3, 2650.0
MU = 0.3
R = 1e-3                       # sphere radius: R* = R/2
DELTA0 = 1e-6                  # initial overlap, delta/R = 1e-3
BOX = 7e-3                     # cube edge: no second image of the partner within 2R + skin
DT = 1e-7                      # ~0.1 of the Rayleigh time of these spheres (docs/theory.md §4.1)
STEPS = 1000
REACH = 0.8                    # the imposed tangential displacement, in units of u* (sliding)

G = E / (2 * (1 + NU))
E_STAR = E / (2 * (1 - NU**2))         # like spheres (docs/theory.md §0)
G_STAR = G / (2 * (2 - NU))
R_STAR = R / 2


def hertz(delta):
    """Normal force and contact radius of the Hertz contact (docs/theory.md §1.6)."""
    a = math.sqrt(R_STAR * delta)
    return 4 / 3 * E_STAR * math.sqrt(R_STAR) * delta**1.5, a


def mindlin(u, delta):
    """Mindlin's initial loading at constant normal force (docs/theory.md §2.1):
    T = mu P [1 - (1 - u/u*)^(3/2)], u* = 3 mu P/(16 G* a)."""
    P, a = hertz(delta)
    u_star = 3 * MU * P / (16 * G_STAR * a)
    return MU * P * (1 - (1 - np.minimum(u / u_star, 1.0)) ** 1.5), u_star


def box_matrix(lx, ly, lz, xy, xz, yz):
    return np.array([[lx, xy, xz], [0.0, ly, yz], [0.0, 0.0, lz]])


# The cases: fix deform's erate per tilt (shares of one rate), the initial tilts (fractions of
# BOX), and the axis along which the contact crosses the periodic boundary: its branch vector
# l0 points along that axis, so that the affine displacement L l0 is tangential
CASES = {
    # simple shear xy: the contact crosses the y boundary, image shift (xy, ly, 0)
    "xy": dict(rates={"xy": 1.0}, tilts={"xy": 0.2}, axis=1),
    # simple shear xz, crossing z: image shift (xz, yz, lz)
    "xz": dict(rates={"xz": 1.0}, tilts={"xz": -0.3, "yz": 0.1}, axis=2),
    # simple shear yz, crossing z
    "yz": dict(rates={"yz": 1.0}, tilts={"xy": 0.25, "yz": -0.2}, axis=2),
    # all three tilts at once: L_xz = (hdot_xz - hdot_xy yz/ly)/lz has the coupling term of
    # the full upper-triangular L = hdot h^-1
    "all": dict(rates={"xy": 0.6, "xz": 0.5, "yz": -0.7},
                tilts={"xy": 0.2, "xz": -0.15, "yz": 0.35}, axis=2),
}


TILT_INDEX = {"xy": (0, 1), "xz": (0, 2), "yz": (1, 2)}


def shear_rate_scale(case):
    """The erate that takes the contact to REACH u* in STEPS steps: per step the affine
    displacement is hdot s dt (constant, h s = l), with fix deform's hdot = erate * (the box
    edge perpendicular to the shear at the start) = erate * BOX for every tilt."""
    P, a = hertz(DELTA0)
    u_star = 3 * MU * P / (16 * G_STAR * a)
    h0 = initial_box(case)
    s = np.linalg.solve(h0, branch0(case))
    hdot = np.zeros((3, 3))
    for name, share in case["rates"].items():
        hdot[TILT_INDEX[name]] = share * BOX
    return REACH * u_star / (STEPS * DT * np.linalg.norm(hdot @ s))


def initial_box(case, tilts=None):
    t = {"xy": 0.0, "xz": 0.0, "yz": 0.0}
    t.update(case["tilts"] if tilts is None else tilts)
    return box_matrix(BOX, BOX, BOX, t["xy"] * BOX, t["xz"] * BOX, t["yz"] * BOX)


def branch0(case):
    """x_2' - x_1 at the start: along the crossing axis, length 2R - delta0 (x_2' the image
    of atom 2 across the upper boundary of that axis)."""
    l = np.zeros(3)
    l[case["axis"]] = 2 * R - DELTA0
    return l


def atom_positions(case, h0):
    """Atom 1 just below the upper boundary of the crossing axis, atom 2 just above the lower
    one; atom 2's image across that boundary is at x_1 + l0."""
    s1 = np.full(3, 0.5)
    s1[case["axis"]] = 1.0 - 0.5 * (2 * R - DELTA0) / BOX
    s2 = s1 + np.linalg.solve(h0, branch0(case))
    s2[case["axis"]] -= 1.0
    assert np.all((s2 > 0) & (s2 < 1))
    return h0 @ s1, h0 @ s2


def deck(case, h0, rate, flip=False, steps=STEPS):
    x1, x2 = atom_positions(case, h0)
    deform = " ".join(f"{name} erate {share * rate!r}" for name, share in case["rates"].items())
    columns = {"step": "step", "fx1": "fx[1]", "fy1": "fy[1]", "fz1": "fz[1]",
               "fx2": "fx[2]", "fy2": "fy[2]", "fz2": "fz[2]",
               "lx": "lx", "ly": "ly", "lz": "lz", "xy": "xy", "xz": "xz", "yz": "yz"}
    defs = "\n".join(f"variable c_{c} equal {expr}" for c, expr in columns.items())
    line = " ".join("${c_" + c + "}" for c in columns)
    return f"""units si
atom_style sphere
atom_modify map array
boundary p p p
comm_modify vel yes
region box prism 0 {h0[0, 0]!r} 0 {h0[1, 1]!r} 0 {h0[2, 2]!r} {h0[0, 1]!r} {h0[0, 2]!r} {h0[1, 2]!r} units box
create_box 1 box
create_atoms 1 single {x1[0]!r} {x1[1]!r} {x1[2]!r} units box
create_atoms 1 single {x2[0]!r} {x2[1]!r} {x2[2]!r} units box
set atom * diameter {2 * R!r} density {RHO!r}
{LOAD_TYLMP}
pair_style thornton/yin
pair_coeff * * {E!r} {NU!r} {MU!r} 0.0
neighbor 1e-5 bin
neigh_modify every 1 delay 0 check yes
timestep {DT!r}
fix shear all deform 1 {deform} remap x flip {"yes" if flip else "no"}
{defs}
fix out all print 1 "{line}" file out.txt screen no title "# {' '.join(columns)}"
run {steps}
"""


def run_case(tmp_path, case, h0, rate, name, **kw):
    work = tmp_path / name
    work.mkdir()
    np_ranks = kw.pop("np_ranks", 1)
    text = deck(case, h0, rate, **kw)
    if np_ranks > 1:    # split the box across the contact: its partner is a ghost of the
        grid = ["1", "1", "1"]    # other rank and of the periodic image
        grid[case["axis"]] = str(np_ranks)
        text = text.replace("boundary p p p", f"boundary p p p\nprocessors {' '.join(grid)}")
    out = run_ok(text, work, np_ranks=np_ranks)
    # no warning, in particular none of the pair's box-rate check at a flip (a flip is no
    # change of the box's rate); 4 Feb 2025 notes that no fix integrates this static deck
    warnings = [line for line in out.splitlines()
                if "WARNING" in line and "No fixes with time integration" not in line]
    assert not warnings, out[-3000:]
    table = read_table(work / "out.txt")
    return {k: v[1:] for k, v in table.items()}    # row 0: the setup, before any step


def forces(data, atom):
    return np.stack([data[f"f{c}{atom}"] for c in "xyz"], axis=1)


def boxes(data):
    return [box_matrix(*(data[k][i] for k in ("lx", "ly", "lz", "xy", "xz", "yz")))
            for i in range(len(data["step"]))]


@pytest.mark.parametrize("name", list(CASES))
def test_affine_velocity_across_a_tilted_periodic_boundary_follows_mindlin(tmp_path, name):
    case = CASES[name]
    h0 = initial_box(case)
    rate = shear_rate_scale(case)
    data = run_case(tmp_path, case, h0, rate, name)
    F1, F2 = forces(data, 1), forces(data, 2)
    scale = np.abs(F1).max()
    assert np.abs(F1 + F2).max() <= 1e-14 * scale                    # Newton's third law

    # geometry from the printed box alone: the fractional branch s is fixed (remap x, no
    # integration), so at the force evaluation of step k the branch is h_(k-1) s and the
    # tangential displacement taken by then is (h_k - h0) s: the step-k increment of the
    # pair is L l dt = hdot s dt, the change of h s over that step
    s = np.linalg.solve(h0, branch0(case))
    H = boxes(data)
    previous = [h0] + H[:-1]
    worst = 0.0
    for k in range(len(H)):
        l = previous[k] @ s                          # x_2' - x_1 at the force evaluation
        n = l / np.linalg.norm(l)
        delta = 2 * R - np.linalg.norm(l)
        P, _ = hertz(delta)
        Fn = F1[k] @ n                               # on atom 1, pushed away from 2: -P
        assert Fn == pytest.approx(-P, rel=1e-9)
        T = F1[k] - Fn * n
        d = (H[k] - h0) @ s                          # displacement of 2' relative to 1
        d_t = d - (d @ n) * n
        expected, u_star = mindlin(np.linalg.norm(d_t), delta)
        # atom 2 drags atom 1 along: T on atom 1 points along d_t
        assert np.linalg.norm(np.cross(T, d_t)) <= 1e-6 * np.linalg.norm(T) * np.linalg.norm(d_t)
        assert T @ d_t > 0
        worst = max(worst, abs(np.linalg.norm(T) - expected) / (MU * P))
    u_end = np.linalg.norm(((H[-1] - h0) @ s))
    print(f"{name}: u/u* = {u_end / u_star:.4f}, |T - Mindlin| <= {worst:.3g} mu P")
    assert u_end / u_star == pytest.approx(REACH, rel=1e-3)          # the loading was made
    # Thornton's increments (explicit in theta) against the closed form, STEPS steps to 0.8 u*:
    # 2.2e-4 mu P measured; the affine displacement one step early or late would be off by a
    # step's initial stiffness k0 (0.8 u*/STEPS) = 1.2e-3 mu P
    assert worst < 5e-4


# Tilt flips (docs/theory.md §10.3): the run starts with the sheared tilt just below half the
# box, so that fix deform's `flip yes` replaces it by the equivalent tilt one box length lower
# half-way through the loading (a flip of yz also moves xz by xy). The same contact in a box
# that does not flip (the tilts of CASES) is the reference: the branch vector, its affine
# displacement hdot s dt (independent of the initial tilts for these single shears) and so the
# force are the same; the positions differ, so the two agree to round-off only
FLIPS = {"xy": "xy", "yz": "yz"}


def flipping(case, tilt):
    rate = shear_rate_scale(case)
    change = STEPS * DT * rate * BOX                   # of the tilt over the run
    tilts = dict(case["tilts"])
    tilts[tilt] = 0.5 - 0.5 * change / BOX
    return tilts, rate


@pytest.mark.parametrize("name", list(FLIPS))
def test_contact_history_survives_a_tilt_flip(tmp_path, name):
    case, tilt = CASES[name], FLIPS[name]
    tilts, rate = flipping(case, tilt)
    flipped = run_case(tmp_path, case, initial_box(case, tilts), rate, "flip", flip=True)
    reference = run_case(tmp_path, case, initial_box(case), rate, "reference", flip=True)
    # one flip, half-way: the tilt drops by a box length (a yz flip moves xz by -xy too)
    jumps = np.flatnonzero(np.abs(np.diff(flipped[tilt])) > 0.5 * BOX)
    assert len(jumps) == 1 and 0.3 * STEPS < jumps[0] < 0.7 * STEPS, jumps
    k = jumps[0] + 1                                   # the first row after the flip
    assert flipped[tilt][k] - flipped[tilt][k - 1] == pytest.approx(-BOX, rel=1e-6)
    if tilt == "yz":
        assert flipped["xz"][k] - flipped["xz"][k - 1] == pytest.approx(
            -case["tilts"]["xy"] * BOX, rel=1e-9)
    assert np.all(np.abs(np.diff(reference[tilt])) < 1e-6 * BOX)    # no flip there
    F, F_ref = forces(flipped, 1), forces(reference, 1)
    P = np.linalg.norm(F_ref, axis=1)
    T_ref = np.linalg.norm(np.cross(F_ref, branch0(case)), axis=1) / (2 * R - DELTA0)
    assert T_ref[k] > 0.3 * MU * P[k]                 # the contact is well loaded at the flip
    difference = np.abs(F - F_ref).max() / np.abs(F_ref).max()
    jump = np.abs((F[k] - F[k - 1]) - (F_ref[k] - F_ref[k - 1])).max() / np.abs(F_ref[k]).max()
    print(f"flip of {tilt} at step {flipped['step'][k]:.0f}: |F - F_ref| <= {difference:.2g} |F|, "
          f"extra change across the flip {jump:.2g} |F|")
    # continuous across the flip and the same as without one, to round-off
    assert jump <= 1e-10
    assert difference <= 1e-10


# The same on 2 ranks, the box split across the contact: the partner is a ghost of the other
# rank through the periodic boundary, and at a flip the atoms migrate between ranks
@pytest.mark.parametrize("name, flip", [("all", False), ("xy", True), ("yz", True)])
def test_two_ranks_give_the_forces_of_one(tmp_path, name, flip):
    case = CASES[name]
    if flip:
        tilts, rate = flipping(case, FLIPS[name])
        h0 = initial_box(case, tilts)
    else:
        rate, h0 = shear_rate_scale(case), initial_box(case)
    one = run_case(tmp_path, case, h0, rate, "one", flip=flip)
    two = run_case(tmp_path, case, h0, rate, "two", flip=flip, np_ranks=2)
    assert np.array_equal(one["step"], two["step"])
    if flip:
        assert np.abs(np.diff(two[FLIPS[name]])).max() > 0.5 * BOX    # it did flip
    for atom in (1, 2):
        F1, F2 = forces(one, atom), forces(two, atom)
        difference = np.abs(F2 - F1).max() / np.abs(F1).max()
        print(f"{name}: 2 ranks against 1, atom {atom}: {difference:.2g} |F|")
        assert difference <= 1e-12
