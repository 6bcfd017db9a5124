#!/usr/bin/env python3
"""Weak and strong scaling of pair thornton/yin on this machine, with memory per sphere and
the share of communication, and a projection to many ranks.

    /usr/bin/python3 bench/weak_scaling.py [--replicate 3] [--ranks 1 2] [--repeats 3]
        [--atom-steps 2e7] [--gamma 0.6 0] [--out bench/results/weak_scaling]

Specimens: the committed paper specimen bench/data/dense_paper_100kPa.data (3620 spheres of
the paper's size distribution, dense, p = 100 kPa) and the same packing replicated
REPLICATE^3 times by LAMMPS's `replicate` command (3: 97 740 spheres in a 12.9 mm cell): a
periodic packing of the paper's distribution at the same state, generated when the benchmark
runs (no file is committed). Every run is plain NVE from fresh contacts, as in
bench/pair_speed.py (same deck, timestep, neighbor settings), for about ATOM_STEPS atom-steps
(the step count is ATOM_STEPS / N), on 1 and 2 ranks (mpirun), the runs of all cases taken in
alternation, `repeats` times; the figure is the median.

Per run it records, from LAMMPS's own output: the loop time (atom-steps/s, per rank), the
share of the loop in each timing section (Pair, Neigh, Comm, Modify, Other), LAMMPS's
"Per MPI rank memory allocation" (its own arrays: atoms, neighbor lists, the contact
histories of fix neigh/history), and the peak resident memory of the process (GNU time's %M,
1 rank only: with mpirun it measures the launcher). Bytes per sphere are the difference
between the two specimen sizes over the difference in spheres (what a sphere costs, the
fixed cost of the program removed).

Writes OUT.csv (every run) and OUT.json (medians and the per-sphere figures) and prints a
table; the projection to 64-1024 ranks is written in docs/performance.md from these figures.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pair_speed  # noqa: E402  the same deck, timestep and neighbor settings
from pair_speed import DATA, E, MU, NU  # noqa: E402
from lammps_log import first_loop, section  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import write_result  # noqa: E402

SECTIONS = ("Pair", "Neigh", "Comm", "Modify", "Output", "Other")


def scaled_deck(data, replicate, gamma, steps):
    """pair_speed's NVE deck with `replicate R R R` after read_data."""
    pair_lines = f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} {gamma}\n"
    text = pair_speed.deck(data, pair_lines, steps)
    if replicate > 1:
        text = text.replace(f"read_data {data}\n",
                            f"read_data {data}\nreplicate {replicate} {replicate} {replicate}\n")
    return text


def parse(out, ranks):
    """Loop time, steps, atoms, section shares (% of the loop), LAMMPS's memory line and, on one
    rank, the peak resident memory (None on more: GNU time would measure mpirun)."""
    run = first_loop(out, "weak scaling run")
    row = {"loop_s": run["seconds"], "procs": run["procs"], "steps": run["steps"],
           "atoms": run["atoms"]}
    for sec in SECTIONS:
        rows = section(out, sec)
        if not rows:
            raise RuntimeError(f"no '{sec}' line in LAMMPS's timing breakdown")
        row[f"pct_{sec.lower()}"] = rows[0]["pct"]
    mem = re.search(r"Per MPI rank memory allocation \(min/avg/max\) = ([0-9.eE+-]+) \| "
                    r"([0-9.eE+-]+) \| ([0-9.eE+-]+) Mbytes", out)
    if not mem:
        raise RuntimeError("no 'Per MPI rank memory allocation' line in LAMMPS's output")
    row["lammps_mbytes_per_rank"] = float(mem.group(3))
    row["maxrss_kB"] = None
    if ranks == 1:
        rss = re.search(r"^tylmp-maxrss-kB (\d+)$", out, re.M)
        if not rss:
            raise RuntimeError("no peak resident memory from /usr/bin/time")
        row["maxrss_kB"] = int(rss.group(1))
    return row


