#!/usr/bin/env python3
"""The dense axisymmetric test at constant p (inputs/axisym.in, quick scale) under LAMMPS
4 Feb 2025, driven two ways (docs/comparison.md, "fix deform/pressure as a peer"):

  thornton/yin + cell/servo    pair thornton/yin + fix cell/servo axisym x RATE 1e5 (the deck
                               as it is: axial rate, sigma2 = sigma3, p = 100 kPa)
  granular + deform/pressure   pair granular jkr ... tangential mindlin (Gamma = 0.6 J/m^2,
      pressure/mean            mu = 0.3) + fix deform/pressure 1 x trate -RATE
                               y pressure/mean 1e5 K z pressure/mean 1e5 K normalize/pressure yes
                               max/rate M remap x (EXTRA-FIX, 17 Apr 2024; its third example):
                               equal lateral strains, the mean stress held
  ..., virial                  the same with `fix_modify ID press` of a virial-only pressure
                               compute (the fix's own one includes the kinetic term)
  ... lateral stress           y pressure v_lat K z pressure v_lat K, v_lat = (3 p - sigma1)/2
                               from the virial: each lateral stress held at the value that
                               keeps p, so sigma2 = sigma3 as in the servo's test
  thornton/yin + deform/pressure lateral stress   our pair under that fix

    W=$(TYLMP_LAMMPS2025_NO_TESTS=1 bash scripts/lammps2025.sh | tail -1)
    /usr/bin/python3 bench/compare_deform_pressure.py --lmp2025 "$W" [--strain 0.30]
        [--gain 1e-2] [--max-rate 1e-3] [--work DIR]
        [--out docs/comparison_deform_pressure.png]
        [--json bench/results/compare_deform_pressure.json]

Every run starts from the same specimen, tylmp_specimens/dense_quick.restart in the work
directory (prepared by the first run through inputs/common/prepare.in under the same LAMMPS;
--work DIR keeps it for later runs), with the deck's numerics (inputs/common/numerics.in).
Records every 200 steps the natural strains -ln(L_i/L_i0), the contact (virial) stresses,
compression positive, the full pressure with the kinetic term (thermo `press`), and the mean
number of touching neighbours; prints the servo quality (mean stress and lateral stress
balance past 1 % deviator strain), the deviatoric stiffness q/eps1 at the first record,
sin(phi) at the peak and at the end, and the volumetric strain.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import write_result  # noqa: E402
from pair_speed import LOAD  # noqa: E402  (the two lines that load the plugin's styles)

P0, RATE = 1e5, 1e-4                  # the deck's mean stress [Pa], quick-scale rate [1/s]
E, NU, MU, GAMMA = 70e9, 0.3, 0.3, 0.6
PAIRS = {
    "granular": (f"pair_style granular\npair_coeff * * jkr {E} 0.0 {NU} {GAMMA} "
                 f"damping viscoelastic tangential mindlin NULL 0.0 {MU}\n"),
    "thornton/yin": f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} {GAMMA}\n",
}
EVERY = 200

PEER = """{load}read_restart tylmp_specimens/dense_quick.restart
comm_modify vel yes
{pair}variable scale index quick
include bench/decks_timestep.in
fix integrate all nve/sphere
compute virial all pressure NULL virial
compute touching all contact/atom
compute z all reduce ave c_touching
variable lx0 equal $(lx)
variable ly0 equal $(ly)
variable lz0 equal $(lz)
variable lat equal (3*{p0!r}-c_virial[1])/2
fix shear all deform/pressure 1 x trate {rate_x!r} y {lateral} {gain!r} z {lateral} {gain!r} normalize/pressure yes max/rate {max_rate!r} remap x
{press}variable eps1 equal -ln(lx/v_lx0)
variable eps2 equal -ln(ly/v_ly0)
variable eps3 equal -ln(lz/v_lz0)
variable d13 equal v_eps1-v_eps3
fix out all print {every} "$(step) $(v_eps1:%.10g) $(v_eps2:%.10g) $(v_eps3:%.10g) $(c_virial[1]:%.10g) $(c_virial[2]:%.10g) $(c_virial[3]:%.10g) $(press:%.10g) $(c_z:%.6g)" file {name}.txt screen no title "# step eps1 eps2 eps3 sig1 sig2 sig3 press_full Z"
fix stop all halt 500 v_d13 >= {strain!r} error continue
thermo 5000
run $(ceil(1.1*{strain!r}/(1.5*{rate!r}*dt)))
"""


def lmp_run(lmp, work, name, text=None, args=()):
    path = os.path.join(work, f"in.{name}")
    if text is not None:
        with open(path, "w") as fh:
            fh.write(text)
    cmd = [lmp, "-in", path if text is not None else args[0], "-log", f"{name}.log", "-nocite"]
    cmd += list(args[1:]) if text is None else []
    proc = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
    out = proc.stdout + proc.stderr
    if proc.returncode != 0 or "ERROR" in out:
        raise RuntimeError(f"{name}: {' '.join(cmd)} failed\n{out[-3000:]}")
    return out


def read_txt(path):
    with open(path) as fh:
        names = fh.readline().lstrip("#").split()
    data = np.loadtxt(path, ndmin=2)
    return {n: data[:, k] for k, n in enumerate(names)}


def read_servo_csv(path):
    with open(path) as fh:
        names = fh.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    d = {n: data[:, k] for k, n in enumerate(names)}
    return {"step": d["step"], "eps1": d["eps1"], "eps2": d["eps2"], "eps3": d["eps3"],
            "sig1": d["sig1"], "sig2": d["sig2"], "sig3": d["sig3"],
            "press_full": d["p"] + d["p_kinetic"], "Z": d["Z"]}


def summary(r):
    p = (r["sig1"] + r["sig2"] + r["sig3"]) / 3
    q = r["sig1"] - 0.5 * (r["sig2"] + r["sig3"])
    d13 = r["eps1"] - r["eps3"]
    sinphi = (r["sig1"] - r["sig3"]) / (r["sig1"] + r["sig3"])
    past = d13 > 0.01
    k = int(np.argmax(np.where(past, sinphi, -np.inf)))
    first = int(np.argmax(r["eps1"] > 1e-5))           # the first record after the start
    q0 = q[0] if abs(r["eps1"][0]) < 1e-12 else 0.0     # the record at the start, if any
    return {"rows": int(len(p)), "d13_end": float(d13[-1]),
            "initial_q_over_eps1_MPa": float((q[first] - q0) / r["eps1"][first] / 1e6),
            "eps1_of_initial": float(r["eps1"][first]),
            "p_mean_error_rel": float(np.mean(p[past] / P0 - 1)),
            "p_max_error_rel": float(np.max(np.abs(p[past] / P0 - 1))),
            "lateral_imbalance_max_rel": float(np.max(np.abs(r["sig2"][past] - r["sig3"][past])
                                                      / p[past])),
            "kinetic_share_of_full_pressure_max": float(np.max(np.abs(r["press_full"][past]
                                                                      - p[past]) / p[past])),
            "sinphi_peak": float(sinphi[k]), "d13_at_peak": float(d13[k]),
            "sinphi_end": float(sinphi[-1]), "q_over_p_end": float(q[-1] / p[-1]),
            "eps_v_end": float(r["eps1"][-1] + r["eps2"][-1] + r["eps3"][-1]),
            "Z_end": float(r["Z"][-1])}


def plot(records, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from tylmp.analysis.figures import save_figure
    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(13, 4))
    for name, r in records.items():
        d13 = (r["eps1"] - r["eps3"]) * 100
        p = (r["sig1"] + r["sig2"] + r["sig3"]) / 3
        a1.plot(d13, (r["sig1"] - r["sig3"]) / (r["sig1"] + r["sig3"]), label=name)
        a2.plot(d13, p / 1e3, label=name)
        a3.plot(d13, (r["eps1"] + r["eps2"] + r["eps3"]) * 100, label=name)
    a1.set_ylabel("sin φ = (σ1 − σ3)/(σ1 + σ3)")
    a2.set_ylabel("p (contact stress) [kPa]")
    a3.set_ylabel("ε_v [%] (compression positive)")
    for a in (a1, a2, a3):
        a.set_xlabel("ε1 − ε3 [%]")
        a.grid(alpha=0.3)
    a1.legend(fontsize=8)
    fig.suptitle("dense 500-sphere specimen, axisymmetric compression at p = 100 kPa, "
                 "LAMMPS 4 Feb 2025")
    return save_figure(fig, png)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lmp2025", required=True, metavar="WRAPPER",
                    help="the lmp of LAMMPS 4 Feb 2025 (last line of scripts/lammps2025.sh)")
    ap.add_argument("--strain", type=float, default=0.30, help="end deviator strain eps1 - eps3")
    ap.add_argument("--gain", type=float, default=1e-2,
                    help="fix deform/pressure gain k [1/s] (normalize/pressure yes)")
    ap.add_argument("--max-rate", type=float, default=1e-3, help="its max/rate [1/s]")
    ap.add_argument("--work", help="work directory (kept; reuses its specimen)")
    ap.add_argument("--out", default=os.path.join(REPO, "docs", "comparison_deform_pressure.png"))
    ap.add_argument("--json", default=os.path.join(REPO, "bench", "results",
                                                   "compare_deform_pressure.json"))
    args = ap.parse_args(argv)
    lmp = os.path.abspath(args.lmp2025)
    with tempfile.TemporaryDirectory() as tmp:
        work = os.path.abspath(args.work or tmp)
        os.makedirs(work, exist_ok=True)
        for tree in ("inputs", "bench"):  # the decks and bench/decks_timestep.in
            if not os.path.exists(os.path.join(work, tree)):
                os.symlink(os.path.join(REPO, tree), os.path.join(work, tree))
        records, warnings = {}, {}
        out = lmp_run(lmp, work, "servo", args=(os.path.join("inputs", "axisym.in"), "-var",
                                                 "out", "servo", "-var", "strain",
                                                 repr(args.strain)))
        records["thornton/yin + cell/servo"] = read_servo_csv(os.path.join(work, "servo.csv"))
        warnings["thornton/yin + cell/servo"] = sorted(set(re.findall(r"WARNING: (.*)", out)))
        virial = "fix_modify shear press virial\n"
        mean, lateral = f"pressure/mean {P0!r}", "pressure v_lat"
        peers = [("granular + deform/pressure pressure/mean", "granular", mean, ""),
                 ("granular + deform/pressure pressure/mean, virial", "granular", mean, virial),
                 ("granular + deform/pressure lateral stress", "granular", lateral, virial),
                 ("thornton/yin + deform/pressure lateral stress", "thornton/yin", lateral,
                  virial)]
        for k, (label, pair, style, press) in enumerate(peers):
            name = f"peer{k}"
            text = PEER.format(load=LOAD, pair=PAIRS[pair], rate_x=-RATE, rate=RATE, p0=P0,
                               gain=args.gain, max_rate=args.max_rate, press=press,
                               lateral=style, every=EVERY, name=name, strain=args.strain)
            out = lmp_run(lmp, work, name, text)
            records[label] = read_txt(os.path.join(work, f"{name}.txt"))
            warnings[label] = sorted(set(re.findall(r"WARNING: (.*)", out)))
    table = {name: summary(r) for name, r in records.items()}
    for name, s in table.items():
        print(f"{name}: " + ", ".join(f"{k} {v:.4g}" for k, v in s.items()))
        for w in warnings[name]:
            print(f"    WARNING: {w}")
    write_result(args.json, {"lammps": "4 Feb 2025", "rate": RATE, "p0": P0, "gain": args.gain,
                           "max_rate": args.max_rate, "strain": args.strain,
                           "runs": table, "warnings": warnings}, indent=2, lmp=args.lmp2025)
    print("wrote", args.json)
    print("wrote", plot(records, args.out))


if __name__ == "__main__":
    main()
