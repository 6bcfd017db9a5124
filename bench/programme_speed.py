#!/usr/bin/env python3
"""Wall time of the paper's whole programme (`tyanalysis reproduce`: every preparation and run
behind docs/validation.md, two at a time, then the figures) with two builds of the library on
the same decks: a commit's build ("before", by default 3585d58, the last commit whose pair
evaluated the law in its own loop with the staged scalar kernel, before the batch entry
tycore::advance_batch and its SIMD builds) and this tree's ("after").

    /usr/bin/python3 bench/programme_speed.py [--scale quick|paper] [--repeats 1]
        [--variant both|before|after] [--append] [--adopt DIR] [--missing]
        [--before 3585d58] [--decks 1c07cef] [--after build/python/tylmp/tylmp-20210929.so]
        [--jobs 2] [--dir DIR] [--out PREFIX]

Both builds run the decks of one commit (--decks, by default 1c07cef: the newest decks that
the "before" library understands; later decks use fix cell/servo's `variables yes`), checked
out by `git archive` into DIR/decks, so that the library is the only difference; TYLMP_LIBRARY
picks the build for each call (python/tylmp/__init__.py). The "before" build is configured
and built once from `git archive BEFORE` into $TYLMP_CACHE/bench/BEFORE (default
~/.cache/tylmp) and reused.

The two builds' trajectories are bitwise the same (tests/test_batch_isa_trajectory.py and the
batch entry's differential tests), so both calls do the same work, step for step: every call
records a digest of its CSV records' bytes (the preparations' records, the runs' records), and
the benchmark says whether all calls wrote the same. Calls alternate (before, after, before,
...), `repeats` of each; the figure is the median wall time of the whole call, with the sum of
the LAMMPS loop times and steps over all its logs beside it.

Run it on an otherwise idle machine. At paper scale the before call (about three hours on two
cores) is longer than a working session, whose processes end when it stops: the halves are then
measured job by job. Every finished job (preparation or run) of every call gets a row in
PREFIX_jobs.csv with its LAMMPS loop times and steps; `--adopt DIR --variant V` records the
finished jobs of a call that was stopped (reproduce's own log DIR.out), `--variant V --missing`
calls only the runs that half still lacks (their specimens are prepared again, bitwise the same),
and the programme's loop time is the sum over its jobs, equal steps job by job showing that
both builds did the same work. Each row carries its start (UTC), so the tables say when each
part was measured.

Writes PREFIX.csv (one row per whole call), PREFIX_jobs.csv (one row per finished job) and
PREFIX.json (medians, the ratios, whether the records agree, the job accounting; default
PREFIX: programme_speed_SCALE in the results folder beside this script), each rewritten
atomically after every call, and prints a table.
"""
import argparse
import csv
import glob
import hashlib
import io
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "analysis"))
from tyanalysis.io import write_json, write_text  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from lammps_log import loops  # noqa: E402


def cache_dir():
    return os.environ.get("TYLMP_CACHE", os.path.expanduser("~/.cache/tylmp"))


def archive(commit, paths, dest):
    """`git archive COMMIT PATHS` extracted into dest (made anew)."""
    shutil.rmtree(dest, ignore_errors=True)
    os.makedirs(dest)
    tar = subprocess.run(["git", "-C", REPO, "archive", commit] + paths, check=True,
                         stdout=subprocess.PIPE).stdout
    subprocess.run(["tar", "x", "-C", dest], input=tar, check=True)


