#!/usr/bin/env python3
"""Two spheres held at a fixed overlap and sheared through a tangential hysteresis loop with
pair thornton/yin and with LAMMPS's `pair granular ... tangential mindlin`, against the closed
forms of docs/theory.md §2 (docs/comparison.md, "Tangential loop of two spheres").

    /usr/bin/python3 bench/compare_tangential.py [--out docs/comparison_tangential.png]
        [--steps-per-slide 4000] [--keep DIR]

Two equal glass-like spheres (R = 0.1 mm, R* = 0.05 mm, E = 70 GPa, nu = 0.3, mu = 0.3).
Sphere 1 is held at the origin; sphere 2 is moved by `fix move variable` on a circle about
sphere 1 (centre distance 2R - delta held exactly, so P is constant) through the arc length
s = 0 -> +A -> -A -> +A, A = 2 x the Mindlin-Deresiewicz slip distance 3 mu P_eff/(16 G* a_T).
Neither sphere spins (fix move leaves omega = 0), so s is the tangential displacement of the
contact in both styles. Cases:
  (a) Gamma = 0,   delta = 100 nm: thornton/yin vs granular hertz/material + mindlin
  (b) Gamma = 0.6, delta = 30 nm  (P ~ 6 Pc, sliding during peeling): vs granular jkr + mindlin
  (c) Gamma = 0.6, delta = 200 nm (P ~ 114 Pc, peeling ends at T_c before sliding): the same
Prints the measured initial stiffnesses, sliding forces, end of peeling and the largest
deviations from the closed forms; writes the figure.
"""
import argparse
import math
import os
import shutil
import subprocess
import sys
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
from tylmp.analysis.figures import save_figure  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pair_speed import LOAD  # noqa: E402  (the two lines that load the plugin's styles)

E, NU, MU, RHO = 70e9, 0.3, 0.3, 2650.0
R = 1.0e-4                                   # sphere radius; R* = R/2
R_STAR = R / 2
E_STAR = 1.0 / (2 * (1 - NU ** 2) / E)
G = E / (2 * (1 + NU))
G_STAR = 1.0 / (2 * (2 - NU) / G)

CASES = [   # (key, title, Gamma, delta)
    ("a", "(a) Γ = 0, δ = 100 nm", 0.0, 100e-9),
    ("b", "(b) Γ = 0.6 J/m², δ = 30 nm", 0.6, 30e-9),
    ("c", "(c) Γ = 0.6 J/m², δ = 200 nm", 0.6, 200e-9),
]


# ---------------------------------------------------------------- closed forms (docs/theory.md)
def jkr_radius(delta, Gamma):
    """Stable-branch JKR contact radius for overlap delta (docs/theory.md §1.1), by bisection."""
    if Gamma == 0:
        return math.sqrt(R_STAR * delta)
    f = lambda a: a * a / R_STAR - 2 * math.sqrt(math.pi * Gamma * a / E_STAR) - delta
    a0 = (9 * math.pi * Gamma * R_STAR ** 2 / E_STAR) ** (1 / 3)
    lo, hi = a0 * 6 ** (-2 / 3), 10 * (a0 + math.sqrt(R_STAR * abs(delta)))
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return 0.5 * (lo + hi)


def jkr_force(a, Gamma):
    return 4 * E_STAR * a ** 3 / (3 * R_STAR) - 4 * math.sqrt(math.pi * Gamma * E_STAR * a ** 3)


