#!/usr/bin/env python3
"""Oblique impact of an elastic sphere on an elastic half-space at angles 1-85 degrees: the
classical elastic-frictional theory (Maw, Barber & Fawcett 1976), computed in time with the
oracle of tests/mdr_oracle.py (tests/oblique_reference.py), against pair thornton/yin and
LAMMPS's `pair granular hertz/material ... tangential mindlin`, `mindlin_rescale`,
`mindlin/force` and `mindlin_rescale/force` (docs/comparison.md, "Oblique impact";
docs/theory.md §3.6). With --adhesion also thornton/yin with Gamma > 0: the normal restitution
against the closed form of docs/theory.md §3.2 and the tangential outputs beside Gamma = 0.

    /usr/bin/python3 bench/oblique_impact.py [--out docs/comparison_oblique_impact.png]
        [--json bench/results/oblique_impact.json] [--steps 1000] [--keep DIR] [--plot]
        [--other-lmp LMP]

Configuration (Maw et al.'s): a glass sphere, R = 0.1 mm, E = 70 GPa, nu = 0.3,
rho = 2650 kg/m^3, mu = 0.3, at V = 0.1 m/s with no spin against a fixed glass sphere of
radius 0.1 m (a half-space to 1e-3: R* = R/1.001, E* = E/(2(1 - nu^2)), G* = G/(2(2 - nu))).
The big sphere is not integrated; no damping, no gravity. The time step is the Hertz contact
time of V_n over --steps.
"""
import argparse
import functools
import math
import os
import shutil
import sys
import tempfile

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.environ.get("TYLMP_BUILD_DIR", os.path.join(REPO, "build"))
sys.path.insert(0, os.path.join(REPO, "tests"))
import jkr_reference as jkr  # noqa: E402
import oblique_reference as ob  # noqa: E402
from lmprun import LOAD_TYLMP, run_deck  # noqa: E402

R, R_WALL = 1.0e-4, 0.1
E, NU, RHO, MU = 70e9, 0.3, 2650.0, 0.3
V = 0.1
GAMMA = 0.3                       # J/m^2, the adhesive runs (docs/theory.md §1.8)
ANGLES = [1, 2, 5, 10, 15, 20, 25, 30, 35, 40, 45, 50, 55, 60, 65, 70, 75, 80, 85]
TABLE_ANGLES = [5, 20, 30, 45, 60, 75]
ADHESIVE_ANGLES = [0, 20, 45, 60, 70, 75, 80]
MODELS = ["thornton/yin", "mindlin", "mindlin_rescale", "mindlin/force", "mindlin_rescale/force"]
MAT = ob.Material(R, E, NU, RHO, MU, R_other=R_WALL)


def pair_lines(model, Gamma=0.0):
    if model == "thornton/yin":
        return f"{LOAD_TYLMP}pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} {Gamma}\n"
    # zero viscoelastic damping: eta_n = 0, and the tangential damping x_gamma,t eta_n = 0
    return (f"pair_style granular\npair_coeff * * hertz/material {E} 0.0 {NU} "
            f"damping viscoelastic tangential {model} NULL 0.0 {MU}\n")


