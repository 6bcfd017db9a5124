#!/usr/bin/env python3
"""Speed against error at test level: the dense axisymmetric test (inputs/axisym.in) at several
strain rates and timestep fractions, each to the same deviator strain, against the slowest run.

    /usr/bin/python3 bench/rate_error.py --specimen DIR/tylmp_specimens [--scale paper]
        [--runs 1e-5:0.2 2e-5:0.2 ...] [--strain 0.10] [--jobs 1]
        [--out bench/results/rate_error] [--plot docs/performance_rate_error.png]

Every run is `lmp -in inputs/axisym.in -var scale SCALE -var rate RATE -var dt_fraction F
-var strain STRAIN` in its own directory under --work, the specimen directory linked in, so all
runs shear the same packing. Measured per run: wall time of the lmp process, the median
inertial number, the peak sin(phi) and eps_v at the end strain (interpolated in eps1 - eps3),
and the mean |p - 100 kPa|. Errors are differences to the reference run (the smallest
rate x dt_fraction). A run already recorded in OUT.csv (same rate, dt_fraction, strain, scale)
is not repeated unless --force: the paper-scale reference takes about 20 minutes.
Writes OUT.csv (one row per run, appended as runs finish), OUT.json (with errors) and the plot.
"""
import argparse
import csv
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from lammps_log import loops  # noqa: E402

FIELDS = ["scale", "rate", "dt_fraction", "strain", "wall_s", "steps", "inertial_number",
          "sinphi_max", "eps_d13_at_peak", "eps_v_end", "p_dev_kPa"]
# rates at the decks' timestep, timesteps at 1e-4, and the runs that differ from another only
# by 0.01 t_R (the run-to-run scatter of docs/performance.md)
DEFAULT_RUNS = ["1e-5:0.2", "2e-5:0.2", "5e-5:0.2", "1e-4:0.2", "2e-4:0.2", "5e-4:0.2",
                "1e-3:0.2", "1e-4:0.1", "1e-4:0.3", "1e-4:0.4", "5e-5:0.19", "5e-5:0.21",
                "1e-5:0.19"]


def run_name(rate, frac):
    return f"rate{rate:g}_dt{frac:g}"


def measure(csv_path, strain):
    import numpy as np
    from tylmp.analysis.io import read_servo_csv as read_csv
    t = read_csv(csv_path)
    d13, sinphi = np.asarray(t["eps_d13"]), np.asarray(t["sinphi"])
    keep = d13 <= strain * (1 + 1e-9)
    k = int(np.argmax(np.where(keep, sinphi, -np.inf)))
    return {
        "sinphi_max": float(sinphi[k]),
        "eps_d13_at_peak": float(d13[k]),
        "eps_v_end": float(np.interp(strain, d13, np.asarray(t["eps_v"]))),
        "inertial_number": float(np.median(np.asarray(t["inertial_number"])[1:])),
        "p_dev_kPa": float(np.mean(np.abs(np.asarray(t["p"])[1:] - 1e5)) / 1e3),
        "steps": int(t["step"][-1] - t["step"][0]),
    }


def one_run(args, rate, frac):
    name = run_name(rate, frac)
    work = os.path.join(args.work, name)
    os.makedirs(work, exist_ok=True)
    for link, target in (("inputs", os.path.join(REPO, "inputs")),
                         ("tylmp_specimens", os.path.abspath(args.specimen))):
        path = os.path.join(work, link)
        if not os.path.lexists(path):
            os.symlink(target, path)
    record = os.path.join(work, name + ".csv")
    if args.reuse and os.path.exists(record):    # a finished run whose row was not written
        row = {"scale": args.scale, "rate": rate, "dt_fraction": frac, "strain": args.strain,
               "wall_s": logged_wall_time(os.path.join(work, "log.lammps"))}
        row.update(measure(record, args.strain))
        print(f"  {name}: reused ({row['wall_s']:.0f} s)", flush=True)
        return row
    cmd = ["lmp", "-in", "inputs/axisym.in", "-log", "log.lammps", "-screen", "none",
           "-var", "scale", args.scale, "-var", "specimen", "dense", "-var", "rate", f"{rate:g}",
           "-var", "dt_fraction", f"{frac:g}", "-var", "strain", f"{args.strain:g}",
           "-var", "out", name]
    start = time.monotonic()
    proc = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
    wall = time.monotonic() - start
    if proc.returncode != 0:
        raise RuntimeError(f"{name} failed:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    row = {"scale": args.scale, "rate": rate, "dt_fraction": frac, "strain": args.strain,
           "wall_s": wall}
    row.update(measure(os.path.join(work, name + ".csv"), args.strain))
    print(f"  {name}: {wall:.0f} s, I = {row['inertial_number']:.3g}, "
          f"sinphi_max {row['sinphi_max']:.4f}, eps_v {row['eps_v_end']:.5f}", flush=True)
    return row


