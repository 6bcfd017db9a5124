#!/usr/bin/env python3
"""Assembly check of the Thornton-Yin model in LIGGGHTS (build/bin/tyliggghts) against
`pair thornton/yin` in LAMMPS: the 3620-sphere dense specimen (bench/data, docs/specimen.md)
read by both, the material and time step of bench/pair_speed.py, plain NVE (fix nve/sphere in
both), --steps steps. Every --every steps both print the virial stress tensor, the kinetic
energies and the number of overlapping pairs (compute contact/atom); the table gives, per
row, the largest difference of a stress component relative to |p| of LAMMPS, and the contact
counts. Both engines integrate with the same velocity-Verlet of fix nve/sphere; what may
differ is the order of force summation (neighbour lists), which a dense packing amplifies
over many steps.

    /usr/bin/python3 bench/liggghts_assembly.py [--gamma 0.6] [--steps 2000] [--every 250]
        [--ranks 1] [--tyliggghts build/bin/tyliggghts] [--json bench/results/liggghts_assembly.json]
"""
import argparse
import json
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pair_speed  # noqa: E402

COLUMNS = ["step", "ke", "erot", "contacts", "p", "pxx", "pyy", "pzz", "pxy", "pxz", "pyz"]


def measure(liggghts, every):
    # LIGGGHTS's compute pressure needs a temperature compute (it has no thermo_temp)
    temp = "compute tt all temp\n" if liggghts else ""
    return (f"{temp}compute pv all pressure {'tt' if liggghts else 'NULL'} virial\n"
            "compute ke all ke\ncompute erot all erotate/sphere\n"
            "compute ca all contact/atom\ncompute nc all reduce sum c_ca\n"
            "thermo_style custom step c_ke c_erot c_nc c_pv c_pv[1] c_pv[2] c_pv[3] c_pv[4] "
            f"c_pv[5] c_pv[6]\nthermo_modify norm no format float %.15g\nthermo {every}")


def rows(out):
    found = {}
    for line in out.splitlines():
        fields = line.split()
        if len(fields) == len(COLUMNS) and re.fullmatch(r"\d+", fields[0]):
            try:
                found[int(fields[0])] = dict(zip(COLUMNS, map(float, fields)))
            except ValueError:
                pass
    return found


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", default=pair_speed.DATA)
    ap.add_argument("--gamma", default="0.6", choices=["0.6", "0"])
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--every", type=int, default=250)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--tyliggghts", default=pair_speed.TYLIGGGHTS)
    ap.add_argument("--json", help="write the table and settings here")
    args = ap.parse_args(argv)
    if not os.access(args.tyliggghts, os.X_OK):
        sys.exit(f"no launcher {args.tyliggghts} (apt-get install liggghts libliggghts-dev; "
                 "rebuild)")
    pair_speed.TYLIGGGHTS = args.tyliggghts
    cases = {"lammps": f"thornton/yin G={args.gamma}", "liggghts": f"liggghts thornton_yin G={args.gamma}"}
    data = os.path.abspath(args.data)
    result = {}
    with tempfile.TemporaryDirectory() as work:
        for engine, name in cases.items():
            text = pair_speed.case_deck(name, data, args.steps, measure(engine == "liggghts", args.every))
            result[engine] = rows(pair_speed.run_deck(name, text, args.ranks, work))
    table = []
    for step in sorted(result["lammps"]):
        a, b = result["lammps"][step], result["liggghts"].get(step)
        if b is None:
            continue
        scale = abs(a["p"])
        table.append({"step": step, "p_lammps": a["p"], "p_liggghts": b["p"],
                      "stress_rel_diff": max(abs(a[k] - b[k]) for k in COLUMNS[4:]) / scale,
                      "contacts_lammps": a["contacts"] / 2, "contacts_liggghts": b["contacts"] / 2,
                      "ke_lammps": a["ke"], "ke_liggghts": b["ke"]})
    print(f"{data}: Gamma = {args.gamma} J/m^2, {args.ranks} rank(s), dt = {pair_speed.DT:.6g} s")
    print("| step | p LAMMPS (Pa) | p LIGGGHTS (Pa) | max stress diff / abs(p) | contacts LAMMPS | "
          "contacts LIGGGHTS | KE LAMMPS (J) | KE LIGGGHTS (J) |\n|---|---|---|---|---|---|---|---|")
    for r in table:
        print(f"| {r['step']} | {r['p_lammps']:.10g} | {r['p_liggghts']:.10g} | "
              f"{r['stress_rel_diff']:.2e} | {r['contacts_lammps']:.0f} | "
              f"{r['contacts_liggghts']:.0f} | {r['ke_lammps']:.6g} | {r['ke_liggghts']:.6g} |")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump({"data": os.path.relpath(data, pair_speed.REPO), "gamma": float(args.gamma),
                       "steps": args.steps, "ranks": args.ranks, "timestep": pair_speed.DT,
                       "rows": table}, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
