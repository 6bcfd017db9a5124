"""LAMMPS's analytic DEM verification problems that a particle-particle pair style can run,
with pair thornton/yin and, beside it, LAMMPS's pair granular (hertz/material, mindlin).

LAMMPS's development tree (after 4 Feb 2025) has a YAML-driven DEM verification suite,
unittest/granular: at first the MFiX-DEM cases DEM-01 ... DEM-06 of Garg et al. (Powder Technol.
220, 2012), since extended with the particle-impact benchmarks of Chung & Ooi (Granular Matter
13, 2011). Its closed forms are in unittest/granular/test_analytic_models.cpp. Of the MFiX set,
DEM-01, -02, -04 are sphere-wall problems (fix wall/gran), DEM-03 is a stack between two walls
with linear springs and DEM-06 a settling sphere in a fluid, so none of them is a problem of a
pair style alone; what a pair style can run are the two-sphere problems, each with its closed
form as upstream states it (docs/lammps_harness.md lists the upstream files):

* collision_restitution (upstream dem01-hertz-twosphere-3d-si.yaml: its parameters): head-on
  impact of two spheres spinning so that their contact points move together (zero slip, so
  spin_no_friction too): -(v1' - v2')/(2 v_in) = e, momentum 0, spins unchanged;
* hertz_normal_impact and hertz_peak (dem02-hertzmaterial-twosphere-3d-si.yaml, Chung & Ooi
  test 1): at the largest overlap (1/2) m_red V^2 = (2/5) P_max alpha_max,
  alpha_max = (5 m_red V^2/(4 K))^(2/5), P_max = K alpha_max^(3/2), K = (4/3) E* sqrt(R*);
* oblique_impact_pair (upstream test_dem_15; Chung & Ooi test 5 in pair form): gross sliding,
  per sphere v_n' = -e v_n, v_t' = v_t - mu (1+e) v_n, omega' = -(5/2) mu (1+e) v_n / r;
* momentum_conservation: an off-centre frictional impact; linear momentum, and angular momentum
  about the origin (orbital plus spin I omega, which upstream's sphere case leaves out), as
  before the impact;
* pulloff_jkr (Gamma > 0): at zero overlap the tensile force is (8/9) of the pull-off force,
  |F| = (8/3) pi Gamma R*.

At Gamma = 0 the law of thornton/yin is Hertz-Mindlin-Deresiewicz; `pair granular` with
hertz/material and mindlin has the same Hertz normal force and a tangential spring of the same
initial stiffness 8 G* a (without the Mindlin-Deresiewicz micro-slip), so both must meet each
closed form. The tolerances are upstream's (analytic_tol) where it gives one; the numbers each
pair reaches are in docs/lammps_harness.md (`python3 -m pytest -s` prints them).
"""
import math

import pytest

import jkr_reference as ref
import test_lammps_versions as versions
from lmprun import LOAD_TYLMP, read_table, run_ok

BOX = "-0.2 0.2 -0.2 0.2 -0.2 0.2"
COLUMNS = "x1 y1 x2 y2 vx1 vy1 vx2 vy2 wz1 wz2 fx1 fy1"


def pair_lines(style, E, nu, mu, e=1.0, Gamma=0.0):
    """The contact law of `style` ('thornton/yin' or 'granular') for spheres of modulus E,
    Poisson ratio nu, friction mu; normal restitution e (viscous damping), adhesion Gamma."""
    if style == "thornton/yin":
        from tylmp.decks import damping_ratio_for_restitution
        damping = f" damping {damping_ratio_for_restitution(e)!r} 0" if e < 1 else ""
        return (f"{LOAD_TYLMP}pair_style thornton/yin\n"
                f"pair_coeff * * {E} {nu} {mu} {Gamma}{damping}\n")
    normal = f"jkr {E} 0.0 {nu} {Gamma}" if Gamma > 0 else f"hertz/material {E} 0.0 {nu}"
    damping = ""
    if e < 1:
        # the restitution as the damping's parameter (coeff_restitution: 4 Feb 2025, not 29 Sep
        # 2021)
        normal = f"hertz/material {E} {e} {nu}"
        damping = " damping coeff_restitution"
    return (f"pair_style granular\n"
            f"pair_coeff * * {normal} tangential mindlin NULL 0.0 {mu}{damping}\n")


