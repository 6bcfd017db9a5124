"""fix cell/servo: stress-controlled periodic cell (docs/theory.md §5–§7).

Every expected number comes from theory or an independent calculation: the Hertz
closed form of a simple-cubic lattice, the prescribed strain programme, the Pi-plane
geometry, Mindlin's initial tangential stiffness, and the energy balance of the
fluctuation-velocity bookkeeping.
"""

import os

import numpy as np
import pytest

from cellspec import (DT, E, HEADER, LATTICE_SPECIMEN, NU, RHO, bisect, effective_modulus,
                      effective_shear_modulus, hertz_force, pi_coordinates, read_csv,
                      restart_deck)
from lmprun import LOAD_TYLMP, run_deck, run_ok

P0 = 1e5      # target mean stress of every test on the specimen [Pa]


# ---------------------------------------------------------------------------------------------
# 1. the specimen: 216 spheres, frictionless isotropic compression to 100 kPa


@pytest.fixture(scope="session")
def specimen(tmp_path_factory):
    work = tmp_path_factory.mktemp("specimen")
    deck = LATTICE_SPECIMEN + f"""pair_style thornton/yin
pair_coeff * * {E} {NU} 0.0 0.0
neighbor 2e-5 bin
timestep {DT}
fix nve all nve/sphere
fix prep all cell/servo iso {P0} max_rate 2e-3 csv prep.csv 100
fix damp all damping/cundall 0.2 0.2
thermo 10000
run 40000
unfix damp
write_restart spec.restart
"""
    run_ok(deck, work)
    rows = read_csv(work / "prep.csv")
    # the preparation reached a dense, jammed state at the target pressure
    assert abs(rows["p"][-1] / P0 - 1.0) < 0.01
    assert rows["solid_fraction"][-1] > 0.6
    assert rows["Z"][-1] > 4.0
    return work / "spec.restart"


def shear_run(specimen, work, fix_line, steps, extra="", mu=0.3, gamma=0.6, np_ranks=1,
              name="in.shear"):
    deck = restart_deck(specimen, mu, gamma) + extra + fix_line + f"\nrun {steps}\n"
    return run_ok(deck, work, np_ranks=np_ranks, name=name)


# ---------------------------------------------------------------------------------------------
# 2. Hertz lattice: equal spheres on a simple-cubic lattice, closed-form strain at p*


# one default servo setting from 1 kPa to 10 MPa (the gain is normalised by the stiffness);
# the same strain-rate cap everywhere, so that only the gain's normalisation is under test
@pytest.mark.parametrize("p_star", [1e3, 1e6, 1e7])
def test_hertz_lattice_isotropic_compression(tmp_path, p_star):
    R, n = 1e-4, 4
    s0 = 2.0 * R * 1.0005           # a small initial gap: the servo starts from a gas
    deck = HEADER + f"""lattice sc {s0}
region box block 0 {n} 0 {n} 0 {n}
create_box 1 box
create_atoms 1 box
set atom * diameter {2 * R} density {RHO}
""" + LOAD_TYLMP + f"""pair_style thornton/yin
pair_coeff * * {E} {NU} 0.0 0.0
neighbor 2e-5 bin
timestep {DT}
fix nve all nve/sphere
fix cell all cell/servo iso {p_star} max_rate 1e-4 csv hertz.csv 50
fix damp all damping/cundall 0.2 0.2
run 10000
"""
    run_ok(deck, tmp_path)
    rows = read_csv(tmp_path / "hertz.csv")
    E_star, R_star = effective_modulus(), R / 2.0

    def strain_at(sigma):
        # sigma = F/s^2 with F = (4/3) E* sqrt(R*) (2R - s)^(3/2); solve for the spacing s
        s = bisect(lambda s: hertz_force(2 * R - s, R_star, E_star) / s ** 2 - sigma,
                   1.9 * R, 2.0 * R)
        return -np.log(s / s0)

    eps_target = strain_at(p_star)
    last = {k: v[-1] for k, v in rows.items()}
    # isotropic cell: the three strains are equal
    assert last["eps1"] == pytest.approx(last["eps2"], rel=1e-9)
    assert last["eps1"] == pytest.approx(last["eps3"], rel=1e-9)
    # the servo reached the target, and the cell strain is the closed-form one
    assert last["p"] == pytest.approx(p_star, rel=2e-3)
    print(f"hertz lattice: eps1={last['eps1']:.8g} closed form at p*: {eps_target:.8g} "
          f"(rel {last['eps1'] / eps_target - 1:.2g}), at measured p: "
          f"rel {last['eps1'] / strain_at(last['p']) - 1:.2g}; p/p*-1 = {last['p'] / p_star - 1:.2g}")
    assert last["eps1"] == pytest.approx(eps_target, rel=5e-3)
    # sharper: the lattice state is the closed form at the stress actually measured
    assert last["eps1"] == pytest.approx(strain_at(last["p"]), rel=1e-4)
    # solid fraction of a sc lattice of touching-ish spheres: (4/3 pi R^3)/s^3
    s = s0 * np.exp(-last["eps1"])
    assert last["solid_fraction"] == pytest.approx(4.0 / 3.0 * np.pi * R ** 3 / s ** 3, rel=1e-9)
    assert last["Z"] == pytest.approx(6.0)
    # no oscillation: once within 1 % of the target, p stays there
    first = np.argmax(np.abs(rows["p"] / p_star - 1.0) < 0.01)
    assert np.all(np.abs(rows["p"][first:] / p_star - 1.0) < 0.01)


# ---------------------------------------------------------------------------------------------
# 3. axisymmetric compression and extension at constant p

AXIAL_RATE = 2e-5      # 1/s (scaled time): 1 % axial strain in 25000 steps, I ~ 7e-4
SHEAR_STEPS = 25000


def settled(rows, steps=500):
    """Rows after the first `steps` steps of the run."""
    keep = rows["step"] - rows["step"][0] >= steps
    return {k: v[keep] for k, v in rows.items()}


@pytest.mark.parametrize("sign", [+1, -1], ids=["compression", "extension"])
def test_axisymmetric_constant_p(specimen, tmp_path, sign):
    rate = sign * AXIAL_RATE
    shear_run(specimen, tmp_path, f"fix sh all cell/servo axisym x {rate} {P0} csv sh.csv 50",
              SHEAR_STEPS)
    rows = read_csv(tmp_path / "sh.csv")
    n = rows["step"] - rows["step"][0]
    # the box at the end of step n has been deformed n - 1 times (the rate decided at the end
    # of a step deforms the cell at the start of the next): eps1 = rate * dt * (n - 1)
    expected = rate * DT * np.maximum(n - 1, 0)
    assert np.max(np.abs(rows["eps1"] - expected)) < 1e-9 * AXIAL_RATE * DT * SHEAR_STEPS + 1e-15
    assert np.allclose(rows["rate1"][1:], rate, rtol=1e-12)
    late = settled(rows)
    assert np.max(np.abs(late["p"] / P0 - 1.0)) < 0.01
    # lateral stresses equal; b = 0 in compression (sigma1 major), 1 in extension
    q = late["q"]
    big = q > 0.2 * P0
    assert big.sum() > 0.5 * big.size
    assert np.max(np.abs(late["sig2"] - late["sig3"])[big] / q[big]) < 0.01
    b_expected = 0.0 if sign > 0 else 1.0
    assert np.max(np.abs(late["b"][big] - b_expected)) < 0.01
    # the axial stress is the major (compression) or minor (extension) one
    if sign > 0:
        assert np.all(late["sig1"][big] > late["sig2"][big])
    else:
        assert np.all(late["sig1"][big] < late["sig2"][big])
    # the total axial strain is 1 % (the lateral strains are free: equal stresses, not
    # equal strains, in a 216-sphere specimen)
    assert rows["eps1"][-1] == pytest.approx(sign * 0.01, rel=1e-3)


# ---------------------------------------------------------------------------------------------
# 4. constant b at constant p


