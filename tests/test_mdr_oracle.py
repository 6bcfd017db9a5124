"""The oracle of the tangential law (tests/mdr_oracle.py, the method of dimensionality
reduction) against the closed forms it must reproduce before it may judge the law:
Hertz's normal force, Mindlin & Deresiewicz's (1953) loading curve at constant normal load
and its Masing unloading branch (docs/theory.md §2.1), and the no-slip return of a
proportional oblique loading below mu (§2.5), with the frictional work of a closed loop
equal to the loop's area."""
import numpy as np
import pytest

from mdr_oracle import HertzMDR, hertz_overlap

E, NU, R, MU = 70e9, 0.3, 5e-5, 0.3
E_STAR = E / (2 * (1 - NU**2))
G_STAR = E / (2 * (1 + NU)) / (2 * (2 - NU))
P0 = 1e-2
D0 = hertz_overlap(P0, R, E_STAR)
A0 = np.sqrt(R * D0)
S_SLIDE = 3 * MU * P0 / (16 * G_STAR * A0)       # Mindlin's sliding displacement


def virgin(s):
    """Mindlin & Deresiewicz at constant P: T = mu P [1 - (1 - 16 G* a s/(3 mu P))^(3/2)]."""
    return MU * P0 * (1 - (1 - s / S_SLIDE) ** 1.5)


def loaded_contact(steps=200):
    c = HertzMDR(R, E_STAR, G_STAR, MU, D0)
    for d in np.linspace(0, D0, steps + 1)[1:]:
        P, T = c.step(d, 0.0)
    return c, P


def test_normal_force_is_hertz():
    c, P = loaded_contact()
    assert P == pytest.approx(P0, rel=1e-6)


def test_loading_unloading_and_loop_energy_follow_mindlin_deresiewicz():
    c, _ = loaded_contact()
    reversal = 0.9 * S_SLIDE
    loading = np.linspace(0, reversal, 301)[1:]
    T_load = np.array([c.step(D0, s)[1] for s in loading])
    assert np.max(np.abs(T_load - virgin(loading))) < 1e-6 * MU * P0
    T_star = T_load[-1]
    back = np.linspace(reversal, -reversal, 601)[1:]
    T_back = np.array([c.step(D0, s)[1] for s in back])
    masing = T_star - 2 * virgin((reversal - back) / 2)      # Masing: the virgin curve doubled
    assert np.max(np.abs(T_back - masing)) < 1e-6 * MU * P0
    assert T_back[-1] == pytest.approx(-T_star, abs=1e-6 * MU * P0)
    stored, lost_before = c.stored_energy(), c.dissipation
    forward = np.linspace(-reversal, reversal, 601)[1:]
    T_fwd = np.array([c.step(D0, s)[1] for s in forward])
    assert T_fwd[-1] == pytest.approx(T_star, abs=1e-6 * MU * P0)
    # a closed loop from the lower reversal back to it is not needed: from T* down and up again
    # the state returns, so the work done over the loop is the frictional loss the springs
    # booked (summed slip by slip) and the stored energy is where it started
    back2 = np.linspace(reversal, -reversal, 601)[1:]
    T_back2 = np.array([c.step(D0, s)[1] for s in back2])
    assert c.stored_energy() == pytest.approx(stored, rel=1e-6)
    s_loop = np.r_[-reversal, forward, back2]
    T_loop = np.r_[T_back[-1], T_fwd, T_back2]
    work = np.sum(0.5 * (T_loop[1:] + T_loop[:-1]) * np.diff(s_loop))
    assert work > 0
    assert c.dissipation - lost_before == pytest.approx(work, rel=1e-3)


def test_proportional_loading_below_mu_returns_elastically():
    c = HertzMDR(R, E_STAR, G_STAR, MU, D0)
    k = 0.2                                           # ds/d(delta): dT/dP = (4G*/E*) k < mu
    for d in np.linspace(0, D0, 401)[1:]:
        P, T = c.step(d, k * d)
    ratio = 4 * G_STAR / E_STAR * k
    assert T / P == pytest.approx(ratio, rel=1e-9)
    for d in np.linspace(D0, 0.4 * D0, 401)[1:]:
        P, T = c.step(d, k * d)
    assert T / P == pytest.approx(ratio, rel=1e-9)
    assert c.dissipation == 0.0
