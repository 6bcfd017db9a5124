#!/usr/bin/env python3
"""The same dense 500-sphere specimen sheared the same way by pair thornton/yin and by LAMMPS's
`pair granular ... tangential mindlin` (docs/comparison.md, "Assembly").

    /usr/bin/python3 bench/compare_assembly.py [--specimen tylmp_specimens/dense_quick.restart]
        [--rate 1e-4] [--strain 0.05] [--every 20] [--gain 1e-4] [--tests volume servo]
        [--cases NAME ...] [--out docs/comparison_assembly.png] [--keep DIR]

fix cell/servo needs pair thornton/yin, so both tests are driven by stock `fix deform`, from
the quick-scale dense specimen (inputs/axisym.in prepares it: 500 spheres at p = 100 kPa),
mu = 0.3, no damping, dt = 0.2 Rayleigh time, the same neighbor settings and step count:
  volume  undrained (constant-volume) axisymmetric compression,
          x trate -rate  y trate rate/2  z trate rate/2        (true strain rates: volume exact)
  servo   drained axisymmetric compression at p = 100 kPa: thornton/yin runs under fix
          cell/servo axisym (as inputs/axisym.in); every case then follows that principal strain
          path with fix deform in chunks of `every` steps, the lateral rates corrected chunk by
          chunk by gain x (p/100 kPa - 1) so that each style stays near p = 100 kPa.
`trate` and not `volume` for y and z: LAMMPS 29Sep2021 fix deform leaves domain->h_rate = 0 for
`volume` dimensions (fix_deform.cpp: "still need to set h_rate for these dims"), so neither the
affine velocity of thornton/yin (remap x) nor the ghost velocities of remap v would see the
lateral strain; the case "thornton/yin G=0.6 volume" shows what that does.

Each style runs with `remap x` (particle velocities are fluctuations; thornton/yin adds the
affine relative velocity L (x_i - x_j) to the contact velocity, the built-in styles do not) and
with `remap v` (velocities carry the affine field L (x - centre), set at the start and adjusted
at every change of L; ghosts across the boundary get the box rate; thornton/yin adds nothing).
Records p, q = sigma_x - (sigma_y + sigma_z)/2 (compression positive, contact virial), q/p and
the mean number of touching neighbours against the axial natural strain; prints tables with
the LAMMPS loop time of each run (summed over chunks) and the differences between cases.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
from tylmp.analysis.figures import save_figure  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pair_speed import LOAD  # noqa: E402  (the two lines that load the plugin's styles)
from lammps_log import loops, section  # noqa: E402
E, NU, MU, GAMMA = 70e9, 0.3, 0.3, 0.6

PAIRS = {
    "thornton/yin G=0.6": f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} {GAMMA}\n",
    "thornton/yin G=0": f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} 0.0\n",
    "granular jkr+mindlin": (f"pair_style granular\npair_coeff * * jkr {E} 0.0 {NU} {GAMMA} "
                             f"damping viscoelastic tangential mindlin NULL 0.0 {MU}\n"),
    "granular hertz/material+mindlin": (
        f"pair_style granular\npair_coeff * * hertz/material {E} 0.0 {NU} "
        f"damping viscoelastic tangential mindlin NULL 0.0 {MU}\n"),
}
# case name -> (pair, remap, lateral style)
CASES = {}
for _pair in PAIRS:
    for _remap in ("x", "v"):
        CASES[f"{_pair} remap {_remap}"] = (_pair, _remap, "trate")
CASES["thornton/yin G=0.6 volume"] = ("thornton/yin G=0.6", "x", "volume")

STYLE = {"thornton/yin G=0.6": ("C0", "adhesive"), "granular jkr+mindlin": ("C3", "adhesive"),
         "thornton/yin G=0": ("C0", "hertz"), "granular hertz/material+mindlin": ("C3", "hertz")}


HEAD = """{load}read_restart {specimen}
comm_modify vel yes
{pair}neighbor 1.35e-5 bin
neigh_modify every 1 delay 0 check yes
timestep {dt!r}
fix integrate all nve/sphere
compute stress all pressure NULL virial
compute touching all contact/atom
compute z all reduce ave c_touching
variable lx0 equal $(lx)
variable eps equal -ln(lx/v_lx0)
variable sx equal c_stress[1]
variable sy equal c_stress[2]
variable sz equal c_stress[3]
fix out all print {every} "$(step) $(v_eps:%.10g) $(v_sx:%.10g) $(v_sy:%.10g) $(v_sz:%.10g) $(vol:%.10g)" file out.txt screen no title "# step eps_a sx sy sz volume"
fix outz all print {every} "$(step) $(c_z:%.6g)" file touching.txt screen no title "# step touching"
thermo_style custom step v_eps c_stress[1] c_stress[2] c_stress[3]
"""


def streaming(rates):
    """Add the affine velocity field L (x - centre), L = diag(rates), to every atom."""
    return (f"variable ax atom {rates[0]!r}*(x-0.5*(xlo+xhi))\n"
            f"variable ay atom {rates[1]!r}*(y-0.5*(ylo+yhi))\n"
            f"variable az atom {rates[2]!r}*(z-0.5*(zlo+zhi))\n"
            "velocity all set v_ax v_ay v_az sum yes\n")


def volume_deck(specimen, pair, remap, lateral, rate, nsteps, every, dt):
    """Constant-volume axisymmetric compression with one fix deform."""
    if lateral == "trate":
        deform = f"x trate {-rate!r} y trate {rate / 2!r} z trate {rate / 2!r}"
    else:
        deform = f"x trate {-rate!r} y volume z volume"
    stream = streaming((-rate, rate / 2, rate / 2)) if remap == "v" else ""
    return (HEAD.format(load=LOAD, specimen=specimen, pair=PAIRS[pair], dt=dt, every=every)
            + f"""{stream}fix shear all deform 1 {deform} remap {remap}
