"""Which material an unlike contact gets (explicit pair_coeff I J, a `* *` line, or mixing),
and fix adapt of mu and Gamma during a run: forces of a two-sphere contact against the Hertz,
JKR and sliding-limit closed forms (docs/theory.md §1-2)."""
import numpy as np
import pytest

from cellspec import bisect
from lmprun import LOAD_TYLMP, reduce_local, run_ok

R = 1e-4                 # both spheres
DELTA = 1e-6             # overlap
R_STAR = R / 2


def e_star(E1, nu1, E2, nu2):
    return 1.0 / ((1 - nu1 ** 2) / E1 + (1 - nu2 ** 2) / E2)


def hertz(Es, delta=DELTA):
    return 4.0 / 3.0 * Es * np.sqrt(R_STAR) * delta ** 1.5


def jkr_force(Es, gamma, delta=DELTA):
    # stable branch of delta = a^2/R* - 2 sqrt(pi Gamma a/E*), then P(a)
    a = bisect(lambda a: a * a / R_STAR - 2 * np.sqrt(np.pi * gamma * a / Es) - delta,
               1e-9, 1e-4)
    return 4 * Es * a ** 3 / (3 * R_STAR) - 4 * np.sqrt(np.pi * gamma * Es * a ** 3)


def two_spheres(coeffs, extra="", run="run 0", vy=0.0):
    """sphere 1 of type 1 and sphere 2 of type 2 at overlap DELTA; prints the contact's P and
    |T| and sliding flag from compute thornton/yin/contacts after `run`"""
    return f"""units si
atom_style sphere
atom_modify map array
boundary p p p
comm_modify vel yes
region box block 0 1e-3 0 1e-3 0 1e-3
create_box 2 box
create_atoms 1 single 4e-4 5e-4 5e-4
create_atoms 2 single {4e-4 + 2 * R - DELTA} 5e-4 5e-4
set atom * diameter {2 * R} density 2650
velocity all set 0 0 0
set atom 2 vy {vy}
{LOAD_TYLMP}pair_style thornton/yin
{coeffs}
neighbor 1e-5 bin
timestep 1e-9
fix hold all setforce 0 0 0
fix nve all nve/sphere
compute c all thornton/yin/contacts
{reduce_local("P", "c_c[12]")}{reduce_local("Tsq", "c_c[6]", "c_c[7]", "c_c[8]")}{reduce_local("sl", "c_c[15]")}{extra}
thermo_style custom step c_P c_sl c_Tsq[1] c_Tsq[2] c_Tsq[3]
thermo_modify format float %.16g
{run}
print "FORCE $(c_P:%.16g) $(c_sl) $(sqrt(c_Tsq[1]^2+c_Tsq[2]^2+c_Tsq[3]^2):%.16g)"
"""


def force_of(out):
    line = [l for l in out.splitlines() if l.startswith("FORCE ")][-1]
    return tuple(map(float, line.split()[1:]))


GLASS, STEEL = (70e9, 0.3), (200e9, 0.29)


@pytest.mark.parametrize("coeffs, expected_E_star", [
    # only like types given: 1-2 is mixed from both materials
    ("pair_coeff 1 1 70e9 0.3 0.3 0.0\npair_coeff 2 2 200e9 0.29 0.3 0.0",
     e_star(*GLASS, *STEEL)),
    # a '* *' line first sets 1-2 explicitly (as in every LAMMPS pair style): the later
    # '2 2' line does not make 1-2 mixed, it stays the '* *' material
    ("pair_coeff * * 70e9 0.3 0.3 0.0\npair_coeff 2 2 200e9 0.29 0.3 0.0",
     e_star(*GLASS, *GLASS)),
    # re-issuing the same pair_style keeps the '* *' coefficients; 'pair_style none' first
    # starts afresh and 1-2 is mixed (the mixing example of docs/pair_thornton_yin.md)
    ("pair_coeff * * 70e9 0.3 0.3 0.0\npair_style thornton/yin\n"
     "pair_coeff 2 2 200e9 0.29 0.3 0.0", e_star(*GLASS, *GLASS)),
    ("pair_coeff * * 70e9 0.3 0.3 0.0\npair_style none\npair_style thornton/yin\n"
     "pair_coeff 1 1 70e9 0.3 0.3 0.0\npair_coeff 2 2 200e9 0.29 0.3 0.0",
     e_star(*GLASS, *STEEL)),
    # an explicit I J line: both spheres of the given material
    ("pair_coeff 1 1 70e9 0.3 0.3 0.0\npair_coeff 2 2 200e9 0.29 0.3 0.0\n"
     "pair_coeff 1 2 200e9 0.29 0.3 0.0", e_star(*STEEL, *STEEL)),
])
def test_unlike_contact_material(coeffs, expected_E_star, tmp_path):
    P, _, _ = force_of(run_ok(two_spheres(coeffs), tmp_path))
    assert P == pytest.approx(hertz(expected_E_star), rel=1e-12)