@pytest.mark.parametrize("b", [0.5, 0.25])
def test_constant_b(specimen, tmp_path, b):
    # max_rate raised: the default cap (servo rate at I = 1e-3, 2.7e-5/s here) saturates the
    # minor axis, which must extend at about the axial rate plus dilatancy when b = 0.5
    # (measured with the default: p off by 2 %, b by 0.016)
    shear_run(specimen, tmp_path,
              f"fix sh all cell/servo constant_b {b} x {AXIAL_RATE} {P0} max_rate 1e-4 "
              "csv sh.csv 50",
              SHEAR_STEPS // 2)
    rows = read_csv(tmp_path / "sh.csv")
    late = settled(rows)
    assert np.max(np.abs(late["p"] / P0 - 1.0)) < 0.01
    big = late["q"] > 0.2 * P0
    assert big.sum() > 0.5 * big.size
    # b from the principal stresses, recomputed here: (s2 - s3)/(s1 - s3), x major, z minor
    s1, s2, s3 = late["sig1"][big], late["sig2"][big], late["sig3"][big]
    assert np.max(np.abs((s2 - s3) / (s1 - s3) - b)) < 0.01
    assert np.max(np.abs(late["b"][big] - b)) < 0.01
    assert np.all(s1 > s2) and np.all(s2 >= s3)
    # the stress Lode angle: tan(theta) = sqrt3 b/(2 - b)   (docs/theory.md §7.2)
    theta = np.degrees(np.arctan2(np.sqrt(3.0) * b, 2.0 - b))
    assert np.max(np.abs(late["lode_deg"][big] - theta)) < 1.0


# ---------------------------------------------------------------------------------------------
# 5. prescribed rates from equal-style variables: deviatoric mode, and mixed axes mode


def test_deviatoric_mode_with_variables(specimen, tmp_path):
    # a deliberately non-traceless request: only its deviator is prescribed, the mean
    # strain rate belongs to the p servo; r2 varies with the step
    extra = ("variable r1 equal 3e-5\n"
             "variable r2 equal -1e-5+1e-9*step\n"
             "variable r3 equal 0.5e-5\n")
    shear_run(specimen, tmp_path,
              f"fix sh all cell/servo deviatoric v_r1 v_r2 v_r3 {P0} csv sh.csv 10", 3000,
              extra=extra)
    rows = read_csv(tmp_path / "sh.csv")
    step0 = rows["step"][0]
    r = rows["step"] > step0 + 1
    # a row holds the rate applied at the end of the previous step (variables evaluated then)
    prev = rows["step"][r] - 1
    req = np.stack([np.full(prev.shape, 3e-5), -1e-5 + 1e-9 * prev, np.full(prev.shape, 0.5e-5)])
    req_dev = req - req.mean(axis=0)
    got = np.stack([rows["rate1"][r], rows["rate2"][r], rows["rate3"][r]])
    got_dev = got - got.mean(axis=0)
    # (the CSV keeps 12 significant digits)
    assert np.max(np.abs(got_dev - req_dev)) < 1e-10 * np.max(np.abs(req_dev))
    late = settled(rows)
    assert np.max(np.abs(late["p"] / P0 - 1.0)) < 0.01


def test_axes_mode_mixed_stress_and_rate(specimen, tmp_path):
    extra = ("variable rx equal 2e-5*(1+step/1e5)\n"
             "variable sz equal 1.2e5\n")
    shear_run(specimen, tmp_path,
              f"fix sh all cell/servo axes x rate v_rx y stress {P0} z stress v_sz "
              "csv sh.csv 10", 3000, extra=extra)
    rows = read_csv(tmp_path / "sh.csv")
    r = rows["step"] > rows["step"][0] + 1
    prev = rows["step"][r] - 1
    assert np.max(np.abs(rows["rate1"][r] - 2e-5 * (1 + prev / 1e5))) < 1e-11 * 2e-5
    late = settled(rows, 1000)
    assert np.max(np.abs(late["sig2"] / P0 - 1.0)) < 0.01
    assert np.max(np.abs(late["sig3"] / 1.2e5 - 1.0)) < 0.01


# a servo at its strain-rate cap whose stress error does not shrink has lost control: the fix
# warns; at the cap while the error shrinks (a slow approach to a far target, as in the two-stage
# preparation's compression) it only sets the pace, and the fix stays silent
CAP_WARNING = "WARNING: fix cell/servo: the servo has been at its strain-rate cap"


def test_cap_warning_when_the_servo_loses_control(specimen, tmp_path):
    # axial compression at 1e-3 1/s with the lateral servo capped at 1e-8 1/s: Poisson's
    # stresses of the axial strain outgrow what the capped lateral axes can relieve
    out = shear_run(specimen, tmp_path, "fix sh all cell/servo axisym x 1e-3 "
                    f"{P0} max_rate 1e-8", 2100)
    assert out.count(CAP_WARNING) == 1, out[-3000:]
    assert "and its stress error grew from" in out
    assert "raise max_rate or lower the prescribed rate (said once per run)" in out
    # the same with cap_warning no: silent (a deck that runs at the cap on purpose)
    out = shear_run(specimen, tmp_path, "fix sh all cell/servo axisym x 1e-3 "
                    f"{P0} max_rate 1e-8 cap_warning no", 2100, name="in.quiet")
    assert CAP_WARNING not in out, out[-3000:]


def test_no_cap_warning_while_the_error_shrinks(specimen, tmp_path):
    # from 100 kPa towards 300 kPa at 1e-6 1/s: at the cap throughout (the stiffness would
    # take the servo there in a few steps), the error shrinking every check
    out = shear_run(specimen, tmp_path, "fix sh all cell/servo iso 3e5 max_rate 1e-6 "
                    "csv sh.csv 100", 3000)
    rows = read_csv(tmp_path / "sh.csv")
    fastest = np.max(np.abs([rows[f"rate{k}"][1:] for k in (1, 2, 3)]), axis=0)
    assert np.all(np.abs(fastest - 1e-6) < 1e-12)                  # at the cap throughout
    assert np.all(np.diff(rows["p"]) > 0) and rows["p"][-1] < 2e5  # still far from 300 kPa
    assert CAP_WARNING not in out, out[-3000:]


# ---------------------------------------------------------------------------------------------
# 6. circular strain path in the Pi-plane at constant p

PRESTRAIN = 0.00285    # eps1 - eps3 at the end of the axisymmetric pre-strain leg


def strain_pi(rows):
    e = [rows[f"eps{k}"] for k in (1, 2, 3)]
    return pi_coordinates(*e)


@pytest.mark.parametrize("rotation", ["cw", "ccw"])
def test_circle_path(specimen, tmp_path, rotation):
    sweep, speed = 60.0, 3e-5
    radius = PRESTRAIN * np.sqrt(2.0 / 3.0)     # (d/3)(2,-1,-1): |e| = d sqrt(2/3)
    length = radius * (1.0 + np.radians(sweep))
    steps = int(1.05 * length / (speed * DT)) + 200
    shear_run(specimen, tmp_path,
              f"fix sh all cell/servo circle {PRESTRAIN} {P0} rotation {rotation} "
              f"sweep {sweep} speed {speed} csv sh.csv 20", steps)
    rows = read_csv(tmp_path / "sh.csv")
    x, y = strain_pi(rows)
    # the fix's own Pi coordinates agree with the strains it reports
    assert np.allclose(rows["pi_ex"], x, atol=1e-12) and np.allclose(rows["pi_ey"], y, atol=1e-12)
    rad = np.hypot(x, y)
    theta = np.degrees(np.arctan2(x, y))
    on_arc = rows["progress"] > (radius / length) * 1.0 + 0.01
    assert on_arc.sum() > 20
    assert np.max(np.abs(rad[on_arc] / radius - 1.0)) < 0.01
    print(f"circle {rotation}: max radius error {np.max(np.abs(rad[on_arc] / radius - 1.0)):.3g}")
    # pre-strain leg: along the axis-1 ray (eps2 = eps3 deviatorically: x = 0)
    leg = (rows["progress"] < radius / length - 0.01) & (rows["step"] > rows["step"][0] + 50)
    assert np.max(np.abs(x[leg])) < 0.01 * radius
    # Lode angle of the strain turns monotonically in the requested sense
    sense = 1.0 if rotation == "cw" else -1.0
    turn = sense * np.diff(theta[on_arc])
    assert np.all(turn > -1e-3)
    assert rows["progress"][-1] == pytest.approx(1.0)
    assert sense * theta[-1] == pytest.approx(sweep, abs=0.5)
    late = settled(rows)
    assert np.max(np.abs(late["p"] / P0 - 1.0)) < 0.01


# ---------------------------------------------------------------------------------------------
# 7. triangular (multi-axial plane strain) path


def deviator_from_pi(xy):
    # inverse of the Pi coordinates for a traceless triple (docs/theory.md §7.2)
    ex = np.array([0.0, 1.0, -1.0]) / np.sqrt(2.0)
    ey = np.array([2.0, -1.0, -1.0]) / np.sqrt(6.0)
    return xy[0] * ex + xy[1] * ey


@pytest.mark.parametrize("plane", ["total", "deviatoric"])
def test_triangle_path(specimen, tmp_path, plane):
    prestrain, speed = 0.001, 4e-5
    r = prestrain * np.sqrt(2.0 / 3.0)
    # vertices (own geometry): A = r at Lode 0; B, C, D at 2r and Lode 60, 180, 300
    def point(rad, deg):
        return np.array([rad * np.sin(np.radians(deg)), rad * np.cos(np.radians(deg))])
    O, A, B, C, D = point(0, 0), point(r, 0), point(2 * r, 60), point(2 * r, 180), point(2 * r, 300)
    verts = [O, A, B, C, D, A]
    a = prestrain / 3.0
    for v, e in ((A, a * np.array([2, -1, -1])), (B, 2 * a * np.array([1, 1, -2])),
                 (C, 2 * a * np.array([-2, 1, 1])), (D, 2 * a * np.array([1, -2, 1]))):
        assert np.allclose(pi_coordinates(*e), v, atol=1e-15)
    legs = np.array([np.linalg.norm(verts[k + 1] - verts[k]) for k in range(5)])
    cum = np.concatenate([[0.0], np.cumsum(legs)]) / legs.sum()
    steps = int(1.03 * legs.sum() / (speed * DT)) + 200
    shear_run(specimen, tmp_path,
              f"fix sh all cell/servo triangle {prestrain} {P0} rotation cw speed {speed} "
              f"plane_strain {plane} csv sh.csv 10", steps)
    rows = read_csv(tmp_path / "sh.csv")
    eps = np.stack([rows[f"eps{k}"] for k in (1, 2, 3)])
    dev = eps - eps.mean(axis=0)          # deviatoric strain e_i
    x, y = strain_pi(rows)
    prog = rows["progress"]
    if plane == "total":
        # true plane strain (paper section 5): on legs A-B, B-C, C-D, D-A the total strain of
        # axis 1, 2, 3, 1 does not move; each leg ends where the two free axes have the
        # difference of its end vertex (e.g. B: eps2 - eps3 = e2 - e3 = 2d)
        ends = (B, C, D, A)
        for k, axis in zip(range(1, 5), (0, 1, 2, 0)):
            inside = (prog > cum[k] + 0.005) & (prog < cum[k + 1] - 0.005)
            assert inside.sum() > 10
            assert np.all(rows[f"rate{axis + 1}"][inside] == 0.0), k
            held = eps[axis][inside]
            assert np.ptp(held) <= 1e-12 * max(np.max(np.abs(held)), prestrain), k
            i, j = (axis + 1) % 3, (axis + 2) % 3
            vertex = deviator_from_pi(ends[k - 1])
            end_row = np.argmin(np.abs(prog - cum[k + 1]))
            assert abs((eps[i] - eps[j])[end_row] - (vertex[i] - vertex[j])) < 0.02 * r, k
        late = settled(rows)
        assert np.max(np.abs(late["p"] / P0 - 1.0)) < 0.01
        return
    # legs A-B, B-C, C-D, D-A keep e1, e2, e3, e1 fixed (plane strain of the deviator)
    for k, axis in zip(range(1, 5), (0, 1, 2, 0)):
        inside = (prog > cum[k] + 0.005) & (prog < cum[k + 1] - 0.005)
        assert inside.sum() > 10
        fixed = dev[axis][inside]
        # A = (d/3)(2,-1,-1), B = (2d/3)(1,1,-2), C = (2d/3)(-2,1,1), D = (2d/3)(1,-2,1):
        # the component held on each leg is 2d/3
        assert np.max(np.abs(fixed - 2.0 / 3.0 * prestrain)) < 0.01 * r, (k, axis)
        print(f"triangle leg {k}: max |e_{axis + 1} - 2d/3|/r = "
              f"{np.max(np.abs(fixed - 2.0 / 3.0 * prestrain)) / r:.3g}")
    # every vertex is reached (closest recorded point within 1 % of r)
    for v in (A, B, C, D):
        assert np.min(np.hypot(x - v[0], y - v[1])) < 0.01 * r
    assert prog[-1] == pytest.approx(1.0)
    late = settled(rows)
    assert np.max(np.abs(late["p"] / P0 - 1.0)) < 0.01


# ---------------------------------------------------------------------------------------------
# 8. periodic bookkeeping: a contact across the boundary = the same contact inside the cell


def two_sphere_deck(x1, x2, box, rate, steps, mu=0.3):
    R = 1e-4
    return HEADER + f"""region box block 0 {box} 0 {box} 0 {box}
create_box 1 box
create_atoms 1 single {x1[0]!r} {x1[1]!r} {x1[2]!r} units box
create_atoms 1 single {x2[0]!r} {x2[1]!r} {x2[2]!r} units box
set atom * diameter {2 * R} density {RHO}
""" + LOAD_TYLMP + f"""pair_style thornton/yin
pair_coeff * * {E} {NU} {mu} 0.0
neighbor 2e-5 bin
timestep {DT}
fix cell all cell/servo axes x rate {rate} y rate {-rate} z rate 0
run {steps}
print "F1 $(fx[1]:%.17g) $(fy[1]:%.17g) $(fz[1]:%.17g)"
print "F2 $(fx[2]:%.17g) $(fy[2]:%.17g) $(fz[2]:%.17g)"
print "X1 $(x[1]:%.17g) $(y[1]:%.17g) $(z[1]:%.17g)"
print "X2 $(x[2]:%.17g) $(y[2]:%.17g) $(z[2]:%.17g)"
print "L $(lx:%.17g) $(ly:%.17g) $(lz:%.17g)"
"""


def parse_prints(out, key):
    for line in out.splitlines():
        if line.startswith(key + " "):
            return np.array([float(v) for v in line.split()[1:]])
    raise AssertionError(f"no '{key}' line in the output:\n" + out[-2000:])


def test_contact_across_periodic_boundary(tmp_path):
    """Two spheres at rest (no time integration at all: positions follow the cell only).
    Branch along (1,1,0)/sqrt2 and rates (r, -r, 0): the affine relative velocity
    L (x2 - x1) is purely tangential, so every tangential force comes from the affine term."""
    R, box, rate, steps, mu = 1e-4, 1e-3, 1e-5, 100, 0.3
    delta0 = 1e-7
    l = 2 * R - delta0
    n = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)
    c = np.full(3, 0.5 * box)
    inside = (c - 0.5 * l * n, c + 0.5 * l * n)
    # the same pair moved by half a cell along x and y: it straddles both boundaries
    shift = np.array([0.5 * box, 0.5 * box, 0.0])
    across = tuple(np.mod(p + shift, box) for p in inside)
    assert across[0][0] > 0.5 * box and across[1][0] < 0.5 * box
    out_in = run_ok(two_sphere_deck(*inside, box, rate, steps, mu), tmp_path, name="in.inside")
    out_x = run_ok(two_sphere_deck(*across, box, rate, steps, mu), tmp_path, name="in.across")
    F_in, F_x = parse_prints(out_in, "F1"), parse_prints(out_x, "F1")
    assert np.allclose(parse_prints(out_in, "F2"), -F_in, rtol=0, atol=1e-15 * np.abs(F_in).max())
    # same forces to round-off (the positions differ by the cell shift only)
    print(f"periodic: |F_across - F_inside|/|F| = "
          f"{np.max(np.abs(F_x - F_in)) / np.linalg.norm(F_in):.3g}")
    assert np.max(np.abs(F_x - F_in)) < 1e-7 * np.linalg.norm(F_in)

    # the state after `steps` steps: the cell's rates r, -r, 0 (independent of the fix)
    x1, x2 = parse_prints(out_in, "X1"), parse_prints(out_in, "X2")
    branch = x2 - x1
    # the box has been deformed steps - 1 times: the rate decided at the end of a step is
    # applied at the next step (post_integrate), the first step applies the initial rate 0
    strain = rate * DT * (steps - 1)
    assert branch[0] == pytest.approx(l * n[0] * np.exp(-strain), rel=1e-9)
    assert branch[1] == pytest.approx(l * n[1] * np.exp(strain), rel=1e-9)
    nn = branch / np.linalg.norm(branch)
    Fn = F_in @ nn
    T = F_in - Fn * nn
    # normal force: Hertz at the current overlap (the force on atom 1 points away from 2)
    E_star, R_star = effective_modulus(), R / 2
    delta = 2 * R - np.linalg.norm(branch)
    P = hertz_force(delta, R_star, E_star)
    assert -Fn == pytest.approx(P, rel=1e-6)
    # tangential force: present although nothing moves but the cell, along the mean-field
    # relative velocity of 2 w.r.t. 1, L (x2 - x1) ~ (-1, 1, 0)
    t_dir = np.array([-1.0, 1.0, 0.0]) / np.sqrt(2.0)
    assert T @ t_dir > 0.1 * mu * P
    assert np.linalg.norm(T - (T @ t_dir) * t_dir) < 1e-3 * np.linalg.norm(T)
    # magnitude: Mindlin loading at constant P from zero, T = mu P (1 - (1 - u/u*)^(3/2)),
    # u* = 3 mu P/(2 k0), k0 = 8 G* a (Thornton-Randall); u = affine tangential displacement
    # = |L (x2 - x1)| summed over the steps, the branch turning only to second order
    a = np.sqrt(R_star * delta)
    k0 = 8.0 * effective_shear_modulus() * a
    u = sum(rate * l * np.sqrt(np.cosh(2 * rate * DT * k)) * DT for k in range(steps - 1))
    u_star = 1.5 * mu * P / k0
    assert u < 0.5 * u_star
    T_mindlin = mu * P * (1.0 - (1.0 - u / u_star) ** 1.5)
    print(f"periodic: T = {T @ t_dir:.6g} N, Mindlin {T_mindlin:.6g} N, mu P = {mu * P:.4g} N")
    assert T @ t_dir == pytest.approx(T_mindlin, rel=0.01)