def logged_wall_time(log):
    """'Total wall time: h:mm:ss' of a LAMMPS log, or the last 'Loop time' if the log has no
    total (a run that stopped with an error after its last step), in seconds."""
    import re
    text = open(log).read()
    found = re.findall(r"Total wall time: (\d+):(\d+):(\d+)", text)
    if found:
        h, m, sec = (int(x) for x in found[-1])
        return 3600 * h + 60 * m + sec
    runs = loops(text)
    if not runs:
        raise RuntimeError(f"{log}: neither 'Total wall time' nor 'Loop time'")
    return runs[-1]["seconds"]


def load_rows(path):
    if not os.path.exists(path):
        return []
    with open(path) as fh:
        return [{k: (v if k == "scale" else float(v)) for k, v in r.items()}
                for r in csv.DictReader(fh)]


def append_row(path, row):
    new = not os.path.exists(path)
    with open(path, "a") as fh:    # append-only: finished runs survive an interrupted study
        w = csv.DictWriter(fh, fieldnames=FIELDS)
        if new:
            w.writeheader()
        w.writerow({k: row[k] for k in FIELDS})


def same(r, scale, rate, frac, strain):
    return (r["scale"] == scale and abs(r["rate"] / rate - 1) < 1e-9
            and abs(r["dt_fraction"] / frac - 1) < 1e-9 and abs(r["strain"] / strain - 1) < 1e-9)


def with_errors(rows, reference=(1e-5, 0.2)):
    """Errors against the run at `reference` = (rate, dt_fraction) (the paper's rate at the
    decks' timestep), or the slowest run with the timestep nearest to it if that is missing."""
    ref = min(rows, key=lambda r: (abs(r["rate"] / reference[0] - 1) > 1e-9, r["rate"],
                                   abs(r["dt_fraction"] - reference[1])))
    out = []
    for r in rows:
        e = dict(r, reference=r is ref)
        e["error_sinphi_max"] = r["sinphi_max"] - ref["sinphi_max"]
        e["error_eps_v_end"] = r["eps_v_end"] - ref["eps_v_end"]
        e["relative_error_sinphi_max"] = e["error_sinphi_max"] / ref["sinphi_max"]
        e["relative_error_eps_v_end"] = e["error_eps_v_end"] / ref["eps_v_end"]
        e["speedup"] = ref["wall_s"] / r["wall_s"]
        out.append(e)
    return ref, out


def scatter_floor(rows, ref):
    """Run-to-run scatter: the spread of the runs that differ from another run only by a small
    change of the timestep (same rate), i.e. by a different but equally valid trajectory."""
    floors = [0.0, 0.0]
    for r in rows:
        for o in rows:
            if r is not o and r["rate"] == o["rate"] and 0 < abs(r["dt_fraction"] - o["dt_fraction"]) <= 0.02:
                for k, key in enumerate(("sinphi_max", "eps_v_end")):
                    floors[k] = max(floors[k], abs(r[key] - o[key]) / abs(ref[key]))
    return floors