def two_sphere_deck(law, diameter, density, p1, p2, v1, v2, w1=(0, 0, 0), w2=(0, 0, 0),
                    dt=1e-8, steps=0, every=1):
    """Two spheres at p1, p2 with velocities v1, v2 and spins w1, w2, integrated by fix
    nve/sphere; every `every` steps a line of COLUMNS (and the forces on sphere 1) to out.txt."""
    return f"""units si
atom_style sphere
atom_modify map array
boundary f f f
comm_modify vel yes
region box block {BOX} units box
create_box 1 box
create_atoms 1 single {p1[0]!r} {p1[1]!r} {p1[2]!r} units box
create_atoms 1 single {p2[0]!r} {p2[1]!r} {p2[2]!r} units box
set group all diameter {diameter!r} density {density!r}
velocity all set 0 0 0
set atom 1 vx {v1[0]!r} vy {v1[1]!r} vz {v1[2]!r} omega {w1[0]!r} {w1[1]!r} {w1[2]!r}
set atom 2 vx {v2[0]!r} vy {v2[1]!r} vz {v2[2]!r} omega {w2[0]!r} {w2[1]!r} {w2[2]!r}
{law}neighbor {0.05 * diameter!r} bin
neigh_modify delay 0 every 1 check yes
timestep {dt!r}
fix integrate all nve/sphere
compute w all property/atom omegax omegay omegaz
fix out all print {every} "$(x[1]) $(y[1]) $(x[2]) $(y[2]) $(vx[1]) $(vy[1]) $(vx[2]) &
  $(vy[2]) $(C_w[1][3]) $(C_w[2][3]) $(fx[1]) $(fy[1])" file out.txt screen no title "# {COLUMNS}"
thermo 0
run {steps}
print "FINAL $(x[1]:%.17g) $(y[1]:%.17g) $(z[1]:%.17g) $(x[2]:%.17g) $(y[2]:%.17g) &
  $(z[2]:%.17g) $(vx[1]:%.17g) $(vy[1]:%.17g) $(vz[1]:%.17g) $(vx[2]:%.17g) $(vy[2]:%.17g) &
  $(vz[2]:%.17g) $(C_w[1][1]:%.17g) $(C_w[1][2]:%.17g) $(C_w[1][3]:%.17g) $(C_w[2][1]:%.17g) &
  $(C_w[2][2]:%.17g) $(C_w[2][3]:%.17g) $(mass[1]:%.17g) $(mass[2]:%.17g) $(fx[1]:%.17g) &
  $(fy[1]:%.17g) $(fz[1]:%.17g)"
"""


def final_state(out):
    """The FINAL line: positions, velocities, spins of spheres 1 and 2, masses, force on 1."""
    line = [ln for ln in out.splitlines() if ln.startswith("FINAL ")][-1]
    v = [float(t) for t in line.split()[1:]]
    return {"x1": v[0:3], "x2": v[3:6], "v1": v[6:9], "v2": v[9:12], "w1": v[12:15],
            "w2": v[15:18], "m1": v[18], "m2": v[19], "f1": v[20:23]}


STYLES = ["thornton/yin", "granular"]
RESULTS = {}            # case -> style -> {quantity: relative error}, printed at the end


def record(case, style, **errors):
    RESULTS.setdefault(case, {})[style] = errors
    print(f"\n{case} [{style}]: " + ", ".join(f"{k} {v:.6g}" for k, v in errors.items()))


def rel(value, expected):
    return abs(value - expected) / abs(expected)


# ---- collision_restitution + spin_no_friction: upstream dem01-hertz-twosphere-3d-si.yaml ----