# ---------------------------------------------------------------------------------------------
# 9. restart: 1000 steps in one go = 500 + write_restart + new process + 500

SHEAR_FIX = f"fix sh all cell/servo axisym x {AXIAL_RATE} {P0} csv sh.csv 10"
COMPARED = ["eps1", "eps2", "eps3", "sig1", "sig2", "sig3", "p", "q", "rate1", "rate2",
            "rate3", "boundary_work", "volume", "Z"]


def max_relative_difference(a, b, names=COMPARED):
    # strain rates relative to the largest principal rate (the servo's share of a lateral
    # rate is a small difference of large terms; its own maximum is no physical scale)
    rate_scale = max(np.max(np.abs(a[k])) for k in ("rate1", "rate2", "rate3"))
    worst = 0.0
    for k in names:
        scale = rate_scale if k.startswith("rate") else np.max(np.abs(a[k]))
        scale = max(scale, 1e-300)
        worst = max(worst, np.max(np.abs(a[k] - b[k])) / scale)
    return worst


# mu = 0.3 checks the frictional history too. 3D friction is round-off chaotic
# (tests/test_pair_mpi.py), and the restart rebuilds the neighbor lists (another summation
# order); over 500 steps this stayed at 3.7e-10 relative, inside the 1e-9 requirement.
RESTART_CASES = [pytest.param(0.0, id="mu0"), pytest.param(0.3, id="mu0.3")]