class Contact:
    """Closed-form quantities of one case (docs/theory.md §1.1, §2.1, §2.2)."""

    def __init__(self, Gamma, delta):
        self.Gamma, self.delta = Gamma, delta
        self.a = jkr_radius(delta, Gamma)
        self.P = jkr_force(self.a, Gamma)
        self.Pc = 3 * math.pi * Gamma * R_STAR
        self.Peff = self.P + 2 * self.Pc
        self.L = MU * self.Peff                                       # sliding limit mu(P+2Pc)
        self.aT = (3 * R_STAR * self.Peff / (4 * E_STAR)) ** (1 / 3)  # micro-slip radius
        self.k0 = 8 * G_STAR * self.a                                 # initial stiffness
        self.kT = 8 * G_STAR * self.aT
        self.slip = 1.5 * self.L / self.kT          # MD slip distance 3 mu Peff/(16 G* a_T)
        self.Tc = 4 * math.sqrt(self.Pc * (self.P + self.Pc) * G_STAR / E_STAR) if Gamma else 0.0
        self._virgin()

    def _virgin(self):
        """Virgin loading curve s(T) -> tabulated T(s): Savkoor-Briggs peeling with
        dT/ds = 8G* a_peel(T), 4E*a_peel^3/(3R*) = P + 2Pc + sqrt(4PPc + 4Pc^2 - T^2 E*/(4G*)),
        until T_c (docs/theory.md §2.2, peeling), then the Mindlin-Deresiewicz loading curve for
        P + 2Pc continued from T_c (stage B), then sliding at L (stage C)."""
        L = self.L
        T_end_peel = min(self.Tc, L)
        if T_end_peel > 0:
            T = T_end_peel * (1 - np.linspace(1, 0, 200001) ** 2)   # dense near T_c
            disc = np.maximum(4 * self.P * self.Pc + 4 * self.Pc ** 2
                              - T ** 2 * E_STAR / (4 * G_STAR), 0.0)
            a_peel = (3 * R_STAR * (self.Peff + np.sqrt(disc)) / (4 * E_STAR)) ** (1 / 3)
            inv_k = 1 / (8 * G_STAR * a_peel)
            s = np.concatenate(([0.0], np.cumsum(0.5 * (inv_k[1:] + inv_k[:-1]) * np.diff(T))))
        else:
            T, s = np.array([0.0]), np.array([0.0])
        if self.Tc < L:                                  # micro-slip from T_c to L
            T2 = L - (L - T[-1]) * np.linspace(1, 0, 20001) ** 2
            s2 = s[-1] + self.slip * ((1 - T[-1] / L) ** (2 / 3) - (1 - T2 / L) ** (2 / 3))
            T, s = np.concatenate((T, T2[1:])), np.concatenate((s, s2[1:]))
        self.s_peel_end = s[np.searchsorted(T, T_end_peel)] if T_end_peel > 0 else 0.0
        self.s_slide = s[-1]
        self.virgin_s, self.virgin_T = s, T

    def virgin(self, s):
        return np.where(s >= self.s_slide, self.L, np.interp(s, self.virgin_s, self.virgin_T))

    def md(self, x):
        """Mindlin-Deresiewicz loading curve of P + 2Pc from zero (docs/theory.md §2.1)."""
        x = np.clip(x, 0, self.slip)
        return self.L * (1 - (1 - x / self.slip) ** 1.5)

    def reference(self, s, leg, A):
        """Thornton's law along the loop: virgin curve, then Masing's rule about each reversal
        (loading curve doubled in both axes, docs/theory.md §2.1); both reversals start from the
        sliding limit, so T* = L and T** = -L."""
        return np.select([leg == 0, leg == 1],
                         [self.virgin(s), self.L - 2 * self.md((A - s) / 2)],
                         -self.L + 2 * self.md((s + A) / 2))

    def linear_capped(self, s):
        """What `tangential mindlin` integrates: T += 8G*a ds, |T| <= mu |P + 2Pc| (the JKR a,
        or the Hertz a when Gamma = 0; pair_granular.cpp of LAMMPS 29Sep2021)."""
        T = np.zeros_like(s)
        for k in range(1, len(s)):
            T[k] = np.clip(T[k - 1] + self.k0 * (s[k] - s[k - 1]), -self.L, self.L)
        return T


# ---------------------------------------------------------------- LAMMPS runs
def pair_lines(style, Gamma):
    if style == "thornton/yin":
        return f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} {Gamma}\n"
    normal = f"jkr {E} 0.0 {NU} {Gamma}" if Gamma > 0 else f"hertz/material {E} 0.0 {NU}"
    return (f"pair_style granular\npair_coeff * * {normal} damping viscoelastic "
            f"tangential mindlin NULL 0.0 {MU}\n")