def build_commit(commit, library_name):
    """The library of `commit`, built once into the cache; returns the path of the build named
    library_name (e.g. tylmp-20210929.so: the same LAMMPS version as the "after" build)."""
    full = subprocess.run(["git", "-C", REPO, "rev-parse", commit], check=True,
                          stdout=subprocess.PIPE, text=True).stdout.strip()
    root = os.path.join(cache_dir(), "bench", full[:12])
    library = os.path.join(root, "build", "python", "tylmp", library_name)
    if os.path.isfile(library):
        return library
    archive(full, [], os.path.join(root, "src"))
    build = os.path.join(root, "build")
    print(f"programme_speed: building the library of {commit} into {build} (once)", flush=True)
    subprocess.run(["cmake", "-S", os.path.join(root, "src"), "-B", build,
                    "-DCMAKE_BUILD_TYPE=Release"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", build, "--target", "tylmp", "-j2"], check=True,
                   stdout=subprocess.DEVNULL)
    if not os.path.isfile(library):
        sys.exit(f"programme_speed: the build of {commit} has no {library_name} "
                 f"(found: {os.listdir(os.path.dirname(library))})")
    return library


def records(rundir):
    """The CSV records of a reproduce call, relative paths: runs and preparations."""
    found = glob.glob(os.path.join(rundir, "*.csv"))
    found += glob.glob(os.path.join(rundir, "tylmp_specimens", "*.csv"))
    return sorted(os.path.relpath(p, rundir) for p in found)


def records_digest(rundir):
    """(count, sha256) of a call's records: the digest of every record's name and bytes, so
    that two calls, in one session or in two, are compared byte for byte."""
    whole = hashlib.sha256()
    names = records(rundir)
    for name in names:
        with open(os.path.join(rundir, name), "rb") as f:
            whole.update(name.encode() + b"\0" + hashlib.sha256(f.read()).digest())
    return len(names), whole.hexdigest()


def call_row(variant, rundir, wall, started, jobs):
    """The row of a whole call: its loop time and steps are the sums over its jobs' rows."""
    count, digest = records_digest(rundir)
    return {"variant": variant, "started_utc": started, "machine": jobs[0]["machine"],
            "wall_s": wall, "loop_s": sum(j["loop_s"] for j in jobs),
            "steps": sum(j["steps"] for j in jobs), "records": count, "records_sha256": digest}


DONE = re.compile(r"^\[\s*[0-9.]+ min\] \[\d+/\d+\] done (\S+) in ([0-9.]+) min$", re.M)
JOB_FIELDS = ["variant", "job", "started_utc", "machine", "job_wall_s", "loop_s", "steps"]


def job_rows(variant, rundir, started):
    """One row per job (preparation or run) that reproduce logged as done in RUNDIR.out: its
    wall time (reproduce's "done NAME in X min") and the loop times and steps of its LAMMPS log
    RUNDIR/NAME.log. A job still running when a call was stopped has no row."""
    with open(rundir + ".out", errors="replace") as f:
        done = DONE.findall(f.read())
    rows, cpu = [], machine()
    for job, minutes in done:
        with open(os.path.join(rundir, job + ".log"), errors="replace") as f:
            runs = loops(f.read())
        rows.append({"variant": variant, "job": job, "started_utc": started, "machine": cpu,
                     "job_wall_s": 60.0 * float(minutes),
                     "loop_s": sum(r["seconds"] for r in runs),
                     "steps": sum(r["steps"] for r in runs)})
    return rows


def programme_jobs():
    """Every job of the paper programme: the preparations and the runs (tyanalysis.reproduce)."""
    from tyanalysis import reproduce
    names = list(reproduce.PROGRAMME)
    preps = sorted({reproduce.prepare_name(reproduce.specimen_of(n)) for n in names})
    return preps + names


def machine():
    """The processor a call ran on (model, logical CPUs, widest SIMD, clock): timings of
    different machines are not comparable (docs/performance.md)."""
    model, isa, mhz = "unknown", "no AVX2", ""
    with open("/proc/cpuinfo") as f:
        for line in f:
            key, _, value = line.partition(":")
            key, value = key.strip(), value.strip()
            if key == "model name" and model == "unknown":
                model = value
            elif key == "cpu MHz" and not mhz:
                mhz = f", {float(value):.0f} MHz"
            elif key == "flags":
                flags = value.split()
                isa = "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else isa
    return f"{model}, {os.cpu_count()} CPUs, {isa}{mhz}"


def utc(seconds_since_epoch):
    return time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime(seconds_since_epoch))