def resumed_deck(restart, steps):
    """A new process: no pair_style/pair_coeff (kept by the restart), same fix ID and mode."""
    return (LOAD_TYLMP + f"read_restart {restart}\ncomm_modify vel yes\n"
            "neighbor 2e-5 bin\nfix nve all nve/sphere\n" + SHEAR_FIX + f"\nrun {steps}\n")


@pytest.mark.parametrize("mu", RESTART_CASES)
def test_restart_continues_exactly(specimen, tmp_path, mu):
    one, split = tmp_path / "one", tmp_path / "split"
    one.mkdir(), split.mkdir()
    shear_run(specimen, one, SHEAR_FIX, 1000, mu=mu)
    deck = restart_deck(specimen, mu) + SHEAR_FIX + "\nrun 500\nwrite_restart half.restart\n"
    run_ok(deck, split, name="in.first")
    out = run_ok(resumed_deck("half.restart", 500), split, name="in.second")
    assert "restoring pair style thornton/yin" in out
    a, b = read_csv(one / "sh.csv"), read_csv(split / "sh.csv")
    # the record continues: no duplicated row at the split, same steps, and the fix's own
    # `time` (from the start of the test) continues, although LAMMPS' own `time` restarts
    # after read_restart in 29Sep2021
    assert np.array_equal(a["step"], b["step"])
    assert np.allclose(b["time"], (b["step"] - b["step"][0]) * DT, rtol=1e-12, atol=0)
    after = a["step"] > a["step"][0] + 500
    a_after, b_after = ({k: v[after] for k, v in r.items()} for r in (a, b))
    record = [k for k in COMPARED if not k.startswith("rate")]
    diff = max_relative_difference(a_after, b_after, record)
    # the servo's rates amplify round-off of the summation order (a rebuilt neighbor list)
    rates = max_relative_difference(a_after, b_after, ["rate1", "rate2", "rate3"])
    print(f"restart mu={mu}: stress-strain record {diff:.3g}, strain rates {rates:.3g}")
    assert diff <= 1e-9, diff
    assert rates <= 1e-8, rates


# ---------------------------------------------------------------------------------------------
# 10. MPI: 2 ranks = 1 rank to round-off


# with mu = 0.3 1 and 2 ranks differed by 2.1e-10 before the kernel was sped up and by 9e-12
# after (round-off of the summation order over 200 steps; the 3D friction law amplifies it
# over longer runs: tests/test_pair_mpi.py)
MPI_CASES = [pytest.param(0.0, id="mu0"), pytest.param(0.3, id="mu0.3")]


@pytest.mark.parametrize("mu", MPI_CASES)
def test_two_ranks_equal_one(specimen, tmp_path, mu):
    serial, parallel = tmp_path / "np1", tmp_path / "np2"
    serial.mkdir(), parallel.mkdir()
    shear_run(specimen, serial, SHEAR_FIX, 200, mu=mu)
    out = shear_run(specimen, parallel, SHEAR_FIX, 200, mu=mu, np_ranks=2)
    assert "on 2 procs" in out
    a, b = read_csv(serial / "sh.csv"), read_csv(parallel / "sh.csv")
    assert np.array_equal(a["step"], b["step"])
    diff = max_relative_difference(a, b, COMPARED + ["unbalanced", "p_kinetic", "Zm"])
    print("MPI max relative difference", diff)
    # round-off of the summation order, amplified by the packing's chaos over 200 steps: the
    # amplification depends on the specimen (6.3e-12 at mu = 0.3 on the specimen prepared
    # before the servo's rate floor of docs/theory.md §6.2, 2.5e-10 on the one prepared with
    # it, whose first contacts, along the lattice axes, no longer freeze the loaded axis)
    assert diff <= 1e-9, diff


# ---------------------------------------------------------------------------------------------
# 11. energy balance: boundary work = stored + kinetic (incl. rotation) + dissipated


@pytest.mark.parametrize("gamma", [0.0, 0.6])
def test_energy_balance(specimen, tmp_path, gamma):
    steps = 5000
    # (compute erot/sphere is not in the Debian build: 0.5 I w^2 with I = 0.4 m r^2)
    extra = ("compute sp all property/atom radius omegax omegay omegaz\n"
             "variable erot atom 0.2*mass*c_sp[1]^2*(c_sp[2]^2+c_sp[3]^2+c_sp[4]^2)\n"
             "compute erot all reduce sum v_erot\ncompute ke all ke\n"
             "compute dis all pair thornton/yin\n")
    report = ('print "E $(step) $(pe:%.17g) $(c_ke:%.17g) $(c_erot:%.17g) '
              '$(c_dis[1]:%.17g) $(c_dis[2]:%.17g) $(c_dis[3]:%.17g) $(f_sh[33]:%.17g)"\n')
    deck = (restart_deck(specimen, 0.3, gamma) + extra + SHEAR_FIX
            + "\nthermo_style custom step pe c_ke c_erot c_dis[1] c_dis[2] c_dis[3] f_sh[33]\n"
            "thermo 1000\nrun 0\n" + report + f"run {steps}\n" + report)
    out = run_ok(deck, tmp_path)
    rows = [np.array([float(v) for v in line.split()[1:]])
            for line in out.splitlines() if line.startswith("E ")]
    start, end = rows
    d = end - start
    work = d[7]
    stored, kinetic, dissipated = d[1], d[2] + d[3], d[4] + d[5] + d[6]
    assert work > 0 and dissipated > 0
    balance = stored + kinetic + dissipated
    print(f"energy gamma={gamma}: W={work:.6g} dPE={stored:.4g} dKE={kinetic:.4g} "
          f"D={dissipated:.4g} (friction {d[4]:.4g}, break {d[5]:.4g}, damping {d[6]:.4g}) "
          f"balance error {(balance - work) / work:.3g}")
    assert balance == pytest.approx(work, rel=0.01), (work, stored, kinetic, dissipated)


# ---------------------------------------------------------------------------------------------
# 12. bad input: each error names the problem

SMALL = """lattice sc 2.8e-4
region box block 0 2 0 2 0 2
create_box 1 box
create_atoms 1 box
set atom * diameter 2e-4 density {rho}
""".format(rho=RHO)
PAIR = f"pair_style thornton/yin\npair_coeff * * {E} {NU} 0.3 0.0\nneighbor 2e-5 bin\n"


def small_deck(fix, boundary="p p p", box=None, pair=PAIR, run=10):
    head = HEADER.replace("boundary p p p", f"boundary {boundary}")
    body = SMALL if box is None else SMALL.replace(
        "region box block 0 2 0 2 0 2", box)
    return head + body + LOAD_TYLMP + pair + f"timestep {DT}\n{fix}\nrun {run}\n"


BAD_INPUT = [
    ("nonperiodic", small_deck(f"fix c all cell/servo iso {P0}", boundary="p p f"),
     "requires a fully periodic box"),
    ("shear_on_orthogonal_box", small_deck(f"fix c all cell/servo shear xz 1e-4 {P0}"),
     "needs a triclinic box"),
    ("shear_axes_on_orthogonal_box",
     small_deck(f"fix c all cell/servo axes x rate 0 y rate 0 z stress {P0} xz rate 1e-4"),
     "needs a triclinic box"),
    ("unknown_mode", small_deck(f"fix c all cell/servo shearing {P0}"), "unknown mode 'shearing'"),
    ("unknown_keyword", small_deck(f"fix c all cell/servo iso {P0} gian 0.1"),
     "unknown keyword 'gian'"),
    ("b_outside", small_deck(f"fix c all cell/servo constant_b 1.5 x 1e-5 {P0}"),
     "constant_b b = 1.5 is outside the accepted range [0, 1]"),
    ("b_negative", small_deck(f"fix c all cell/servo constant_b -0.1 x 1e-5 {P0}"),
     "is outside the accepted range [0, 1]"),
    ("p_zero", small_deck("fix c all cell/servo iso 0"), "must be positive"),
    ("p_negative", small_deck("fix c all cell/servo axisym x 1e-5 -1e5"), "must be positive"),
    ("axes_stress_negative", small_deck("fix c all cell/servo axes x stress -1 y rate 0 z rate 0"),
     "target stress of axis x"),
    ("axes_missing_axis", small_deck(f"fix c all cell/servo axes x rate 0 y stress {P0}"),
     "axis z has no control"),
    ("shrink_below_cutoff",
     small_deck("fix c all cell/servo axes x rate 0.1 y rate 0 z rate 0", run=1000),
     "has shrunk below twice the neighbor cutoff"),
    ("not_granular", small_deck(f"fix c all cell/servo iso {P0}",
                                pair="pair_style zero 3e-4\npair_coeff * *\n"),
     "needs a granular pair style"),
    ("path_without_speed", small_deck(f"fix c all cell/servo circle 0.001 {P0}"),
     "a Pi-plane path needs 'speed V'"),
    ("speed_outside_path", small_deck(f"fix c all cell/servo iso {P0} speed 1e-5"),
     "applies only to circle, triangle and polygon"),
]


@pytest.mark.parametrize("deck,message", [c[1:] for c in BAD_INPUT],
                         ids=[c[0] for c in BAD_INPUT])