def plot(rows, ref, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    noise = scatter_floor(rows, ref)
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for r in rows:
        if r["reference"]:
            continue
        marker = "o" if r["dt_fraction"] == ref["dt_fraction"] else "s"
        for k, key in enumerate(("relative_error_sinphi_max", "relative_error_eps_v_end")):
            y = max(abs(r[key]), 1e-4)
            ax[k].loglog(r["steps"], y, marker, color="C0" if marker == "o" else "C1")
            ax[k].annotate(f"{r['rate']:g}, {r['dt_fraction']:g}", (r["steps"], y),
                           fontsize=7, xytext=(3, 3), textcoords="offset points")
    for k, what in enumerate(("|error of peak sin φ| / sin φ", "|error of ε_v at end| / ε_v")):
        ax[k].axhline(noise[k], color="0.6", lw=0.8, ls="--")
        ax[k].set_xlabel(f"steps (cost; the reference took {ref['steps']:.0f} steps, "
                         f"{ref['wall_s'] / 60:.0f} min on 1 core)", fontsize=8)
        ax[k].set_ylabel(what)
        ax[k].grid(True, which="both", alpha=0.3)
    fig.suptitle(f"dense axisymmetric test to ε1-ε3 = {ref['strain']:g}: error against the run at "
                 f"rate {ref['rate']:g} 1/s, Δt = {ref['dt_fraction']:g} t_R\n"
                 f"(circles: Δt = {ref['dt_fraction']:g} t_R; squares: other Δt; labels: rate, Δt/t_R; "
                 f"dashed: run-to-run scatter)",
                 fontsize=8)
    from tylmp.analysis.figures import save_figure
    save_figure(fig, path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--specimen", required=True, help="directory holding dense_<scale>.restart")
    ap.add_argument("--scale", default="paper")
    ap.add_argument("--runs", nargs="*", default=DEFAULT_RUNS, help="RATE:DT_FRACTION ...")
    ap.add_argument("--strain", type=float, default=0.10)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--work", default=os.path.abspath("rate_error_runs"))
    ap.add_argument("--out", default=os.path.join(REPO, "bench", "results", "rate_error"))
    ap.add_argument("--plot", default=os.path.join(REPO, "docs", "performance_rate_error.png"))
    ap.add_argument("--reference", default="1e-5:0.2", help="RATE:DT_FRACTION of the reference run")
    ap.add_argument("--force", action="store_true")
    ap.add_argument("--reuse", action="store_true",
                    help="take finished records in --work instead of running them again")
    args = ap.parse_args(argv)
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    wanted = [tuple(float(x) for x in r.split(":")) for r in args.runs]
    rows = load_rows(args.out + ".csv")
    todo = [(rate, frac) for rate, frac in wanted
            if args.force or not any(same(r, args.scale, rate, frac, args.strain) for r in rows)]
    todo.sort(key=lambda rf: rf[0] * rf[1])    # longest first keeps both cores busy to the end
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for row in pool.map(lambda rf: one_run(args, *rf), todo):
            append_row(args.out + ".csv", row)
            rows.append(row)
    rows = [r for r in rows if r["scale"] == args.scale and abs(r["strain"] / args.strain - 1) < 1e-9]
    ref, table = with_errors(rows, tuple(float(x) for x in args.reference.split(":")))
    floors = scatter_floor(table, ref)
    from provenance import write_result
    write_result(args.out + ".json", {"reference": ref, "runs": table,
                                    "scatter_relative": {"sinphi_max": floors[0],
                                                         "eps_v_end": floors[1]}})
    plot(table, ref, args.plot)
    print(f"run-to-run scatter (same rate, dt changed by <= 0.02 t_R): sinphi_max "
          f"{floors[0]:.2e}, eps_v {floors[1]:.2e} (relative)")
    print(f"{'rate':>8} {'dt/tR':>6} {'I':>9} {'wall[s]':>8} {'sinphi':>8} {'err':>9} "
          f"{'eps_v':>9} {'err':>9}")
    for r in sorted(table, key=lambda r: (r["dt_fraction"], r["rate"])):
        print(f"{r['rate']:8.2g} {r['dt_fraction']:6.2g} {r['inertial_number']:9.3g} "
              f"{r['wall_s']:8.0f} {r['sinphi_max']:8.4f} {r['relative_error_sinphi_max']:9.2e} "
              f"{r['eps_v_end']:9.5f} {r['relative_error_eps_v_end']:9.2e}")


if __name__ == "__main__":
    main()
