#!/usr/bin/env python3
"""Throughput of pair thornton/yin (and its specialised kernels) against LAMMPS's granular
styles on the same packed specimen, plain NVE, identical neighbor settings and step counts.

    /usr/bin/python3 bench/pair_speed.py [--specimen tylmp_specimens/dense_quick.restart]
        [--steps 2000] [--repeats 5] [--ranks 1] [--out bench/results/pair_speed]
        [--variant NAME=PATH/tylmp.so ...]

Every case runs `repeats` times, the cases taken in alternation so that drifts of the
machine's speed hit all of them alike; the figure is the median of the LAMMPS loop time,
reported as atom-steps per second and as a ratio to thornton/yin with Gamma = 0.6.
With --variant (repeatable) every thornton/yin case runs once per build of the library
(TYLMP_LIBRARY set per run), all in the same alternation, to compare code variants; the
table then also gives, per case, the median over repeats of the per-repeat time ratio of each
variant to the first one.
Writes OUT.csv (every run), OUT.json (medians and ratios) and prints a table.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LOAD = ('python tylmp_load input 1 SELF format p here "from tylmp import load as tylmp_load"\n'
        "python tylmp_load invoke\n")

# E = 70 GPa, nu = 0.3, mu = 0.3; no damping anywhere (the paper uses none)
E, NU, MU, GAMMA = 70e9, 0.3, 0.3, 0.6
E_STAR = E / (2 * (1 - NU ** 2))
KN_HOOKE_HERTZ = 4.0 / 3.0 * E_STAR          # gran/hertz/history: F = kn sqrt(R* delta) delta
KT_HOOKE_HERTZ = KN_HOOKE_HERTZ * 2 * (1 - NU) / (2 - NU)

CASES = {
    "thornton/yin G=0.6": f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} {GAMMA}\n",
    "thornton/yin G=0.6 generic": (f"pair_style thornton/yin paths generic\n"
                                   f"pair_coeff * * {E} {NU} {MU} {GAMMA}\n"),
    "thornton/yin G=0": f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} 0.0\n",
    "thornton/yin G=0 generic": (f"pair_style thornton/yin paths generic\n"
                                 f"pair_coeff * * {E} {NU} {MU} 0.0\n"),
    "granular jkr+mindlin": (f"pair_style granular\npair_coeff * * jkr {E} 0.0 {NU} {GAMMA} "
                             f"damping viscoelastic tangential mindlin NULL 0.0 {MU}\n"),
    "granular hertz/material+mindlin": (
        f"pair_style granular\npair_coeff * * hertz/material {E} 0.0 {NU} "
        f"damping viscoelastic tangential mindlin NULL 0.0 {MU}\n"),
    "gran/hertz/history": (f"pair_style gran/hertz/history {KN_HOOKE_HERTZ} {KT_HOOKE_HERTZ} "
                           f"0.0 0.0 {MU} 0\npair_coeff * *\n"),
}


def deck(specimen, pair_lines, steps):
    return f"""{LOAD}read_restart {specimen}