@pytest.mark.parametrize("style", STYLES)
@pytest.mark.parametrize("e", [1.0, 0.5])
def test_collision_restitution_of_counter_spinning_spheres(tmp_path, style, e):
    if style == "granular" and e < 1 and versions.LMP_VERSION < versions.V2025:
        pytest.skip("pair granular of 29 Sep 2021 has no 'damping coeff_restitution'; its "
                    "'damping tsuji' with e = 0.5 rebounds with e = 0.616 here")
    d, rho, E, nu, mu, vin, w0 = 0.005, 2700.0, 7.0e10, 0.33, 0.4, 2.0, 22.0
    sep, dt = 0.00255, 1.0e-8
    law = pair_lines(style, E, nu, mu, e=e)
    out = run_ok(two_sphere_deck(law, d, rho, (-sep, 0, 0), (sep, 0, 0), (vin, 0, 0),
                                 (-vin, 0, 0), (0, 0, w0), (0, 0, -w0), dt=dt, steps=5100,
                                 every=100), tmp_path)
    s = final_state(out)
    assert s["x2"][0] - s["x1"][0] > d                     # separated again
    e_measured = -(s["v1"][0] - s["v2"][0]) / (2 * vin)
    momentum = abs(s["m1"] * s["v1"][0] + s["m2"] * s["v2"][0]) / ((s["m1"] + s["m2"]) * vin)
    spin = max(abs(s["w1"][2] - w0), abs(s["w2"][2] + w0)) / w0
    sideways = max(abs(s["v1"][1]), abs(s["v2"][1])) / vin
    record(f"collision_restitution e={e}", style, e=rel(e_measured, e), momentum=momentum,
           spin=spin, sideways=sideways)
    # upstream's analytic_tol is 0.02; both laws are exact for a Hertz impact, so only the
    # time step (1e-8 s, contact time 13 us) limits them
    assert e_measured == pytest.approx(e, rel=2e-3)
    assert momentum < 1e-12
    assert spin < 1e-12 and sideways < 1e-12                # zero slip: no tangential force


# ---- hertz_normal_impact, hertz_peak: upstream dem02-hertzmaterial-twosphere-3d-si.yaml ------

@pytest.mark.parametrize("style", STYLES)
def test_hertz_normal_impact_peak(tmp_path, style):
    d, rho, E, nu, mu, vin, sep, dt = 0.02, 2800.0, 4.8e10, 0.20, 0.35, 10.0, 0.0101, 2.0e-8
    law = pair_lines(style, E, nu, mu)
    run_ok(two_sphere_deck(law, d, rho, (-sep, 0, 0), (sep, 0, 0), (vin, 0, 0), (-vin, 0, 0),
                           dt=dt, steps=3500), tmp_path)
    data = read_table(tmp_path / "out.txt")
    overlap = d - (data["x2"] - data["x1"])
    peak = overlap.argmax()
    alpha, p_max = overlap[peak], abs(data["fx1"][peak])
    m = rho * math.pi / 6 * d**3
    m_red, v_rel = m / 2, 2 * vin
    K = 4 / 3 * ref.effective_modulus(E, nu) * math.sqrt(d / 4)
    alpha_pred = (5 * m_red * v_rel**2 / (4 * K)) ** 0.4
    ke, pe = 0.5 * m_red * v_rel**2, 0.4 * p_max * alpha
    record("hertz_normal_impact", style, energy=rel(pe, ke), alpha_max=rel(alpha, alpha_pred),
           P_max=rel(p_max, K * alpha_pred**1.5))
    assert pe == pytest.approx(ke, rel=2e-3)                # upstream: 0.01
    assert alpha == pytest.approx(alpha_pred, rel=1e-3)
    assert p_max == pytest.approx(K * alpha_pred**1.5, rel=2e-3)


# ---- oblique_impact_pair (upstream test_dem_15) ----------------------------------------------

@pytest.mark.parametrize("style", STYLES)
def test_oblique_impact_pair_in_gross_sliding(tmp_path, style):
    d, rho, E, nu, mu = 0.005, 2700.0, 7.0e10, 0.33, 0.4
    vn, vt, e, dt = 0.01, 0.05, 1.0, 2.0e-8
    r, sep = d / 2, d / 2 + 1e-6
    assert vt > 3.5 * mu * (1 + e) * vn                     # gross sliding throughout
    y0 = vt * (sep - r) / vn                                # line of centres along x at touch
    law = pair_lines(style, E, nu, mu)
    out = run_ok(two_sphere_deck(law, d, rho, (-sep, -y0, 0), (sep, y0, 0), (vn, vt, 0),
                                 (-vn, -vt, 0), dt=dt, steps=8000, every=1000), tmp_path)
    s = final_state(out)
    dvt = mu * (1 + e) * vn
    errors = {"v1x": rel(s["v1"][0], -e * vn), "v1y": rel(s["v1"][1], vt - dvt),
              "v2x": rel(s["v2"][0], e * vn), "v2y": rel(s["v2"][1], -(vt - dvt)),
              "w1z": rel(s["w1"][2], -2.5 * dvt / r), "w2z": rel(s["w2"][2], -2.5 * dvt / r)}
    record("oblique_impact_pair", style, **errors)
    # the contact normal turns by 2 vt t_c / d = 7e-4 rad during the impact (t_c = 33 us), so
    # x and y are the normal and tangential directions to 7e-4 vt/vn = 3.5e-3 in v_x
    assert max(errors.values()) < 5e-3