def run_call(variant, library, decks, scale, jobs, rundir, only=None):
    """One reproduce call with `library`: (its row, or None when `only` limited it to some
    runs, and the rows of its jobs)."""
    shutil.rmtree(rundir, ignore_errors=True)
    env = dict(os.environ, TYLMP_LIBRARY=library,
               PYTHONPATH=os.path.join(REPO, "analysis") + os.pathsep
               + os.environ.get("PYTHONPATH", ""))
    cmd = [sys.executable, "-m", "tyanalysis", "reproduce", "--scale", scale, "--jobs",
           str(jobs), "--dir", rundir, "--inputs", decks] + (["--only"] + only if only else [])
    print(f"programme_speed: {variant}: {' '.join(cmd)} (TYLMP_LIBRARY={library})", flush=True)
    started = utc(time.time())
    start = time.monotonic()
    with open(rundir + ".out", "w") as out:
        rc = subprocess.run(cmd, env=env, stdout=out, stderr=subprocess.STDOUT).returncode
    wall = time.monotonic() - start
    if rc != 0:
        sys.exit(f"programme_speed: the {variant} call failed (exit {rc}); see {rundir}.out")
    jobs = job_rows(variant, rundir, started)
    row = call_row(variant, rundir, wall, started, jobs)
    print(f"programme_speed: {variant}: {wall / 60:.2f} min wall, loop time {row['loop_s']:.1f} s, "
          f"{row['steps']} steps, {row['records']} records", flush=True)
    return (None if only else row), jobs


ELAPSED = re.compile(r"^\[\s*([0-9.]+) min\]", re.M)


def adopt_call(variant, rundir):
    """The rows of a reproduce call made outside this script (e.g. by an earlier process that
    was stopped): (the call's row, or None if it did not finish the whole programme without
    failures, and the rows of its finished jobs). Wall times are the elapsed times reproduce
    logged in RUNDIR.out (0.1 min resolution); the call's start is that file's modification
    time less the last elapsed time."""
    out = rundir + ".out"
    with open(out, errors="replace") as f:
        text = f.read()
    wall = 60.0 * float(ELAPSED.findall(text)[-1])
    started = utc(os.path.getmtime(out) - wall)
    whole = (re.search(r"\d+ figures/tables in .*; 0 run\(s\) failed", text)
             and "--only" not in text.splitlines()[0])
    jobs = job_rows(variant, rundir, started)
    return (call_row(variant, rundir, wall, started, jobs) if whole else None), jobs


FIELDS = ["variant", "started_utc", "machine", "wall_s", "loop_s", "steps", "records", "records_sha256"]


def read_rows(path, fields, floats, ints):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    missing = [k for k in fields if rows and k not in rows[0]]
    if missing:
        sys.exit(f"programme_speed: {path} lacks the columns {missing} (written by an older "
                 "version of this script: measure anew, without --append)")
    for r in rows:
        for k in floats:
            r[k] = float(r[k])
        for k in ints:
            r[k] = int(r[k])
    return rows


def summarise_jobs(jrows):
    """Per variant: the programme's jobs measured (median over repeats of each job) and, when
    every job of the programme is measured, the sum of their loop times and steps: the
    programme's work, which halves measured in different calls add up to."""
    every = programme_jobs()
    out = {}
    for v in ("before", "after"):
        per = {}
        for j in every:
            mine = [r for r in jrows if r["variant"] == v and r["job"] == j]
            if mine:
                per[j] = {k: statistics.median(r[k] for r in mine)
                          for k in ("loop_s", "steps", "job_wall_s")}
        if per:
            out[v] = {"jobs_measured": len(per), "jobs_in_programme": len(every),
                      "missing": [j for j in every if j not in per],
                      "sessions_utc": sorted({r["started_utc"][:10] for r in jrows
                                              if r["variant"] == v}),
                      "machines": sorted({r["machine"] for r in jrows if r["variant"] == v}),
                      "per_job": per}
            if len(per) == len(every):
                out[v]["loop_s"] = sum(p["loop_s"] for p in per.values())
                out[v]["steps"] = sum(p["steps"] for p in per.values())
    if all(v in out and "loop_s" in out[v] for v in ("before", "after")):
        b, a = out["before"]["per_job"], out["after"]["per_job"]
        out["same_steps_every_job"] = all(b[j]["steps"] == a[j]["steps"] for j in b)
        out["loop_speedup"] = out["before"]["loop_s"] / out["after"]["loop_s"]
    return out