comm_modify vel yes
{pair_lines}neighbor 1.35e-5 bin
neigh_modify every 1 delay 0 check yes
timestep $(0.2*PI*0.0675e-3*sqrt(2650e12/(70e9/2.6))/(0.1631*0.3+0.8766))
fix integrate all nve/sphere
thermo {steps}
run {steps}
"""


def run_case(specimen, name, steps, ranks, workdir, library=None):
    path = os.path.join(workdir, "in.bench")
    with open(path, "w") as fh:
        fh.write(deck(specimen, CASES[name], steps))
    cmd = ["lmp", "-in", path, "-log", "none", "-nocite"]
    if ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
    env = dict(os.environ)
    if library:
        env["TYLMP_LIBRARY"] = library
    out = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True, env=env).stdout
    m = re.search(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", out)
    if not m:
        raise RuntimeError(f"{name}: no loop time\n{out[-2000:]}")
    loop, nsteps, natoms = float(m.group(1)), int(m.group(2)), int(m.group(3))
    pair = re.search(r"^Pair\s*\|\s*[0-9.]+\s*\|\s*([0-9.]+)", out, re.M)
    return loop, natoms * nsteps / loop, float(pair.group(1)) if pair else float("nan")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--specimen", default=os.path.join(REPO, "tylmp_specimens", "dense_quick.restart"))
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--cases", nargs="*", default=list(CASES))
    ap.add_argument("--out", default=os.path.join(REPO, "bench", "results", "pair_speed"))
    ap.add_argument("--variant", action="append", default=[],
                    help="NAME=PATH of a tylmp.so build; thornton/yin cases run once per variant")
    args = ap.parse_args(argv)
    variants = [tuple(v.split("=", 1)) for v in args.variant]
    runs = []    # (label, case, library)
    for name in args.cases:
        if variants and name.startswith("thornton/yin"):
            runs += [(f"{name} [{vn}]", name, os.path.abspath(lib)) for vn, lib in variants]
        else:
            runs.append((name, name, os.path.abspath(variants[0][1]) if variants else None))
    specimen = os.path.abspath(args.specimen)
    if not os.path.exists(specimen):
        sys.exit(f"no specimen {specimen}: run 'lmp -in inputs/axisym.in' once from the "
                 "repository root (it prepares tylmp_specimens/dense_quick.restart)")
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for rep in range(args.repeats):
            for label, name, library in runs:
                loop, rate, pair = run_case(specimen, name, args.steps, args.ranks, work, library)
                rows.append({"case": label, "repeat": rep, "ranks": args.ranks,
                             "loop_s": loop, "atom_steps_per_s": rate, "pair_s": pair})
                print(f"  {label:44s} run {rep}: {rate:.4g} atom-steps/s", flush=True)
    with open(args.out + ".csv", "w") as fh:
        fh.write("case,repeat,ranks,loop_s,atom_steps_per_s,pair_s\n")
        for r in rows:
            fh.write(f"{r['case']},{r['repeat']},{r['ranks']},{r['loop_s']},"
                     f"{r['atom_steps_per_s']},{r['pair_s']}\n")
    medians = {label: statistics.median(r["atom_steps_per_s"] for r in rows if r["case"] == label)
               for label, _, _ in runs}
    base = medians.get("thornton/yin G=0.6") or medians.get(
        f"thornton/yin G=0.6 [{variants[0][0]}]" if variants else "")
    speedups = {}
    if len(variants) > 1:
        for name in args.cases:
            if not name.startswith("thornton/yin"):
                continue
            first = f"{name} [{variants[0][0]}]"
            for vn, _ in variants[1:]:
                label = f"{name} [{vn}]"
                ratios = [a["loop_s"] / b["loop_s"]
                          for a in rows if a["case"] == first
                          for b in rows if b["case"] == label and b["repeat"] == a["repeat"]]
                speedups[label] = statistics.median(ratios)
    summary = {"specimen": specimen, "steps": args.steps, "repeats": args.repeats,
               "ranks": args.ranks, "median_atom_steps_per_s": medians,
               "ratio_to_thornton_yin_G0.6": {k: v / base for k, v in medians.items()} if base else {},
               "speedup_vs_first_variant": speedups}
    with open(args.out + ".json", "w") as fh:
        json.dump(summary, fh, indent=2)
    print(f"\n| case ({args.ranks} rank(s), {args.steps} steps, median of {args.repeats}) "
          f"| atom-steps/s | ratio to thornton/yin G=0.6 |\n|---|---|---|")
    for name, v in medians.items():
        print(f"| {name} | {v:.4g} | {v / base if base else float('nan'):.3f} |")
    if speedups:
        print(f"\n| variant | median per-repeat speed-up vs [{variants[0][0]}] |\n|---|---|")
        for label, v in speedups.items():
            print(f"| {label} | {v:.3f} |")


if __name__ == "__main__":
    main()
