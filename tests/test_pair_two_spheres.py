"""Two spheres driven kinematically through LAMMPS (fix move): the normal cycle, the Γ = 0
limit against LAMMPS's own hertz/material, tangential cycles, objectivity, Newton's third law.
Reference values come from tests/jkr_reference.py (bisection, quadrature), not from the plugin."""
import math

import numpy as np
import pytest

import jkr_reference as ref
from lmprun import LOAD_TYLMP, read_table, run_ok, two_spheres_box

E, NU, RHO = 70e9, 0.3, 2650.0
R = 1.0e-4                         # sphere radius: R* = 50 µm (docs/theory.md §1.8)
R_STAR = R / 2
E_STAR = ref.effective_modulus(E, NU)
G_STAR = ref.effective_shear_modulus(E, NU)


def two_sphere_deck(pair_lines, motion, nsteps, dt, columns, every=1, extra=""):
    """Atom 1 at the origin held still, atom 2 moved by `motion` (fix move args)."""
    defs = "\n".join(f"variable {c} equal {expr}" for c, expr in columns.items())
    return two_spheres_box(2 * R, 2 * R, RHO, types=2) + f"""{LOAD_TYLMP}
{pair_lines}
neighbor 2e-6 bin
neigh_modify every 1 delay 0 check yes
timestep {dt}
fix hold one move linear 0 0 0
fix drive two {motion}
{extra}
{defs}
fix out all print {every} "{" ".join("${" + c + "}" for c in columns)}" file out.txt screen no title "# {" ".join(columns)}"
run {nsteps}
"""


def normal_cycle(tmp_path, pair_lines, gap, delta_max, delta_end, speed, dt):
    """Atom 2 starts `gap` apart, approaches to overlap delta_max, retracts to delta_end."""
    t_in = (gap + delta_max) / speed
    t_total = t_in + (delta_max - delta_end) / speed
    x0 = 0.0                        # fix move variable: displacement from the start, 2R + gap
    pos = f"({x0}-{speed}*step*dt*(step*dt<{t_in})-({speed}*{t_in}-{speed}*(step*dt-{t_in}))*(step*dt>={t_in}))"
    vel = f"(-{speed}*(step*dt<{t_in})+{speed}*(step*dt>={t_in}))"
    motion = "move variable v_px NULL NULL v_vx NULL NULL"
    extra = f"variable px equal {pos}\nvariable vx equal {vel}"
    cols = {"t": "step*dt", "d": f"{2 * R}-x[2]", "fx": "fx[2]", "f1x": "fx[1]"}
    nsteps = int(t_total / dt) + 1
    deck = two_sphere_deck(pair_lines, motion, nsteps, dt, cols, extra=extra)
    deck = deck.replace(f"create_atoms 2 single {2 * R} 0 0", f"create_atoms 2 single {2 * R + gap} 0 0")
    run_ok(deck, tmp_path)
    table = read_table(tmp_path / "out.txt")
    return {k: v[1:] for k, v in table.items()}    # row 0 is printed before fix move acts


@pytest.mark.parametrize("Gamma", [0.3, 3.0])
def test_adhesive_normal_cycle_follows_jkr_and_breaks_at_delta_f(tmp_path, Gamma):
    # snap-in at -8/9 Pc, JKR curve both ways, minimum -Pc, break at delta_f with -5/9 Pc
    Pc = ref.pull_off_force(Gamma, R_STAR)
    delta_f = ref.break_overlap(R_STAR, E_STAR, Gamma)
    a0 = ref.zero_load_radius(Gamma, R_STAR, E_STAR)
    delta_u = a0**2 / R_STAR
    data = normal_cycle(tmp_path, f"pair_style thornton/yin\npair_coeff * * {E} {NU} 0.3 {Gamma}",
                        gap=0.2 * delta_u, delta_max=4 * delta_u, delta_end=1.3 * delta_f,
                        speed=1e-3, dt=delta_u / 1e-3 / 2000)
    d, P = data["d"], data["fx"]            # force on atom 2 along +x = P (repulsive > 0)
    assert np.allclose(P, -data["f1x"], rtol=0, atol=1e-12 * Pc)      # Newton's third law
    approach = np.arange(len(d)) <= np.argmax(d)
    before_touch = approach & (d < 0)
    assert np.all(P[before_touch] == 0.0)                              # no long-range force
    first = np.argmax(approach & (d >= 0))
    assert P[first] == pytest.approx(ref.normal_force(d[first], R_STAR, E_STAR, Gamma), rel=1e-9)
    # snap-on at first touch, P = -8/9 Pc (docs/theory.md §1.2)
    assert P[first] / Pc == pytest.approx(-8 / 9, abs=2e-3)
    in_contact = np.arange(len(d)) >= first
    alive = in_contact & (P != 0.0)
    expected = np.array([ref.normal_force(x, R_STAR, E_STAR, Gamma) for x in d[alive]])
    # single JKR curve on loading and unloading, compressive and tensile
    assert np.max(np.abs(P[alive] - expected)) <= 1e-6 * max(Pc, np.max(np.abs(expected)))
    assert P[alive].min() / Pc == pytest.approx(-1.0, abs=1e-4)        # load-controlled pull-off
    last = np.nonzero(alive)[0][-1]
    assert d[last] >= delta_f and d[last + 1] < delta_f                 # breaks exactly past delta_f
    # -5/9 Pc is reached at delta_f itself; one step before it P - P_f grows like
    # sqrt(delta - delta_f) (fold of the JKR curve), i.e. ~0.04 Pc for steps of delta_u/2000
    assert P[last] / Pc == pytest.approx(-5 / 9, abs=0.03)
    assert np.all(P[last + 1:] == 0.0)