def test_fix_adapt_gamma_changes_the_jkr_force(tmp_path):
    # Gamma 0 -> 0.3 J/m^2 by fix adapt: the contact's force follows JKR at the same overlap
    Es = e_star(*GLASS, *GLASS)
    out = run_ok(two_spheres("pair_coeff * * 70e9 0.3 0.3 0.0",
                             "variable g equal 0.3\n"
                             "fix adapt all adapt 1 pair thornton/yin Gamma * * v_g", "run 1"),
                 tmp_path)
    P, _, _ = force_of(out)
    assert P == pytest.approx(jkr_force(Es, 0.3), rel=1e-9)
    assert P < hertz(Es)


def test_fix_adapt_mu_sets_the_sliding_limit(tmp_path):
    # sphere 2 moves tangentially at 1 m/s (20 nm in 20 steps); with mu adapted to 1e-4 the contact slides at
    # once and |T| = mu P (Gamma = 0)
    Es = e_star(*GLASS, *GLASS)
    out = run_ok(two_spheres("pair_coeff * * 70e9 0.3 0.3 0.0",
                             "variable m equal 1e-4\n"
                             "fix adapt all adapt 1 pair thornton/yin mu * * v_m", "run 20",
                             vy=1.0), tmp_path)
    P, sliding, T = force_of(out)
    # after 20 steps of 1 ns at 1 m/s (forces held at 0) the centres are 20 nm apart sideways
    delta = 2 * R - np.hypot(2 * R - DELTA, 20 * 1e-9 * 1.0)
    assert P == pytest.approx(hertz(Es, delta), rel=1e-9)
    assert sliding == 1.0
    assert T == pytest.approx(1e-4 * P, rel=1e-9)
    # without fix adapt (mu = 0.3) the same motion stays in micro-slip, well below mu P
    P0, sliding0, T0 = force_of(run_ok(two_spheres("pair_coeff * * 70e9 0.3 0.3 0.0",
                                                   run="run 20", vy=1.0), tmp_path))
    assert sliding0 == 0.0 and 1e-4 * P0 < T0 < 0.3 * P0


def g_star(E1, nu1, E2, nu2):
    # Mindlin (1949): 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2, G = E/(2(1 + nu)) (docs/theory.md §0)
    G1, G2 = E1 / (2 * (1 + nu1)), E2 / (2 * (1 + nu2))
    return 1.0 / ((2 - nu1) / G1 + (2 - nu2) / G2)


def test_unlike_contact_tangential_stiffness_is_8_G_star_a(tmp_path):
    # Glass on steel, mixed, against glass on glass and steel on steel: sphere 2 moves sideways
    # at 1 mm/s for one step of 1 ns. The spheres overlap before the run: the contact is pressed
    # without tangential displacement (docs/theory.md §1.3), so the step of ds = 1 pm is
    # Mindlin-Deresiewicz's first loading at constant P (§2.1), T = mu P [1 - (1 - ds/s_c)^(3/2)]
    # with s_c = 3 mu P/(16 G* a), a = sqrt(R* delta) at Gamma = 0: the initial stiffness 8 G* a
    # less the curve's bend over the step, a relative ds/(4 s_c) = 7e-7 (so the tangent
    # 8 G* a ds alone would not meet rel 1e-9; a law without the bend, Thornton's increment
    # with theta = 1, would be that far off). P is the Hertz force (asserted to rel 1e-9).
    # One step only: over more steps the tangential force spins the spheres (setforce holds
    # forces, not torques), which takes a material-dependent share of ds.
    a = np.sqrt(R_STAR * DELTA)
    ds, mu = 1e-3 * 1e-9, 0.3
    for name, coeffs, materials in (
            ("unlike", "pair_coeff 1 1 70e9 0.3 0.3 0.0\npair_coeff 2 2 200e9 0.29 0.3 0.0",
             GLASS + STEEL),
            ("glass", "pair_coeff * * 70e9 0.3 0.3 0.0", GLASS + GLASS),
            ("steel", "pair_coeff * * 200e9 0.29 0.3 0.0", STEEL + STEEL)):
        (tmp_path / name).mkdir()
        P, sliding, T = force_of(run_ok(two_spheres(coeffs, run="run 1", vy=1e-3), tmp_path / name))
        assert sliding == 0.0
        assert P == pytest.approx(hertz(e_star(*materials)), rel=1e-9)
        P_hertz, G = hertz(e_star(*materials)), g_star(*materials)
        s_c = 3 * mu * P_hertz / (16 * G * a)
        first_loading = -mu * P_hertz * np.expm1(1.5 * np.log1p(-ds / s_c))    # no cancellation
        assert T == pytest.approx(first_loading, rel=1e-9), name
        assert T == pytest.approx(8 * G * a * ds, rel=2e-6), name       # the bend: 7e-7