def summarise(rows, jrows, args, before, after):
    variants = [v for v in ("before", "after") if any(r["variant"] == v for r in rows)]
    median = {v: {k: statistics.median(r[k] for r in rows if r["variant"] == v)
                  for k in ("wall_s", "loop_s", "steps")} for v in variants}
    digests = {r["records_sha256"] for r in rows}
    summary = {
        "scale": args.scale, "jobs_at_once": args.jobs, "before_commit": args.before,
        "decks_commit": args.decks, "before_library": before, "after_library": after,
        "calls": {v: sum(r["variant"] == v for r in rows) for v in variants},
        "sessions_utc": sorted({r["started_utc"][:10] for r in rows}),
        "machines": sorted({r["machine"] for r in rows} | {r["machine"] for r in jrows}),
        "median": median,
        "records_identical": len(digests) <= 1,
        "records_note": ("no whole call yet" if not rows else
                         f"all {len(rows)} calls wrote the same {rows[0]['records']} records, "
                         "byte for byte" if len(digests) == 1 else
                         f"the calls' records differ: {len(digests)} different digests"),
        "jobs": summarise_jobs(jrows),
    }
    if len(variants) == 2:
        summary["wall_speedup"] = median["before"]["wall_s"] / median["after"]["wall_s"]
        summary["loop_speedup"] = median["before"]["loop_s"] / median["after"]["loop_s"]
    return summary


def csv_text(rows, fields):
    table = io.StringIO()
    w = csv.DictWriter(table, fieldnames=fields)
    w.writeheader()
    w.writerows(rows)
    return table.getvalue()