def deck(style, c, A, steps_per_slide):
    d0 = 2 * R - c.delta
    ds = c.slip / steps_per_slide               # arc length per step
    dt = 1e-9
    speed = ds / dt
    turns = [(0.0, 0.0), (A / speed, A), (3 * A / speed, -A), (5 * A / speed, A)]
    s_terms, v_terms = [], []
    for (t0, s0), (t1, s1) in zip(turns[:-1], turns[1:]):
        slope = (s1 - s0) / (t1 - t0)
        window = f"(step*dt>{t0!r})*(step*dt<={t1!r})"
        s_terms.append(f"({s0!r}+{slope!r}*(step*dt-{t0!r}))*{window}")
        v_terms.append(f"{slope!r}*{window}")
    nsteps = int(round(turns[-1][0] / dt))
    peel = ""
    columns = "step x2 y2 fx2 fy2"
    values = "${step} ${x2} ${y2} ${fx2} ${fy2}"
    if style == "thornton/yin":
        # LAMMPS 21 Nov 2023 and later reduce local values only when told ("inputs local")
        reduce = "compute flags all reduce max c_pl[1] c_pl[2]"
        peel = (f"compute pl all pair/local p6 p5\nif \"$(version) >= 20231121\" then "
                f"\"{reduce} inputs local\" else \"{reduce}\"\n"
                "variable peel equal c_flags[1]\nvariable slide equal c_flags[2]\n")
        columns += " peel slide"
        values += " ${peel} ${slide}"
    return f"""units si
atom_style sphere
atom_modify map array
boundary f f f
comm_modify vel yes
region box block -1e-3 1e-3 -1e-3 1e-3 -1e-3 1e-3
create_box 1 box
create_atoms 1 single 0 0 0
create_atoms 1 single {d0!r} 0 0
set atom * diameter {2 * R!r} density {RHO}
group one id 1
group two id 2
{LOAD}{pair_lines(style, c.Gamma)}neighbor 2e-6 bin
neigh_modify every 1 delay 0 check yes
timestep {dt}
# arc length s(t) of sphere 2 on the circle of radius d0 about sphere 1: 0 -> A -> -A -> A
variable s equal {'+'.join(s_terms)}
variable sd equal {'+'.join(v_terms)}
variable px equal {d0!r}*cos(v_s/{d0!r})-{d0!r}
variable py equal {d0!r}*sin(v_s/{d0!r})
variable vx equal -sin(v_s/{d0!r})*v_sd
variable vy equal cos(v_s/{d0!r})*v_sd
variable zero equal 0
fix hold one move linear 0 0 0
fix drive two move variable v_px v_py v_zero v_vx v_vy v_zero
{peel}variable step equal step
variable x2 equal x[2]-x[1]
variable y2 equal y[2]-y[1]
variable fx2 equal fx[2]
variable fy2 equal fy[2]
fix out all print 1 "{values}" file out.txt screen no title "# {columns}"
thermo {nsteps}
run {nsteps}
""", nsteps


def run(style, c, A, steps_per_slide, work, name):
    text, nsteps = deck(style, c, A, steps_per_slide)
    with open(os.path.join(work, f"{name}.in"), "w") as fh:
        fh.write(text)
    proc = subprocess.run(["lmp", "-in", f"{name}.in", "-log", f"{name}.log", "-nocite"],
                          cwd=work, capture_output=True, text=True)
    if proc.returncode != 0 or "ERROR" in proc.stdout:
        raise RuntimeError(f"{name}: LAMMPS failed\n{proc.stdout[-3000:]}{proc.stderr[-2000:]}")
    shutil.move(os.path.join(work, "out.txt"), os.path.join(work, f"{name}.txt"))
    with open(os.path.join(work, f"{name}.txt")) as fh:
        header = fh.readline().lstrip("#").split()
    raw = np.loadtxt(os.path.join(work, f"{name}.txt"), comments="#", ndmin=2)
    d = {k: raw[1:, i] for i, k in enumerate(header)}    # row 0: before the first move
    r = np.hypot(d["x2"], d["y2"])
    nx, ny = d["x2"] / r, d["y2"] / r
    d["P"] = d["fx2"] * nx + d["fy2"] * ny               # on sphere 2 along n: repulsive > 0
    d["T"] = -(-d["fx2"] * ny + d["fy2"] * nx)           # resisting force along +s
    d["s"] = (2 * R - c.delta) * np.arctan2(d["y2"], d["x2"])
    d["delta_meas"] = 2 * R - r
    # leg index (0 loading, 1 unloading, 2 reloading): a new leg starts where s turns back
    turn = np.concatenate(([False], np.diff(np.sign(np.diff(d["s"]))) != 0, [False]))
    d["leg"] = np.minimum(np.cumsum(turn), 2)
    return d


