#!/usr/bin/env python3
"""Compare the records of the YADE cross-check (docs/validation.md, "Axisymmetric compression against YADE"):
the LAMMPS run of bench/yade_axisym.in and the YADE run(s) of bench/yade_axisym.py, all in the
fix cell/servo column layout.

    /usr/bin/python3 bench/yade_compare.py --ref LABEL=CSV --other LABEL=CSV [--other ...]
        [--out bench/results/yade_axisym]

Writes OUT.json (per run: the secant q/(eps1 - eps3) at 0.001 %, q at eps1 - eps3 = 0.01 %,
0.1 % and 0.285 %, peak sinphi, the strain where it occurs and the strain range where sinphi
is within 1 % of it, eps_v at 5 % and 10 %, the largest dilation rate -d eps_v/d(eps1 - eps3)
over intervals of 0.25 % and where, Z and Zm at 0, 1, 5 and 10 %, the range of p past 0.5 %;
and every other run's differences from --ref), OUT_curves.csv (q/p, eps_v, Z, Zm against eps1 - eps3 of
every run, one long table: run, eps_d13, q_over_p, eps_v, Z, Zm) and OUT.png (q/p, eps_v, Z
against eps1 - eps3, and q over the first 0.05 %). A response a run does not reach is null.
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

NEEDED = ("step", "time", "eps1", "eps2", "eps3", "sig1", "sig2", "sig3", "Z", "Zm")
Q_AT = (0.0001, 0.001, 0.00285)  # eps1 - eps3 of the initial-stiffness responses (0.285 %: the paper's pre-strain)
EPS_V_AT = (0.05, 0.10)
Z_AT = (0.0, 0.01, 0.05, 0.10)
DILATION_STEP = 0.0025      # intervals of eps1 - eps3 for the dilation rate
EARLY_PCT = 0.05            # the small-strain panel of the figure: q over the first 0.05 %


def responses(path):
    t = read_servo_csv(path, require=NEEDED)
    d = metrics.derived(t)
    ed, q, s, ev = d["eps_d13"], d["q"], d["sinphi"], d["eps_v"]
    i = int(np.nanargmax(s))
    out = {"file": os.path.relpath(path, REPO), "rows": len(t), "steps": int(t["step"][-1]),
           "dt": float(t["time"][-1] / t["step"][-1]) if t["step"][-1] > 0 else None,
           "eps_d13_end_pct": float(ed[-1] * 100),
           "sinphi_max": float(s[i]), "eps_d13_at_sinphi_max_pct": float(ed[i] * 100),
           "peak_inside_record": bool(i < len(s) - 1),
           # the peak is broad: the strain range over which sinphi stays within 1 % of its maximum
           "eps_d13_sinphi_within_1pct_from_pct": float(ed[np.argmax(s >= 0.99 * s[i])] * 100),
           "eps_d13_sinphi_within_1pct_to_pct": float(ed[len(s) - 1 - np.argmax(s[::-1] >= 0.99 * s[i])] * 100),
           "p_min_kPa": float(np.min(d["p"]) / 1e3), "p_max_kPa": float(np.max(d["p"]) / 1e3),
           "p_past_0.5pct_min_kPa": float(np.min(d["p"][ed > 0.005]) / 1e3),
           "p_past_0.5pct_max_kPa": float(np.max(d["p"][ed > 0.005]) / 1e3),
           "lateral_mismatch_max_kPa": float(np.max(np.abs(t["sig2"] - t["sig3"])) / 1e3)}
    v = metrics.value_at(ed, q, 1e-5)
    out["secant_q_over_eps_d13_at_0.001pct_MPa"] = None if v is None else v / 1e-5 / 1e6
    for x in Q_AT:
        v = metrics.value_at(ed, q, x)
        out[f"q_at_{x * 100:g}pct_kPa"] = None if v is None else v / 1e3
    for x in EPS_V_AT:
        v = metrics.value_at(ed, ev, x)
        out[f"eps_v_at_{x * 100:g}pct_pct"] = None if v is None else v * 100
    grid = np.arange(0.0, ed[-1], DILATION_STEP)
    mono = np.maximum.accumulate(ed)
    rate = -np.diff(np.interp(grid, mono, ev)) / DILATION_STEP
    x_mid = 0.5 * (grid[1:] + grid[:-1])
    k = int(np.argmax(rate))
    out["dilation_rate_max"] = float(rate[k])
    out["eps_d13_at_dilation_rate_max_pct"] = float(x_mid[k] * 100)
    for x in Z_AT:
        for col in ("Z", "Zm"):
            out[f"{col}_at_{x * 100:g}pct"] = metrics.value_at(ed, t[col], x) if x > 0 else float(t[col][0])
    return out, {"eps_d13": ed, "q_over_p": q / d["p"], "q": q, "eps_v": ev, "Z": t["Z"], "Zm": t["Zm"]}


def differences(ref, other):
    out = {}
    for k, v in other.items():
        r = ref.get(k)
        if isinstance(v, float) and isinstance(r, float) and k not in ("dt",):
            out[k] = {"diff": v - r, "rel": (v - r) / r if r else None}
    return out


def plot(curves, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 2, figsize=(10, 7.5))
    for k, (label, c) in enumerate(curves.items()):
        x, col = 100 * c["eps_d13"], f"C{k}"
        ax[0, 0].plot(x, c["q_over_p"], lw=0.8, color=col, label=label)
        ax[0, 1].plot(x, 100 * c["eps_v"], lw=0.8, color=col, label=label)
        ax[1, 0].plot(x, c["Z"], lw=0.8, color=col, label=f"{label} Z")
        ax[1, 0].plot(x, c["Zm"], lw=0.8, color=col, ls="--", label=f"{label} Z_m")
        early = x <= EARLY_PCT
        ax[1, 1].plot(x[early], c["q"][early] / 1e3, lw=0.8, color=col, label=label)
    ax[0, 0].set_ylabel("q/p")
    ax[0, 1].set_ylabel("ε_v (%), compression > 0")
    ax[1, 0].set_ylabel("coordination")
    ax[1, 1].set_ylabel("q (kPa)")
    ax[1, 1].set_xlabel(f"ε1 − ε3 (%), first {EARLY_PCT:g} %")
    for a in ax.flat:
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
        if a is not ax[1, 1]:
            a.set_xlabel("ε1 − ε3 (%)")
    fig.suptitle("Dense paper specimen, axisymmetric compression, p = 100 kPa, Γ = 0, μ = 0.3, "
                 "ε̇1 = 5e-5 1/s, no damping", fontsize=9)
    save_figure(fig, png, dpi=120)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ref", required=True, help="LABEL=CSV of the reference run (ours)")
    ap.add_argument("--other", action="append", required=True, help="LABEL=CSV (repeatable)")
    ap.add_argument("--out", default=os.path.join(REPO, "bench", "results", "yade_axisym"))
    a = ap.parse_args(argv)
    runs = [a.ref] + a.other
    if any("=" not in r for r in runs):
        ap.error("runs are given as LABEL=CSV")
    labels = [r.split("=", 1)[0] for r in runs]
    results, curves = {}, {}
    for r in runs:
        label, path = r.split("=", 1)
        results[label], curves[label] = responses(path)
    ref = labels[0]
    summary = {"reference": ref, "runs": results,
               "differences_from_reference": {k: differences(results[ref], results[k])
                                              for k in labels[1:]}}
    write_result(a.out + ".json", summary)
    tmp = a.out + "_curves.csv.tmp"
    with open(tmp, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(["run", "eps_d13", "q_over_p", "eps_v", "Z", "Zm"])
        for label, c in curves.items():
            for row in zip(c["eps_d13"], c["q_over_p"], c["eps_v"], c["Z"], c["Zm"]):
                w.writerow([label] + [repr(float(v)) for v in row])
    os.replace(tmp, a.out + "_curves.csv")
    plot(curves, a.out + ".png")
    keys = [k for k in results[ref] if k not in ("file",)]
    print("response".ljust(28) + "".join(lbl.rjust(18) for lbl in labels))
    for k in keys:
        vals = [results[lbl].get(k) for lbl in labels]
        print(k.ljust(28) + "".join((f"{v:18.5g}" if isinstance(v, float) else f"{str(v):>18}")
                                     for v in vals))


if __name__ == "__main__":
    main()