def save(out, rows, jrows, summary):
    """PREFIX.csv (whole calls), PREFIX_jobs.csv (every finished job) and PREFIX.json, each
    written whole and atomically after every call, so that an interrupted measurement keeps
    what it finished."""
    write_text(out + ".csv", csv_text(rows, FIELDS))
    write_text(out + "_jobs.csv", csv_text(jrows, JOB_FIELDS))
    write_json(out + ".json", summary)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scale", choices=("quick", "paper"), default="quick")
    ap.add_argument("--repeats", type=int, default=1, help="calls of each build (alternated)")
    ap.add_argument("--variant", choices=("both", "before", "after"), default="both",
                    help="which builds to call (default both, alternated)")
    ap.add_argument("--append", action="store_true",
                    help="keep the calls already in PREFIX.csv (halves measured in two calls)")
    ap.add_argument("--adopt", metavar="DIR", default=None,
                    help="record the call in DIR (its log DIR.out; finished or stopped) as "
                    "--variant, instead of calling the programme")
    ap.add_argument("--missing", action="store_true",
                    help="call only the runs that PREFIX_jobs.csv lacks for --variant (the "
                    "rest of a half that a stopped call began; implies --append)")
    ap.add_argument("--before", default="3585d58", help="commit of the 'before' library")
    ap.add_argument("--decks", default="1c07cef", help="commit of the decks both builds run")
    ap.add_argument("--after", default=None, help="the 'after' library (default: this tree's "
                    "build of the running lmp's version, build/python/tylmp/tylmp-*.so)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--dir", default=None, help="work directory (default: a new one in /tmp)")
    ap.add_argument("--out", default=None,
                    help="output prefix (default: results/programme_speed_SCALE beside this script)")
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error("--repeats must be at least 1")
    if (args.adopt or args.missing) and args.variant == "both":
        ap.error("--adopt and --missing need --variant before or --variant after")
    if args.scale != "paper" and (args.adopt or args.missing):
        ap.error("--adopt and --missing are for the paper programme (--scale paper)")
    out = args.out or os.path.join(REPO, "bench", "results", f"programme_speed_{args.scale}")
    after = args.after
    if after is None:
        builds = sorted(glob.glob(os.path.join(REPO, "build", "python", "tylmp", "tylmp-*.so")))
        if len(builds) != 1:
            sys.exit("programme_speed: give --after PATH (this tree's build/python/tylmp holds "
                     f"{len(builds)} versioned libraries)")
        after = builds[0]
    after = os.path.abspath(after)
    if not os.path.isfile(after):
        sys.exit(f"programme_speed: no library {after} (build this tree first: cmake --build "
                 "build)")
    before = build_commit(args.before, os.path.basename(after))
    keep = args.append or args.adopt or args.missing
    rows = read_rows(out + ".csv", FIELDS, ("wall_s", "loop_s"), ("steps", "records")) \
        if keep else []
    jrows = read_rows(out + "_jobs.csv", JOB_FIELDS, ("job_wall_s", "loop_s"), ("steps",)) \
        if keep else []
    only = None
    if args.missing:
        have = {r["job"] for r in jrows if r["variant"] == args.variant}
        only = [j for j in programme_jobs() if j not in have and not j.startswith("prepare_")]
        if not only:
            sys.exit(f"programme_speed: every run of the programme has a row for {args.variant}")
    if args.adopt:
        row, jobs = adopt_call(args.variant, os.path.abspath(args.adopt))
        rows += [row] if row else []
        jrows += jobs
        save(out, rows, jrows, summarise(rows, jrows, args, before, after))
    else:
        work = args.dir or os.path.join("/tmp", f"programme_speed_{args.scale}")
        os.makedirs(work, exist_ok=True)
        decks = os.path.join(work, "decks")
        archive(args.decks, ["inputs"], decks)
        decks = os.path.join(decks, "inputs")
        variants = ("before", "after") if args.variant == "both" else (args.variant,)
        for rep in range(args.repeats):
            for variant in variants:
                library = before if variant == "before" else after
                row, jobs = run_call(variant, library, decks, args.scale, args.jobs,
                                     os.path.join(work, f"{variant}_{rep}"), only)
                rows += [row] if row else []
                jrows += jobs
                save(out, rows, jrows, summarise(rows, jrows, args, before, after))
    summary = summarise(rows, jrows, args, before, after)
    print("\n| | calls | wall time | loop time of all LAMMPS runs | steps |\n|---|---|---|---|---|")
    for v, m in summary["median"].items():
        print(f"| {v} | {summary['calls'][v]} | {m['wall_s'] / 60:.1f} min | {m['loop_s']:.1f} s "
              f"| {m['steps']:.0f} |")
    if "wall_speedup" in summary:
        print(f"\nspeed-up: {summary['wall_speedup']:.2f}x wall, {summary['loop_speedup']:.2f}x "
              "loop", end="; ")
    for v, j in summary["jobs"].items():
        if v in ("before", "after"):
            total = (f"loop time {j['loop_s']:.1f} s, {j['steps']:.0f} steps" if "loop_s" in j
                     else f"missing {', '.join(j['missing'])}")
            print(f"\njobs {v}: {j['jobs_measured']} of {j['jobs_in_programme']} measured "
                  f"(sessions {', '.join(j['sessions_utc'])}); {total}")
    if "loop_speedup" in summary["jobs"]:
        print(f"programme's loop time, job by job: {summary['jobs']['loop_speedup']:.2f}x; "
              f"same steps in every job: {summary['jobs']['same_steps_every_job']}")
    print(f"{summary['records_note']}; wrote {out}.csv, {out}.json")
    return 0 if summary["records_identical"] else 1


if __name__ == "__main__":
    sys.exit(main())
