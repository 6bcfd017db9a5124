#!/usr/bin/env python3
"""Throughput of pair thornton/yin (and its specialised kernels) against LAMMPS's granular
styles and LIGGGHTS's Hertz model on the same packed specimen, plain NVE, identical neighbor
settings, timestep and step counts.

    /usr/bin/python3 bench/pair_speed.py [--data bench/data/dense_paper_100kPa.data |
        --specimen RESTART] [--steps 2000] [--repeats 5] [--ranks 1]
        [--out bench/results/pair_speed] [--cases NAME ...] [--variant NAME=PATH/tylmp.so ...]
        [--build-variant NAME=CMAKE_OPTION[,CMAKE_OPTION ...] ...]
        [--liggghts liggghts] [--lmp2025 WRAPPER]

Specimen: every case starts from the same LAMMPS data file, by default the committed
bench/data/dense_paper_100kPa.data (3620 spheres of the paper's size distribution, dense,
isotropic p = 100 kPa, positions and velocities; how it was made: bench/data/README.md).
LAMMPS cases read it with `atom_style sphere`, `units si`, `boundary p p p`, `read_data`;
the LIGGGHTS case with `atom_style granular` and `read_data` of the same file (the Atoms and
Velocities columns of the two styles are identical: id type diameter density x y z, and
id vx vy vz wx wy wz). --specimen RESTART (a restart of the plugin's styles, e.g.
tylmp_specimens/dense_quick.restart written by `lmp -in inputs/axisym.in`) is first turned
into a data file in the temporary directory (`read_restart` + `write_data ... nocoeff`), which
every case then reads. All cases: `neighbor 1.35e-5 bin`, `neigh_modify every 1 delay 0 check
yes`, velocities communicated to ghosts, `fix nve/sphere`, the same timestep (0.2 Rayleigh
times of the smallest sphere, 0.0144 s with the scaled density 2.65e15 kg/m^3).

Cases: thornton/yin with Gamma = 0.6 and 0, each also through the scalar build of the law
("isa scalar": run with the environment variable TYLMP_LAW_ISA=scalar); LAMMPS
`granular` jkr+mindlin and hertz/material+mindlin; LAMMPS `gran/hertz/history`; and
"liggghts hertz+history": LIGGGHTS `pair_style gran model hertz tangential history` with
the material in `fix property/global` (youngsModulus 70e9, poissonsRatio 0.3,
coefficientFriction 0.3, coefficientRestitution 1.0, the largest LIGGGHTS accepts: its
damping coefficient is proportional to ln(e), so e = 1 means exactly no damping, like every
other case). LIGGGHTS needs `newton off` (its shear history requires newton pair off; the
LAMMPS cases keep LAMMPS's default newton on), `hard_particles yes` (it refuses E > 1e9 Pa in SI
units otherwise) and `communicate single vel yes`. Its Hertz-Mindlin law (kt = 8 G* a,
Coulomb cap at mu Fn) is that of `granular hertz/material ... tangential mindlin NULL 0 0.3`
(they differ only in how the history is incremented and rotated);
bench/check_liggghts_equivalence.py checks that the stresses at step 0 agree to 1e-6.

LIGGGHTS (Debian 12: LIGGGHTS-PUBLIC 3.8.0, binary /usr/bin/liggghts, MPI-enabled):

    apt-get update && apt-get install -y liggghts

Without the binary (or --liggghts PATH) the LIGGGHTS case is skipped with a message; the
others run. With --ranks N > 1 every case, LIGGGHTS's included, runs under
`mpirun --allow-run-as-root --oversubscribe -np N`.

With --lmp2025 WRAPPER (the lmp of LAMMPS 4 Feb 2025 that `bash scripts/lammps2025.sh` builds
and names on its last line) every LAMMPS case also runs under that LAMMPS, labelled
"CASE @4Feb2025", in the same alternation and on the same data file: thornton/yin with the
build of tylmp for it, and the 2025 built-ins (`granular jkr ... tangential mindlin`,
`granular hertz/material ...`, `gran/hertz/history`) in the same syntax. The timed comparison:

    W=$(TYLMP_LAMMPS2025_NO_TESTS=1 bash scripts/lammps2025.sh | tail -1)
    PYTHONPATH=$PWD/build/python /usr/bin/python3 bench/pair_speed.py --lmp2025 "$W" \
        --steps 5000 --repeats 7 --cases "thornton/yin G=0.6" "thornton/yin G=0" \
        "granular jkr+mindlin" "granular hertz/material+mindlin" gran/hertz/history \
        "liggghts thornton_yin G=0.6" "liggghts thornton_yin G=0" "liggghts hertz+history" \
        --out bench/results/pair_speed_law_now

Every case runs `repeats` times, the cases taken in alternation so that drifts of the
machine's speed hit all of them alike; the figure is the median of the loop time ("Loop time
of ..." in both programs' output), reported as atom-steps per second and as a ratio to
thornton/yin with Gamma = 0.6.
With --variant (repeatable) every thornton/yin case runs once per build of the library
(TYLMP_LIBRARY set per run), all in the same alternation, to compare code variants; the
table then also gives, per case, the median over repeats of the per-repeat time ratio of each
variant to the first one. --build-variant NAME=OPTIONS (repeatable) first builds such a variant
with the CMake options given (comma-separated) into build-bench-NAME/ of the repository and
then runs it as --variant NAME=build-bench-NAME/python/tylmp/tylmp.so, e.g.
--build-variant scalar=-DTYLMP_VECTOR_LAW=OFF for the plugin built with the scalar law alone.
The benchmark builds of the plugin (bench/variants.cmake; not part of the product) are
targets of a build configured with -DTYLMP_BENCH=ON:

    cmake -S . -B build -DTYLMP_BENCH=ON && cmake --build build --target tylmp tylmp_generic tylmp_plumbing
    /usr/bin/python3 bench/pair_speed.py --variant specialised=build/python/tylmp/tylmp.so \
        --variant generic=build/bench/generic/tylmp.so \
        --variant plumbing=build/bench/plumbing/tylmp.so \
        --cases "thornton/yin G=0.6" "thornton/yin G=0"

(generic: the adhesive, damped law for every scene, what the specialisations gain;
plumbing: the law replaced by a Hertz normal force, what everything around it costs).
Writes OUT.csv (every run), OUT.json (medians and ratios), OUT.png (atom-steps per second of
every case: median and the range of the repeats) and prints a table.

    /usr/bin/python3 bench/pair_speed.py --plot CSV [CSV ...] --png PNG

redraws the figure from earlier runs' CSV files without running anything (one bar per case
and file, e.g. two calls side by side: docs/performance_throughput.png).
"""
import argparse
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import lammps_version, write_result  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from lammps_log import first_loop, section  # noqa: E402
DATA = os.path.join(REPO, "bench", "data", "dense_paper_100kPa.data")
LOAD = ('python tylmp_load input 1 SELF format p here "from tylmp import load as tylmp_load"\n'
        "python tylmp_load invoke\n")