def test_hertz_limit_equals_lammps_granular_hertz_material(tmp_path):
    # Γ = 0: normal force identical to pair granular hertz/material (undamped) to round-off
    kw = dict(gap=1e-8, delta_max=2e-7, delta_end=-1e-8, speed=1e-2, dt=1e-8)
    ours = normal_cycle(tmp_path, f"pair_style thornton/yin\npair_coeff * * {E} {NU} 0.3 0.0", **kw)
    theirs = normal_cycle(tmp_path, "pair_style granular\n"
                          f"pair_coeff * * hertz/material {E} 0.0 {NU} tangential linear_nohistory 0 0",
                          **kw)
    assert np.array_equal(ours["d"], theirs["d"])
    scale = np.max(np.abs(theirs["fx"]))
    assert scale > 0
    assert np.max(np.abs(ours["fx"] - theirs["fx"])) <= 1e-12 * scale
    touching = ours["d"] > 0
    hertz = 4 / 3 * E_STAR * np.sqrt(R_STAR) * ours["d"][touching] ** 1.5
    assert np.allclose(ours["fx"][touching], hertz, rtol=1e-12)


def tangential_cycle(tmp_path, Gamma, mu, delta, amplitudes, speed, dt):
    """Hold overlap delta, move atom 2 along y through the turning points `amplitudes`."""
    times, t = [0.0], 0.0
    pos = [0.0]
    for target in amplitudes:
        t += abs(target - pos[-1]) / speed
        times.append(t)
        pos.append(target)
    # piecewise-linear y(t) and its velocity as LAMMPS equal-style expressions
    terms_y, terms_v = [], []
    for k in range(len(amplitudes)):
        t0, t1, y0, y1 = times[k], times[k + 1], pos[k], pos[k + 1]
        s = (y1 - y0) / (t1 - t0)
        window = f"(step*dt>={t0})*(step*dt<{t1})"
        terms_y.append(f"({y0}+{s}*(step*dt-{t0}))*{window}")
        terms_v.append(f"{s}*{window}")
    extra = (f"variable py equal {'+'.join(terms_y)}+{pos[-1]}*(step*dt>={times[-1]})\n"
             f"variable vy equal {'+'.join(terms_v)}\n"
             "variable zero equal 0\n"
             "compute torque all property/atom tqz")
    motion = "move variable v_zero v_py v_zero v_zero v_vy v_zero"    # x, z held: constant overlap
    cols = {"t": "step*dt", "y": "y[2]", "fx": "fx[2]", "fy": "fy[2]", "f1y": "fy[1]",
            "tz1": "C_torque[1]", "tz2": "C_torque[2]"}
    nsteps = int(times[-1] / dt)
    deck = two_sphere_deck(f"pair_style thornton/yin\npair_coeff * * {E} {NU} {mu} {Gamma}",
                           motion, nsteps, dt, cols, extra=extra)
    deck = deck.replace(f"create_atoms 2 single {2 * R} 0 0", f"create_atoms 2 single {2 * R - delta} 0 0")
    run_ok(deck, tmp_path)
    data = read_table(tmp_path / "out.txt")
    # normal and tangential components on atom 2: n = (2R - delta, y)/r tilts as atom 2 moves
    x_sep = 2 * R - delta
    r = np.hypot(x_sep, data["y"])
    data["P"] = (data["fx"] * x_sep + data["fy"] * data["y"]) / r
    data["T"] = -(data["fy"] * x_sep - data["fx"] * data["y"]) / r    # on atom 1, along +y
    data["delta"] = 2 * R - r
    return data


