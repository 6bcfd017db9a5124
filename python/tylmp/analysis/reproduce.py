"""The paper's programme in one command: every run behind the figures of docs/validation.md,
as many at once as there are cores, then every figure and the summary table.

    tyanalysis reproduce [--programme paper|fidelity] [--scale paper|quick] [--dir paper_runs]
                         [--jobs N] [--inputs DIR] [--only NAME ...] [--dry-run]

The runs are the decks of inputs/ with the settings validation.md gives for each figure
(programmes.PROGRAMME). Each specimen is prepared once (one job each, in DIR/tylmp_specimens,
reused by every later run and by a later call); a shear run starts as soon as its specimen is
ready, longest first, at most `jobs` runs at a time (default: the number of cores). Each run writes its CSV record and a
LAMMPS log in DIR; a run whose record already ends at its target (a finished earlier call)
is not run again, so an interrupted call resumes where it stopped (its preparations find their
cached specimens and log beside the first call's logs, free_log). Progress: a line when a
run starts or ends, and every `--every` seconds the progress (fix cell/servo output 27) of each
running record. Then the figures of validation.md (the `tyanalysis` commands, PNGs in DIR) and
the summary table paper against ours (summary.md in DIR, `tyanalysis compare`).

`--scale quick` runs the same programme on the decks' quick scale (500 spheres, ten times the
paper's rates): minutes instead of hours, for checking the machinery.
"""
import os
import re
import shlex
import subprocess
import time

from ..specimen.paper import SCALES
from .programmes import PREP_WEIGHT, PROGRAMME, PROGRAMMES, entry, factor_rank, record_name


def rank_of(name, prog=PROGRAMME):
    """Start order of a run's group: in the trace study its factor's place in
    programmes.FACTORS, so that an interrupted call leaves whole factors, the first ones;
    0 for every run of the paper programme."""
    return factor_rank(name) if prog is PROGRAMMES["fidelity"] else 0


def specimen_of(name, prog=PROGRAMME):
    """The specimen a run shears (the decks' default: dense) and its preparation variables."""
    deck, vars_, _, _, prep = entry(name, prog)
    return vars_.get("specimen", "dense"), tuple(sorted(prep.items()))


def command(name, scale, inputs, prog=PROGRAMME):
    """lmp command line of a run (cwd: the run directory)."""
    deck, vars_, out, _, prep = entry(name, prog)
    cmd = ["lmp", "-in", os.path.join(inputs, deck), "-var", "scale", scale, "-var", "out", out]
    for k, v in list(prep.items()) + list(vars_.items()):
        if scale == "quick" and k == "rate":    # quick scale: the deck's own (faster) rates
            continue
        cmd += ["-var", k, v]
    return cmd + ["-log", f"{name}.log", "-nocite"]


def prepare_name(specimen):
    """Job name of the preparation of (specimen, preparation variables)."""
    name, prep = specimen
    return "prepare_" + "_".join([name] + [f"{k}{v}" for k, v in prep])


def free_log(workdir, stem):
    """STEM.log, or STEM.N.log with the first N free when an earlier call's log is there: a
    resumed call's preparation only finds its cached specimen, and its log must not replace the
    log of the preparation that made it."""
    if workdir is None or not os.path.exists(os.path.join(workdir, f"{stem}.log")):
        return f"{stem}.log"
    n = 1
    while os.path.exists(os.path.join(workdir, f"{stem}.{n}.log")):
        n += 1
    return f"{stem}.{n}.log"


def prepare_command(specimen, scale, inputs, workdir=None):
    name, prep = specimen
    cmd = ["lmp", "-in", os.path.join(inputs, "prepare_specimen.in"), "-var", "specimen",
           name, "-var", "scale", scale]
    for k, v in prep:
        cmd += ["-var", k, v]
    return cmd + ["-log", free_log(workdir, prepare_name(specimen)), "-nocite"]


def last_progress(path):
    """progress column of the last complete row of a fix cell/servo record, or None."""
    try:
        with open(path, "rb") as fh:
            header = fh.readline().decode().strip().split(",")
            fh.seek(0, 2)
            size = fh.tell()
            fh.seek(max(0, size - 4096))
            lines = fh.read().decode(errors="replace").split("\n")
    except OSError:
        return None
    rows = [ln for ln in lines[:-1] if ln and not ln.startswith(header[0])]    # whole lines
    if "progress" not in header or not rows:
        return None
    cells = rows[-1].split(",")
    try:
        return float(cells[header.index("progress")])
    except (ValueError, IndexError):
        return None


def finished(path):
    p = last_progress(path)
    return p is not None and p >= 1.0 - 1e-9