def deck(model, theta, V=V, Gamma=0.0, steps=1000):
    """Sphere 1 (R) at the origin moving at V, theta from the normal +x, towards the fixed
    sphere 2 (R_WALL); prints the rebound of sphere 1 after the impact."""
    V_n, V_t = V * math.cos(theta), V * math.sin(theta)
    dt = MAT.hertz(V_n)[1] / steps
    gap = 3 * V_n * dt
    x2 = R + R_WALL + gap
    # Hertz contact time plus margin; an adhesive contact lasts longer (it breaks at delta_f)
    nsteps = int((1.2 if Gamma == 0 else 4.0) * steps) + 10
    dissipation = ("compute diss all pair thornton/yin\n"
                   "variable Df equal c_diss[1]\nvariable Db equal c_diss[2]\n"
                   if model == "thornton/yin" else "variable Df equal 0\nvariable Db equal 0\n")
    return f"""units si
atom_style sphere
atom_modify map array
boundary f f f
comm_modify vel yes
region box block -1e-3 {x2 + 0.01!r} -1e-3 1e-3 -1e-3 1e-3
create_box 2 box
create_atoms 1 single 0 0 0
create_atoms 2 single {x2!r} 0 0
set atom 1 diameter {2 * R!r} density {RHO!r}
set atom 2 diameter {2 * R_WALL!r} density {RHO!r}
group one id 1
velocity one set {V_n!r} {V_t!r} 0
{pair_lines(model, Gamma)}neighbor 1e-7 bin
neigh_modify every 1 delay 0 check yes
timestep {dt!r}
fix nve one nve/sphere
compute spin all property/atom omegaz
{dissipation}variable d equal {R + R_WALL!r}-(x[2]-x[1])
variable w equal C_spin[1]
# thermo on the last step makes the computes current for the print after the run
thermo_style custom step v_w v_Df v_Db
thermo {nsteps}
run {nsteps}
print "RESULT $(vx[1]:%.17g) $(vy[1]:%.17g) $(v_w:%.17g) $(v_d:%.17g) $(v_Df:%.17g) $(v_Db:%.17g)"
"""


def package_path():
    """PYTHONPATH with the build's package first, for the decks' loader lines (the tests'
    conftest has set it already)"""
    here, current = os.path.join(BUILD, "python"), os.environ.get("PYTHONPATH", "")
    if here in current.split(os.pathsep):
        return None
    return {"PYTHONPATH": os.pathsep.join([here] + ([current] if current else []))}


def run(model, theta, work, V=V, Gamma=0.0, steps=1000, program=("lmp", "-nocite")):
    """One impact in LAMMPS: the outputs of tests/oblique_reference.py (omega in the rolling
    sense: sphere 2 lies along +x, so friction turns sphere 1 about -z)."""
    rc, out = run_deck(deck(model, theta, V, Gamma, steps), work, program=program,
                       environment=package_path())
    lines = [line for line in out.splitlines() if line.startswith("RESULT")]
    if rc != 0 or "ERROR" in out or not lines:
        raise RuntimeError(f"{model} at {math.degrees(theta):g} deg failed:\n{out[-3000:]}")
    vx, vy, wz, d, Df, Db = (float(x) for x in lines[-1].split()[1:])
    V_n, V_t = V * math.cos(theta), V * math.sin(theta)
    w = -wz
    V_s_out = vy - R * w
    return {"theta": theta, "V_n": V_n, "V_t": V_t, "e_n": -vx / V_n,
            "e_t": V_s_out / V_t if V_t else None,
            "psi1": MAT.psi(V_t, V_n), "psi2": MAT.psi(V_s_out, V_n),
            "Omega": MAT.k * R * w / (MU * V_n), "delta_end": d,
            "friction_dissipation": Df, "break_dissipation": Db,
            "kinetic_in": 0.5 * MAT.m * V**2,
            "kinetic_out": 0.5 * MAT.m * (vx**2 + vy**2) + 0.5 * MAT.I * w**2}


def reference(theta, steps=4000, springs=5000, V=V):
    """the classical solution at theta (tests/oblique_reference.py), the pair's lever arm"""
    return ob.impact(MAT, V, theta, steps=steps, springs=springs, lever="pair")


@functools.lru_cache(maxsize=None)
def separation_work(Gamma):
    """W of docs/theory.md §3.2, by quadrature of the JKR curve (tests/jkr_reference.py)"""
    return jkr.separation_work(MAT.R_star, MAT.E_star, Gamma, n=4001)


def law_path(path):
    """build/law_path (tests/law_path/law_path.cpp: one contact of the law) through the
    overlaps path[:, 0] and tangential displacements path[:, 1]: its output columns"""
    import subprocess
    ds = np.diff(np.r_[0.0, path[:, 1]])
    lines = "\n".join(f"{d!r} {x!r} 0.0" for d, x in zip(path[:, 0], ds))
    out = subprocess.run([os.path.join(BUILD, "law_path"), repr(MAT.E_star), repr(MAT.G_star),
                          repr(MU), "0.0", repr(MAT.R_star)], input=lines, capture_output=True,
                         text=True, check=True).stdout
    return np.array([[float(x) for x in line.split()] for line in out.splitlines()])


