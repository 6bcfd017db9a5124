"""The oblique impact of an elastic sphere on an elastic half-space of the same material,
computed in time with the oracle of tests/mdr_oracle.py: the classical elastic-frictional
theory of Maw, Barber & Fawcett (1976), "The oblique impact of elastic spheres", Wear 38,
101-114 (docs/theory.md §3.6).

Written from the mechanics, not from plugin/core: a sphere of radius R, mass m and moment of
inertia I = (2/5) m R^2 meets the half-space with normal speed V_n, tangential speed V_t and no
spin. The contact is the method of dimensionality reduction's spring row (HertzMDR): the
normal force from its springs is Hertz, the tangential force from its springs is exact
Mindlin-Deresiewicz for this collinear history (the impact stays in one plane). The motion is
integrated by velocity Verlet, as LAMMPS's fix nve/sphere does:

    m dV_n/dt = -P(delta),  m dv_t/dt = -T,  I d(omega)/dt = l T,
    d(delta)/dt = V_n,      ds/dt = v_t - l omega,

omega the spin in the rolling sense (the sense friction drives), s the tangential displacement
of the contact point, l its lever arm: R (the classical theory) or R - delta/2 (the distance
from the centre to the contact plane, what pair thornton/yin uses, docs/theory.md §2.3).

Outputs (docs/theory.md §3.6), with k = 4G*/E* (= 2(1 - nu)/(2 - nu) for like materials) and
V_s = v_t - R omega the tangential velocity of the contact point:
    e_n = -V_n'/V_n, e_t = V_s'/V_s, Psi1 = k V_s/(mu V_n), Psi2 = k V_s'/(mu V_n),
    Omega = k R omega'/(mu V_n).
An impact of two equal spheres maps onto this one with the relative velocities, the pair's
E*, G*, R*, the effective mass and R(omega1 + omega2) for R omega; the bench and the tests use
the sphere on a half-space, Maw et al.'s configuration.
"""
import math

import numpy as np

from mdr_oracle import HertzMDR


class Material:
    """A sphere of radius R against an elastic half-space (a sphere of radius R_other, or None
    for a plane) of the same material E, nu, density rho, friction mu."""

    def __init__(self, R, E, nu, rho, mu, R_other=None):
        self.R, self.E, self.nu, self.rho, self.mu = R, E, nu, rho, mu
        self.R_star = R if R_other is None else R * R_other / (R + R_other)
        self.E_star = E / (2 * (1 - nu**2))
        self.G_star = E / (2 * (1 + nu)) / (2 * (2 - nu))
        self.m = rho * 4 / 3 * math.pi * R**3
        self.I = 0.4 * self.m * R**2
        self.k = 4 * self.G_star / self.E_star              # 2(1 - nu)/(2 - nu)
        self.K = 4 / 3 * self.E_star * math.sqrt(self.R_star)   # P = K delta^(3/2)

    def hertz(self, V_n):
        """delta_max and contact time of the elastic head-on impact at V_n (docs/theory.md §3.1)"""
        delta_max = (15 * self.m * V_n**2 / (16 * self.E_star * math.sqrt(self.R_star))) ** 0.4
        return delta_max, 2.9432 * delta_max / V_n

    def psi(self, V_s, V_n):
        return self.k * V_s / (self.mu * V_n)

    def incidence_for_psi(self, psi1):
        """the impact angle (rad, from the normal) of Psi1 for a sphere without spin"""
        return math.atan(psi1 * self.mu / self.k)


def impact(mat, V, theta, steps=2000, springs=20000, lever="pair", record=False):
    """One impact at speed V and angle theta (rad, from the normal), no initial spin.
    steps: time steps per Hertz contact time of V_n; springs: the oracle's resolution.
    lever: "pair" (R - delta/2) or "rigid" (R)."""
    V_n, V_t = V * math.cos(theta), V * math.sin(theta)
    delta_max, t_c = mat.hertz(V_n)
    dt = t_c / steps
    contact = HertzMDR(mat.R_star, mat.E_star, mat.G_star, mat.mu, 1.03 * delta_max,
                       springs=springs)
    m, I, R = mat.m, mat.I, mat.R

    def arm(delta):
        return R - 0.5 * max(delta, 0.0) if lever == "pair" else R

    def kick(vn, vt, w, P, T, delta):
        """half a step of the forces: velocities and spin"""
        return (vn - 0.5 * dt * P / m, vt - 0.5 * dt * T / m, w + 0.5 * dt * arm(delta) * T / I)

    delta, s = 0.0, 0.0
    vn, vt, w = V_n, V_t, 0.0
    P, T = 0.0, 0.0
    trace = []
    for _ in range(50 * steps):
        vn, vt, w = kick(vn, vt, w, P, T, delta)          # velocity Verlet: half kick,
        delta = delta + dt * vn                            # drift,
        s = s + dt * (vt - arm(delta) * w)
        P, T = contact.step(delta, s)                      # force,
        vn, vt, w = kick(vn, vt, w, P, T, delta)          # half kick
        if record:
            trace.append((delta, s, P, T, vn, vt, w))
        if delta < 0.0:
            break
    else:
        raise RuntimeError("the sphere did not leave the half-space")
    V_s, V_s_out = V_t, vt - R * w
    out = {
        "theta": theta, "V_n": V_n, "V_t": V_t,
        "e_n": -vn / V_n, "e_t": V_s_out / V_s if V_s else None,
        "psi1": mat.psi(V_s, V_n), "psi2": mat.psi(V_s_out, V_n),
        "Omega": mat.k * R * w / (mat.mu * V_n),
        "v_t": vt, "omega": w, "V_n_out": -vn,
        "dissipation": contact.dissipation,
        "kinetic_in": 0.5 * m * (V_n**2 + V_t**2),
        "kinetic_out": 0.5 * m * (vn**2 + vt**2) + 0.5 * I * w**2,
    }
    if record:
        out["trace"] = np.array(trace)
    return out


