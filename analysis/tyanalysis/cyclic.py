"""Cyclic axisymmetric records (inputs/cyclic.in): reversals and the work of each cycle.

In an axisymmetric state (axis 1 loaded, sigma2 = sigma3) the work per unit volume is
dW = sigma1 deps1 + 2 sigma3 deps3 = p deps_v + (2/3)(sigma1 - sigma3) d(eps1 - eps3), so the
work of a closed cycle is (2/3) of the area of the loop of sigma1 - sigma3 against eps1 - eps3,
plus the loop integral of p deps_v (p Delta eps_v at constant p).
"""
import numpy as np

from .metrics import derived


def reversals(table):
    """Row indices where the axial strain rate (rate1) changes sign: the last row of each
    half cycle."""
    sign = np.sign(table["rate1"])
    moving = np.flatnonzero(sign != 0)
    turns = moving[:-1][np.diff(sign[moving]) != 0]
    return turns


def cycle_work(table):
    """Work per unit volume [J/m3] of each complete cycle between every other reversal
    (from one reversal to the next reversal of the same sign): (2/3) the loop area of the
    signed deviator against eps1 - eps3 plus the integral of p deps_v."""
    d = derived(table)
    turns = reversals(table)
    works = []
    for a, b in zip(turns[:-2], turns[2:]):
        seg = slice(a, b + 1)
        deviatoric = np.trapz(d["dev_stress"][seg], d["eps_d13"][seg])
        volumetric = np.trapz(d["p"][seg], d["eps_v"][seg])
        works.append(2.0 / 3.0 * deviatoric + volumetric)
    return np.array(works[::2]) if len(works) else np.array([])