def initial_stiffness(s, T, leg, c):
    """Slopes of T(s) at the start of loading and of unloading: least squares through the
    starting point over the first 2 % of the sliding limit of the change of T."""
    slopes = []
    for k in (0, 1):
        s0, T0 = (0.0, 0.0) if k == 0 else (s[leg == 1][0], T[leg == 1][0])   # turning point
        m = (leg == k) & (np.abs(T - T0) < 0.02 * c.L) & (s != s0)
        x, y = s[m] - s0, T[m] - T0
        slopes.append(np.sum(x * y) / np.sum(x * x))
    return slopes


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(REPO, "docs", "comparison_tangential.png"))
    ap.add_argument("--steps-per-slide", type=int, default=4000,
                    help="time steps per Mindlin-Deresiewicz slip distance (resolution)")
    ap.add_argument("--keep", help="keep the decks and records in this directory")
    args = ap.parse_args(argv)
    work = args.keep or tempfile.mkdtemp(prefix="cmp_tangential_")
    os.makedirs(work, exist_ok=True)

    fig, axes = plt.subplots(1, 3, figsize=(15, 5.6))
    print(f"E = {E:g} Pa, nu = {NU}, mu = {MU}, R* = {R_STAR:g} m: E* = {E_STAR:.5g} Pa, "
          f"G* = {G_STAR:.5g} Pa")
    for (key, title, Gamma, delta), ax in zip(CASES, axes):
        c = Contact(Gamma, delta)
        A = 2 * c.slip
        builtin = "granular jkr+mindlin" if Gamma else "granular hertz/material+mindlin"
        ty = run("thornton/yin", c, A, args.steps_per_slide, work, f"{key}_thornton_yin")
        gr = run("granular", c, A, args.steps_per_slide, work, f"{key}_granular")
        print(f"\n{title}: P = {c.P:.5g} N" + (f" = {c.P / c.Pc:.3f} Pc, Pc = {c.Pc:.5g} N" if Gamma else "")
              + f", a = {c.a:.5g} m, a_T = {c.aT:.5g} m, mu(P+2Pc) = {c.L:.5g} N, "
              f"8G*a = {c.k0:.5g} N/m, MD slip distance {c.slip:.5g} m"
              + (f", T_c = {c.Tc:.5g} N = {c.Tc / c.L:.4f} mu(P+2Pc)" if Gamma else ""))
        for name, d in (("thornton/yin", ty), (builtin, gr)):
            ref = c.reference(d["s"], d["leg"], A)
            lin = c.linear_capped(d["s"])
            end1 = np.flatnonzero(d["leg"] == 0)[-1]
            k_load, k_unload = initial_stiffness(d["s"], d["T"], d["leg"], c)
            kr_load, kr_unload = initial_stiffness(d["s"], ref, d["leg"], c)
            print(f"  {name:32s} P range [{d['P'].min():.6g}, {d['P'].max():.6g}] N; "
                  f"initial stiffness: loading {k_load / c.k0:.4f}, unloading {k_unload / c.k0:.4f} "
                  f"x 8G*a (closed form {kr_load / c.k0:.4f}, {kr_unload / c.k0:.4f}; "
                  f"a_T/a = {c.aT / c.a:.4f}); "
                  f"T at s = +A {d['T'][end1] / c.L:.6f}, min T {d['T'].min() / c.L:.6f}, "
                  f"T at end {d['T'][-1] / c.L:.6f} x mu(P+2Pc)")
            print(f"  {'':32s} max |T - Thornton closed form| = {np.max(np.abs(d['T'] - ref)) / c.L:.4f} "
                  f"mu(P+2Pc) (loading {np.max(np.abs(d['T'] - ref)[d['leg'] == 0]) / c.L:.4f}, "
                  f"unloading {np.max(np.abs(d['T'] - ref)[d['leg'] == 1]) / c.L:.4f}, "
                  f"reloading {np.max(np.abs(d['T'] - ref)[d['leg'] == 2]) / c.L:.4f}); "
                  f"max |T - linear capped| = {np.max(np.abs(d['T'] - lin)) / c.L:.4f}")
            # work put into the contact over the closed loop s = A -> -A -> A (= dissipation)
            loop = d["leg"] >= 1
            work_in = np.trapz(d["T"][loop], d["s"][loop])
            work_ref = np.trapz(ref[loop], d["s"][loop])
            print(f"  {'':32s} dissipation over the closed loop s = A -> -A -> A: "
                  f"{work_in / (c.L * c.slip):.4f} mu(P+2Pc) x slip distance "
                  f"(closed form {work_ref / (c.L * c.slip):.4f})")
        s_first_slide = ty["s"][np.argmax(ty["slide"] > 0)]
        print(f"  thornton/yin first slides at s = {s_first_slide / c.slip:.4f} x slip distance "
              f"(closed form {c.s_slide / c.slip:.4f})")
        if Gamma:
            k = np.argmax(ty["peel"] == 0)
            print(f"  thornton/yin peeling flag off at step {int(ty['step'][k])}: T = {ty['T'][k]:.5g} N "
                  f"= {ty['T'][k] / c.L:.4f} mu(P+2Pc), previous step T = {ty['T'][k - 1] / c.L:.4f} "
                  f"(closed form: end of peeling at min(T_c, mu(P+2Pc)) = "
                  f"{min(c.Tc, c.L) / c.L:.4f}), s = {ty['s'][k] / c.slip:.4f} x slip distance "
                  f"(closed form {c.s_peel_end / c.slip:.4f})")
        gr_slide = np.argmax(gr["T"] >= c.L * (1 - 1e-9))
        print(f"  {builtin} reaches mu(P+2Pc) at s = {gr['s'][gr_slide] / c.slip:.4f} x slip "
              f"distance (linear: {c.L / c.k0 / c.slip:.4f})")

        # figure
        x = lambda d: d["s"] / c.slip
        ss = np.linspace(0, 1, 400)
        s_ref = np.concatenate((A * ss, A - 2 * A * ss, -A + 2 * A * ss))
        leg_ref = np.repeat([0, 1, 2], len(ss))
        ax.plot(s_ref / c.slip, c.reference(s_ref, leg_ref, A) / c.L, c="k", lw=4, alpha=0.25,
                label="closed form (Thornton: peeling, MD, Masing)" if Gamma
                else "closed form (Mindlin–Deresiewicz, Masing)")
        ax.plot(x(ty), ty["T"] / c.L, c="C0", lw=1.4, label="pair thornton/yin")
        ax.plot(x(gr), gr["T"] / c.L, c="C3", lw=1.2, ls="--", label=f"pair {builtin}")
        if Gamma and c.Tc < c.L:
            ax.axhline(c.Tc / c.L, c="grey", ls=":", lw=0.8)
            ax.text(-1.9, c.Tc / c.L + 0.02, "T_c (end of peeling)", fontsize=8, color="grey")
        ax.set_xlabel("tangential displacement s / (3μP_eff/(16G*a_T))")
        ax.set_ylabel("T / μ(P + 2Pc)" if Gamma else "T / μP")
        ax.set_xlim(-2.1, 2.1)
        ax.set_ylim(-1.15, 1.15)
        ax.axhline(0, c="k", lw=0.4)
        ax.axvline(0, c="k", lw=0.4)
        sub = f"P = {c.P:.3g} N" + (f" = {c.P / c.Pc:.1f} Pc" if Gamma else "")
        ax.set_title(f"{title}\n{sub}", fontsize=10)
        if Gamma and c.Tc >= c.L:
            ax.text(-1.9, 0.75, f"T_c = {c.Tc / c.L:.2f} μ(P + 2Pc):\nslides while peeling",
                    fontsize=8, color="grey")
        ax.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(0.0, -0.16), frameon=False)
    fig.suptitle("Tangential loop at fixed overlap: R = 0.1 mm, E = 70 GPa, ν = 0.3, μ = 0.3",
                 fontsize=11)
    save_figure(fig, args.out)
    print(f"\nwrote {args.out}" + (f"; decks and records in {work}" if args.keep else ""))
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