# E = 70 GPa, nu = 0.3, mu = 0.3; no damping anywhere (the paper uses none)
E, NU, MU, GAMMA = 70e9, 0.3, 0.3, 0.6
E_STAR = E / (2 * (1 - NU ** 2))
KN_HOOKE_HERTZ = 4.0 / 3.0 * E_STAR          # gran/hertz/history: F = kn sqrt(R* delta) delta
KT_HOOKE_HERTZ = KN_HOOKE_HERTZ * 2 * (1 - NU) / (2 - NU)
# 0.2 Rayleigh times of the smallest sphere (R = 0.0675 mm, scaled density 2.65e15 kg/m^3,
# G = E/2.6), as inputs/common/numerics.in; one number written into every deck
DT = 0.2 * math.pi * 0.0675e-3 * math.sqrt(2650e12 / (E / 2.6)) / (0.1631 * NU + 0.8766)
NEIGHBOR = "neighbor 1.35e-5 bin\nneigh_modify every 1 delay 0 check yes\n"

CASES = {
    "thornton/yin G=0.6": f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} {GAMMA}\n",
    "thornton/yin G=0": f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} 0.0\n",
    # frictionless, as the dense specimen's preparation (inputs/common/prepare.in)
    "thornton/yin G=0 mu=0": f"pair_style thornton/yin\npair_coeff * * {E} {NU} 0.0 0.0\n",
    # the same law through the scalar build of the batch entry (the environment variable
    # TYLMP_LAW_ISA=scalar, CASE_ENVIRONMENT): what the SIMD builds gain in situ (the results
    # are bitwise the same)
    "thornton/yin G=0.6 isa scalar": f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} {GAMMA}\n",
    "thornton/yin G=0 isa scalar": f"pair_style thornton/yin\npair_coeff * * {E} {NU} {MU} 0.0\n",
    "granular jkr+mindlin": (f"pair_style granular\npair_coeff * * jkr {E} 0.0 {NU} {GAMMA} "
                             f"damping viscoelastic tangential mindlin NULL 0.0 {MU}\n"),
    "granular hertz/material+mindlin": (
        f"pair_style granular\npair_coeff * * hertz/material {E} 0.0 {NU} "
        f"damping viscoelastic tangential mindlin NULL 0.0 {MU}\n"),
    "gran/hertz/history": (f"pair_style gran/hertz/history {KN_HOOKE_HERTZ} {KT_HOOKE_HERTZ} "
                           f"0.0 0.0 {MU} 0\npair_coeff * *\n"),
    # LIGGGHTS: damping ~ ln(coefficientRestitution), so e = 1 is exactly undamped (e <= 1 is
    # required); one atom type, as in the data file
    "liggghts hertz+history": (
        f"fix m1 all property/global youngsModulus peratomtype {E}\n"
        f"fix m2 all property/global poissonsRatio peratomtype {NU}\n"
        f"fix m3 all property/global coefficientRestitution peratomtypepair 1 1.0\n"
        f"fix m4 all property/global coefficientFriction peratomtypepair 1 {MU}\n"
        "pair_style gran model hertz tangential history\npair_coeff * *\n"),
}
# LIGGGHTS with its simplified JKR cohesion (sjkr: F = k A_overlap, k = cohesionEnergyDensity;
# 1e6 J/m^3, a value of its examples' order), and our law in LIGGGHTS (the launcher
# build/bin/tyliggghts, --tyliggghts): the same specimen and material
_LIGGGHTS_MATERIAL = CASES["liggghts hertz+history"].split("pair_style")[0]
CASES["liggghts hertz+history+sjkr"] = (
    _LIGGGHTS_MATERIAL + "fix m5 all property/global cohesionEnergyDensity peratomtypepair 1 1e6\n"
    "pair_style gran model hertz tangential history cohesion sjkr\npair_coeff * *\n")
