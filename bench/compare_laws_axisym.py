#!/usr/bin/env python3
"""The paper's axisymmetric test at constant p under fix cell/servo with four contact laws, on
one specimen (docs/comparison.md, "The four laws under fix cell/servo").

    /usr/bin/python3 bench/compare_laws_axisym.py [--strain 0.03] [--rate 5e-5]
        [--cases NAME ...] [--out bench/results/compare_laws_axisym] [--figure PNG]

Since fix cell/servo works with any granular pair style (docs/theory.md §6.5), every law runs
the same test the same way: the committed 3620-sphere dense specimen at 100 kPa
(bench/data/dense_paper_100kPa.data, fresh contacts), mu = 0.3, no damping, the time step of
the decks, `fix cell/servo axisym x RATE 1e5` to eps1 - eps3 = STRAIN. The laws are those of
bench/pair_speed.py (CASES; the same parameters as its speed comparison): thornton/yin at
Gamma = 0.6 and 0, LAMMPS `granular jkr` and `hertz/material` with `tangential mindlin`, and
`gran/hertz/history`. thornton/yin adds the affine contact velocity of the deforming cell, the
built-in styles do not (docs/theory.md §5.2). Writes PREFIX.json (peak and end values, initial
stiffness) and the figure (q/p and eps_v against eps1 - eps3).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pair_speed import CASES, DT, LOAD, NEIGHBOR, REPO  # noqa: E402
from provenance import stamp, write_result  # noqa: E402
sys.path.insert(0, os.path.join(REPO, "python"))
from tylmp.analysis.figures import save_figure  # noqa: E402

LAWS = ["thornton/yin G=0.6", "granular jkr+mindlin", "thornton/yin G=0",
        "granular hertz/material+mindlin", "gran/hertz/history"]
SPECIMEN = os.path.join(REPO, "bench", "data", "dense_paper_100kPa.data")
STYLE = {"thornton/yin G=0.6": ("k", "-"), "granular jkr+mindlin": ("k", "--"),
         "thornton/yin G=0": ("tab:blue", "-"), "granular hertz/material+mindlin": ("tab:blue", "--"),
         "gran/hertz/history": ("tab:red", ":")}


def deck(law, rate, strain, every):
    return (f"{LOAD}units si\natom_style sphere\nboundary p p p\ncomm_modify vel yes\n"
            f"read_data {SPECIMEN}\n{CASES[law]}{NEIGHBOR}timestep {DT!r}\n"
            "fix integrate all nve/sphere\n"
            f"fix cell all cell/servo axisym x {rate!r} 1e5 until eps_d13 {strain!r} "
            f"csv rec.csv {every}\n"
            "thermo 5000\n"
            f"run {int(1.2 * strain / (1.5 * rate * DT)) + 1000}\n")


def run(law, args, work):
    os.makedirs(work, exist_ok=True)
    with open(os.path.join(work, "in.law"), "w") as fh:
        fh.write(deck(law, args.rate, args.strain, args.every))
    proc = subprocess.run(["lmp", "-in", "in.law", "-log", "log.lammps", "-nocite"], cwd=work,
                          capture_output=True, text=True)
    if proc.returncode != 0 or "ERROR" in proc.stdout:
        sys.exit(f"compare_laws_axisym: {law} failed:\n{proc.stdout[-3000:]}{proc.stderr}")
    return np.genfromtxt(os.path.join(work, "rec.csv"), delimiter=",", names=True)


def summary_of(rec):
    d, q, p, ev = rec["eps_d13"], rec["sig1"] - rec["sig3"], rec["p"], rec["eps_v"]
    k = int(np.argmax(rec["sinphi"]))
    at = {s: float(np.interp(s, d, q / p)) for s in (0.002, 0.01, 0.02) if s <= d[-1]}
    early = d <= 2e-4
    return {"sinphi_max": float(rec["sinphi"][k]), "eps_d13_at_peak": float(d[k]),
            "q_over_p_at": at, "eps_v_end": float(ev[-1]), "eps_d13_end": float(d[-1]),
            "initial_stiffness_MPa": float(np.polyfit(d[early], q[early], 1)[0] / 1e6)
            if early.sum() > 2 else None,
            "p_rms_deviation_kPa": float(np.sqrt(np.mean((p[d > 0.002] - 1e5) ** 2)) / 1e3)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--strain", type=float, default=0.03)
    ap.add_argument("--rate", type=float, default=5e-5)
    ap.add_argument("--every", type=int, default=50)
    ap.add_argument("--cases", nargs="+", default=LAWS, choices=LAWS)
    ap.add_argument("--out", default=os.path.join(REPO, "bench", "results", "compare_laws_axisym"))
    ap.add_argument("--figure", default=os.path.join(REPO, "docs", "comparison_laws_axisym.png"))
    args = ap.parse_args(argv)
    records, table = {}, {}
    provenance = stamp()    # the code and machine of the runs, not of the moment they end
    with tempfile.TemporaryDirectory() as tmp:
        for n, law in enumerate(args.cases):
            print(f"compare_laws_axisym: {law}", flush=True)
            records[law] = run(law, args, os.path.join(tmp, str(n)))
            table[law] = summary_of(records[law])
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    for law, rec in records.items():
        colour, dash = STYLE[law]
        a1.plot(100 * rec["eps_d13"], (rec["sig1"] - rec["sig3"]) / rec["p"], color=colour,
                ls=dash, label=law)
        a2.plot(100 * rec["eps_d13"], 100 * rec["eps_v"], color=colour, ls=dash, label=law)
    a1.set(xlabel="ε1 − ε3 (%)", ylabel="q/p, q = σ1 − σ3",
           title=f"3620 spheres, p = 100 kPa, ε̇1 = {args.rate:g} 1/s, μ = 0.3")
    a2.set(xlabel="ε1 − ε3 (%)", ylabel="ε_v (%), compression positive")
    a1.legend(fontsize=8)
    save_figure(fig, args.figure)
    write_result(args.out + ".json", {"specimen": SPECIMEN, "strain": args.strain,
                                      "rate": args.rate, "timestep": DT, "laws": table,
                                      "provenance": provenance})
    print(f"\n| law | sinφ_max | at ε1−ε3 | q/p at 1 % | ε_v at {100 * args.strain:g} % | "
          "initial q/ε (MPa) | p rms dev (kPa) |\n|---|---|---|---|---|---|---|")
    for law, s in table.items():
        stiff = s["initial_stiffness_MPa"]
        print(f"| {law} | {s['sinphi_max']:.4f} | {100 * s['eps_d13_at_peak']:.2f} % | "
              f"{s['q_over_p_at'].get(0.01, float('nan')):.4f} | {100 * s['eps_v_end']:.3f} % | "
              f"{'—' if stiff is None else f'{stiff:.0f}'} | {s['p_rms_deviation_kPa']:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
