"""Numerical stability on hard cases (issue: speed against error). Each case either runs with
bounded energy and no NaN, or stops with a clear error that says what to change."""
import math

import numpy as np
import pytest

from cellspec import read_csv, restart_deck
from lmprun import read_table, run_deck, run_ok
from test_cell_servo import specimen  # noqa: F401  (session fixture: the dense specimen)
from test_pair_impacts import impact_deck

E, NU, RHO = 70e9, 0.3, 2650.0


def rayleigh_time(R, E=E, nu=NU, rho=RHO):
    # docs/theory.md §4.1
    G = E / (2 * (1 + nu))
    return math.pi * R * math.sqrt(rho / G) / (0.1631 * nu + 0.8766)


def test_fast_impact_with_a_large_overlap_stops_with_a_clear_error(tmp_path):
    R = 1e-4
    # 0.5 Rayleigh step and 4000 m/s: the spheres pass two radii into each other per step
    deck = impact_deck(R, R, E, NU, E, NU, RHO, RHO, 0.3, 0.0, (2000.0, 0, 0), (-2000.0, 0, 0),
                       0.5 * rayleigh_time(R), 200)
    rc, out = run_deck(deck, tmp_path)
    assert rc != 0
    assert "exceeds the radius of the smaller sphere" in out and "reduce the timestep" in out


@pytest.mark.parametrize("speed", [1.0, 30.0])
def test_size_ratio_ten_impact_conserves_energy(tmp_path, speed):
    """Elastic frictionless Hertz impact of spheres with radii R and 10 R, the timestep set by
    the small one: kinetic energy after the impact equals that before (no damping, Gamma = 0)."""
    R = 1e-4
    m1, m2 = RHO * 4 / 3 * math.pi * R ** 3, RHO * 4 / 3 * math.pi * (10 * R) ** 3
    v1 = speed * m2 / (m1 + m2)
    v2 = -speed * m1 / (m1 + m2)
    # contact duration (Hertz) ~ 2.87 (m*^2/(R* E*^2 v))^(1/5)
    m_star, R_star = m1 * m2 / (m1 + m2), R * 10 * R / (11 * R)
    E_star = E / (2 * (1 - NU ** 2))
    t_c = 2.87 * (m_star ** 2 / (R_star * E_star ** 2 * speed)) ** 0.2
    dt = 0.2 * rayleigh_time(R)
    steps = int(3 * t_c / dt) + 200
    run_ok(impact_deck(R, 10 * R, E, NU, E, NU, RHO, RHO, 0.0, 0.0, (v1, 0, 0), (v2, 0, 0),
                       dt, steps, gap=1e-3 * R), tmp_path)
    t = read_table(tmp_path / "out.txt")
    assert np.all(np.isfinite(t["ke"]))
    ke0 = 0.5 * (m1 * v1 ** 2 + m2 * v2 ** 2)
    # bounded: the explicit step's energy error during contact stays O(dt^2) small
    assert np.max(t["ke"]) <= ke0 * (1 + 1e-3)
    assert t["d"][-1] < 0.0                               # separated again
    assert t["ke"][-1] == pytest.approx(ke0, rel=2e-3)    # elastic: all returned
    assert t["vx1"][-1] == pytest.approx(-v1, rel=1e-2)   # head-on elastic: velocities reverse


def test_timestep_near_the_stability_limit_warns_what_to_change(tmp_path):
    R = 1e-4
    deck = impact_deck(R, R, E, NU, E, NU, RHO, RHO, 0.3, 0.6, (0.1, 0, 0), (-0.1, 0, 0),
                       0.6 * rayleigh_time(R), 10)
    out = run_ok(deck, tmp_path)
    assert "exceeds" in out and "Rayleigh time" in out and "reduce" in out.lower()


def test_strong_adhesion_at_low_stress(specimen, tmp_path):
    """The dense specimen (216 spheres, 100 kPa) given Gamma = 5 J/m^2 and unloaded to
    p = 1 kPa: adhesion (Pc = 3 pi Gamma R* ~ 1.2e-3 N) dwarfs the contact force that 1 kPa needs
    (~5e-5 N); the servo must still reach the target and nothing may blow up."""
    deck = restart_deck(specimen, mu=0.3, gamma=5.0) + """fix damp all damping/cundall 0.3 0.3
fix cell all cell/servo iso 1e3 csv cell.csv 100
run 20000
"""
    run_ok(deck, tmp_path)
    rows = read_csv(tmp_path / "cell.csv")
    assert all(np.all(np.isfinite(v)) for k, v in rows.items() if k not in ("b", "lode_deg", "eta_LD", "sinphi", "unbalanced", "inertial_number"))
    late = rows["step"] > rows["step"][0] + 15000
    print(f"strong adhesion: p {rows['p'][late].min():.1f}..{rows['p'][late].max():.1f} Pa, "
          f"p_kinetic {rows['p_kinetic'][late].max():.3g} Pa, Z {rows['Z'][-1]:.2f}")
    assert np.max(np.abs(rows["p"][late] / 1e3 - 1.0)) < 0.05
    assert np.max(rows["p_kinetic"][late]) < 0.01 * 1e3
    assert rows["Z"][-1] > 4.0     # the adhesive network holds together