for _label, _gamma in (("G=0.6", GAMMA), ("G=0", 0.0)):
    CASES[f"liggghts thornton_yin {_label}"] = (
        _LIGGGHTS_MATERIAL + f"fix m5 all property/global interfaceEnergy peratomtypepair 1 {_gamma}\n"
        "pair_style gran model thornton_yin tangential thornton_yin\npair_coeff * *\n")
# the same with LIGGGHTS's pair/gran/local compute defined (never invoked): LIGGGHTS's own pair
# loop then runs, reading each contact's force as the model returns it, so the model runs the
# contacts one at a time in the scalar build instead of in batches in its own pair loop
# (plugin/liggghts/normal_model_thornton_yin.h, liggghts_loop_feature)
for _label in ("G=0.6", "G=0"):
    CASES[f"liggghts thornton_yin {_label} one at a time"] = (
        CASES[f"liggghts thornton_yin {_label}"]
        + "compute one_at_a_time all pair/gran/local id force\n")
TYLIGGGHTS_CASES = {f"liggghts thornton_yin {g}{w}" for g in ("G=0.6", "G=0")
                    for w in ("", " one at a time")}
TYLIGGGHTS = os.path.join(REPO, "build", "bin", "tyliggghts")
LIGGGHTS_CASES = {"liggghts hertz+history", "liggghts hertz+history+sjkr"} | TYLIGGGHTS_CASES
LMP2025_SUFFIX = " @4Feb2025"       # label of a case run with the lmp of --lmp2025
LIGGGHTS_MISSING = ("no LIGGGHTS binary '{}' on PATH: skipping the case 'liggghts hertz+history' "
                    "(install it with 'apt-get install liggghts'; Debian 12: LIGGGHTS-PUBLIC "
                    "3.8.0)")


def build_variant(name, options):
    """Configure and build the plugin with the CMake `options` into build-bench-NAME of the
    repository; returns the path of its tylmp.so."""
    build = os.path.join(REPO, f"build-bench-{name}")
    subprocess.run(["cmake", "-S", REPO, "-B", build, "-DCMAKE_BUILD_TYPE=Release"] + options,
                   check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", build, "--target", "tylmp", "-j2"], check=True,
                   stdout=subprocess.DEVNULL)
    return os.path.join(build, "python", "tylmp", "tylmp.so")