def sliding(mat, psi1, e_n=1.0):
    """Rigid-body gross sliding throughout the impact (docs/theory.md §3.4, §3.6): the tangential
    impulse is mu times the normal one, so V_s drops by (1 + m R^2/I) mu (1 + e_n) V_n:
    Psi2 = Psi1 - k (1 + mR^2/I)(1 + e_n), Omega = k (mR^2/I)(1 + e_n)."""
    g = mat.m * mat.R**2 / mat.I                              # 5/2
    return {"psi2": psi1 - mat.k * (1 + g) * (1 + e_n), "Omega": mat.k * g * (1 + e_n)}


def sliding_threshold(mat, e_n=1.0):
    """Psi1 above which the contact slides throughout an elastic impact (derived in
    docs/theory.md §3.6): Psi2 = -e_n (the slip speed reaches zero exactly at separation)."""
    g = mat.m * mat.R**2 / mat.I
    return mat.k * (1 + g) * (1 + e_n) - e_n


def no_slip_restitution(mat, n=20000):
    """e_t of the impact with no slip anywhere (mu -> infinity; the limit of the elastic theory
    as Psi1 -> 0), computed without the spring row: each annulus that enters the contact keeps
    the displacement it took since, so the tangential force is
        T(t) = 8G* int over the annuli in contact of (s(t) - s(tau)) da(tau),
    tau the time the contact radius a passed the annulus on the way in (Mindlin 1949 for each
    annulus; on the way out the annulus at radius a(t) entered at 2 t_m - t, the Hertz impact
    being symmetric in time). The contact point's mass is m/(1 + m R^2/I); the normal motion is
    Hertz's, integrated here with scipy."""
    from scipy.integrate import solve_ivp
    V_n = 1.0
    delta_max, t_c = mat.hertz(V_n)
    sol = solve_ivp(lambda t, y: [y[1], -mat.K * max(y[0], 0.0)**1.5 / mat.m], (0, 1.2 * t_c),
                    [0.0, V_n], rtol=1e-12, atol=1e-12 * delta_max, dense_output=True,
                    events=lambda t, y: y[1], max_step=t_c / 200)
    t_m = sol.t_events[0][0]                          # the deepest point, half the impact
    half = n // 2
    dt = t_m / half
    t_in = np.linspace(0.0, t_m, half + 1)            # the way in, where the annuli enter
    a = np.sqrt(mat.R_star * np.maximum(sol.sol(t_in)[0], 0.0))
    m_c = mat.m / (1 + mat.m * mat.R**2 / mat.I)
    s = np.zeros(n + 1)
    sda = np.zeros(half + 1)                          # int_0^t s da on the way in (trapezoid)
    v, force = 1.0, 0.0
    for k in range(n):
        v_h = v - 0.5 * dt * force / m_c
        s[k + 1] = s[k] + dt * v_h
        if k + 1 <= half:
            # on the way in every annulus entered since t = 0
            sda[k + 1] = sda[k] + 0.5 * (s[k] + s[k + 1]) * (a[k + 1] - a[k])
            force = 8 * mat.G_star * (s[k + 1] * a[k + 1] - sda[k + 1])
        else:
            # on the way out the annuli in contact entered before tau = 2 t_m - t
            tau = (n - (k + 1)) * dt
            j = min(int(tau / dt), half - 1)
            frac = tau / dt - j
            a_tau = a[j] + frac * (a[j + 1] - a[j])
            s_tau = s[j] + frac * (s[j + 1] - s[j])
            inside = sda[j] + 0.5 * (s[j] + s_tau) * (a_tau - a[j])
            force = 8 * mat.G_star * (s[k + 1] * a_tau - inside)
        v = v_h - 0.5 * dt * force / m_c
    return v
