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
    """Work per unit volume [J/m3] of each complete cycle, numbered as inputs/cyclic.in numbers
    them: cycle k runs from -A (where cycle k - 1 ended; the first from 0) to +A and back to -A,
    so the complete loops are cycles 2, 3, ...: from one turn at -A to the next (the record's
    last row is the last turn when the test ends in extension, as the deck ends it). Each
    work is (2/3) the loop area of the signed deviator against eps1 - eps3 plus the integral of
    p deps_v. Returns {cycle number: work}."""
    d = derived(table)
    sign = np.sign(table["rate1"])
    ends = [int(t) for t in reversals(table) if sign[t] < 0]
    moving = np.flatnonzero(sign != 0)
    if len(moving) and sign[moving[-1]] < 0 and (not ends or ends[-1] != len(sign) - 1):
        ends.append(len(sign) - 1)
    works = {}
    for k, (a, b) in enumerate(zip(ends[:-1], ends[1:])):
        seg = slice(a, b + 1)
        deviatoric = np.trapz(d["dev_stress"][seg], d["eps_d13"][seg])
        volumetric = np.trapz(d["p"][seg], d["eps_v"][seg])
        works[k + 2] = 2.0 / 3.0 * deviatoric + volumetric
    return works