def sticking_velocity(Gamma):
    """V_s = sqrt(2W/m*) of docs/theory.md §3.2 for the sphere on the fixed sphere: m* = m"""
    return math.sqrt(2 * separation_work(Gamma) / MAT.m)


def adhesive_restitution(V_n, Gamma):
    """e = sqrt(1 - (V_s/V_n)^2) above V_s, 0 below (docs/theory.md §3.2)"""
    Vs = sticking_velocity(Gamma)
    return math.sqrt(1 - (Vs / V_n) ** 2) if V_n > Vs else 0.0


STYLE = {
    "reference": dict(color="k", lw=2.2, ls="-", marker=None,
                      label="reference: MD oracle in time (Maw et al. 1976)"),
    "thornton/yin": dict(color="C3", ls="none", marker="o", ms=6, mfc="none",
                         label="pair thornton/yin"),
    "mindlin": dict(color="C0", ls="--", marker="s", ms=4, label="granular … mindlin"),
    "mindlin_rescale": dict(color="C2", ls="--", marker="^", ms=4,
                            label="granular … mindlin_rescale"),
    "mindlin/force": dict(color="C1", ls=":", marker="v", ms=4, label="granular … mindlin/force"),
    "mindlin_rescale/force": dict(color="C4", ls=":", marker="D", ms=3.5,
                                  label="granular … mindlin_rescale/force"),
}


def figure(results, out):
    """e_t, Psi2 and Omega against Psi1 for the reference and every model, with the sliding
    branch and the no-slip limit of docs/theory.md §3.6"""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sys.path.insert(0, os.path.join(REPO, "python"))
    from tylmp.analysis.figures import save_figure

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    for key in ["reference"] + MODELS:
        rows = results[key]
        x = np.array([r["psi1"] for r in rows])
        for ax, q in zip(axes, ("e_t", "psi2", "Omega")):
            ax.plot(x, [r[q] for r in rows], zorder=3 if key == "thornton/yin" else 2, **STYLE[key])
    threshold = ob.sliding_threshold(MAT)
    psi = np.geomspace(threshold, 35, 200)
    slide = ob.sliding(MAT, psi)
    band = dict(color="0.6", lw=6, alpha=0.35, zorder=0)
    axes[0].plot(psi, slide["psi2"] / psi, **band)
    axes[1].plot(psi, slide["psi2"], label="gross sliding throughout (rigid-body impulse)", **band)
    axes[2].plot(psi, np.full_like(psi, slide["Omega"]), **band)
    e0 = ob.no_slip_restitution(MAT, n=8000)
    axes[0].plot([0.04, 0.1], [e0, e0], color="k", lw=1, ls=":")
    axes[0].annotate(f"no slip: {e0:.3f}", (0.045, e0), xytext=(0, 6), textcoords="offset points",
                     fontsize=8)
    labels = ("tangential restitution e_t = V_s'/V_s", "Ψ2 = k V_s'/(μ V_n)  (rebound angle)",
              "Ω = k R ω'/(μ V_n)  (rebound spin)")
    for ax, label in zip(axes, labels):
        ax.set_xlabel("Ψ1 = k V_s/(μ V_n) = k tanθ/μ,  k = 4G*/E* = 2(1−ν)/(2−ν)")
        ax.set_ylabel(label)
        ax.axvline(threshold, color="0.7", lw=0.8, ls="-.")
        ax.axhline(0, color="0.85", lw=0.6)
        ax.grid(alpha=0.3, which="both")
    axes[0].set_xscale("log")
    axes[2].set_xscale("log")
    axes[1].set_xlim(0, 12)
    axes[1].set_ylim(-2, 7)
    axes[1].legend(fontsize=7.5, loc="upper left")
    fig.suptitle(f"Oblique impact of a glass sphere (R = 0.1 mm) on a glass half-space, "
                 f"V = {V} m/s, μ = {MU}, ν = {NU}, Γ = 0; dash-dot: Ψ1 = {threshold:.3f}, "
                 "sliding throughout above", fontsize=10)
    return save_figure(fig, out)


