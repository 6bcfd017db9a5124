#!/usr/bin/env python3
"""SHA-256 digests of short trajectories of the shipped specimens: the check that a change of
the code leaves every trajectory bitwise the same (a refactor), or the record of which ones a
change of the physics moves.

    /usr/bin/python3 bench/trajectory_digest.py [--lmp CMD] [--library PATH/tylmp.so]
        [--pythonpath DIR] [--liggghts PATH | --no-liggghts] [--steps 1000]
        [--runs NAME ...] [--isa scalar|sse2|avx2|avx512] [--keep DIR] [--json FILE]

Each run starts from a specimen of bench/data/ (positions and velocities, fresh contacts),
takes `--steps` steps (default 1000) and writes x, v, f and torque of every atom at the end,
sorted by id, each number at full precision (%.17g), with the box in the header; the digest is
the SHA-256 of that snapshot (ITEM lines included, so the box and the step count too). Two
builds that give the same digest for every run computed the same trajectories to the last bit.

Runs (LAMMPS: `pair_style thornton/yin`, pair_coeff 70e9 0.3 0.3 GAMMA, timestep 0.0144 s =
0.2 Rayleigh times of the smallest sphere, `neighbor 1.35e-5 bin`, fix nve/sphere):

  nve_quick_G0.6      500-sphere quick specimen (seed 1), NVE, Gamma = 0.6 J/m^2
  nve_quick_G0        the same at Gamma = 0 (Hertz-Mindlin)
  nve_paper_G0.6      the 3620-sphere paper specimen, NVE, Gamma = 0.6
  servo_axisym        quick specimen, `fix cell/servo axisym x 1e-3 1e5` (contacts slide)
  servo_shear_xz      quick specimen, `change_box all triclinic`, `fix cell/servo shear xz
                      1e-4 1e5` (simple shear of a triclinic cell, affine contact velocity)
  servo_newton_off    servo_axisym with `newton off`
  servo_mpi2          servo_axisym on 2 MPI ranks
  restart_G0.6        nve_quick_G0.6 as two halves, the second in a new process from the
                      first's restart (the contact history through a restart file)
  liggghts_G0.6       LIGGGHTS 3.8 (`--liggghts`, default build/bin/tyliggghts when built):
                      quick specimen, `pair_style gran model thornton_yin`, NVE, Gamma = 0.6

The plugin: PYTHONPATH is `--pythonpath` (default build/python of this repository) in front of
the inherited one, and `--library` sets TYLMP_LIBRARY (a build of tylmp.so for the lmp run).
`--lmp` is the command (split like a shell would) that runs a deck: default `lmp`; the LAMMPS
4 Feb 2025 wrapper from the last line of `TYLMP_LAMMPS2025_NO_TESTS=1 bash
scripts/lammps2025.sh` takes its library from its own build (give no --library then).
`--isa` runs the law's build for that instruction set (TYLMP_LAW_ISA).

Typical use, before and after a change:

    /usr/bin/python3 bench/trajectory_digest.py --json before.json     (on the old build)
    /usr/bin/python3 bench/trajectory_digest.py --json after.json      (on the new build)
    diff before.json after.json
"""
import argparse
import hashlib
import json
import os
import shlex
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "bench", "data")
QUICK = os.path.join(DATA, "dense_quick_100kPa_seed1.data")
PAPER = os.path.join(DATA, "dense_paper_100kPa.data")

LOADER = ('python tylmp_load input 1 SELF format p here "from tylmp import load as tylmp_load"\n'
          "python tylmp_load invoke\n")
COLUMNS = "id x y z vx vy vz fx fy fz tqx tqy tqz"
SNAPSHOT = f"write_dump all custom final.dump {COLUMNS} modify sort id format float %.17g\n"


def lammps_run(gamma, steps, fix="", end=SNAPSHOT):
    """The pair, the neighbour settings, the integrator, `fix`, `steps` steps and `end`."""
    return f"""pair_style thornton/yin
pair_coeff * * 70e9 0.3 0.3 {gamma}
neighbor 1.35e-5 bin
neigh_modify every 1 delay 0 check yes
timestep 0.0144
fix integrate all nve/sphere
{fix}thermo {steps}
run {steps}
{end}"""


def lammps_deck(data, steps, gamma=0.6, newton="on", extra="", fix="", end=SNAPSHOT):
    """A LAMMPS deck of one run: `steps` steps, then `end` (the snapshot)."""
    return f"""{LOADER}units si
atom_style sphere
atom_modify map array
boundary p p p
newton {newton}
comm_modify vel yes
read_data {data}
{extra}""" + lammps_run(gamma, steps, fix, end)


def restart_decks(data, steps, gamma=0.6):
    """The run as two halves: the first writes a restart, the second reads it."""
    half = steps // 2
    first = lammps_deck(data, half, gamma, end="write_restart half.restart\n")
    second = f"{LOADER}read_restart half.restart\ncomm_modify vel yes\n" + lammps_run(
        gamma, steps - half)
    return [first, second]


def liggghts_deck(data, steps, gamma=0.6):
    """The LIGGGHTS deck (3.8: newton off, `communicate`, material in fix property/global;
    its dump_modify takes one format string for all columns)."""
    line = " ".join(["%d"] + ["%.17g"] * 12)
    return f"""units si
atom_style sphere
atom_modify map array
boundary p p p
newton off
communicate single vel yes
read_data {data}
fix m1 all property/global youngsModulus peratomtype 70e9
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientFriction peratomtypepair 1 0.3
fix m4 all property/global interfaceEnergy peratomtypepair 1 {gamma}
pair_style gran model thornton_yin tangential thornton_yin
pair_coeff * *
neighbor 1.35e-5 bin
neigh_modify every 1 delay 0 check yes
timestep 0.0144
fix integrate all nve/sphere
thermo {steps}
dump final all custom {steps} final.dump {COLUMNS}
dump_modify final sort id format "{line}"
run {steps}
"""