def test_bad_input(tmp_path, deck, message):
    rc, out = run_deck(deck, tmp_path)
    assert "ERROR" in out, out[-2000:]
    error_line = next(line for line in out.splitlines() if "ERROR" in line)
    assert message in error_line, error_line


def documented_bad_inputs(section="fix cell/servo"):
    """(commands, message) of every table row of `## {section}` in docs/bad_inputs.md."""
    import os
    import re
    path = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs",
                        "bad_inputs.md")
    with open(path) as fh:
        text = fh.read()
    body = text.split(f"## {section}\n", 1)[1].split("\n## ", 1)[0]
    rows = []
    for line in body.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 2 or not cells[0].startswith("`"):
            continue
        commands = re.findall(r"`([^`]+)`", cells[0])
        message = re.findall(r"`([^`]+)`", cells[1])[0]
        rows.append((commands, message))
    return rows


DOCUMENTED_BAD_INPUT = documented_bad_inputs()


def test_documented_bad_inputs_are_listed():
    assert len(DOCUMENTED_BAD_INPUT) >= 20


@pytest.mark.parametrize("commands,message", DOCUMENTED_BAD_INPUT,
                         ids=[" ; ".join(c) for c, _ in DOCUMENTED_BAD_INPUT])
def test_documented_bad_input(tmp_path, commands, message):
    """docs/bad_inputs.md: each bad input stops with the message the page gives."""
    rc, out = run_deck(small_deck("\n".join(commands)), tmp_path)
    assert rc != 0 or "ERROR" in out, out[-2000:]
    error_line = next(line for line in out.splitlines() if "ERROR" in line)
    assert message in error_line, error_line


def test_good_small_deck_runs(tmp_path):
    """The bad decks differ from this one only in the item under test."""
    run_ok(small_deck(f"fix c all cell/servo iso {P0}"), tmp_path)


# ---------------------------------------------------------------------------------------------
# 13. programmes that read the fix's own outputs; minimize


def test_minimize_is_refused(tmp_path):
    deck = small_deck(f"fix nve all nve/sphere\nfix c all cell/servo iso {P0}", run=0)
    deck = deck.replace("run 0\n", "minimize 1e-10 1e-10 100 1000\n")
    rc, out = run_deck(deck, tmp_path)
    error_line = next((line for line in out.splitlines() if "ERROR" in line), "")
    assert "fix cell/servo cannot be used with minimize" in error_line, out[-2000:]


def test_stress_target_reading_the_fix_itself(specimen, tmp_path):
    """sigma_z* = 1.5e5 - 0.5 sigma_x read from f_sh[7] every step: the servo settles on the
    line sigma_z = 1.5e5 - 0.5 sigma_x while sigma_x grows under the prescribed rate (issue
    14; it used to stop with "Virial was not tallied on needed timestep")."""
    extra = "variable s equal 1.5e5-0.5*f_sh[7]\n"
    shear_run(specimen, tmp_path,
              f"fix sh all cell/servo axes x rate {AXIAL_RATE} y stress {P0} z stress v_s "
              "csv sh.csv 10", 4000, extra=extra)
    record = read_csv(tmp_path / "sh.csv")
    rows = settled(record, 1000)
    target = 1.5e5 - 0.5 * rows["sig1"]
    assert np.max(np.abs(rows["sig3"] / target - 1.0)) < 0.01
    assert np.max(np.abs(rows["sig2"] / P0 - 1.0)) < 0.01
    # the target moved: sigma_x grew under compression, sigma_z fell with it
    assert record["sig1"][-1] - record["sig1"][0] > 0.3 * P0
    assert record["sig3"][-1] < record["sig3"][0] - 0.1 * P0


# ---------------------------------------------------------------------------------------------
# 14. multi-stage tests: a redefined fix continues the test; resuming after a crash


def two_stages(specimen, first, second, steps, name="in.stages"):
    """A deck: fix sh defined with `first`, run, redefined with `second`, run."""
    return (restart_deck(specimen) + f"fix sh all cell/servo {first}\nrun {steps}\n"
            f"fix sh all cell/servo {second}\nrun {steps}\n")


def test_redefined_fix_continues_the_test(specimen, tmp_path):
    """Compression, then the same fix ID redefined for extension: one record, one strain
    reference, one clock (issue 14: the first segment used to be truncated away and the
    strains and time to restart)."""
    r = AXIAL_RATE
    run_ok(two_stages(specimen, f"axisym x {r} {P0} csv sh.csv 10",
                      f"axisym x {-r} {P0} csv sh.csv 10", 500), tmp_path)
    rows = read_csv(tmp_path / "sh.csv")
    n = rows["step"] - rows["step"][0]
    # every row once, in order, from the start of the first segment
    assert np.array_equal(n, np.arange(0, 1001, 10))
    assert np.allclose(rows["time"], n * DT, rtol=1e-12, atol=0)
    # eps1 = integral of the applied axial rate from the first definition: +r for steps
    # 2..501 (the rate decided at the end of a step deforms the next one), -r after
    expected = np.where(n <= 501, np.maximum(n - 1, 0), 500 - (n - 501)) * r * DT
    assert np.max(np.abs(rows["eps1"] - expected)) < 1e-9 * r * DT * 500
    # the boundary work continues too: no jump back to zero at the redefinition
    w = rows["boundary_work"]
    at = np.searchsorted(n, 500)
    assert abs(w[at + 1] - w[at]) < 0.1 * abs(w[at] - w[at - 10])


def test_record_has_a_row_at_the_start_of_each_run(tmp_path):
    """The record holds a row every N steps and one at the start of each run (it was written
    only when that step was a multiple of N): runs of 5, 12 and 0 steps with N = 10 give the
    rows 0, 5, 10 and 17, each step once, and each row the state of its step (eps1 of the
    prescribed rate, the cell moving from the second step on). (The first run ends with
    `post no`: the box the fix left is still known to the next run, no change is reported.)"""
    run_ok(small_deck(f"fix c all cell/servo axes x rate {RATE} y rate 0 z rate 0 csv a.csv 10\n"
                      "run 5 post no\nrun 12\nrun 0", run=0), tmp_path)
    rows = read_csv(tmp_path / "a.csv")
    assert list(rows["step"]) == [0, 5, 10, 17]
    np.testing.assert_allclose(rows["eps1"], RATE * DT * np.maximum(rows["step"] - 1, 0),
                               rtol=1e-9, atol=0)


def test_continue_no_starts_a_new_test(specimen, tmp_path):
    r = AXIAL_RATE
    run_ok(two_stages(specimen, f"axisym x {r} {P0} csv a.csv 10",
                      f"axisym x {r} {P0} continue no csv b.csv 10", 300), tmp_path)
    b = read_csv(tmp_path / "b.csv")
    assert b["time"][0] == 0.0 and b["eps1"][0] == 0.0
    # a fresh fix starts from rest: the first step applies no rate
    assert b["eps1"][-1] == pytest.approx(r * DT * 299, rel=1e-9)
    # and it may not overwrite the record of the test it replaces
    rc, out = run_deck(restart_deck(specimen)
                       + f"fix sh all cell/servo axisym x {r} {P0} csv a.csv 10\nrun 10\n"
                       f"fix sh all cell/servo axisym x {r} {P0} continue no csv a.csv 10\n",
                       tmp_path, name="in.overwrite")
    assert "would overwrite a.csv, the record of the test it replaces" in out, out[-2000:]


def test_resume_after_crash_appends_without_repeated_steps(specimen, tmp_path):
    """A run writes a restart file at step 300 and goes on to 500 before it dies; resumed from
    the restart file, the record is the one of a run that never stopped: rows 310-500 of the
    dead run are replaced, not repeated (issue 15: five duplicated steps and a jump back)."""
    one, crash = tmp_path / "one", tmp_path / "crash"
    one.mkdir(), crash.mkdir()
    shear_run(specimen, one, SHEAR_FIX, 500, mu=0.0)
    run_ok(restart_deck(specimen, 0.0) + SHEAR_FIX + "\nrun 300\nwrite_restart r300.restart\n"
           "run 200\n", crash, name="in.first")
    with open(crash / "sh.csv", "a") as fh:     # the line it was writing when it died
        fh.write("5010,0.0")
    out = run_ok(resumed_deck("r300.restart", 200), crash, name="in.second")
    assert "dropped 21 row(s)" in out
    a, b = read_csv(one / "sh.csv"), read_csv(crash / "sh.csv")
    assert np.array_equal(a["step"], b["step"])
    assert np.all(np.diff(b["step"]) > 0)
    assert np.allclose(b["time"], a["time"], rtol=1e-12, atol=0)
    assert max_relative_difference(a, b, ["eps1", "eps2", "eps3", "p", "q"]) < 1e-9


def restart_record_offset(data, tag=8462.0, version=4.0):
    import struct
    at = data.find(struct.pack("<dd", tag, version))
    assert at >= 0, "no cell/servo record in the restart file"
    return at


