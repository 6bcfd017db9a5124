#!/usr/bin/env python3
"""Physics check behind the LIGGGHTS case of bench/pair_speed.py: on the same data file, with
the decks of that benchmark (same read_data, timestep, neighbor settings, material), the
virial stress at step 0 of LIGGGHTS `pair_style gran model hertz tangential history` must equal
that of LAMMPS `pair_style granular` hertz/material + mindlin, `thornton/yin` with Gamma = 0
and `gran/hertz/history` (all Hertz with E* = E/(2(1-nu^2)); at step 0 there is no tangential
history, so only the normal law counts), to --tol relative to the mean stress.
After --steps steps of NVE the kinetic energies are reported too: they should be of similar
size, not identical (the tangential laws differ in how the history is incremented/rotated).

    PYTHONPATH=... TYLMP_LIBRARY=... /usr/bin/python3 bench/check_liggghts_equivalence.py
        [--data bench/data/dense_paper_100kPa.data] [--steps 2000] [--ranks 1] [--tol 1e-6]

Needs `liggghts` (apt-get install liggghts). Exit status 1 if a step-0 stress differs by more
than --tol.
"""
import argparse
import os
import re
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pair_speed  # noqa: E402

REFERENCE = "liggghts hertz+history"
COMPARED = ["granular hertz/material+mindlin", "thornton/yin G=0", "gran/hertz/history"]
COLUMNS = ["step", "ke", "erot", "p", "pxx", "pyy", "pzz", "pxy", "pxz", "pyz"]


def measure(name, steps):
    # LIGGGHTS's compute pressure needs a temperature compute (it has no thermo_temp)
    temp = "compute tt all temp\n" if name in pair_speed.LIGGGHTS_CASES else ""
    return (f"{temp}compute pv all pressure {'tt' if temp else 'NULL'} virial\n"
            "compute ke all ke\ncompute erot all erotate/sphere\n"
            "thermo_style custom step c_ke c_erot c_pv c_pv[1] c_pv[2] c_pv[3] c_pv[4] c_pv[5] "
            "c_pv[6]\nthermo_modify norm no format float %.15g\n"
            f"thermo {steps}")


def thermo_rows(out):
    rows = {}
    for line in out.splitlines():
        fields = line.split()
        if len(fields) == len(COLUMNS) and re.fullmatch(r"\d+", fields[0]):
            try:
                rows[int(fields[0])] = dict(zip(COLUMNS, map(float, fields)))
            except ValueError:
                pass
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", default=pair_speed.DATA)
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--tol", type=float, default=1e-6)
    ap.add_argument("--liggghts", default="liggghts")
    args = ap.parse_args(argv)
    if not shutil.which(args.liggghts):
        sys.exit(f"no LIGGGHTS binary '{args.liggghts}' on PATH: install it with "
                 "'apt-get install liggghts' (Debian 12: LIGGGHTS-PUBLIC 3.8.0)")
    data = os.path.abspath(args.data)
    results = {}
    with tempfile.TemporaryDirectory() as work:
        for name in [REFERENCE] + COMPARED:
            text = pair_speed.case_deck(name, data, args.steps, measure(name, args.steps))
            out = pair_speed.run_deck(name, text, args.ranks, work, liggghts=args.liggghts)
            rows = thermo_rows(out)
            if 0 not in rows or args.steps not in rows:
                raise RuntimeError(f"{name}: no thermo output\n{out[-2000:]}")
            results[name] = rows
    ref0 = results[REFERENCE][0]
    scale = abs(ref0["p"])
    print(f"data {data}, {args.ranks} rank(s); virial stress at step 0 (Pa), "
          f"difference relative to |p| of {REFERENCE}")
    print("| case | p | pxx | pyy | pzz | pxy | pxz | pyz | max rel. diff |\n|---|" + "---|" * 8)
    worst = 0.0
    for name in [REFERENCE] + COMPARED:
        r = results[name][0]
        rel = max(abs(r[k] - ref0[k]) / scale for k in COLUMNS[3:])
        if name != REFERENCE:
            worst = max(worst, rel)
        print(f"| {name} | " + " | ".join(f"{r[k]:.12g}" for k in COLUMNS[3:])
              + (f" | {rel:.2e} |" if name != REFERENCE else " | - |"))
    print(f"\nafter {args.steps} steps (dt = {pair_speed.DT:.6g} s); kinetic energies in J")
    print("| case | translational KE at 0 | translational KE | rotational KE | p (Pa) |\n"
          "|---|---|---|---|---|")
    for name in [REFERENCE] + COMPARED:
        r0, r = results[name][0], results[name][args.steps]
        print(f"| {name} | {r0['ke']:.6g} | {r['ke']:.6g} | {r['erot']:.6g} | {r['p']:.8g} |")
    ok = worst <= args.tol
    print(f"\nstep-0 stresses: largest relative difference {worst:.2e} "
          f"({'within' if ok else 'ABOVE'} tolerance {args.tol:g})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
