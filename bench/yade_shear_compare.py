#!/usr/bin/env python3
"""Compare the records of the simple-shear cross-check against YADE (docs/validation.md,
"Simple shear against YADE"): LAMMPS runs of bench/yade_simple_shear.in (fix cell/servo shear
xz) and YADE runs of bench/yade_simple_shear.py, each a record with the columns gamma, tau,
sig_n, tau_ratio and eps_v.

    /usr/bin/python3 bench/yade_shear_compare.py --ref LABEL=CSV --other LABEL=CSV [--other ...]
        [--pair A,B ...] [--gamma-end 0.10] [--out bench/results/yade_simple_shear]

Per run: the peak of tau/sigma_n averaged over gamma windows of 0.5 % (and of the rows
themselves), the gamma where it occurs and the gamma range where the average stays within 1 %
of it (the peak of a dense specimen is broad), the gamma where the average first comes within
2 % of its peak (the peak's onset, gamma_at_98pct_of_peak_pct), eps_v (compression positive) at
gamma = --gamma-end or, for a run that stops short, at the largest gamma it reached (the key
eps_v_at_gamma_end_pct, with gamma_eps_v_pct saying where it was read), tau/sigma_n averaged
over gamma from 2 % to that gamma (tau_ratio_mean_from_2pct), the largest dilatancy
-d eps_v/d gamma (over intervals of 0.5 % of gamma), and the range of sigma_n past gamma = 0.5 %;
every other run's differences from --ref, and for each --pair A,B the differences of A from B
with the largest |eps_v(A) - eps_v(B)| over the gamma both reached. Writes OUT.json, OUT_curves.csv (run, gamma,
tau_ratio, eps_v, sig_n) and OUT.png (tau/sigma_n, eps_v, sigma_n against gamma; a run
labelled yade... dashed, in the colour of the run labelled ours... with the same suffix).
"""
import argparse
import csv
import os
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
from tylmp.analysis import metrics  # noqa: E402
from tylmp.analysis.figures import save_figure  # noqa: E402
from tylmp.analysis.io import read_servo_csv  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import write_result  # noqa: E402

NEEDED = ("step", "gamma", "tau", "sig_n", "tau_ratio", "eps_v")
DILATANCY_STEP = 0.005        # intervals of gamma for -d eps_v / d gamma
WITHIN = 0.01                 # the peak's plateau: tau/sigma_n within 1 % of its maximum
SMOOTH, FINE = 0.005, 1e-5    # the window in gamma of the averaged tau/sigma_n, its grid
ONSET = 0.02                  # the peak's onset: the average within 2 % of its maximum
MEAN_FROM = 0.02              # tau/sigma_n is averaged from this gamma to the end of reading


def responses(path, gamma_end=0.10):
    t = read_servo_csv(path, require=NEEDED)
    g, r, ev, sn = (np.asarray(t[c], float) for c in ("gamma", "tau_ratio", "eps_v", "sig_n"))
    # the peak of tau/sigma_n averaged over gamma windows of SMOOTH (a 500-sphere record
    # fluctuates by +-0.02 from row to row; its largest row is the largest fluctuation)
    fine = np.arange(0.0, g[-1] + 0.5 * FINE, FINE)
    half = int(round(0.5 * SMOOTH / FINE))
    kernel = np.ones(2 * half + 1) / (2 * half + 1)
    smooth = np.convolve(np.interp(fine, g, r), kernel, mode="same")
    inside = np.arange(len(fine))
    inside = (inside >= half) & (inside < len(fine) - half)
    fine, smooth = fine[inside], smooth[inside]
    i = int(np.nanargmax(smooth))
    near = np.nonzero(smooth >= (1 - WITHIN) * smooth[i])[0]
    row = int(np.nanargmax(r))
    g_read = min(gamma_end, float(g[-1]))
    out = {"file": os.path.relpath(os.path.abspath(path), REPO), "rows": len(t),
           "steps": int(t["step"][-1]), "gamma_end_pct": float(g[-1] * 100),
           "tau_ratio_max": float(smooth[i]), "gamma_at_tau_ratio_max_pct": float(fine[i] * 100),
           "peak_inside_record": bool(i < len(smooth) - 1),
           "gamma_within_1pct_of_peak_from_pct": float(fine[near[0]] * 100),
           "gamma_within_1pct_of_peak_to_pct": float(fine[near[-1]] * 100),
           # the onset of the peak: where the average first comes within ONSET of it (the
           # maximum itself may sit on either end of a plateau: two near-equal maxima at 2 and
           # 9.4 % in one 500-sphere record)
           "gamma_at_98pct_of_peak_pct": float(fine[np.argmax(smooth >= (1 - ONSET) * smooth[i])] * 100),
           "tau_ratio_max_row": float(r[row]), "gamma_at_tau_ratio_max_row_pct": float(g[row] * 100),
           "gamma_eps_v_pct": g_read * 100,
           "eps_v_at_gamma_end_pct": metrics.value_at(g, ev, g_read) * 100}
    # the level past the peak's rise: tau/sigma_n averaged uniformly in gamma over 2 % to the
    # gamma where eps_v is read (a record that stops before 2 % has none)
    if g_read > MEAN_FROM:
        span = np.linspace(MEAN_FROM, g_read, 2001)
        out["tau_ratio_mean_from_2pct"] = float(np.trapz(np.interp(span, g, r), span) / (g_read - MEAN_FROM))
    past = g > 0.005
    if np.any(past):
        out["sig_n_past_0.5pct_min_kPa"] = float(np.min(sn[past]) / 1e3)
        out["sig_n_past_0.5pct_max_kPa"] = float(np.max(sn[past]) / 1e3)
    grid = np.arange(0.0, g[-1], DILATANCY_STEP)
    if len(grid) > 1:
        rate = -np.diff(np.interp(grid, g, ev)) / DILATANCY_STEP
        k = int(np.argmax(rate))
        out["dilatancy_max"] = float(rate[k])
        out["gamma_at_dilatancy_max_pct"] = float(0.5 * (grid[k] + grid[k + 1]) * 100)
    return out, {"gamma": g, "tau_ratio": r, "eps_v": ev, "sig_n": sn}


