#!/usr/bin/env python3
"""Two adhesive spheres pressed together and pulled apart (inputs/two_spheres.in) with
pair thornton/yin and with LAMMPS's `pair granular jkr`: the normal force against overlap,
plotted together (docs/comparison.md).

    /usr/bin/python3 bench/compare_normal_cycle.py [--out docs/comparison_normal_cycle.png]
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
sys.path.insert(0, os.path.join(REPO, "analysis"))
from tyanalysis.figures import save_figure  # noqa: E402
GAMMA, R_STAR = 0.3, 0.5e-4
PC = 3 * np.pi * GAMMA * R_STAR
GRANULAR = ("pair_style granular\npair_coeff * * jkr 70e9 0.0 0.3 ${Gamma} "
            "damping viscoelastic tangential linear_nohistory 0.0 0.0\n")


def run(deck_text, work, name):
    path = os.path.join(work, f"{name}.in")
    with open(path, "w") as fh:
        fh.write(deck_text)
    out = subprocess.run(["lmp", "-in", path, "-var", "out", name, "-log", "none"], cwd=work,
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
    args = ap.parse_args(argv)
    with open(os.path.join(REPO, "inputs", "two_spheres.in")) as fh:
        ours = fh.read()
    theirs = re.sub(r"pair_style thornton/yin\npair_coeff .*\n", GRANULAR, ours)
    with tempfile.TemporaryDirectory() as work:
        a, err_a = run(ours, work, "thornton_yin")
        b, err_b = run(theirs, work, "granular_jkr")
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for d, label in ((a, "pair thornton/yin"), (b, "pair granular jkr")):
        ax.plot(d["overlap"] * 1e9, d["normal_force"] / PC, label=label)
    ax.axhline(-5 / 9, ls=":", c="grey")
    ax.axhline(-1, ls=":", c="grey")
    ax.set_xlabel("overlap δ [nm]")
    ax.set_ylabel("normal force P / Pc")
    ax.set_xlim(-6, 20)
    ax.set_ylim(-1.2, 2)
    ax.legend()
    ax.set_title(f"Γ = {GAMMA} J/m², R* = 0.05 mm, E = 70 GPa, ν = 0.3")
    save_figure(fig, args.out)
    for name, d, err in (("thornton/yin", a, err_a), ("granular jkr", b, err_b)):
        s = summary(d)
        print(f"{name}: snap-on {s['snap_on_force_Pc']:.4f} Pc, minimum {s['min_force_Pc']:.4f} Pc, "
              f"last contact {s['break_force_Pc']:.4f} Pc at {s['break_overlap_m']:.3g} m"
              + (f"; {err}" if err else ""))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
