#!/usr/bin/env python3
"""Instructions executed in the pair force computation per atom-step, for the cases of
bench/pair_speed.py, counted by valgrind's callgrind: a figure of the work per contact that
does not depend on the machine's load (wall-clock ratios from pair_speed.py need a quiet
machine; this one does not).

    /usr/bin/python3 bench/instruction_profile.py [--data bench/data/dense_paper_100kPa.data]
        [--steps 200] [--cases NAME ...] [--out bench/results/instruction_profile]
        [--branch-sim] [--keep DIR] [--scope pair|run]

Each case runs the deck of pair_speed.py (same data file, neighbor settings, timestep) under
`valgrind --tool=callgrind --toggle-collect=<the pair style's compute()>`, so only the pair
compute and what it calls are counted (not neighbor builds, communication or integration).
Writes OUT.json and prints instructions per atom-step and the ratio to thornton/yin G=0.6.
With --branch-sim, callgrind also simulates a branch predictor (`--branch-sim=yes`, a simple
table of 2-bit counters: a processor's predictor does better, so the figure ranks branches
rather than predicting cycles) and the mispredicted conditional branches per atom-step are
added. TYLMP_LIBRARY in the environment selects the build of the plugin, as for pair_speed.py.
"""
import argparse
import os
import re
import subprocess
import sys
import shutil
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pair_speed    # noqa: E402

COMPUTE = {    # case -> the function whose inclusive cost is counted
    "thornton/yin": "LAMMPS_NS::PairThorntonYin::compute*",
    "granular": "LAMMPS_NS::PairGranular::compute*",
    "gran/hertz/history": "LAMMPS_NS::PairGranHertzHistory::compute*",
    "liggghts": "LAMMPS_NS::PairGran::compute*",
}


def toggle_for(case):
    for prefix, pattern in COMPUTE.items():
        if case.startswith(prefix):
            return pattern
    raise KeyError(case)


RUN_LOOP = "LAMMPS_NS::Verlet::run*"    # --scope run: the whole time-step loop, both engines


def count(case, data, steps, work, branch_sim=False, keep=None, scope="pair"):
    deck = pair_speed.case_deck(case, data, steps)
    path = os.path.join(work, "in.profile")
    with open(path, "w") as fh:
        fh.write(deck)
    out = os.path.join(work, "callgrind.out")
    exe = (pair_speed.TYLIGGGHTS if case in pair_speed.TYLIGGGHTS_CASES
           else "liggghts" if case in pair_speed.LIGGGHTS_CASES else "lmp")
    toggle = toggle_for(case) if scope == "pair" else RUN_LOOP
    cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
           f"--toggle-collect={toggle}"] + (["--branch-sim=yes"] if branch_sim else [])
    cmd += [exe, "-in", path, "-log", "none", "-nocite"]
    env = dict(os.environ, **pair_speed.CASE_ENVIRONMENT.get(case, {}))
    proc = subprocess.run(cmd, cwd=work, capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        raise RuntimeError(f"{case}: {proc.stderr[-2000:]}")
    if keep:    # the profile itself, for callgrind_annotate --inclusive=yes (where the work is)
        os.makedirs(keep, exist_ok=True)
        shutil.copy(out, os.path.join(keep, "callgrind." + re.sub(r"[^A-Za-z0-9.=]+", "_", case)
                                      + ".out"))
    summary = subprocess.run(["callgrind_annotate", out], capture_output=True, text=True).stdout
    events = re.search(r"^Events shown:\s+(.*)$", summary, re.M).group(1).split()
    m = re.search(r"^(.*)PROGRAM TOTALS", summary, re.M)
    numbers = re.findall(r"([\d,]+) \(", m.group(1)) if m else []
    totals = {e: int(n.replace(",", "")) for e, n in zip(events, numbers)}
    natoms = int(re.search(r"^(\d+) atoms", open(data).read(4096), re.M).group(1))
    # setup computes the forces once more (Verlet::setup, outside Verlet::run)
    atom_steps = natoms * (steps + 1 if scope == "pair" else steps)
    return totals.get("Ir", 0), {e: n / atom_steps for e, n in totals.items()}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", default=pair_speed.DATA)
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--cases", nargs="*", default=list(pair_speed.CASES))
    ap.add_argument("--branch-sim", action="store_true",
                    help="also count mispredicted conditional branches (simulated)")
    ap.add_argument("--scope", choices=("pair", "run"), default="pair",
                    help="count the pair style's compute() (pair) or the whole time-step loop, "
                    "Verlet::run: pair, neighbour lists, integration, communication (run)")
    ap.add_argument("--keep", metavar="DIR",
                    help="keep each case's callgrind output in DIR (callgrind.CASE.out)")
    ap.add_argument("--out", default=os.path.join(pair_speed.REPO, "bench", "results",
                                                  "instruction_profile"))
    args = ap.parse_args(argv)
    data = os.path.abspath(args.data)
    rows = {}
    with tempfile.TemporaryDirectory() as work:
        for case in args.cases:
            if case in pair_speed.LIGGGHTS_CASES and not shutil.which("liggghts"):
                print(f"  {case}: skipped (no liggghts binary)")
                continue
            total, per = count(case, data, args.steps, work, args.branch_sim, args.keep,
                               args.scope)
            if total == 0:
                print(f"  {case}: no instructions counted (no symbol {toggle_for(case)})")
                continue
            rows[case] = {"instructions": total, "per_atom_step": per["Ir"]}
            line = f"  {case:36s} {per['Ir']:8.0f} instructions per atom-step"
            if "Bcm" in per:
                rows[case]["mispredicted_branches_per_atom_step"] = per["Bcm"]
                line += f", {per['Bcm']:5.2f} mispredicted branches (simulated)"
            print(line, flush=True)
    base = rows.get("thornton/yin G=0.6", {}).get("per_atom_step")
    for r in rows.values():
        r["ratio_to_thornton_yin_G0.6"] = r["per_atom_step"] / base if base else None
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    pair_speed.write_result(args.out + ".json", {"data": os.path.relpath(data, pair_speed.REPO),
                                               "steps": args.steps, "scope": args.scope,
                                               "library": os.environ.get("TYLMP_LIBRARY"),
                                               "cases": rows})


if __name__ == "__main__":
    main()