thermo {max(nsteps // 10, 1)}
run {nsteps}
""")


def servo_deck(specimen, pair, rate, nsteps, every, dt):
    """thornton/yin under fix cell/servo: axial rate prescribed, lateral stresses equal,
    p = 100 kPa (as inputs/axisym.in); its strain record is the path the replays follow."""
    return (HEAD.format(load=LOAD, specimen=specimen, pair=PAIRS[pair], dt=dt, every=every)
            + f"""fix cell all cell/servo axisym x {rate!r} 1e5 csv servo.csv {every}
thermo {max(nsteps // 10, 1)}
run {nsteps}
""")


def replay_deck(specimen, pair, remap, path, every, dt, gain):
    """Follow the principal strain path of a servo run (path: rows of eps1, eps2, eps3 every
    `every` steps) with fix deform, one chunk of `every` steps at constant true strain rates
    each. The lateral rates get a proportional correction gain x (p/100 kPa - 1) from the
    mean stress at the end of the previous chunk, so that every style is held near the servo's
    p (gain 0: pure strain replay). With remap v the streaming velocities follow every change
    of L (dL (x - centre) added to every atom)."""
    lines = [HEAD.format(load=LOAD, specimen=specimen, pair=PAIRS[pair], dt=dt, every=every),
             "thermo 0\nvariable py equal 0.0\nvariable pz equal 0.0\nvariable px equal 0.0\n"
             "variable perr equal (c_stress[1]+c_stress[2]+c_stress[3])/3e5-1\n"]
    for k in range(len(path) - 1):
        rates = -(path[k + 1] - path[k]) / (every * dt)     # L_ii = d ln(l_i)/dt = -d eps_i/dt
        fb = "0.0" if k == 0 or gain == 0 else f"{gain!r}*v_perr"
        lines.append(f"variable rx equal {rates[0]!r}\n"
                     f"variable ry equal $({rates[1]!r}+{fb})\n"
                     f"variable rz equal $({rates[2]!r}+{fb})\n")
        if remap == "v":
            lines.append("variable ax atom (${rx}-${px})*(x-0.5*(xlo+xhi))\n"
                         "variable ay atom (${ry}-${py})*(y-0.5*(ylo+yhi))\n"
                         "variable az atom (${rz}-${pz})*(z-0.5*(zlo+zhi))\n"
                         "velocity all set v_ax v_ay v_az sum yes\n")
        lines.append("variable px equal ${rx}\nvariable py equal ${ry}\nvariable pz equal ${rz}\n"
                     f"fix shear all deform 1 x trate ${{rx}} y trate ${{ry}} z trate ${{rz}} "
                     f"remap {remap}\nrun {every}\nunfix shear\n")
    return "".join(lines)


def read_record(work, tag):
    with open(os.path.join(work, f"{tag}.txt")) as fh:
        header = fh.readline().lstrip("#").split()
    raw = np.loadtxt(os.path.join(work, f"{tag}.txt"), ndmin=2)
    d = {k: raw[:, i] for i, k in enumerate(header)}
    z = np.loadtxt(os.path.join(work, f"{tag}_touching.txt"), ndmin=2)
    d["touching"] = np.interp(d["step"], z[:, 0], z[:, 1])
    d["p"] = (d["sx"] + d["sy"] + d["sz"]) / 3
    d["q"] = d["sx"] - 0.5 * (d["sy"] + d["sz"])
    d["eta"] = d["q"] / d["p"]
    return d


def run_deck(text, tag, work, reuse=False):
    """Run one deck (reuse: only read what an earlier run left in `work`); returns its record
    with the summed LAMMPS loop and pair times."""
    if reuse:
        return parse_run(tag, work, float("nan"))
    with open(os.path.join(work, f"{tag}.in"), "w") as fh:
        fh.write(text)
    t0 = time.perf_counter()
    proc = subprocess.run(["lmp", "-in", f"{tag}.in", "-log", f"{tag}.log", "-nocite",
                           "-screen", "none"], cwd=work, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    with open(os.path.join(work, f"{tag}.log")) as fh:
        log = fh.read()
    if proc.returncode != 0 or "ERROR" in log:
        raise RuntimeError(f"{tag}: LAMMPS failed\n{log[-3000:]}{proc.stderr[-1000:]}")
    for name in ("out", "touching"):
        shutil.move(os.path.join(work, f"{name}.txt"),
                    os.path.join(work, f"{tag}.txt" if name == "out" else f"{tag}_touching.txt"))
    if os.path.exists(os.path.join(work, "servo.csv")):
        shutil.move(os.path.join(work, "servo.csv"), os.path.join(work, f"{tag}_servo.csv"))
    return parse_run(tag, work, wall)


def parse_run(tag, work, wall):
    with open(os.path.join(work, f"{tag}.log")) as fh:
        log = fh.read()
    runs = loops(log)
    d = read_record(work, tag)
    d["loop_s"] = sum(r["seconds"] for r in runs)
    d["pair_s"] = sum(r["avg"] for r in section(log, "Pair"))
    d["steps"] = sum(r["steps"] for r in runs)
    d["atoms"] = runs[-1]["atoms"]
    d["wall_s"] = wall
    return d


def at(d, eps, key):
    return float(np.interp(eps, d["eps_a"], d[key]))


def table(runs, strain, marks=(0.0002, 0.001, 0.005, 0.01, 0.02, 0.05)):
    print("| case | q/p at eps_a = " + " | ".join(f"{m:g}" for m in marks)
          + " | max q/p (at eps_a) | p at 0 / end [kPa] | touching/sphere at 0 / end "
          "| loop [s] | pair [s] | wall [s] | atom-steps/s |")
    print("|---" * (len(marks) + 8) + "|")
    for name, d in runs.items():
        k = int(np.argmax(d["eta"]))
        print(f"| {name} | " + " | ".join(f"{at(d, m, 'eta'):.4f}" for m in marks)
              + f" | {d['eta'][k]:.4f} ({d['eps_a'][k]:.4f}) | {d['p'][0] / 1e3:.1f} / "
              f"{at(d, strain, 'p') / 1e3:.1f} | {d['touching'][0]:.3f} / "
              f"{at(d, strain, 'touching'):.3f} | {d['loop_s']:.2f} | {d['pair_s']:.2f} | "
              f"{d['wall_s']:.1f} | "
              f"{d['atoms'] * d['steps'] / d['loop_s']:.3g} |")


def differences(runs, strain, pairs):
    grid = np.linspace(0.01, strain, 200)
    full = np.linspace(0.0, strain, 1000)
    for a, b in pairs:
        if a in runs and b in runs:
            da, db = runs[a], runs[b]
            f = lambda d, x: np.interp(x, d["eps_a"], d["eta"])
            diff, dfull = f(da, grid) - f(db, grid), f(da, full) - f(db, full)
            dp = np.interp(grid, da["eps_a"], da["p"]) / np.interp(grid, db["eps_a"], db["p"]) - 1
            print(f"  {a}  minus  {b}: q/p mean {diff.mean():+.4f}, max |.| {np.abs(dfull).max():.4f}"
                  f"; p ratio - 1 mean {dp.mean():+.4f}")


def log_bins(x, y, width=0.03):
    """Averages of y over bins of x of relative width `width` (display only: a 500-sphere
    specimen fluctuates from record to record; small strains keep every record)."""
    edges = np.exp(np.arange(np.log(x[x > 0].min()), np.log(x.max()) + width, width))
    idx = np.digitize(x, edges)
    keep = [k for k in np.unique(idx) if np.any(idx == k)]
    return (np.array([x[idx == k].mean() for k in keep]),
            np.array([y[idx == k].mean() for k in keep]))


def secant_modulus(d, eps=2e-4):
    """q/eps_a at eps_a = eps (initial deviatoric stiffness, Pa)."""
    return at(d, eps, "q") / eps


COMPARE = [
    ("thornton/yin G=0.6 remap x", "granular jkr+mindlin remap x"),
    ("thornton/yin G=0.6 remap x", "granular jkr+mindlin remap v"),
    ("thornton/yin G=0 remap x", "granular hertz/material+mindlin remap x"),
    ("thornton/yin G=0 remap x", "granular hertz/material+mindlin remap v"),
    ("thornton/yin G=0.6 remap x", "thornton/yin G=0.6 remap v"),
    ("thornton/yin G=0 remap x", "thornton/yin G=0 remap v"),
    ("granular jkr+mindlin remap v", "granular jkr+mindlin remap x"),
    ("granular hertz/material+mindlin remap v", "granular hertz/material+mindlin remap x"),
    ("thornton/yin G=0.6 remap x", "thornton/yin G=0.6 volume"),
    ("thornton/yin G=0.6 servo", "thornton/yin G=0.6 remap x"),
    ("thornton/yin G=0 servo", "thornton/yin G=0 remap x"),
    ("thornton/yin G=0.6 remap x", "thornton/yin G=0 remap x"),
    ("granular jkr+mindlin remap v", "granular hertz/material+mindlin remap v"),
]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--specimen", default=os.path.join(REPO, "tylmp_specimens", "dense_quick.restart"))
    ap.add_argument("--rate", type=float, default=1e-4, help="axial true strain rate [1/s]")
    ap.add_argument("--strain", type=float, default=0.05, help="axial natural strain at the end")
    ap.add_argument("--every", type=int, default=20,
                    help="record (and replay chunk) every N steps")
    ap.add_argument("--gain", type=float, default=1e-4,
                    help="constant-p test: lateral strain-rate correction per unit relative "
                         "error of p [1/s] (0: replay the servo's strain path unaltered)")
    ap.add_argument("--tests", nargs="*", default=["volume", "servo"], choices=["volume", "servo"])
    ap.add_argument("--cases", nargs="*", default=list(CASES))
    ap.add_argument("--out", default=os.path.join(REPO, "docs", "comparison_assembly.png"))
    ap.add_argument("--keep", help="keep the decks, logs and records in this directory")
    ap.add_argument("--reuse", action="store_true",
                    help="do not run: read the logs and records an earlier run left in --keep "
                         "(tables and figure again; wall times are not kept)")
    args = ap.parse_args(argv)
    if args.reuse and not args.keep:
        sys.exit("--reuse needs --keep DIR")
    specimen = os.path.abspath(args.specimen)
    if not os.path.exists(specimen):
        sys.exit(f"no specimen {specimen}: run 'lmp -in inputs/axisym.in -var strain 0.001' once "
                 "(it prepares tylmp_specimens/dense_quick.restart)")
    dt = 0.2 * np.pi * 0.0675e-3 * np.sqrt(2650e12 / (70e9 / 2.6)) / (0.1631 * 0.3 + 0.8766)
    nsteps = args.every * int(np.ceil(args.strain / (args.rate * dt) / args.every))
    work = args.keep or tempfile.mkdtemp(prefix="cmp_assembly_")
    os.makedirs(work, exist_ok=True)
    print(f"specimen {specimen}; axial true strain rate {args.rate:g} 1/s, dt = {dt:.6g} s, "
          f"{nsteps} steps to {nsteps * args.rate * dt:.4g} axial strain; 1 rank")
    results = {}
    if "volume" in args.tests:
        print("\nconstant volume: fix deform x trate -rate y trate rate/2 z trate rate/2")
        runs = results["volume"] = {}
        for name in args.cases:
            pair, remap, lateral = CASES[name]
            tag = "vol_" + re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_")
            runs[name] = run_deck(volume_deck(specimen, pair, remap, lateral, args.rate, nsteps,
                                              args.every, dt), tag, work, args.reuse)
            print(f"  {name:42s} loop {runs[name]['loop_s']:7.2f} s", flush=True)
    if "servo" in args.tests:
        print("\nconstant p: thornton/yin under fix cell/servo axisym (p = 100 kPa), then every "
              "case follows that principal strain path with fix deform, lateral rates corrected "
              f"by {args.gain:g} x (p/100 kPa - 1) 1/s every {args.every} steps")
        runs = results["servo"] = {}
        paths = {}
        for pair in ("thornton/yin G=0.6", "thornton/yin G=0"):
            if not any(CASES[c][0] == pair or STYLE[CASES[c][0]][1] == STYLE[pair][1]
                       for c in args.cases):
                continue
            name = f"{pair} servo"
            tag = "servo_" + re.sub(r"[^A-Za-z0-9]+", "_", pair).strip("_")
            runs[name] = run_deck(servo_deck(specimen, pair, args.rate, nsteps, args.every, dt),
                                  tag, work, args.reuse)
            rec = np.genfromtxt(os.path.join(work, f"{tag}_servo.csv"), delimiter=",", names=True)
            paths[STYLE[pair][1]] = np.column_stack((rec["eps1"], rec["eps2"], rec["eps3"]))
            print(f"  {name:42s} loop {runs[name]['loop_s']:7.2f} s; p at end "
                  f"{rec['p'][-1] / 1e3:.2f} kPa, eps_v at end {rec['eps_v'][-1]:+.4f}", flush=True)
        for name in args.cases:
            pair, remap, lateral = CASES[name]
            if lateral != "trate" or STYLE[pair][1] not in paths:
                continue
            tag = "rep_" + re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_")
            runs[name] = run_deck(replay_deck(specimen, pair, remap, paths[STYLE[pair][1]],
                                              args.every, dt, args.gain), tag, work, args.reuse)
            print(f"  {name:42s} loop {runs[name]['loop_s']:7.2f} s", flush=True)

    for test, runs in results.items():
        print(f"\n{'constant volume' if test == 'volume' else 'constant p (servo path + p feedback)'}:")
        table(runs, nsteps * args.rate * dt)
        print("\ninitial deviatoric stiffness q/eps_a at eps_a = 2e-4 [MPa]: " + ", ".join(
            f"{n} {secant_modulus(d) / 1e6:.1f}" for n, d in runs.items()))
        print("differences (q/p over eps_a in [0.01, end] and max over the run; p ratio):")
        differences(runs, nsteps * args.rate * dt, COMPARE)

    tests = list(results)
    fig, axes = plt.subplots(len(tests), 3, figsize=(16, 4.6 * len(tests)), squeeze=False)
    for row, test in zip(axes, tests):
        for name, d in results[test].items():
            pair = name.rsplit(" ", 2)[0] if "remap" in name else name.rsplit(" ", 1)[0]
            remap = CASES[name][1] if name in CASES else "servo"
            lateral = CASES[name][2] if name in CASES else "servo"
            color, group = STYLE[pair]
            ls = {"x": "-", "v": "--", "servo": "-"}[remap]
            lw = 1.3
            if lateral == "volume":
                color, ls = "C2", ":"
            if remap == "servo":
                color, lw = "k", 2.5
            ax = row[0] if group == "adhesive" else row[1]
            label = f"{pair}, " + ("fix cell/servo" if remap == "servo" else f"remap {remap}") \
                + (", y/z volume" if lateral == "volume" else "")
            eps = np.maximum(d["eps_a"], 1e-6) * 100
            ax.plot(*log_bins(eps, d["eta"]), c=color, ls=ls, lw=lw,
                    alpha=0.35 if remap == "servo" else 1, label=label)
            pcol = color if group == "adhesive" else \
                ("k" if remap == "servo" else "C9" if pair.startswith("thornton") else "C1")
            row[2].plot(eps, d["p"] / 1e3, c=pcol, ls=ls, lw=lw, alpha=0.35 if remap == "servo" else 1,
                        label=label)
        kind = "constant volume" if test == "volume" else "constant p (servo path + p feedback)"
        for ax, title in zip(row[:2], ("Γ = 0.6 J/m², μ = 0.3", "Γ = 0, μ = 0.3")):
            ax.set_xscale("log")
            ax.set_xlim(1e-3, args.strain * 100)
            ax.set_xlabel("axial strain ε_a = −ln(l_x/l_x0) [%]")
            ax.set_ylabel("q/p")
            ax.set_title(f"{kind}: {title}", fontsize=10)
            ax.text(0.98, 0.02, "averaged in bins of 3 % of ε_a", transform=ax.transAxes,
                    ha="right", fontsize=7, color="grey")
            if ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize=7.5, loc="upper left")
        row[2].set_xlabel("axial strain ε_a [%]")
        row[2].set_ylabel("mean stress p [kPa] (contact virial)")
        row[2].set_title(f"{kind}: mean stress", fontsize=10)
        row[2].set_xlim(0, args.strain * 100)
        if test == "volume":
            row[2].set_yscale("log")
        if test == "volume":
            row[2].legend(fontsize=6.5, loc="lower right")
        else:
            row[2].set_ylim(85, 135)
            row[2].legend(fontsize=6, loc="upper center", ncol=2, framealpha=0.7)
    fig.suptitle("Axisymmetric compression of the quick dense specimen (500 spheres), "
                 f"ε̇_a = {args.rate:g} 1/s", fontsize=11)
    save_figure(fig, args.out, dpi=110)
    print(f"\nwrote {args.out}" + (f"; decks, logs and records in {work}" if args.keep else ""))
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