def test_tangential_loading_follows_mindlin_and_slides_at_mu_P(tmp_path):
    # Γ = 0, constant overlap: T(δt) = μP[1-(1-16G*aδt/(3μP))^1.5], sliding at δt = 3μP/(16G*a)
    mu, delta = 0.3, 1e-7
    a = math.sqrt(R_STAR * delta)
    P = 4 / 3 * E_STAR * math.sqrt(R_STAR) * delta**1.5
    slide = 3 * mu * P / (16 * G_STAR * a)
    data = tangential_cycle(tmp_path, 0.0, mu, delta, [1.5 * slide], speed=1e-3, dt=slide / 1e-3 / 4000)
    y, T = data["y"], data["T"]           # force on atom 2 opposes its displacement
    assert np.allclose(data["fy"], -data["f1y"], rtol=0, atol=1e-12 * P)   # third law
    loading = (y > 0) & (y < 0.999 * slide)
    mindlin = mu * P * (1 - (1 - y[loading] / slide) ** 1.5)
    assert np.max(np.abs(T[loading] - mindlin)) <= 2e-3 * mu * P
    sliding = y > 1.01 * slide
    assert np.allclose(T[sliding], mu * data["P"][sliding], rtol=1e-9)     # Coulomb limit
    assert np.allclose(data["P"], 4 / 3 * E_STAR * math.sqrt(R_STAR) * data["delta"] ** 1.5, rtol=1e-9)
    # torques: each sphere feels lever*T about z, same sign (docs/theory.md §2.3; LAMMPS
    # convention)
    lever = R - data["delta"] / 2
    assert np.allclose(data["tz1"], data["tz2"], rtol=1e-9, atol=1e-20)
    assert np.allclose(np.abs(data["tz2"]), lever * np.abs(T), rtol=1e-9, atol=1e-20)


def test_tangential_unloading_is_masing(tmp_path):
    # unloading from T* follows the loading curve scaled by 2 about the reversal point
    mu, delta = 0.3, 1e-7
    a = math.sqrt(R_STAR * delta)
    P = 4 / 3 * E_STAR * math.sqrt(R_STAR) * delta**1.5
    slide = 3 * mu * P / (16 * G_STAR * a)
    y_star = 0.6 * slide
    data = tangential_cycle(tmp_path, 0.0, mu, delta, [y_star, -y_star, y_star], speed=1e-3,
                            dt=slide / 1e-3 / 4000)
    y, T = data["y"], data["T"]
    loading_curve = lambda s: mu * P * (1 - (1 - s / slide) ** 1.5)
    T_star = loading_curve(y_star)
    t = data["t"]
    t_rev = y_star / 1e-3
    unloading = (t > t_rev) & (t < 3 * t_rev)
    masing = T_star - 2 * loading_curve((y_star - y[unloading]) / 2)
    assert np.max(np.abs(T[unloading] - masing)) <= 3e-3 * mu * P
    reloading = t > 3 * t_rev
    masing_up = -T_star + 2 * loading_curve((y[reloading] + y_star) / 2)
    assert np.max(np.abs(T[reloading] - masing_up)) <= 3e-3 * mu * P
    assert T[-1] == pytest.approx(T_star, rel=5e-3)                  # loop closes at (δ*, T*)


def test_adhesive_contact_slides_at_mu_P_plus_2Pc(tmp_path):
    # Thornton (1991): sliding limit μ(P + 2Pc); with μ = 0.3 sliding precedes the end of peeling
    mu, Gamma, delta = 0.3, 0.3, 2e-8
    Pc = ref.pull_off_force(Gamma, R_STAR)
    P = ref.normal_force(delta, R_STAR, E_STAR, Gamma)
    limit = mu * (P + 2 * Pc)
    a = ref.contact_radius(delta, R_STAR, E_STAR, Gamma)
    reach = 3 * limit / (8 * G_STAR * a)
    data = tangential_cycle(tmp_path, Gamma, mu, delta, [reach], speed=1e-3, dt=reach / 1e-3 / 4000)
    T = data["T"]
    k = -1                                                            # sliding at the end
    P_k = ref.normal_force(data["delta"][k], R_STAR, E_STAR, Gamma)
    assert T[k] == pytest.approx(mu * (P_k + 2 * Pc), rel=1e-9)
    assert data["P"][-1] == pytest.approx(P_k, rel=1e-9)              # normal force stays JKR
    # initial stiffness is 8 G* a with the JKR contact radius (peeling starts at a(P))
    y = data["y"]
    k0 = np.polyfit(y[1:20], T[1:20], 1)[0]
    assert k0 == pytest.approx(8 * G_STAR * a, rel=2e-2)


