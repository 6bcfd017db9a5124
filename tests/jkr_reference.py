"""Independent reference formulas (docs/theory.md §0–§3) in numpy, for the LAMMPS-level tests.

Written from the equations, not from plugin/core: the JKR contact radius is found by
bisection on delta(a), not by the closed form the plugin uses.
"""
import math

import numpy as np


def effective_modulus(E1, nu1, E2=None, nu2=None):
    E2 = E1 if E2 is None else E2
    nu2 = nu1 if nu2 is None else nu2
    return 1.0 / ((1 - nu1**2) / E1 + (1 - nu2**2) / E2)


def effective_shear_modulus(E1, nu1, E2=None, nu2=None):
    E2 = E1 if E2 is None else E2
    nu2 = nu1 if nu2 is None else nu2
    G1, G2 = E1 / (2 * (1 + nu1)), E2 / (2 * (1 + nu2))
    return 1.0 / ((2 - nu1) / G1 + (2 - nu2) / G2)


def pull_off_force(Gamma, R):
    return 3 * math.pi * Gamma * R


def zero_load_radius(Gamma, R, E):
    return (9 * math.pi * Gamma * R**2 / E) ** (1 / 3)


def overlap_of_radius(a, R, E, Gamma):
    return a**2 / R - 2 * np.sqrt(np.pi * Gamma * a / E)


def force_of_radius(a, R, E, Gamma):
    return 4 * E * a**3 / (3 * R) - 4 * np.sqrt(np.pi * Gamma * E * a**3)


def break_overlap(R, E, Gamma):
    return -(27 * math.pi**2 * Gamma**2 * R / (16 * E**2)) ** (1 / 3)


def contact_radius(delta, R, E, Gamma):
    """Stable-branch root of delta(a) by bisection on [a_f, a_hi] (delta(a) increases there)."""
    if Gamma == 0:
        return math.sqrt(R * max(delta, 0.0))
    a_f = zero_load_radius(Gamma, R, E) * 6 ** (-2 / 3)
    lo, hi = a_f, max(2 * a_f, math.sqrt(R * abs(delta)) * 2 + 10 * a_f)
    while overlap_of_radius(hi, R, E, Gamma) < delta:
        hi *= 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if overlap_of_radius(mid, R, E, Gamma) < delta:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def normal_force(delta, R, E, Gamma):
    return force_of_radius(contact_radius(delta, R, E, Gamma), R, E, Gamma)


def separation_work(R, E, Gamma, n=20001):
    """W = integral of -P d(delta) from delta_f to 0 (docs/theory.md §3.2), by quadrature."""
    d = np.linspace(break_overlap(R, E, Gamma), 0.0, n)
    P = np.array([normal_force(x, R, E, Gamma) for x in d])
    return -np.trapz(P, d)


def sticking_velocity(R, E, Gamma, m_star):
    return math.sqrt(2 * separation_work(R, E, Gamma) / m_star)


def hertz_impact(m_star, E, R, V):
    """Elastic Hertz impact (docs/theory.md §3.1): delta_max, P_max, contact time."""
    delta_max = (15 * m_star * V**2 / (16 * E * math.sqrt(R))) ** 0.4
    P_max = 4 / 3 * E * math.sqrt(R) * delta_max**1.5
    return delta_max, P_max, 2.9432 * delta_max / V