def differences(ref, other):
    out = {}
    for k, v in other.items():
        r = ref.get(k)
        if isinstance(v, float) and isinstance(r, float):
            out[k] = {"diff": v - r, "rel": (v - r) / r if r else None}
    return out


def pair_differences(results, curves, a, b):
    """Run a minus run b: every response, and the largest |eps_v(a) - eps_v(b)| over the gamma
    both reached (on a grid of 0.01 %)."""
    out = {k: v["diff"] for k, v in differences(results[b], results[a]).items()}
    g = np.arange(0.0, min(curves[a]["gamma"][-1], curves[b]["gamma"][-1]), 1e-4)
    dev = np.interp(g, curves[a]["gamma"], curves[a]["eps_v"]) - np.interp(g, curves[b]["gamma"], curves[b]["eps_v"])
    out["eps_v_max_abs_diff_pct"] = float(np.max(np.abs(dev)) * 100)
    return out


def plot(curves, png, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    # a YADE run (label starting 'yade') dashed, in the colour of the run of ours whose label
    # it repeats with 'ours' for 'yade'
    colours = {}
    for label, c in curves.items():
        key = "ours" + label[4:] if label.startswith("yade") else label
        col = colours.setdefault(key, f"C{len(colours)}")
        style = dict(lw=0.8, color=col, label=label, ls="--" if label.startswith("yade") else "-")
        x = 100 * c["gamma"]
        ax[0].plot(x, c["tau_ratio"], **style)
        ax[1].plot(x, 100 * c["eps_v"], **style)
        ax[2].plot(x, c["sig_n"] / 1e3, **style)
    ax[0].set_ylabel("τ/σn")
    ax[1].set_ylabel("ε_v (%), compression > 0")
    ax[2].set_ylabel("σn (kPa)")
    for a in ax:
        a.set_xlabel("γ (%)")
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    fig.suptitle(title, fontsize=9)
    save_figure(fig, png, dpi=110)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ref", required=True, help="LABEL=CSV of the reference run (ours)")
    ap.add_argument("--other", action="append", required=True, help="LABEL=CSV (repeatable)")
    ap.add_argument("--pair", action="append", default=[],
                    help="A,B: the differences of run A from run B (labels; repeatable)")
    ap.add_argument("--gamma-end", type=float, default=0.10, help="gamma where eps_v is read")
    ap.add_argument("--title", default="simple shear at constant σn, Γ = 0, μ = 0.3, no damping")
    ap.add_argument("--out", default=os.path.join(REPO, "bench", "results", "yade_simple_shear"))
    a = ap.parse_args(argv)
    runs = [a.ref] + a.other
    if any("=" not in r for r in runs):
        ap.error("runs are given as LABEL=CSV")
    labels = [r.split("=", 1)[0] for r in runs]
    if len(set(labels)) != len(labels):
        ap.error(f"labels must differ: {labels}")
    results, curves = {}, {}
    for r in runs:
        label, path = r.split("=", 1)
        results[label], curves[label] = responses(path, a.gamma_end)
    ref = labels[0]
    summary = {"reference": ref, "gamma_end": a.gamma_end, "runs": results,
               "differences_from_reference": {k: differences(results[ref], results[k])
                                              for k in labels[1:]}}
    pairs = [p.split(",") for p in a.pair]
    for p in pairs:
        if len(p) != 2 or any(x not in results for x in p):
            ap.error(f"--pair A,B names two runs of {labels}, got {','.join(p)!r}")
    summary["pairs"] = {f"{x} - {y}": pair_differences(results, curves, x, y) for x, y in pairs}
    write_result(a.out + ".json", summary)
    tmp = a.out + "_curves.csv.tmp"
    with open(tmp, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(["run", "gamma", "tau_ratio", "eps_v", "sig_n"])
        for label, c in curves.items():
            for row in zip(c["gamma"], c["tau_ratio"], c["eps_v"], c["sig_n"]):
                w.writerow([label] + [repr(float(v)) for v in row])
    os.replace(tmp, a.out + "_curves.csv")
    plot(curves, a.out + ".png", a.title)
    shown = ("tau_ratio_max", "gamma_at_tau_ratio_max_pct", "gamma_at_98pct_of_peak_pct",
             "tau_ratio_mean_from_2pct",
             "eps_v_at_gamma_end_pct", "eps_v_max_abs_diff_pct")
    for name, d in summary["pairs"].items():
        print(name.ljust(32) + "".join(f"  {k} {d[k]:+.4g}" for k in shown if k in d))
    keys = [k for k in results[ref] if k != "file"]
    print("response".ljust(36) + "".join(lbl.rjust(16) for lbl in labels))
    for k in keys:
        vals = [results[lbl].get(k) for lbl in labels]
        print(k.ljust(36) + "".join((f"{v:16.5g}" if isinstance(v, float) else f"{str(v):>16}")
                                     for v in vals))


if __name__ == "__main__":
    main()