@pytest.mark.parametrize("axis", ["z", "x"])
def test_loaded_pair_rotated_rigidly_keeps_its_force_in_the_body_frame(tmp_path, axis):
    # objectivity: rotation about z turns the normal, rotation about x (the normal) twists T
    mu, delta = 0.3, 1e-7
    P = 4 / 3 * E_STAR * math.sqrt(R_STAR) * delta**1.5
    a = math.sqrt(R_STAR * delta)
    slide = 3 * mu * P / (16 * G_STAR * a)
    y_load = 0.4 * slide
    period = 1e-4
    dt = period / 20000
    deck = two_spheres_box(2 * R - delta, 2 * R, RHO) + f"""{LOAD_TYLMP}
pair_style thornton/yin
pair_coeff * * {E} {NU} {mu} 0.0
neighbor 2e-6 bin
neigh_modify every 1 delay 0 check yes
timestep {dt}
fix hold one move linear 0 0 0
fix load two move linear 0 {y_load / (2000 * dt)} 0
run 2000
unfix hold
unfix load
variable fx equal fx[2]
variable fy equal fy[2]
variable fz equal fz[2]
variable x2 equal x[2]-x[1]
variable y2 equal y[2]-y[1]
variable z2 equal z[2]-z[1]
print "BEFORE ${{fx}} ${{fy}} ${{fz}} ${{x2}} ${{y2}} ${{z2}}"
variable xc equal 0.5*(x[1]+x[2])
variable yc equal 0.5*(y[1]+y[2])
fix spin all move rotate ${{xc}} ${{yc}} 0 {"0 0 1" if axis == "z" else "1 0 0"} {period}
run {int(period / 4 / dt)}
print "AFTER ${{fx}} ${{fy}} ${{fz}} ${{x2}} ${{y2}} ${{z2}}"
"""
    out = run_ok(deck, tmp_path)
    before = np.array([float(v) for v in out.split("BEFORE ")[1].split()[:6]])
    after = np.array([float(v) for v in out.split("AFTER ")[1].split()[:6]])
    rot = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]]) if axis == "z" else \
        np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]])                     # +90° about the axis
    assert np.allclose(after[3:], rot @ before[3:], rtol=0, atol=1e-9 * R)
    F_before, F_after = before[:3], after[:3]
    assert np.linalg.norm(F_before[1:]) > 0.1 * mu * P                     # tangentially loaded
    assert np.allclose(F_after, rot @ F_before, rtol=0, atol=1e-4 * np.linalg.norm(F_before))


def test_example_deck_two_spheres(tmp_path, repo):
    """inputs/two_spheres.in as a user runs it: snap-on at -8/9 Pc, minimum -Pc, break on
    retraction just past delta_f at about -5/9 Pc (docs/theory.md §1.2)."""
    import os
    import subprocess
    deck = os.path.join(repo, "inputs", "two_spheres.in")
    out = subprocess.run(["lmp", "-in", deck, "-log", "none"], cwd=tmp_path,
                         capture_output=True, text=True)
    assert out.returncode == 0 and "ERROR" not in out.stdout, out.stdout[-2000:]
    d = np.genfromtxt(tmp_path / "two_spheres.csv", delimiter=",", names=True)
    Pc = 3 * np.pi * 0.3 * 0.5e-4          # Gamma = 0.3 J/m^2, R* = 0.05 mm
    touching = np.flatnonzero(d["normal_force"] != 0.0)
    assert d["normal_force"][touching[0]] / Pc == pytest.approx(-8.0 / 9.0, rel=1e-9)
    assert d["normal_force"].min() / Pc == pytest.approx(-1.0, rel=1e-4)
    last = d["normal_force"][touching[-1]] / Pc
    assert -0.60 < last < -5.0 / 9.0      # sampled every 10 steps just before delta_f
    assert d["overlap"][-1] < d["overlap"][touching[-1]] < 0.0