@pytest.mark.parametrize("damage", ["path", "plane", "version", "version3", "size", "old"])
def test_mismatched_restart_record_is_refused(tmp_path, damage):
    """The restart record carries tag, version, size, the path or plane of its programme;
    resuming another path or plane, or a record of another version (an earlier build's: 3) or
    size, is refused by name (issue 15)."""
    import struct
    programme = f"shear xz 1e-4 {P0}" if damage == "plane" else f"circle 0.001 {P0} speed 1e-4"
    first = small_deck(("change_box all triclinic\n" if damage == "plane" else "")
                       + f"fix c all cell/servo {programme}", run=10)
    run_ok(first + "write_restart c.restart\n", tmp_path, name="in.first")
    fix = f"fix c all cell/servo {programme}"
    size = None
    if damage == "path":
        fix = f"fix c all cell/servo triangle 0.001 {P0} speed 1e-4"
    elif damage == "plane":
        fix = f"fix c all cell/servo shear yz 1e-4 {P0}"
    else:
        data = bytearray((tmp_path / "c.restart").read_bytes())
        at = restart_record_offset(bytes(data))
        size = struct.unpack("<d", data[at + 16:at + 24])[0]
        if damage.startswith("version"):
            data[at + 8:at + 16] = struct.pack("<d", 3.0 if damage == "version3" else 99.0)
        elif damage == "size":
            data[at + 16:at + 24] = struct.pack("<d", size - 1)
        else:
            data[at:at + 8] = struct.pack("<d", 8461.0)
        (tmp_path / "c.restart").write_bytes(bytes(data))
    second = (LOAD_TYLMP + "read_restart c.restart\ncomm_modify vel yes\nneighbor 2e-5 bin\n"
              + fix + "\nrun 10\n")
    rc, out = run_deck(second, tmp_path, name="in.second")
    expected = {"path": "written by a run on another Pi-plane path",
                "plane": "written by a run on another plane; this one shears yz: resume it on "
                         "the same plane",
                "version": "has version 99, this build reads version 4",
                "version3": "has version 3, this build reads version 4 (a record of an earlier "
                            "build of tylmp)",
                "size": f"says it holds {size - 1:.0f} numbers, but its parts hold {size:.0f}"
                        if size else "",
                "old": "is not a cell/servo record"}[damage]
    error_line = next((line for line in out.splitlines() if "ERROR" in line), out[-2000:])
    assert expected in error_line, error_line


# ---------------------------------------------------------------------------------------------
# 15. polygon: from the current strain, through every vertex, closed on request


def test_polygon_starts_from_current_strain_and_closes(specimen, tmp_path):
    r, speed = 0.001 * np.sqrt(2.0 / 3.0), 4e-5
    verts = np.array([[0.0, r], [r, r], [r, 0.0]])
    length = r + r + r + r * np.sqrt(2.0)        # lead-in O-v1, v1-v2, v2-v3, v3-v1
    steps = int(1.03 * length / (speed * DT)) + 100
    coords = " ".join(f"{x!r} {y!r}" for x, y in verts)
    out = shear_run(specimen, tmp_path,
                    f"fix sh all cell/servo polygon 3 {coords} {P0} speed {speed} close yes "
                    "plane_strain deviatoric csv sh.csv 10", steps)
    assert "a leg of length" in out
    rows = read_csv(tmp_path / "sh.csv")
    x, y = strain_pi(rows)
    assert abs(x[0]) < 1e-15 and abs(y[0]) < 1e-15
    # the lead-in leg O -> v1 is followed (x stays 0 while y grows to r) ...
    lead = rows["progress"] < (r / length) - 0.01
    assert lead.sum() > 20 and np.max(np.abs(x[lead])) < 0.01 * r
    # ... then every vertex is passed, and the polygon closes back on v1
    for v in verts:
        assert np.min(np.hypot(x - v[0], y - v[1])) < 0.01 * r, v
    assert rows["progress"][-1] == pytest.approx(1.0)
    assert np.hypot(x[-1] - verts[0][0], y[-1] - verts[0][1]) < 0.01 * r
    late = settled(rows)
    assert np.max(np.abs(late["p"] / P0 - 1.0)) < 0.01


# ---------------------------------------------------------------------------------------------
# 16. axisym and constant_b rates from variables


def test_axisym_rate_from_a_variable_reverses(specimen, tmp_path):
    """A cyclic axisymmetric test is one fix: the axial rate, a variable of the fix's own time
    (output 36), turns from compression to extension; p and sigma2 = sigma3 stay held."""
    r, turn = AXIAL_RATE, 1000
    extra = f"variable r equal {r}*(1-2*(f_sh[36]>{turn * DT}))\n"
    shear_run(specimen, tmp_path, f"fix sh all cell/servo axisym x v_r {P0} max_rate {8 * r} "
              "csv sh.csv 10", 2 * turn, extra=extra)
    rows = read_csv(tmp_path / "sh.csv")
    n = rows["step"] - rows["step"][0]
    # rate1 of a row is the rate decided at its step: +r up to `turn`, -r after
    assert np.allclose(rows["rate1"][(n > 0) & (n <= turn)], r, rtol=1e-12)
    assert np.allclose(rows["rate1"][n > turn], -r, rtol=1e-12)
    expected = np.where(n <= turn + 1, np.maximum(n - 1, 0), turn - (n - turn - 1)) * r * DT
    assert np.max(np.abs(rows["eps1"] - expected)) < 1e-9 * r * DT * turn
    late = settled(rows)
    assert np.max(np.abs(late["p"] / P0 - 1.0)) < 0.01
    assert np.max(np.abs(late["sig2"] - late["sig3"])) < 0.01 * P0
    # the deviator falls after the reversal: unloading
    peak = np.argmax(rows["q"])
    assert abs(n[peak] - turn) <= 20
    assert rows["q"][-1] < 0.8 * rows["q"][peak]


def test_constant_b_rate_from_a_variable(specimen, tmp_path):
    extra = f"variable r equal {AXIAL_RATE}*(1+step/1e5)\n"
    shear_run(specimen, tmp_path, f"fix sh all cell/servo constant_b 0.5 x v_r {P0} "
              "max_rate 1e-4 csv sh.csv 10", 3000, extra=extra)
    rows = read_csv(tmp_path / "sh.csv")
    r = rows["step"] > rows["step"][0]
    assert np.allclose(rows["rate1"][r], AXIAL_RATE * (1 + rows["step"][r] / 1e5), rtol=1e-11)
    late = settled(rows, 1000)
    big = late["q"] > 0.2 * P0
    assert big.sum() > 10
    assert np.max(np.abs(late["b"][big] - 0.5)) < 0.02


# ---------------------------------------------------------------------------------------------
# 17. 'until NAME VALUE': progress and ETA count to the end of the test, which stops the run


def test_until_counts_progress_to_the_target_and_stops(specimen, tmp_path):
    target = 0.003
    # a second stage continues the test to a further target: the run is not stopped at once
    # (the first stage's stop is reset) and its progress counts from where it starts
    out = shear_run(specimen, tmp_path,
                    f"fix sh all cell/servo axisym x {AXIAL_RATE} {P0} until eps_d13 {target} "
                    "csv sh.csv 50", 100000)
    out2 = run_ok(restart_deck(specimen) +
                  f"fix sh all cell/servo axisym x {AXIAL_RATE} {P0} until eps_d13 {target} "
                  "csv first.csv 50\nrun 100000\n"
                  f"fix sh all cell/servo axisym x {AXIAL_RATE} {P0} until eps_d13 0.004 "
                  "csv second.csv 50\nrun 100000\n", tmp_path, name="in.stages")
    second = read_csv(tmp_path / "second.csv")
    assert second["eps_d13"][-1] >= 0.004 and np.all(second["eps_d13"][:-1] < 0.004)
    assert second["eps_d13"][0] >= target and second["progress"][0] < 0.1
    assert np.all(np.diff(second["progress"]) > 0) and second["progress"][-1] == 1.0
    assert out2.count("reached the target") == 2
    rows = read_csv(tmp_path / "sh.csv")
    d13 = rows["eps_d13"]
    # progress is the fraction of the way from the start to the target (not of the run)
    expected = np.clip((d13 - d13[0]) / (target - d13[0]), 0.0, 1.0)
    assert np.allclose(rows["progress"], expected, rtol=1e-9, atol=1e-12)
    # the run ended at the first step at the target: the last row is that step (written
    # although it is not a multiple of 50), and no row before it had reached it
    assert d13[-1] >= target and np.all(d13[:-1] < target)
    assert rows["progress"][-1] == 1.0
    assert "reached the target 0.003" in out
    # the step at which eps1 - eps3 crossed the target: it advances by about 1.5 rate dt per
    # step in axisymmetric compression, so the run took ~target/(1.5 rate dt) steps, far
    # fewer than the 100000 asked for
    steps = rows["step"][-1] - rows["step"][0]
    assert 0.5 < steps * 1.5 * AXIAL_RATE * DT / target < 1.5


# ---------------------------------------------------------------------------------------------
# 18. extra record columns from computes and variables


@pytest.mark.parametrize("ranks", [1, 2])
def test_extra_columns_from_computes_and_variables(specimen, tmp_path, ranks):
    extra = "compute kin all ke\nvariable twice_p equal 2*f_sh[10]\n"
    shear_run(specimen, tmp_path,
              f"fix sh all cell/servo axisym x {AXIAL_RATE} {P0} "
              "extra 2 kinetic c_kin twice_p v_twice_p csv sh.csv 20", 400, extra=extra,
              np_ranks=ranks)
    rows = read_csv(tmp_path / "sh.csv")
    with open(tmp_path / "sh.csv") as fh:
        assert fh.readline().strip().endswith(",progress,kinetic,twice_p")
    assert np.allclose(rows["twice_p"], 2.0 * rows["p"], rtol=1e-11)
    # compute ke = (1/2) sum m v^2 = (3/2) p_kinetic V (fluctuation velocities both)
    assert np.allclose(rows["kinetic"], 1.5 * rows["p_kinetic"] * rows["volume"], rtol=1e-9)
    assert np.all(rows["kinetic"] > 0)