def find_inputs():
    """The decks: the repository's inputs/ when this package runs from a checkout
    (python/tylmp), else the copy that goes with the package (tylmp/inputs: a build tree's
    python/ or an install)."""
    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    for here in (os.path.join(os.path.dirname(os.path.dirname(package)), "inputs"),
                 os.path.join(package, "inputs")):
        if os.path.isfile(os.path.join(here, "axisym.in")):
            return here
    raise SystemExit("tyanalysis reproduce: no decks found (give --inputs DIR, the "
                     "repository's inputs/)")


def lmp_environment():
    """The environment of the lmp runs: when a build of the library sits in this tylmp
    package, the directory holding the package goes first on PYTHONPATH, so that the decks'
    `from tylmp import load` in LAMMPS's embedded Python takes this package and its library
    whether or not its virtual environment is active (on PATH)."""
    env = dict(os.environ)
    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if any(re.fullmatch(r"tylmp(-\d{8})?\.so", f) for f in os.listdir(package)):
        rest = [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p]
        env["PYTHONPATH"] = os.pathsep.join([os.path.dirname(package)] + rest)
    return env


def figure_commands(d, scale="paper"):
    """The tyanalysis commands of validation.md on the records in d (files that exist); each
    figure's caption names the scale's number of spheres and the specimen its runs shear."""
    def f(name):
        return os.path.join(d, name)

    def about(*runs):
        specimens = sorted({specimen_of(n)[0] for n in runs})
        return ["--n", str(SCALES[scale]), "--specimen", " and ".join(specimens)]
    rec = {n: f(record_name(n)) for n in PROGRAMME}
    friction = [n for n in PROGRAMME if n.startswith("friction_")]
    radial = {s: [f"radial_{s}_b{b}" for b in ("0.25", "0.5", "0.75", "1")]
              for s in ("dense", "loose")}
    cmds = [
        ["axisym", rec["axisym_dense"], rec["axisym_loose"], "--labels", "dense", "loose",
         "--paper", "--out", f("fig1_2_axisym_paper.png")] + about("axisym_dense", "axisym_loose"),
        ["friction"] + [rec[n] for n in friction] +
        ["--paper", "--out", f("fig3_friction_paper.png")] + about(*friction),
        ["radial", rec["axisym_dense"]] + [rec[n] for n in radial["dense"]] +
        ["--labels", "b=0 (axisym)", "b=0.25", "b=0.5", "b=0.75", "b=1",
         "--paper", "--out", f("fig4_6_radial_dense_paper.png")] + about(*radial["dense"]),
        ["radial", rec["axisym_loose"]] + [rec[n] for n in radial["loose"]] +
        ["--labels", "b=0 (axisym)", "b=0.25", "b=0.5", "b=0.75", "b=1",
         "--paper", "--out", f("fig4_6_radial_loose_paper.png")] + about(*radial["loose"]),
        ["pi-plane", rec["cdst"], "--paper", "--out", f("fig7_cdst_paper.png")] + about("cdst"),
        ["pi-plane", rec["plane_strain_cw"], rec["plane_strain_ccw"],
         "--paper", "--out", f("fig8_9_plane_strain_paper.png")] +
        about("plane_strain_cw", "plane_strain_ccw"),
        ["compare", "--dense", rec["axisym_dense"], "--loose", rec["axisym_loose"],
         "--radial"] + [rec[n] for n in radial["dense"]] +
        ["--radial-loose"] + [rec[n] for n in radial["loose"]] +
        ["--cdst", rec["cdst"], "--plane-strain", rec["plane_strain_cw"],
         "--out", f("summary.md")],
    ]
    return cmds


def fidelity_command(d):
    """The tyanalysis command of the trace study's table on the records in d."""
    return ["fidelity", d, "--out", os.path.join(d, "fidelity_table.md")]


class Job:
    def __init__(self, name, cmd, record, weight, needs=None, rank=0):
        self.name, self.cmd, self.record, self.weight = name, cmd, record, weight
        self.needs = needs            # a Job that must have succeeded first, or None
        self.rank = rank              # jobs of a lower rank start first (a factor's place)
        self.proc = self.start = None
        self.state = "pending"        # pending, running, done, failed, skipped