# ---------------------------------------------------------------- the runs
def sweep(work, steps):
    """the reference and every model at ANGLES"""
    results = {"reference": [reference(math.radians(a)) for a in ANGLES]}
    for model in MODELS:
        results[model] = [run(model, math.radians(a), work, steps=steps) for a in ANGLES]
    return results


def rigid(theta, steps=4000, springs=5000):
    """the reference with the classical lever arm R, for its closed forms"""
    return ob.impact(MAT, V, theta, steps=steps, springs=springs, lever="rigid")


def reference_checks(results):
    """the reference against its closed forms (docs/theory.md §3.6), its convergence in time
    step and spring count, and where e_t changes sign and Psi2 is least"""
    from scipy.optimize import brentq, minimize_scalar
    checks = {"sliding_threshold_psi1": ob.sliding_threshold(MAT),
              "no_slip_e_t": ob.no_slip_restitution(MAT)}
    rows = [rigid(math.radians(a)) for a in ANGLES]
    errors = [abs(r[q] - ob.sliding(MAT, r["psi1"], r["e_n"])[q]) for r in rows
              if r["psi1"] >= checks["sliding_threshold_psi1"] for q in ("psi2", "Omega")]
    checks["sliding_branch_max_error"] = max(errors)
    checks["energy_balance_max_error"] = max(
        abs(r["kinetic_in"] - r["kinetic_out"] - r["dissipation"]) / r["kinetic_in"] for r in rows)
    small = [rigid(MAT.incidence_for_psi(p))["e_t"] for p in (0.005, 0.01)]
    checks["e_t_psi1_0.005_0.01"] = small
    checks["e_t_psi1_to_0_linear"] = 2 * small[0] - small[1]
    convergence = {}
    for a in (20, 45):
        base = rigid(math.radians(a))
        for label, st, sp in (("steps 2000", 2000, 5000), ("steps 8000", 8000, 5000),
                              ("springs 20000", 4000, 20000)):
            r = rigid(math.radians(a), steps=st, springs=sp)
            convergence[f"{a} deg, {label}"] = {q: r[q] - base[q] for q in ("e_t", "Omega")}
    checks["convergence"] = convergence
    checks["lever_arm_R_minus_half_delta_vs_R"] = {
        f"{a} deg": {q: p[q] - r[q] for q in ("e_t", "Omega")}
        for a, p, r in zip(ANGLES, results["reference"], rows) if a in TABLE_ANGLES}

    def at(psi1, q):
        return ob.impact(MAT, V, MAT.incidence_for_psi(psi1), steps=2000, springs=2000)[q]
    checks["e_t_changes_sign_at_psi1"] = brentq(lambda p: at(p, "e_t"), 0.5, 1.0, xtol=1e-4)
    for q, lo, hi in (("e_t", 2.0, 4.0), ("psi2", 2.5, 4.76)):
        least = minimize_scalar(lambda p: at(p, q), bounds=(lo, hi), method="bounded",
                                options={"xatol": 1e-3})
        checks[f"least_{q}"] = {"psi1": least.x, q: least.fun}
    return checks


def law_checks():
    """the law alone (build/law_path, one contact of plugin/core) along the reference's own
    path of (delta, s): max |T_law - T_oracle| / (mu P_max), the law apart from the motion"""
    errors = {}
    for a in TABLE_ANGLES:
        path = ob.impact(MAT, V, math.radians(a), steps=1000, springs=5000, record=True)["trace"]
        T_law = law_path(path)[:, 1]
        errors[f"{a} deg"] = float(np.max(np.abs(T_law - path[:, 3])) / (MU * path[:, 2].max()))
    return errors


