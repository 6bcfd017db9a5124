#!/usr/bin/env python3
"""The cost per atom-step of a simple-shear test of the triclinic cell against today's
axisymmetric test of the orthogonal cell (issue: "a 3620-sphere simple shear at the paper's
rate costs no more per atom-step than the axisymmetric test"), on the shipped 3620-sphere dense
specimen, both with pair thornton/yin (Gamma = 0.6, mu = 0.3) and fix cell/servo at the
paper-scale rates of the decks (axisym: eps1_dot = 5e-5 1/s; simple shear: gamma_dot = 1e-4 1/s).

    /usr/bin/python3 bench/cell_speed.py [--steps 2000] [--repeats 3] [--callgrind-steps 100]
        [--out bench/results/cell_speed] [--keep-callgrind DIR]

The plain NVE run of the same specimen and pair (no fix cell/servo) is the baseline of the
servo workload: issue 29 asks that the axisymmetric test cost at most 1.1x its instructions per
atom-step. Two figures: (1) wall clock, the median over `repeats` alternated runs of each deck
of the loop time per atom-step, and their ratios (meaningful on a quiet machine only); (2)
instructions per atom-step of the whole run loop (LAMMPS_NS::Verlet::run, so pair, neighbour
lists, communication, the fix's measurement, servo and box change, flips), counted by
valgrind's callgrind, which does not depend on the machine's load. Writes OUT.json (provenance
stamped); with --keep-callgrind the callgrind outputs go to DIR, callgrind.nve,
callgrind.axisym and callgrind.simple_shear, for a per-function comparison
(callgrind_annotate).
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pair_speed    # noqa: E402
from provenance import write_result    # noqa: E402

REPO = pair_speed.REPO
DATA = os.path.join(REPO, "bench", "data", "dense_paper_100kPa.data")

COMMON = pair_speed.LOAD + """units si
atom_style sphere
boundary p p p
comm_modify vel yes
read_data {data}
{box}pair_style thornton/yin
pair_coeff * * 70e9 0.3 0.3 0.6
neighbor 1.35e-5 bin
neigh_modify every 1 delay 0 check yes
timestep 0.0144
fix integrate all nve/sphere
{fix}
thermo 1000
run {steps}
"""

TESTS = {
    # the same specimen and pair without the servo: the plain NVE benchmark of issue 29
    # (the servo workload's instructions per atom-step against these)
    "nve": ("", ""),
    "axisym": ("", "fix cell all cell/servo axisym x 5e-5 1e5"),
    "simple_shear": ("change_box all triclinic\n", "fix cell all cell/servo shear xz 1e-4 1e5"),
}


def deck(name, steps):
    box, fix = TESTS[name]
    return COMMON.format(data=DATA, box=box, fix=fix, steps=steps)


def loop_seconds(out):
    m = re.search(r"^Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms",
                  out, re.M)
    return float(m.group(1)), int(m.group(2)), int(m.group(3))


def run(name, steps, work, prefix=()):
    path = os.path.join(work, f"in.{name}")
    with open(path, "w") as fh:
        fh.write(deck(name, steps))
    proc = subprocess.run(list(prefix) + ["lmp", "-in", path, "-log", "none", "-nocite"],
                          cwd=work, capture_output=True, text=True)
    if proc.returncode != 0 or "ERROR" in proc.stdout:
        raise RuntimeError(f"{name}: {proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    return proc


def instructions(name, steps, work, keep=None):
    out = os.path.join(keep or work, f"callgrind.{name}")
    run(name, steps, work, ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
                            "--toggle-collect=LAMMPS_NS::Verlet::run*"])
    summary = subprocess.run(["callgrind_annotate", out], capture_output=True, text=True).stdout
    m = re.search(r"^([\d,]+) \(.*PROGRAM TOTALS", summary, re.M)
    natoms = 3620
    return int(m.group(1).replace(",", "")) / (natoms * steps)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--callgrind-steps", type=int, default=100)
    ap.add_argument("--out", default=os.path.join(REPO, "bench", "results", "cell_speed"))
    ap.add_argument("--keep-callgrind", metavar="DIR", default=None)
    args = ap.parse_args(argv)
    if args.keep_callgrind:
        os.makedirs(args.keep_callgrind, exist_ok=True)
    result = {"data": os.path.relpath(DATA, REPO), "steps": args.steps,
              "repeats": args.repeats, "callgrind_steps": args.callgrind_steps, "tests": {}}
    with tempfile.TemporaryDirectory() as work:
        per = {name: [] for name in TESTS}
        for _ in range(args.repeats):            # alternated: a, b, a, b, ...
            for name in TESTS:
                seconds, steps, atoms = loop_seconds(run(name, args.steps, work).stdout)
                per[name].append(seconds / (steps * atoms))
        for name in TESTS:
            ir = (instructions(name, args.callgrind_steps, work, args.keep_callgrind)
                  if args.callgrind_steps else None)
            result["tests"][name] = {"seconds_per_atom_step": per[name],
                                     "median_seconds_per_atom_step": statistics.median(per[name]),
                                     "instructions_per_atom_step": ir}
            print(f"  {name:14s} median {statistics.median(per[name]) * 1e6:8.3f} us/atom-step"
                  + (f", {ir:9.0f} instructions/atom-step" if ir else ""), flush=True)
    for test, base in (("simple_shear", "axisym"), ("axisym", "nve"), ("simple_shear", "nve")):
        t, b = result["tests"][test], result["tests"][base]
        result[f"wall_ratio_{test}_to_{base}"] = (t["median_seconds_per_atom_step"]
                                                  / b["median_seconds_per_atom_step"])
        line = f"  {test} / {base}: wall {result[f'wall_ratio_{test}_to_{base}']:.3f}"
        if b["instructions_per_atom_step"]:
            ratio = t["instructions_per_atom_step"] / b["instructions_per_atom_step"]
            result[f"instruction_ratio_{test}_to_{base}"] = ratio
            line += f", instructions {ratio:.3f}"
        print(line)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    write_result(args.out + ".json", result)


if __name__ == "__main__":
    main()