def run_jobs(jobs, workdir, width, every, log):
    """Run Job objects, at most `width` at once: of the jobs whose prerequisite has succeeded,
    the lowest rank first, and within a rank preparations first, then the longest; a job whose
    prerequisite failed is skipped. Returns the failed and the skipped jobs."""
    pending = sorted(jobs, key=lambda j: (j.rank, j.needs is not None, -j.weight))
    running, failed, done = [], [], 0
    total = len(jobs)
    env = lmp_environment()
    last_report = time.monotonic()
    while pending or running:
        for j in [j for j in pending if j.needs is not None and j.needs.state in ("failed",
                                                                                   "skipped")]:
            pending.remove(j)
            j.state = "skipped"
            failed.append(j)
            done += 1
            log(f"[{done}/{total}] skipped {j.name}: {j.needs.name} failed")
        while len(running) < width:
            ready = [j for j in pending if j.needs is None or j.needs.state == "done"]
            if not ready:
                break
            j = ready[0]
            pending.remove(j)
            j.state = "running"
            j.start = time.monotonic()
            j.proc = subprocess.Popen(j.cmd, cwd=workdir, env=env, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.STDOUT)
            running.append(j)
            log(f"started {j.name}: {shlex.join(j.cmd)}")
        time.sleep(0.5)
        for j in list(running):
            rc = j.proc.poll()
            if rc is None:
                continue
            running.remove(j)
            done += 1
            took = time.monotonic() - j.start
            status = "done" if rc == 0 else f"FAILED (exit {rc}; see {j.cmd[-3]})"
            j.state = "done" if rc == 0 else "failed"
            if rc != 0:
                failed.append(j)
            log(f"[{done}/{total}] {status} {j.name} in {took / 60:.1f} min")
        if running and time.monotonic() - last_report >= every:
            last_report = time.monotonic()
            parts = []
            for j in running:
                p = last_progress(os.path.join(workdir, j.record)) if j.record else None
                parts.append(f"{j.name} {'preparing' if p is None else f'{100 * p:.0f} %'}")
            log("running: " + ", ".join(parts))
    return failed


def main(args, draw):
    """Run the programme of the parsed `tyanalysis reproduce` arguments; draw(argv) runs one
    tyanalysis command (cli.main) for each figure and table once the runs have ended."""
    inputs = os.path.abspath(args.inputs) if args.inputs else find_inputs()
    width = args.jobs or os.cpu_count() or 1
    os.makedirs(args.dir, exist_ok=True)
    workdir = os.path.abspath(args.dir)
    programme = args.programme
    prog = PROGRAMMES[programme]
    names = list(prog)
    if args.only:
        unknown = [n for n in args.only if n not in prog]
        if unknown:
            raise SystemExit(f"tyanalysis reproduce: unknown run(s) {', '.join(unknown)}; "
                             f"the runs are: {', '.join(prog)}")
        names = args.only
    t0 = time.monotonic()

    def log(text):
        print(f"[{(time.monotonic() - t0) / 60:6.1f} min] {text}", flush=True)

    todo = []                   # (run, its record) of the runs still to do
    for n in names:
        record = record_name(n, prog)
        if finished(os.path.join(workdir, record)):
            log(f"{n}: {record} is complete, not run again")
        else:
            todo.append((n, record))
    prep = {}                   # only the specimens of runs still to do
    for n, _ in sorted(todo, key=lambda t: rank_of(t[0], prog)):
        s = specimen_of(n, prog)
        if s not in prep:       # ranked with the first factor that needs it
            prep[s] = Job(prepare_name(s), prepare_command(s, args.scale, inputs, workdir), None,
                          PREP_WEIGHT[s[0]], rank=rank_of(n, prog))
    shear = [Job(n, command(n, args.scale, inputs, prog), record, entry(n, prog)[3],
                 needs=prep[specimen_of(n, prog)], rank=rank_of(n, prog)) for n, record in todo]
    if args.dry_run:
        for j in list(prep.values()) + shear:
            print(shlex.join(j.cmd))
        if programme == "paper":
            for c in figure_commands(workdir, args.scale):
                print(shlex.join(["tyanalysis"] + c))
        else:
            print(shlex.join(["tyanalysis"] + fidelity_command(workdir)))
        return 0
    log(f"{len(prep)} preparations and {len(shear)} runs, {width} at a time, in {workdir}")
    failed = run_jobs(list(prep.values()) + shear, workdir, width, args.every, log)
    if programme != "paper":
        draw(fidelity_command(workdir))
        log(f"{len(failed)} run(s) failed")
        return 1 if failed else 0
    drawn = 0
    for c in figure_commands(workdir, args.scale):
        files = [a for a in c if a.endswith(".csv")]
        if all(os.path.exists(p) for p in files):
            draw(c)
            drawn += 1
        else:
            log(f"not drawn (records missing): tyanalysis {c[0]} ... {c[-1]}")
    log(f"{drawn} figures/tables in {workdir}; {len(failed)} run(s) failed")
    return 1 if failed else 0