def time_step_checks(results, work, steps):
    """thornton/yin at half and twice the steps per contact time, against the sweep"""
    out = {}
    for a in (20, 45, 75):
        ref = results["thornton/yin"][ANGLES.index(a)]
        for st in (steps // 2, 2 * steps):
            r = run("thornton/yin", math.radians(a), work, steps=st)
            out[f"{a} deg, steps {st}"] = {q: r[q] - ref[q] for q in ("e_t", "Omega")}
    return out


def adhesion(work, steps):
    """thornton/yin at GAMMA: e_n against docs/theory.md §3.2 and against the head-on impact at
    the same V_n (the break at delta_f is found to the step: e_n's error is first order in it)"""
    rows = []
    for a in ADHESIVE_ANGLES:
        r = run("thornton/yin", math.radians(a), work, Gamma=GAMMA, steps=steps)
        head_on = r if a == 0 else run("thornton/yin", 0.0, work, V=r["V_n"], Gamma=GAMMA,
                                       steps=steps)
        r["e_n_head_on"] = head_on["e_n"]
        r["e_n_closed_form"] = adhesive_restitution(r["V_n"], GAMMA)
        r["separation_work"] = separation_work(GAMMA)
        rows.append(r)
    return rows


def other_lammps(results, work, steps, program):
    """every model at TABLE_ANGLES with another lmp (e.g. 4 Feb 2025's wrapper from
    scripts/lammps2025.sh): the largest difference from the sweep, per model"""
    out = {}
    for model in MODELS:
        diffs = []
        for a in TABLE_ANGLES:
            r = run(model, math.radians(a), work, steps=steps, program=(program, "-nocite"))
            ref = results[model][ANGLES.index(a)]
            diffs += [abs(r[q] - ref[q]) for q in ("e_n", "e_t", "psi2", "Omega")]
        out[model] = max(diffs)
    return out


# ---------------------------------------------------------------- the report
def booked(r):
    """(friction + break dissipation - kinetic energy lost) / kinetic energy lost"""
    lost = r["kinetic_in"] - r["kinetic_out"]
    return (r["friction_dissipation"] + r["break_dissipation"] - lost) / lost


def largest(results, model, q):
    return max(abs(t[q] - r[q]) for t, r in zip(results[model], results["reference"]))


def report(results, checks, law_error, lammps_dt, adhesive, steps):
    """print the numbers and tables of docs/comparison.md"""
    c = checks
    print(f"k = 4G*/E* = {MAT.k:.6f}; sliding throughout for Psi1 >= "
          f"{c['sliding_threshold_psi1']:.4f}")
    print(f"no-slip limit e_t = {c['no_slip_e_t']:.5f}; reference at Psi1 = 0.005, 0.01: "
          f"{c['e_t_psi1_0.005_0.01'][0]:.5f}, {c['e_t_psi1_0.005_0.01'][1]:.5f}, "
          f"linear to 0: {c['e_t_psi1_to_0_linear']:.5f}")
    print(f"sliding branch, max |error| in Psi2, Omega: {c['sliding_branch_max_error']:.2e}")
    print(f"e_t changes sign at Psi1 = {c['e_t_changes_sign_at_psi1']:.3f}; least e_t "
          f"{c['least_e_t']['e_t']:.4f} at Psi1 = {c['least_e_t']['psi1']:.3f}; least Psi2 "
          f"{c['least_psi2']['psi2']:.4f} at Psi1 = {c['least_psi2']['psi1']:.3f}")
    print("energy balance, max |KE_in - KE_out - dissipation| / KE_in: "
          f"{c['energy_balance_max_error']:.2e}")
    for k, v in c["convergence"].items():
        print(f"reference {k}: d e_t = {v['e_t']:.1e}, d Omega = {v['Omega']:.1e}")
    for k, v in c["lever_arm_R_minus_half_delta_vs_R"].items():
        print(f"lever arm R - delta/2 against R, {k}: d e_t = {v['e_t']:.1e}, "
              f"d Omega = {v['Omega']:.1e}")
    for k, v in law_error.items():
        print(f"law_path along the reference's path, {k}: max |T - T_oracle| = {v:.2e} mu P_max")
    for k, v in lammps_dt.items():
        print(f"thornton/yin {k} against {steps}: d e_t = {v['e_t']:.1e}, "
              f"d Omega = {v['Omega']:.1e}")

    print("\n| θ | Ψ1 | " + " | ".join(["reference"] + MODELS) + " |")
    print("|---|---|" + "---|" * (len(MODELS) + 1))
    for a in TABLE_ANGLES:
        i = ANGLES.index(a)
        cells = [f"{results[k][i]['e_t']:.3f} / {results[k][i]['Omega']:.3f}"
                 for k in ["reference"] + MODELS]
        print(f"| {a}° | {results['reference'][i]['psi1']:.3f} | " + " | ".join(cells) + " |")
    print("\nmax |thornton/yin - reference| over all angles: "
          + ", ".join(f"{q} {largest(results, 'thornton/yin', q):.2e}"
                      for q in ("e_t", "psi2", "Omega")))
    for a, t in zip(ANGLES, results["thornton/yin"]):
        if a in TABLE_ANGLES:
            lost = t["kinetic_in"] - t["kinetic_out"]
            print(f"thornton/yin {a} deg: (friction dissipation - kinetic energy lost) / lost = "
                  f"{(t['friction_dissipation'] - lost) / lost:.2e}")
    for model in MODELS[1:]:
        print(f"max |{model} - reference|: e_t {largest(results, model, 'e_t'):.3f}, "
              f"Omega {largest(results, model, 'Omega'):.3f}")

    print(f"\nadhesion, Gamma = {GAMMA} J/m^2, V_s = {sticking_velocity(GAMMA):.5f} m/s")
    print("| θ | V_n/V_s | e_n | e_n head-on at V_n | closed form | break dissipation / W | "
          "booked − lost | e_t | Ω | e_t, Ω at Γ = 0 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in adhesive:
        a = round(math.degrees(r["theta"]))
        dry = results["thornton/yin"][ANGLES.index(a)] if a in ANGLES else None
        tangential = (f"{r['e_t']:.3f} | {r['Omega']:.3f} | {dry['e_t']:.3f}, {dry['Omega']:.3f}"
                      if dry else "— | — | —")
        print(f"| {a}° | {r['V_n'] / sticking_velocity(GAMMA):.3f} | {r['e_n']:.5f} | "
              f"{r['e_n_head_on']:.5f} | {r['e_n_closed_form']:.5f} | "
              f"{r['break_dissipation'] / r['separation_work']:.4f} | {booked(r):.1e} | "
              f"{tangential} |")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(REPO, "docs", "comparison_oblique_impact.png"))
    ap.add_argument("--json", default=os.path.join(REPO, "bench", "results", "oblique_impact.json"))
    ap.add_argument("--steps", type=int, default=1000, help="LAMMPS steps per Hertz contact time")
    ap.add_argument("--keep", help="keep the decks in this directory")
    ap.add_argument("--plot", action="store_true", help="only redraw the figure from --json")
    ap.add_argument("--other-lmp", metavar="LMP",
                    help="only rerun the table's angles with this lmp (e.g. the 4 Feb 2025 "
                    "wrapper of scripts/lammps2025.sh) and print the largest difference from "
                    "the results in --json")
    args = ap.parse_args(argv)
    if args.plot or args.other_lmp:
        import json
        with open(args.json) as fh:
            saved = json.load(fh)
        if args.plot:
            figure(saved["results"], args.out)
        else:
            work = tempfile.mkdtemp(prefix="oblique_")
            steps = saved["configuration"]["steps_per_contact"]
            for model, d in other_lammps(saved["results"], work, steps, args.other_lmp).items():
                print(f"{model}: largest |difference| in e_n, e_t, Psi2, Omega over "
                      f"{TABLE_ANGLES} degrees: {d:.1e}")
            shutil.rmtree(work, ignore_errors=True)
        return
    work = args.keep or tempfile.mkdtemp(prefix="oblique_")
    os.makedirs(work, exist_ok=True)
    results = sweep(work, args.steps)
    checks = reference_checks(results)
    law_error = law_checks()
    lammps_dt = time_step_checks(results, work, args.steps)
    adhesive = adhesion(work, 4 * args.steps)
    report(results, checks, law_error, lammps_dt, adhesive, args.steps)

    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from provenance import write_result
    checks["law_along_reference_path"] = law_error
    write_result(args.json, {
        "configuration": {"R": R, "R_wall": R_WALL, "E": E, "nu": NU, "rho": RHO, "mu": MU,
                          "V": V, "Gamma_adhesive": GAMMA, "steps_per_contact": args.steps},
        "results": results, "adhesive": adhesive, "checks": checks,
        "lammps_time_step": lammps_dt})
    figure(results, args.out)
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