def deck(data, pair_lines, steps, measure=None):
    """LAMMPS deck: read_data of `data`, then plain NVE for `steps` steps; `measure` replaces
    the default `thermo STEPS` (computes, thermo_style ...)."""
    return f"""{LOAD}atom_style sphere
units si
boundary p p p
read_data {data}
comm_modify vel yes
{pair_lines}{NEIGHBOR}timestep {DT!r}
fix integrate all nve/sphere
{measure or f"thermo {steps}"}
run {steps}
"""


def liggghts_deck(data, pair_lines, steps, measure=None):
    """The same for LIGGGHTS: newton off (its shear history requires newton pair off),
    hard_particles yes (E = 70 GPa is above its SI sanity limit of 1e9 Pa)."""
    return f"""atom_style granular
hard_particles yes
units si
boundary p p p
newton off
communicate single vel yes
read_data {data}
{pair_lines}{NEIGHBOR}timestep {DT!r}
fix integrate all nve/sphere
{measure or f"thermo {steps}"}
run {steps}
"""


def restart_to_data(restart, workdir):
    """A data file in workdir with the atoms of a restart of the plugin's styles."""
    path = os.path.join(workdir, "specimen.data")
    with open(os.path.join(workdir, "in.restart_to_data"), "w") as fh:
        fh.write(f"{LOAD}read_restart {restart}\nwrite_data {path} nocoeff\n")
    proc = subprocess.run(["lmp", "-in", "in.restart_to_data", "-log", "none", "-nocite"],
                          cwd=workdir, capture_output=True, text=True)
    if proc.returncode != 0 or not os.path.exists(path):
        raise RuntimeError(f"write_data from {restart} failed\n{proc.stdout[-2000:]}{proc.stderr}")
    return path


# environment of the cases that run another build of the law than the pair's own choice
CASE_ENVIRONMENT = {"thornton/yin G=0.6 isa scalar": {"TYLMP_LAW_ISA": "scalar"},
                    "thornton/yin G=0 isa scalar": {"TYLMP_LAW_ISA": "scalar"}}


def run_deck(name, text, ranks, workdir, library=None, liggghts="liggghts", lmp="lmp"):
    """Run one deck (LIGGGHTS for the LIGGGHTS cases, `lmp` otherwise); returns its stdout."""
    path = os.path.join(workdir, "in.bench")
    with open(path, "w") as fh:
        fh.write(text)
    exe = TYLIGGGHTS if name in TYLIGGGHTS_CASES else liggghts if name in LIGGGHTS_CASES else lmp
    cmd = [exe, "-in", path, "-log", "none", "-nocite"]
    if ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
    env = dict(os.environ, **CASE_ENVIRONMENT.get(name.split(" @")[0], {}))
    if library:
        env["TYLMP_LIBRARY"] = library
    proc = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        raise RuntimeError(f"{name}: {' '.join(cmd)} failed ({proc.returncode})\n"
                           f"{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    return proc.stdout


def case_deck(name, data, steps, measure=None):
    build = liggghts_deck if name in LIGGGHTS_CASES else deck
    return build(data, CASES[name], steps, measure)


def run_case(data, name, steps, ranks, workdir, library=None, liggghts="liggghts", lmp="lmp"):
    out = run_deck(name, case_deck(name, data, steps), ranks, workdir, library, liggghts, lmp)
    # LAMMPS and LIGGGHTS 3.8 ("..., finish time ...") both print this line
    run = first_loop(out, name)
    loop = run["seconds"]
    pair = section(out, "Pair")    # LAMMPS: the Pair row's average seconds
    if pair:
        pair_s = pair[0]["avg"]
    else:                          # LIGGGHTS: "Pair  time (%) = ..."
        m = re.search(r"^Pair\s+time \(%\) = ([0-9.eE+-]+)", out, re.M)
        pair_s = float(m.group(1)) if m else float("nan")
    return loop, run["atoms"] * run["steps"] / loop, pair_s


def plot(csv_paths, png):
    """Horizontal bars: median atom-steps/s of every case in each CSV (one colour per file,
    labelled by its name and rank count), whiskers from the slowest to the fastest repeat."""
    import csv
    import matplotlib
    import matplotlib.ticker
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from tylmp.analysis.figures import save_figure
    tables = []
    for path in csv_paths:
        with open(path) as fh:
            rows = list(csv.DictReader(fh))
        by_case = {}
        for r in rows:
            by_case.setdefault(r["case"], []).append(float(r["atom_steps_per_s"]))
        name = os.path.splitext(os.path.basename(path))[0]
        tables.append((f"{name}, {rows[0]['ranks']} rank(s)" if rows else path, by_case))
    cases = list(dict.fromkeys(c for _, t in tables for c in t))
    height = 0.8 / len(tables)
    fig, ax = plt.subplots(figsize=(8, 0.45 * len(cases) * len(tables) + 1.2))
    for k, (label, by_case) in enumerate(tables):
        ys, med, lo, hi = [], [], [], []
        for i, case in enumerate(cases):
            if case in by_case:
                v = by_case[case]
                m = statistics.median(v)
                ys.append(i + (k - (len(tables) - 1) / 2) * height)
                med.append(m)
                lo.append(m - min(v))
                hi.append(max(v) - m)
        ax.barh(ys, med, height=height, xerr=[lo, hi], capsize=2, label=label)
    ax.set_yticks(range(len(cases)))
    ax.set_yticklabels(cases)
    ax.invert_yaxis()
    ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda x, _: f"{x / 1e6:g}"))
    ax.set_xlabel("million atom-steps per second\n(median; whiskers: range of the repeats)")
    ax.legend(loc="lower right")
    ax.grid(axis="x", alpha=0.3)
    return save_figure(fig, png)