SERVO = "fix cell all cell/servo axisym x 1e-3 1e5\n"


def runs(steps):
    """name -> (program kind, [decks], MPI ranks)"""
    return {
        "nve_quick_G0.6": ("lammps", [lammps_deck(QUICK, steps, 0.6)], 1),
        "nve_quick_G0": ("lammps", [lammps_deck(QUICK, steps, 0.0)], 1),
        "nve_paper_G0.6": ("lammps", [lammps_deck(PAPER, steps, 0.6)], 1),
        "servo_axisym": ("lammps", [lammps_deck(QUICK, steps, fix=SERVO)], 1),
        "servo_shear_xz": ("lammps", [lammps_deck(
            QUICK, steps, extra="change_box all triclinic\n",
            fix="fix cell all cell/servo shear xz 1e-4 1e5\n")], 1),
        "servo_newton_off": ("lammps", [lammps_deck(QUICK, steps, newton="off", fix=SERVO)], 1),
        "servo_mpi2": ("lammps", [lammps_deck(QUICK, steps, fix=SERVO)], 2),
        "restart_G0.6": ("lammps", restart_decks(QUICK, steps), 1),
        "liggghts_G0.6": ("liggghts", [liggghts_deck(QUICK, steps)], 1),
    }


def final_snapshot(path):
    """The last snapshot of a dump file (from its last 'ITEM: TIMESTEP' on), as bytes."""
    with open(path, "rb") as fh:
        text = fh.read()
    start = text.rfind(b"ITEM: TIMESTEP")
    if start < 0:
        raise RuntimeError(f"{path}: no snapshot")
    return text[start:]


def run_one(name, kind, decks, ranks, program, environment, workdir):
    """Run the decks of one case in workdir/name; the SHA-256 of its final snapshot."""
    directory = os.path.join(workdir, name)
    os.makedirs(directory, exist_ok=True)
    for k, deck in enumerate(decks):
        deck_name = f"in.{k}"
        with open(os.path.join(directory, deck_name), "w") as fh:
            fh.write(deck)
        cmd = [*program, "-in", deck_name, "-log", f"log.{k}"]
        if kind == "lammps":
            cmd.append("-nocite")
        if ranks > 1:
            cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
        proc = subprocess.run(cmd, cwd=directory, capture_output=True, text=True,
                              errors="replace", env=environment)
        output = proc.stdout + proc.stderr
        if proc.returncode != 0 or "ERROR" in output:
            raise RuntimeError(f"{name}: {' '.join(cmd)} failed in {directory}:\n{output[-3000:]}")
    return hashlib.sha256(final_snapshot(os.path.join(directory, "final.dump"))).hexdigest()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lmp", default="lmp", help="command that runs LAMMPS (default: lmp)")
    ap.add_argument("--library", help="tylmp.so to load (sets TYLMP_LIBRARY)")
    ap.add_argument("--pythonpath", default=os.path.join(ROOT, "build", "python"),
                    help="directory of the tylmp package (default: build/python)")
    default_liggghts = os.path.join(ROOT, "build", "bin", "tyliggghts")
    ap.add_argument("--liggghts", default=default_liggghts,
                    help="LIGGGHTS launcher with the model (default: build/bin/tyliggghts)")
    ap.add_argument("--no-liggghts", action="store_true", help="skip the LIGGGHTS run")
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--runs", nargs="+", help="only these runs (default: all)")
    ap.add_argument("--isa", help="the law's build to run (TYLMP_LAW_ISA)")
    ap.add_argument("--keep", help="run in this directory and keep it (default: a temporary one)")
    ap.add_argument("--json", help="also write {run: digest} to this file")
    args = ap.parse_args(argv)

    environment = dict(os.environ, OMPI_MCA_btl_vader_single_copy_mechanism="none")
    if args.pythonpath:
        environment["PYTHONPATH"] = os.pathsep.join(
            p for p in (os.path.abspath(args.pythonpath), os.environ.get("PYTHONPATH")) if p)
    if args.library:
        environment["TYLMP_LIBRARY"] = os.path.abspath(args.library)
    if args.isa:
        environment["TYLMP_LAW_ISA"] = args.isa
    cases = runs(args.steps)
    chosen = args.runs or list(cases)
    unknown = [name for name in chosen if name not in cases]
    if unknown:
        ap.error(f"unknown runs {unknown}; the runs are {list(cases)}")
    if args.no_liggghts or not os.path.exists(args.liggghts):
        if args.runs and any(cases[name][0] == "liggghts" for name in args.runs):
            ap.error(f"no LIGGGHTS launcher at {args.liggghts}")
        if "liggghts_G0.6" in chosen:
            print("# liggghts_G0.6 skipped: no launcher (--liggghts)", file=sys.stderr)
        chosen = [name for name in chosen if cases[name][0] != "liggghts"]

    digests = {}
    with tempfile.TemporaryDirectory(prefix="trajectory_digest_") as scratch:
        workdir = os.path.abspath(args.keep) if args.keep else scratch
        for name in chosen:
            kind, decks, ranks = cases[name]
            program = shlex.split(args.lmp) if kind == "lammps" else [args.liggghts]
            digests[name] = run_one(name, kind, decks, ranks, program, environment, workdir)
            print(f"{digests[name]}  {name}", flush=True)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(digests, fh, indent=1, sort_keys=True)
            fh.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
