#!/usr/bin/env python3
"""Two adhesive spheres pressed together and pulled apart (inputs/two_spheres.in) with
pair thornton/yin and with LAMMPS's `pair granular jkr`: the normal force against overlap,
plotted together (docs/comparison.md).

    /usr/bin/python3 bench/compare_normal_cycle.py [--out docs/comparison_normal_cycle.png]
        [--lmp2025 WRAPPER] [--json bench/results/compare_normal_cycle.json]

With --lmp2025 (the lmp of LAMMPS 4 Feb 2025 named on the last line of
`bash scripts/lammps2025.sh`) both styles also run under LAMMPS 4 Feb 2025: its `granular jkr`
joins the figure, and the summary of every run goes to --json.
"""
import argparse
import os
import re
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
from provenance import write_result  # noqa: E402
GAMMA, R_STAR = 0.3, 0.5e-4
PC = 3 * np.pi * GAMMA * R_STAR
GRANULAR = ("pair_style granular\npair_coeff * * jkr 70e9 0.0 0.3 ${Gamma} "
            "damping viscoelastic tangential linear_nohistory 0.0 0.0\n")


def run(deck_text, work, name, lmp="lmp"):
    path = os.path.join(work, f"{name}.in")
    with open(path, "w") as fh:
        fh.write(deck_text)
    out = subprocess.run([lmp, "-in", path, "-var", "out", name, "-log", "none"], cwd=work,
                         capture_output=True, text=True).stdout
    data = np.genfromtxt(os.path.join(work, f"{name}.csv"), delimiter=",", names=True)
    error = re.search(r"ERROR.*", out)
    return data, error.group(0) if error else None


def summary(data):
    touching = np.flatnonzero(data["normal_force"] != 0.0)
    return {"snap_on_force_Pc": data["normal_force"][touching[0]] / PC,
            "min_force_Pc": data["normal_force"].min() / PC,
            "break_force_Pc": data["normal_force"][touching[-1]] / PC,
            "break_overlap_m": data["overlap"][touching[-1]]}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(REPO, "docs", "comparison_normal_cycle.png"))
    ap.add_argument("--lmp2025", metavar="WRAPPER",
                    help="also run both styles with this lmp of LAMMPS 4 Feb 2025")
    ap.add_argument("--json", default=os.path.join(REPO, "bench", "results",
                                                   "compare_normal_cycle.json"),
                    help="summary of every run (written with --lmp2025)")
    args = ap.parse_args(argv)
    with open(os.path.join(REPO, "inputs", "two_spheres.in")) as fh:
        ours = fh.read()
    theirs = re.sub(r"pair_style thornton/yin\npair_coeff .*\n", GRANULAR, ours)
    runs = [("thornton/yin", ours, "lmp", "pair thornton/yin", "-"),
            ("granular jkr", theirs, "lmp", "pair granular jkr (29 Sep 2021)", "-")]
    if args.lmp2025:
        runs += [("thornton/yin @4Feb2025", ours, os.path.abspath(args.lmp2025), None, None),
                 ("granular jkr @4Feb2025", theirs, os.path.abspath(args.lmp2025),
                  "pair granular jkr (4 Feb 2025)", "--")]
    results = {}
    with tempfile.TemporaryDirectory() as work:
        for k, (name, text, lmp, _, _) in enumerate(runs):
            results[name] = run(text, work, f"run{k}", lmp)
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for name, _, _, label, style in runs:
        if label:
            d = results[name][0]
            ax.plot(d["overlap"] * 1e9, d["normal_force"] / PC, style, label=label)
    ax.axhline(-5 / 9, ls=":", c="grey")
    ax.axhline(-1, ls=":", c="grey")
    ax.set_xlabel("overlap δ [nm]")
    ax.set_ylabel("normal force P / Pc")
    ax.set_xlim(-6, 20)
    ax.set_ylim(-1.2, 2)
    ax.legend()
    ax.set_title(f"Γ = {GAMMA} J/m², R* = 0.05 mm, E = 70 GPa, ν = 0.3")
    save_figure(fig, args.out)
    table = {}
    for name, (d, err) in results.items():
        s = summary(d)
        table[name] = dict(s, error=err)
        print(f"{name}: snap-on {s['snap_on_force_Pc']:.4f} Pc, minimum {s['min_force_Pc']:.4f} Pc, "
              f"last contact {s['break_force_Pc']:.4f} Pc at {s['break_overlap_m']:.3g} m"
              + (f"; {err}" if err else ""))
    if args.lmp2025:
        same = np.array_equal(results["thornton/yin"][0]["normal_force"],
                              results["thornton/yin @4Feb2025"][0]["normal_force"])
        print(f"thornton/yin: 29 Sep 2021 and 4 Feb 2025 records identical: {same}")
        write_result(args.json, {"Pc_N": PC, "Gamma": GAMMA, "R_star_m": R_STAR,
                               "thornton_yin_identical_across_versions": bool(same),
                               "runs": table}, indent=2)
        print(f"wrote {args.json}")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