def run(data, replicate, gamma, steps, ranks, workdir):
    path = os.path.join(workdir, "in.scaling")
    with open(path, "w") as fh:
        fh.write(scaled_deck(data, replicate, gamma, steps))
    cmd = ["lmp", "-in", path, "-log", "none", "-nocite"]
    if ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
    else:    # peak resident memory of the one process
        cmd = ["/usr/bin/time", "-f", "tylmp-maxrss-kB %M"] + cmd
    proc = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({proc.returncode})\n"
                           f"{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    return parse(proc.stdout + "\n" + proc.stderr, ranks)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", default=DATA)
    ap.add_argument("--replicate", type=int, default=3,
                    help="the large specimen is the data file replicated R x R x R times")
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--gamma", type=float, nargs="+", default=[0.6])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--atom-steps", type=float, default=2e7,
                    help="atom-steps per run (steps = this / spheres)")
    ap.add_argument("--out", default=os.path.join(pair_speed.REPO, "bench", "results",
                                                  "weak_scaling"))
    args = ap.parse_args(argv)
    if args.replicate < 2:
        ap.error("--replicate must be at least 2 (1 is the small specimen itself)")
    if any(r < 1 for r in args.ranks) or args.repeats < 1 or not args.atom_steps > 0:
        ap.error("--ranks, --repeats and --atom-steps must be positive")
    n_small = int(open(args.data).read().split(" atoms", 1)[0].split()[-1])
    cases = [(rep, g, ranks) for g in args.gamma for rep in (1, args.replicate)
             for ranks in args.ranks]
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for k in range(args.repeats):
            for rep, g, ranks in cases:
                n = n_small * rep ** 3
                steps = max(100, int(round(args.atom_steps / n / 100)) * 100)
                row = run(os.path.abspath(args.data), rep, g, steps, ranks, work)
                row.update({"repeat": k, "replicate": rep, "gamma": g, "ranks": ranks,
                            "atom_steps_per_s": row["atoms"] * row["steps"] / row["loop_s"]})
                row["atom_steps_per_s_per_rank"] = row["atom_steps_per_s"] / ranks
                rows.append(row)
                print(f"  N = {n:6d} Gamma = {g} ranks {ranks} repeat {k}: "
                      f"{row['atom_steps_per_s']:.4g} atom-steps/s, comm {row['pct_comm']:.1f} %",
                      flush=True)
    keys = list(rows[0])
    with open(args.out + ".csv.tmp", "w") as fh:    # written whole, then renamed
        fh.write(",".join(keys) + "\n")
        for r in rows:
            fh.write(",".join("" if r[k] is None else str(r[k]) for k in keys) + "\n")
    os.replace(args.out + ".csv.tmp", args.out + ".csv")

    def med(rep, g, ranks, key):
        values = [r[key] for r in rows if r["replicate"] == rep and r["gamma"] == g and
                  r["ranks"] == ranks]
        return None if None in values else statistics.median(values)
    summary = {"data": os.path.relpath(args.data, pair_speed.REPO), "replicate": args.replicate,
               "spheres": [n_small, n_small * args.replicate ** 3], "repeats": args.repeats,
               "atom_steps_per_run": args.atom_steps, "cases": []}
    print("\n| spheres | Gamma | ranks | atom-steps/s | per rank | speed-up vs 1 rank | "
          "Pair % | Neigh % | Comm % | LAMMPS MB/rank | peak RSS MB |\n|" + "---|" * 11)
    for g in args.gamma:
        for rep in (1, args.replicate):
            n = n_small * rep ** 3
            one = med(rep, g, min(args.ranks), "atom_steps_per_s")
            for ranks in args.ranks:
                c = {"spheres": n, "gamma": g, "ranks": ranks}
                for key in ("atom_steps_per_s", "atom_steps_per_s_per_rank", "pct_pair",
                            "pct_neigh", "pct_comm", "pct_modify", "pct_other",
                            "lammps_mbytes_per_rank", "maxrss_kB"):
                    c[key] = med(rep, g, ranks, key)
                c["speedup_vs_fewest_ranks"] = c["atom_steps_per_s"] / one
                summary["cases"].append(c)
                print(f"| {n} | {g} | {ranks} | {c['atom_steps_per_s']:.4g} | "
                      f"{c['atom_steps_per_s_per_rank']:.4g} | {c['speedup_vs_fewest_ranks']:.3f} | "
                      f"{c['pct_pair']:.1f} | {c['pct_neigh']:.1f} | {c['pct_comm']:.1f} | "
                      f"{c['lammps_mbytes_per_rank']:.2f} | "
                      + ("—" if c["maxrss_kB"] is None else f"{c['maxrss_kB'] / 1024:.1f}") + " |")
        if 1 in args.ranks:
            small = [c for c in summary["cases"] if c["gamma"] == g and c["ranks"] == 1]
            dn = small[1]["spheres"] - small[0]["spheres"]
            per_sphere = {
                "lammps_bytes_per_sphere":
                    (small[1]["lammps_mbytes_per_rank"] - small[0]["lammps_mbytes_per_rank"])
                    * 1048576 / dn,
                "rss_bytes_per_sphere": (small[1]["maxrss_kB"] - small[0]["maxrss_kB"]) * 1024 / dn}
            summary.setdefault("bytes_per_sphere", {})[str(g)] = per_sphere
            print(f"\nGamma = {g}: {per_sphere['lammps_bytes_per_sphere']:.0f} bytes per sphere "
                  f"in LAMMPS's arrays, {per_sphere['rss_bytes_per_sphere']:.0f} bytes of resident "
                  "memory per sphere (1 rank, between the two sizes)")
    write_result(args.out + ".json", summary, indent=2)


if __name__ == "__main__":
    main()