# ---------------------------------------------------------------------------------------------
# 19. quasi-equilibrium outputs: which criterion holds; kinetic energy without rattlers


def test_equilibrium_criteria_outputs(specimen, tmp_path):
    """Outputs 37-40 say which criterion held at the last check, output 41 is the kinetic
    energy of the particles with two or more contacts over p V (rattlers left out, as in Zm),
    recomputed here from LAMMPS' own contact/atom count and velocities."""
    crit_u, crit_k = 1e-3, 1e-9
    extra = ("compute cont all contact/atom\n"
             "variable ke_bearing atom 0.5*mass*(vx^2+vy^2+vz^2)*(c_cont>=2)\n"
             "compute keb all reduce sum v_ke_bearing\n"
             "compute ke all ke\n")
    report = ('print "EQ $(f_sh[21]:%.17g) $(f_sh[38]) $(f_sh[41]:%.17g) $(f_sh[39]) '
              '$(c_keb:%.17g) $(c_ke:%.17g) $(f_sh[10]:%.17g) $(f_sh[35]:%.17g) $(f_sh[37]) '
              '$(f_sh[40])"\n')
    deck = (restart_deck(specimen, 0.0, 0.0) + extra
            + f"fix sh all cell/servo iso {P0} equilibrium 100 eq_unbalanced {crit_u} "
            f"eq_kinetic {crit_k}\nrun 500\n"
            "thermo_style custom step c_keb c_ke\nrun 0\n" + report)
    out = run_ok(deck, tmp_path)
    line = next(l for l in out.splitlines() if l.startswith("EQ "))
    u, u_ok, k, k_ok, ke_bearing, ke_all, p, volume, s_ok, z_ok = map(float, line.split()[1:])
    # each flag is its criterion applied to the value at the check (the run ends on a check)
    assert u_ok == float(u <= crit_u) and k_ok == float(k <= crit_k)
    assert s_ok in (0.0, 1.0) and z_ok in (0.0, 1.0)
    assert k == pytest.approx(ke_bearing / (P0 * volume), rel=1e-9)
    assert 0.0 < ke_bearing <= ke_all


# ---------------------------------------------------------------------------------------------
# 20. outputs by name: `variables yes` defines v_ID_NAME for every output


def test_named_variables_read_the_outputs(specimen, tmp_path):
    """v_sh_p, v_sh_eps1, v_sh_Z, ... are the outputs of the Output table by name: p the CSV's
    p of the same step, eps1 = -ln(lx/lx0) from LAMMPS's own box lengths, Z twice the contacts
    per sphere that LAMMPS's compute contact/atom counts (Γ = 0: a contact is an overlap; the
    same in v_sh_Z as in f_sh[18]);
    a fix redefined with the same ID defines them again; after `unfix` they are gone."""
    steps = 400
    deck = (restart_deck(specimen, 0.3, 0.0) + "compute cont all contact/atom\n"
            "compute csum all reduce sum c_cont\n"
            "variable lx0 equal $(lx:%.17g)\n"
            f"fix sh all cell/servo axisym x {AXIAL_RATE} {P0} variables yes csv sh.csv 100\n"
            f"run {steps}\n"
            "thermo_style custom step c_csum\nrun 0\n"
            'print "NV $(step) $(v_sh_p:%.17g) $(v_sh_eps1:%.17g) $(-ln(lx/v_lx0):%.17g) '
            '$(v_sh_Z:%.17g) $(f_sh[18]:%.17g) $(c_csum/atoms:%.17g) $(v_sh_progress)"\n'
            f"fix sh all cell/servo axisym x {AXIAL_RATE} {P0} variables yes\nrun 10\n"
            'print "AGAIN $(v_sh_eps1:%.17g) $(-ln(lx/v_lx0):%.17g)"\n'
            "unfix sh\n"
            'print "GONE $(v_sh_p)"\n')
    rc, out = run_deck(deck, tmp_path)
    line = next(ln for ln in out.splitlines() if ln.startswith("NV "))
    step, p, eps1, eps1_box, z, z_by_index, contacts_per_sphere, progress = map(
        float, line.split()[1:])
    rows = read_csv(tmp_path / "sh.csv")
    assert rows["step"][-1] == step                 # the row of the step the variables read
    assert p == pytest.approx(rows["p"][-1], rel=1e-11) and p == pytest.approx(P0, rel=0.05)
    assert eps1 == pytest.approx(eps1_box, rel=1e-9) and eps1 > 0
    # (LAMMPS hands a variable's value to another formula as text of 15 significant digits)
    assert z == pytest.approx(z_by_index, rel=1e-14)
    assert z == pytest.approx(contacts_per_sphere, rel=1e-14)
    assert np.isnan(progress) or 0.0 <= progress <= 1.0
    again = next(ln for ln in out.splitlines() if ln.startswith("AGAIN "))
    a, b = map(float, again.split()[1:])
    assert a == pytest.approx(b, rel=1e-9) and a > eps1      # continued test, same reference
    assert rc != 0 and not any(ln.startswith("GONE ") for ln in out.splitlines())
    error = next(ln for ln in out.splitlines() if ln.startswith("ERROR"))
    assert "Invalid variable reference v_sh_p" in error, error     # deleted, not dangling


def test_named_variables_do_not_overwrite(specimen, tmp_path):
    deck = (restart_deck(specimen) + "variable sh_p equal 42\n"
            f"fix sh all cell/servo axisym x {AXIAL_RATE} {P0} variables yes\nrun 0\n")
    rc, out = run_deck(deck, tmp_path)
    assert rc != 0
    assert ("fix cell/servo: 'variables yes' defines the variable sh_p (output 10 of fix sh), "
            "which exists already: delete it or give the fix another ID") in out


# ---------------------------------------------------------------------------------------------
# 19. hostile input of issue 31: nothing lost, nothing silent (docs/bad_inputs.md)

RATE = 1e-3     # 1/s: 2e-5 strain per step of the small deck, an exact prescribed programme


def first_error(out):
    return next((line for line in out.splitlines() if "ERROR" in line), out[-2000:])


@pytest.mark.parametrize("alias", ["./a.csv", "link.csv", "sub/../a.csv"])
def test_csv_alias_is_refused(tmp_path, alias):
    """'continue no' naming the replaced test's record by another name (./, a symbolic link,
    a .. path) is refused like the name itself: the record of the first test survives (it was
    overwritten before: the names were compared as strings)."""
    (tmp_path / "sub").mkdir()
    os.symlink("a.csv", tmp_path / "link.csv")
    rc, out = run_deck(small_deck(f"fix c all cell/servo axisym x {RATE} {P0} csv a.csv 1\n"
                                  f"run 5\nfix c all cell/servo axisym x {RATE} {P0} "
                                  f"continue no csv {alias} 1"), tmp_path)
    assert (f"whose record {alias} would overwrite a.csv, the record of the test it replaces"
            in first_error(out)), out[-2000:]
    assert list(read_csv(tmp_path / "a.csv")["step"]) == [0, 1, 2, 3, 4, 5]


@pytest.mark.parametrize("setup,path,what", [
    ("log run.log", "./run.log", "the log file of this LAMMPS run"),
    ("", "./in.test", "the input script LAMMPS is reading"),
    ("dump d all atom 5 d.*.txt", "d.10.txt", "the file of dump d"),
    ("restart 5 r.restart", "r.restart.10", "a restart file this run writes")],
    ids=["log", "input", "dump", "restart"])
def test_csv_naming_a_file_lammps_writes_is_refused(tmp_path, setup, path, what):
    rc, out = run_deck(small_deck(f"{setup}\nfix c all cell/servo iso {P0} csv {path} 1"),
                       tmp_path)
    assert f"fix cell/servo c: csv {path} is {what}" in first_error(out), out[-2000:]
    if setup.startswith("log"):    # the log is intact: it holds the fix command, no record
        log = (tmp_path / "run.log").read_text()
        assert "fix c all cell/servo" in log and "step,time" not in log


def test_restart_with_continue_no_starts_a_new_test(tmp_path):
    """A fix defined with 'continue no' after read_restart starts a new test: strains, time
    and record from zero (the state in the restart file used to be taken up regardless)."""
    fix = f"fix c all cell/servo axisym x {RATE} {P0}"
    first = small_deck(f"{fix}\nwrite_restart c.restart", run=10)
    first = first.replace("write_restart c.restart\nrun 10\n", "run 10\nwrite_restart c.restart\n")
    run_ok(first, tmp_path, name="in.first")
    resumed = (LOAD_TYLMP + "read_restart c.restart\ncomm_modify vel yes\nneighbor 2e-5 bin\n"
               "{fix}\nrun 5\n")
    out = run_ok(resumed.format(fix=f"{fix} continue no csv new.csv 1"), tmp_path,
                 name="in.new")
    assert "continue no: the test whose state the restart file holds is not continued" in out
    new = read_csv(tmp_path / "new.csv")
    assert new["time"][0] == 0.0 and new["eps1"][0] == 0.0
    # a fresh test starts from rest: eps1 = RATE dt for each step after the first
    assert new["eps1"][-1] == pytest.approx(RATE * DT * 4, rel=1e-9)
    # without 'continue no' the same restart continues the test: 9 steps of RATE dt before
    run_ok(resumed.format(fix=f"{fix} csv old.csv 1"), tmp_path, name="in.old")
    old = read_csv(tmp_path / "old.csv")
    assert old["eps1"][0] == pytest.approx(RATE * DT * 9, rel=1e-9)


