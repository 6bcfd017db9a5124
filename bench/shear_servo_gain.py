#!/usr/bin/env python3
"""Why a held shear stress gets a gain of its own (docs/fix_cell_servo.md, "The six-component
cell"): on the quick dense specimen (500 glass spheres at 100 kPa, the decks' cache) made
triclinic, (1) the secant shear stiffness d(sigma_xz)/d(gamma_xz) of a strain-controlled shear
of 1e-3 1/s over 50 steps against the affine C_55 the fix reports, and (2) the largest
|sigma_xy|, |sigma_xz|, |sigma_yz| over the second half of 10 000 steps with every component
held (the normal ones at 100 kPa, the shears at 0) at gain 0.25 and at the fix's default for a
held shear stress.

    /usr/bin/python3 bench/shear_servo_gain.py --specimen tylmp_specimens/dense_quick.restart
        [--out bench/results/shear_servo_gain]
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pair_speed    # noqa: E402
from provenance import write_result    # noqa: E402

HEAD = pair_speed.LOAD + """read_restart {specimen}
change_box all triclinic
comm_modify vel yes
neighbor 1.35e-5 bin
neigh_modify every 1 delay 0 check yes
pair_style thornton/yin
pair_coeff * * 70e9 0.3 0.3 0.6
"""

RESPONSE = HEAD + """fix cell all cell/servo axes xx rate 0 yy rate 0 zz rate 0 xy rate 0 xz rate -1e-3 yz rate 0 csv r.csv 50
thermo_style custom step f_cell[5][5]
thermo 50
run 50
"""

HOLD = HEAD + """fix integrate all nve/sphere
fix cell all cell/servo axes xx stress 1e5 yy stress 1e5 zz stress 1e5 xy stress 0 xz stress 0 yz stress 0 {gain} csv h.csv 100
run 10000
"""


def lmp(text, work):
    path = os.path.join(work, "in.deck")
    with open(path, "w") as fh:
        fh.write(text)
    out = subprocess.run(["lmp", "-in", path, "-log", "none", "-nocite"], cwd=work,
                         capture_output=True, text=True)
    if out.returncode != 0 or "ERROR" in out.stdout:
        raise RuntimeError(out.stdout[-2000:] + out.stderr[-2000:])
    return out.stdout


def table(path):
    return np.genfromtxt(path, delimiter=",", names=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--specimen", required=True)
    ap.add_argument("--out", default=os.path.join(pair_speed.REPO, "bench", "results",
                                                  "shear_servo_gain"))
    args = ap.parse_args(argv)
    specimen = os.path.abspath(args.specimen)
    result = {"specimen": os.path.basename(specimen)}
    with tempfile.TemporaryDirectory() as work:
        out = lmp(RESPONSE.format(specimen=specimen), work)
        c55 = float(out.split("f_cell[5][5]")[1].split()[1])    # at step 0
        r = table(os.path.join(work, "r.csv"))
        secant = (r["sig_xz"][-1] - r["sig_xz"][0]) / (r["gamma_xz"][-1] - r["gamma_xz"][0])
        result["affine_C55_Pa"] = c55
        result["secant_dsigma_dgamma_Pa"] = -secant    # sigma compression positive, eps = -gamma
        result["ratio"] = -secant / c55
        print(f"  affine C55 {c55:.3g} Pa, secant {-secant:.3g} Pa, ratio {-secant / c55:.3f}")
        for label, gain in (("gain 0.25", "gain 0.25 integral_gain 0.005"), ("default", "")):
            lmp(HOLD.format(specimen=specimen, gain=gain), work)
            h = table(os.path.join(work, "h.csv"))
            late = slice(len(h) // 2, None)
            worst = {k: float(np.abs(h[k][late]).max()) for k in ("sig_xy", "sig_xz", "sig_yz")}
            result[label] = worst
            print(f"  {label:10s} largest |shear stress| over the second half: "
                  + ", ".join(f"{k} {v:.3g} Pa" for k, v in worst.items()))
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    write_result(args.out + ".json", result)


if __name__ == "__main__":
    main()