def main(argv=None):
    global TYLIGGGHTS
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    src = ap.add_mutually_exclusive_group()
    src.add_argument("--data", default=DATA,
                     help="LAMMPS data file (atom_style sphere) every case starts from")
    src.add_argument("--specimen", default=None,
                     help="a restart of the plugin's styles instead of --data (converted to a "
                          "data file in the temporary directory)")
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--cases", nargs="*", default=list(CASES), choices=list(CASES),
                    metavar="CASE", help="; ".join(CASES))
    ap.add_argument("--out", default=os.path.join(REPO, "bench", "results", "pair_speed"))
    ap.add_argument("--variant", action="append", default=[],
                    help="NAME=PATH of a tylmp.so build; thornton/yin cases run once per variant")
    ap.add_argument("--build-variant", action="append", default=[], metavar="NAME=OPTIONS",
                    help="build tylmp with these comma-separated CMake options into "
                         "build-bench-NAME and run it as --variant NAME")
    ap.add_argument("--liggghts", default="liggghts", help="LIGGGHTS executable")
    ap.add_argument("--tyliggghts", default=TYLIGGGHTS,
                    help="the launcher of our law in LIGGGHTS (CMake builds build/bin/tyliggghts)")
    ap.add_argument("--lmp2025", metavar="WRAPPER",
                    help="also run every LAMMPS case with this lmp of LAMMPS 4 Feb 2025 (the "
                         "last line of 'bash scripts/lammps2025.sh'), labelled 'CASE "
                         f"{LMP2025_SUFFIX.strip()}'")
    ap.add_argument("--plot", nargs="+", metavar="CSV",
                    help="only redraw the figure from these CSV files (see --png)")
    ap.add_argument("--png", help="the figure of --plot")
    args = ap.parse_args(argv)
    TYLIGGGHTS = args.tyliggghts
    if args.plot:
        if not args.png:
            ap.error("--plot needs --png")
        print("wrote", plot(args.plot, args.png))
        return
    variants = [tuple(v.split("=", 1)) for v in args.variant]
    for spec in args.build_variant:
        name, _, options = spec.partition("=")
        if not name or not options.startswith("-D"):
            ap.error(f"--build-variant {spec}: expected NAME=-DOPTION=VALUE[,-DOPTION=VALUE ...]")
        variants.append((name, build_variant(name, options.split(","))))
    if args.lmp2025 and variants:
        ap.error("--variant builds are for one LAMMPS: run --lmp2025 without --variant")
    if args.lmp2025 and not (os.path.isfile(args.lmp2025) and os.access(args.lmp2025, os.X_OK)):
        ap.error(f"--lmp2025 {args.lmp2025}: no such executable (bash scripts/lammps2025.sh "
                 "prints its path on its last line)")
    skipped = []
    if any(name in LIGGGHTS_CASES for name in args.cases) and not shutil.which(args.liggghts):
        print(LIGGGHTS_MISSING.format(args.liggghts), flush=True)
        skipped = [name for name in args.cases if name in LIGGGHTS_CASES]
    elif any(name in TYLIGGGHTS_CASES for name in args.cases) and not os.access(TYLIGGGHTS, os.X_OK):
        print(f"no launcher {TYLIGGGHTS}: skipping the thornton_yin cases in LIGGGHTS (apt-get "
              "install libliggghts-dev, rebuild)", flush=True)
        skipped = [name for name in args.cases if name in TYLIGGGHTS_CASES]
    runs = []    # (label, case, library, lmp)
    for name in args.cases:
        if name in skipped:
            continue
        if variants and name.startswith("thornton/yin"):
            runs += [(f"{name} [{vn}]", name, os.path.abspath(lib), "lmp") for vn, lib in variants]
        elif name in LIGGGHTS_CASES:
            runs.append((name, name, None, "lmp"))
        else:
            runs.append((name, name, os.path.abspath(variants[0][1]) if variants else None, "lmp"))
        if args.lmp2025 and name not in LIGGGHTS_CASES:
            runs.append((name + LMP2025_SUFFIX, name, None, os.path.abspath(args.lmp2025)))
    source = os.path.abspath(args.specimen or args.data)
    if not os.path.exists(source):
        sys.exit(f"no specimen {source}" + (
            ": run 'lmp -in inputs/axisym.in' once from the repository root (it prepares "
            "tylmp_specimens/dense_quick.restart)" if args.specimen else ""))
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory() as work:
        data = restart_to_data(source, work) if args.specimen else source
        for rep in range(args.repeats):
            for label, name, library, lmp in runs:
                loop, rate, pair = run_case(data, name, args.steps, args.ranks, work, library,
                                            args.liggghts, lmp)
                rows.append({"case": label, "repeat": rep, "ranks": args.ranks,
                             "loop_s": loop, "atom_steps_per_s": rate, "pair_s": pair})
                print(f"  {label:44s} run {rep}: {rate:.4g} atom-steps/s", flush=True)
    with open(args.out + ".csv.tmp", "w") as fh:    # written whole, then renamed: no torn file
        fh.write("case,repeat,ranks,loop_s,atom_steps_per_s,pair_s\n")
        for r in rows:
            fh.write(f"{r['case']},{r['repeat']},{r['ranks']},{r['loop_s']},"
                     f"{r['atom_steps_per_s']},{r['pair_s']}\n")
    os.replace(args.out + ".csv.tmp", args.out + ".csv")
    medians = {label: statistics.median(r["atom_steps_per_s"] for r in rows if r["case"] == label)
               for label, _, _, _ in runs}
    base = medians.get("thornton/yin G=0.6") or medians.get(
        f"thornton/yin G=0.6 [{variants[0][0]}]" if variants else "")
    speedups = {}
    if len(variants) > 1:
        for name in args.cases:
            if not name.startswith("thornton/yin"):
                continue
            first = f"{name} [{variants[0][0]}]"
            for vn, _ in variants[1:]:
                label = f"{name} [{vn}]"
                ratios = [a["loop_s"] / b["loop_s"]
                          for a in rows if a["case"] == first
                          for b in rows if b["case"] == label and b["repeat"] == a["repeat"]]
                speedups[label] = statistics.median(ratios)
    summary = {"data": None if args.specimen else source, "specimen": args.specimen and source,
               "timestep": DT, "skipped": skipped, "steps": args.steps, "repeats": args.repeats,
               "ranks": args.ranks, "lmp2025": args.lmp2025,
               "lmp2025_version": args.lmp2025 and lammps_version(args.lmp2025), "median_atom_steps_per_s": medians,
               "ratio_to_thornton_yin_G0.6": {k: v / base for k, v in medians.items()} if base else {},
               "speedup_vs_first_variant": speedups}
    write_result(args.out + ".json", summary, indent=2)
    plot([args.out + ".csv"], args.out + ".png")
    print(f"\n| case ({args.ranks} rank(s), {args.steps} steps, median of {args.repeats}) "
          f"| atom-steps/s | ratio to thornton/yin G=0.6 |\n|---|---|---|")
    for name, v in medians.items():
        print(f"| {name} | {v:.4g} | {v / base if base else float('nan'):.3f} |")
    if speedups:
        print(f"\n| variant | median per-repeat speed-up vs [{variants[0][0]}] |\n|---|---|")
        for label, v in speedups.items():
            print(f"| {label} | {v:.3f} |")


if __name__ == "__main__":
    main()