def test_until_target_behind_the_test_warns(tmp_path):
    """eps1 grows under axial compression: a target below the start is never reached; the
    fix says so in the first steps (today silent, with ETA nan)."""
    out = run_ok(small_deck(f"fix c all cell/servo axisym x {RATE} {P0} until eps1 -0.001",
                            run=20), tmp_path)
    assert "until eps1 -0.001: eps1 moves away from the target" in out, out[-2000:]
    out = run_ok(small_deck(f"fix c all cell/servo axisym x {RATE} {P0} until eps1 0.001",
                            run=20), tmp_path, name="in.toward")
    assert "moves away from the target" not in out


def test_until_target_already_passed_is_refused(tmp_path):
    """A redefinition that continues the test with a target it passed already (eps1 went
    from 0 to 1e-4 and moves on) stops with a named error."""
    fix = f"fix c all cell/servo axisym x {RATE} {P0}"
    rc, out = run_deck(small_deck(f"{fix} until eps1 0.0001\nrun 100\n{fix} until eps1 0.00005"),
                       tmp_path)
    assert ("until eps1 5e-05: the test this fix continues has passed that target already"
            in first_error(out)), out[-2000:]


def test_named_variables_refuse_an_existing_user_variable(tmp_path):
    """'variables yes' never replaces a user's variable of the same name (issue 31 item 9:
    this held already; docs/fix_cell_servo.md)."""
    rc, out = run_deck(small_deck(f"variable c_q equal 42\nfix c all cell/servo iso {P0} "
                                  "variables yes"), tmp_path)
    assert "defines the variable c_q (output 11 of fix c), which exists already" in out


def test_extra_vector_columns_are_expanded(tmp_path):
    """'extra 1 g c_com' (a global vector of 3): columns g[1..3]. The atoms, at rest, follow
    the cell affinely about its centre: the centre of mass of the 8-sphere lattice (0 and
    2.8e-4 on each axis of a 5.6e-4 cell) is 2.8e-4 - 1.4e-4 exp(-eps_k)."""
    run_ok(small_deck("compute com all com\n"
                      f"fix c all cell/servo axes x rate {RATE} y rate {-RATE} z rate 0 "
                      "extra 1 g c_com csv a.csv 1", run=20), tmp_path)
    rows = read_csv(tmp_path / "a.csv")
    for k in (1, 2, 3):
        expected = 2.8e-4 - 1.4e-4 * np.exp(-rows[f"eps{k}"])
        assert np.allclose(rows[f"g[{k}]"], expected, rtol=1e-9, atol=0), k
    assert rows["eps1"][-1] > 0 > rows["eps2"][-1]


EXTRA_REFUSED = [
    ("per_atom", "compute ke all ke/atom", "extra 1 k c_ke csv a.csv 1",
     "extra column k: compute ke is per-atom (not global); extra takes global scalars"),
    ("local", "compute pl all property/local patom1", "extra 1 k c_pl csv a.csv 1",
     "extra column k: compute pl is local (not global)"),
    ("string_variable", "variable s string hello", "extra 1 k v_s csv a.csv 1",
     "extra column k: variable s is not a number each step (it is a string, read as 0)"),
    ("without_csv", "variable x equal 1", "extra 1 k v_x",
     "'extra' adds columns to the record, but this fix writes none: add 'csv FILE N'"),
    ("builtin_name", "variable x equal 1", "extra 1 sliding_fraction v_x csv a.csv 1",
     "extra column sliding_fraction (v_x) has the name of the fix's built-in output "
     "sliding_fraction (output 20)"),
    ("vector_name", "compute com all com\nvariable x equal 1",
     "extra 2 g c_com g[2] v_x csv a.csv 1",
     "extra column g[2] (v_x) has the name of extra column g[2] (c_com[2])"),
]


@pytest.mark.parametrize("setup,keywords,message", [c[1:] for c in EXTRA_REFUSED],
                         ids=[c[0] for c in EXTRA_REFUSED])
def test_extra_bad_reference_is_refused_naming_the_fix(tmp_path, setup, keywords, message):
    rc, out = run_deck(small_deck(f"{setup}\nfix c all cell/servo iso {P0} {keywords}"),
                       tmp_path)
    assert f"fix cell/servo c: {message}" in first_error(out), out[-2000:]


ABSURD = [
    ("sweep", f"circle 0.001 {P0} speed 1e-4 sweep 1e300",
     "sweep = 1e300 is outside the accepted range (0, 36000] degrees"),
    ("speed", f"circle 0.001 {P0} speed 1e-30",
     "speed = 1e-30 1/s strains the cell by 2e-32 per step (timestep 0.02); the accepted "
     "range is 5e-14 to 0.5 1/s"),
    ("rate_small", f"axisym x 1e-30 {P0}", "the accepted range is 5e-14 to 0.5 1/s"),
    ("rate_large", f"axes x rate 1e300 y stress {P0} z stress {P0}",
     "the accepted range is 5e-14 to 0.5 1/s"),
    ("max_rate", f"iso {P0} max_rate 1e300", "max_rate = 1e+300 1/s strains the cell by"),
    ("max_inertial", f"iso {P0} max_inertial 1e300",
     "max_inertial = 1e300 is outside the accepted range (0, 1]"),
    ("prestrain", f"circle 5 {P0} speed 1e-4",
     "circle pre-strain = 5 is outside the accepted range (0, 1]"),
    ("vertex", f"polygon 2 0 0 1e300 0 {P0} speed 1e-5",
     "polygon vertex 2 x = 1e300 is outside the accepted range [-1, 1]"),
    ("gain", f"iso {P0} gain 1e300", "servo gain 1e+300 is outside (0, 1]"),
    ("integral_band", f"iso {P0} integral_band 1e300",
     "integral_band = 1e300 is outside the accepted range [0, 1]"),
    ("eq_kinetic", f"iso {P0} equilibrium 10 eq_kinetic 1e300",
     "eq_kinetic = 1e300 is outside the accepted range (0, 1]"),
]


@pytest.mark.parametrize("programme,message", [c[1:] for c in ABSURD], ids=[c[0] for c in ABSURD])
def test_absurd_magnitude_gets_a_range_error(tmp_path, programme, message):
    rc, out = run_deck(small_deck(f"fix c all cell/servo {programme}"), tmp_path)
    assert message in first_error(out), out[-2000:]


def test_inertial_number_warning_gives_the_quasi_static_rate(tmp_path):
    """I = rate d sqrt(rho/p) (docs/theory.md §4.2) of 1e-3 1/s on spheres of 0.2 mm at
    1e5 Pa is 0.033; the rate at I = 1e-3 is 1e-3 sqrt(p/rho)/d."""
    out = run_ok(small_deck(f"fix c all cell/servo axisym x {RATE} {P0}"), tmp_path)
    limit = 1e-3 * np.sqrt(P0 / RHO) / 2e-4
    line = next(l for l in out.splitlines() if "gives an inertial number" in l)
    assert f"I = {RATE / limit * 1e-3:.3g}" in line and f"use a rate <= {limit:.4g} 1/s" in line
    out = run_ok(small_deck(f"fix c all cell/servo axisym x {0.5 * limit} {P0}"), tmp_path,
                 name="in.slow")
    assert "gives an inertial number" not in out


def test_iso_servo_moves_an_axis_without_contacts(tmp_path):
    """64 spheres, contacts along x only (the lattice squeezed in x), held at 1e5 Pa: the
    loaded x axis reaches its target while y and z, which no contact crosses, close at the
    cap (before, the servo step of x was scaled down behind them by 1e9 and x stalled)."""
    deck = small_deck(f"fix c all cell/servo iso {P0} csv a.csv 100", run=3000,
                      box="region box block 0 4 0 4 0 4")
    deck = deck.replace("pair_style thornton/yin", "change_box all x scale 0.7142 remap\n"
                        "pair_style thornton/yin")
    run_ok(deck, tmp_path)
    rows = read_csv(tmp_path / "a.csv")
    assert rows["sig1"][0] < 0.2 * P0 and rows["sig2"][0] == 0.0
    assert abs(rows["sig1"][-1] / P0 - 1.0) < 0.01
    cap = rows["rate2"][-1]
    assert cap > 0 and np.allclose(rows["rate2"][1:], cap) and np.allclose(rows["rate3"][1:], cap)


def test_axes_cap_warning_names_the_held_targets(specimen, tmp_path):
    """The cap warning of an axes programme names the held stresses and their targets and
    the prescribed rate (it said 'target 0': the mean-stress target of the other modes)."""
    out = shear_run(specimen, tmp_path, f"fix sh all cell/servo axes x rate 1e-3 y stress {P0} "
                    f"z stress {P0} max_rate 1e-8", 2100)
    line = next((l for l in out.splitlines() if CAP_WARNING in l), out[-3000:])
    assert "sig_yy = " in line and "sig_zz = " in line and "target 1e+05" in line, line
    assert "prescribed rate 0.001 1/s" in line and "target 0" not in line, line