# ---- momentum_conservation: an off-centre frictional impact --------------------------------

@pytest.mark.parametrize("style", STYLES)
def test_off_centre_impact_conserves_linear_and_angular_momentum(tmp_path, style):
    d, rho, E, nu, mu, vx, dt = 0.005, 2700.0, 7.0e10, 0.33, 0.4, 1.0, 2.0e-8
    p1 = (-0.00488, 0.0012, 0.0004)            # off centre in y and z, 41 um from touching
    assert math.dist(p1, (0, 0, 0)) > d
    law = pair_lines(style, E, nu, mu)
    out = run_ok(two_sphere_deck(law, d, rho, p1, (0, 0, 0), (vx, 0, 0), (0, 0, 0), dt=dt,
                                 steps=4000, every=100), tmp_path)
    s = final_state(out)
    touched = abs(s["v2"][0]) > 0.1 * vx
    assert touched
    inertia = [0.4 * m * (d / 2) ** 2 for m in (s["m1"], s["m2"])]
    P = [s["m1"] * s["v1"][k] + s["m2"] * s["v2"][k] for k in range(3)]

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    L = [s["m1"] * c1 + s["m2"] * c2 + inertia[0] * w1 + inertia[1] * w2
         for c1, c2, w1, w2 in zip(cross(s["x1"], s["v1"]), cross(s["x2"], s["v2"]),
                                   s["w1"], s["w2"])]
    m1 = s["m1"]
    P0 = [m1 * vx, 0.0, 0.0]
    L0 = cross([m1 * c for c in p1], [vx, 0.0, 0.0])
    p_scale, l_scale = m1 * vx, m1 * vx * math.hypot(p1[1], p1[2])
    dP = max(abs(a - b) for a, b in zip(P, P0)) / p_scale
    dL = max(abs(a - b) for a, b in zip(L, L0)) / l_scale
    spin = max(abs(w) for w in s["w1"] + s["w2"])
    record("momentum_conservation", style, P=dP, L=dL)
    assert spin > 1.0                                       # friction did act
    assert dP < 1e-12
    assert dL < 1e-10


# ---- pulloff_jkr ------------------------------------------------------------------------------

@pytest.mark.parametrize("style", STYLES)
def test_jkr_force_at_zero_overlap_is_eight_ninths_of_pull_off(tmp_path, style):
    d, rho, E, nu, Gamma = 0.001, 2650.0, 70e9, 0.3, 0.5
    overlap = 1e-12 * d                                     # touching: delta -> 0+
    law = pair_lines(style, E, nu, 0.3, Gamma=Gamma)
    out = run_ok(two_sphere_deck(law, d, rho, (0, 0, 0), (d - overlap, 0, 0), (0, 0, 0),
                                 (0, 0, 0), dt=1e-9, steps=0), tmp_path)
    s = final_state(out)
    R_star = d / 4
    expected = 8 / 3 * math.pi * Gamma * R_star             # (8/9) 3 pi Gamma R*
    force = s["f1"][0]                                      # on sphere 1, towards sphere 2
    record("pulloff_jkr", style, F=rel(force, expected))
    assert force == pytest.approx(expected, rel=1e-6)


def teardown_module(module):
    if RESULTS:
        print("\nDEM verification, relative errors against the closed forms:")
        for case, by_style in RESULTS.items():
            for style, errors in by_style.items():
                print(f"  {case:34s} {style:13s} " +
                      "  ".join(f"{k} {v:.2e}" for k, v in errors.items()))
