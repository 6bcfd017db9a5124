#!/usr/bin/env python3
"""Wall time of the paper's whole programme (`tyanalysis reproduce`: every preparation and run
behind docs/validation.md, two at a time, then the figures) with two builds of the library on
the same decks: a commit's build ("before", by default 3585d58, the last commit whose pair
evaluated the law in its own loop with the staged scalar kernel, before the batch entry
tycore::advance_batch and its SIMD builds) and this tree's ("after").

    /usr/bin/python3 bench/programme_speed.py [--scale quick] [--repeats 1]
    /usr/bin/python3 bench/programme_speed.py --scale paper [--missing] [--runs NAME ...]
    /usr/bin/python3 bench/programme_speed.py --scale paper --report
    common: [--before 3585d58] [--decks 1c07cef] [--after build/python/tylmp/tylmp-20210929.so]
            [--jobs 2] [--dir DIR] [--out PREFIX]

Both builds run the decks of one commit (--decks, by default 1c07cef: the newest decks that
the "before" library understands; later decks use fix cell/servo's `variables yes`), checked
out by `git archive` into DIR/decks, so that the library is the only difference; TYLMP_LIBRARY
picks the build for each call (python/tylmp/__init__.py). The "before" build is configured
and built once from `git archive BEFORE` into $TYLMP_CACHE/bench/BEFORE (default
~/.cache/tylmp) and reused.

The two builds' trajectories are bitwise the same (tests/test_batch_isa_trajectory.py and the
batch entry's differential tests), so both do the same work, step for step: every finished job
(preparation or run) gets a row in PREFIX_jobs.csv with its wall time, LAMMPS loop time, steps,
machine and the digest of its record's bytes, and the benchmark says whether the two builds
wrote the same records.

Quick scale (the default): whole calls, `--jobs` at a time, alternated (before, after, before,
...), `repeats` of each; the figure is the median wall time of the whole call (PREFIX.csv),
with the sum of its jobs' loop times and steps beside it.

Paper scale: a call of one build takes hours, more than a working session (whose processes end
when it stops), and the speed of the same machine differs from session to session by more than
the difference between the builds (docs/performance.md), so halves measured in different
sessions cannot be compared. The two builds run side by side instead, at the same time, one core each (two reproduce calls, `--jobs 1`, the same
runs in the same order), and every job is compared with the same job of the other build that
ran beside it: a pair. Job rows are saved as the jobs finish, so a call stopped with its
session keeps its finished pairs; `--missing` calls only the runs that lack a pair (their
specimens are prepared again, bitwise the same: more pairs of the preparations), `--runs`
limits a call to some runs, `--report` summarises the saved rows again without running. Sessions
may land on different machines, whose timings are not comparable: a job's figure is the median
over its pairs on one machine (for a job paired on several, the machine that paired the most of
the programme's steps), and the results also give each machine's totals over the jobs paired
on it. When every job of the programme has a pair, the programme's loop time of each build
(and its job wall time, the jobs run one at a time) is the sum over its jobs' figures, with the
machines named, and equal steps and equal records in
every pair (on every machine: the trajectories are bitwise the same on every instruction set)
as the check of equal work.

Writes PREFIX.csv (one row per whole quick-scale call), PREFIX_jobs.csv (one row per finished
job) and PREFIX.json (medians, ratios, whether the records agree, the job accounting; default
PREFIX: programme_speed_SCALE in the results folder beside this script), each rewritten
atomically whenever a row is added, and prints a table.
"""
import argparse
import csv
import glob
import hashlib
import io
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
from tylmp.analysis.io import write_text  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import machine, write_result  # noqa: E402
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


def digest(rundir, names):
    """sha256 of the named files' names and bytes (paths relative to rundir)."""
    whole = hashlib.sha256()
    for name in names:
        with open(os.path.join(rundir, name), "rb") as f:
            whole.update(name.encode() + b"\0" + hashlib.sha256(f.read()).digest())
    return whole.hexdigest()


def records(rundir):
    """The CSV records of a reproduce call, relative paths: runs and preparations."""
    found = glob.glob(os.path.join(rundir, "*.csv"))
    found += glob.glob(os.path.join(rundir, "tylmp_specimens", "*.csv"))
    return sorted(os.path.relpath(p, rundir) for p in found)


def records_digest(rundir):
    """(count, sha256) of a call's records: the digest of every record's name and bytes, so
    that two calls, in one session or in two, are compared byte for byte."""
    names = records(rundir)
    return len(names), digest(rundir, names)


def job_records(rundir, job):
    """The record(s) of one job: a run's CSV (tylmp.analysis.reproduce.record_name), a
    preparation's specimen CSVs (tylmp_specimens/SPECIMEN_*.csv)."""
    from tylmp.analysis import reproduce
    if job.startswith("prepare_"):
        pattern = os.path.join("tylmp_specimens", job[len("prepare_"):] + "_*.csv")
    else:
        pattern = reproduce.record_name(job)
    return sorted(os.path.relpath(p, rundir) for p in glob.glob(os.path.join(rundir, pattern)))


def call_row(variant, rundir, wall, started, jobs):
    """The row of a whole call: its loop time and steps are the sums over its jobs' rows."""
    count, sha = records_digest(rundir)
    return {"variant": variant, "started_utc": started, "machine": jobs[0]["machine"],
            "wall_s": wall, "loop_s": sum(j["loop_s"] for j in jobs),
            "steps": sum(j["steps"] for j in jobs), "records": count, "records_sha256": sha}


DONE = re.compile(r"^\[\s*[0-9.]+ min\] \[\d+/\d+\] done (\S+) in ([0-9.]+) min$", re.M)
JOB_FIELDS = ["variant", "job", "started_utc", "machine", "job_wall_s", "loop_s", "steps",
              "record_sha256"]


def job_rows(variant, rundir, started, skip=()):
    """One row per job (preparation or run) that reproduce logged as done in RUNDIR.out, except
    the jobs named in skip (rows already read): its wall time (reproduce's "done NAME in X
    min"), the loop times and steps of its LAMMPS log RUNDIR/NAME.log and the digest of its
    record. A job still running has no row."""
    with open(rundir + ".out", errors="replace") as f:
        done = [d for d in DONE.findall(f.read()) if d[0] not in skip]
    rows = []
    for job, minutes in done:
        with open(os.path.join(rundir, job + ".log"), errors="replace") as f:
            runs = loops(f.read())
        rows.append({"variant": variant, "job": job, "started_utc": started,
                     "machine": machine(), "job_wall_s": 60.0 * float(minutes),
                     "loop_s": sum(r["seconds"] for r in runs),
                     "steps": sum(r["steps"] for r in runs),
                     "record_sha256": digest(rundir, job_records(rundir, job))})
    return rows


def programme_jobs():
    """Every job of the paper programme: the preparations and the runs (tylmp.analysis.reproduce)."""
    from tylmp.analysis import reproduce
    names = list(reproduce.PROGRAMME)
    preps = sorted({reproduce.prepare_name(reproduce.specimen_of(n)) for n in names})
    return preps + names


def utc(seconds_since_epoch):
    return time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime(seconds_since_epoch))


def start_call(variant, library, decks, scale, jobs, rundir, only=None):
    """Start one reproduce call with `library` in a new rundir (its log: rundir.out); returns
    the process."""
    shutil.rmtree(rundir, ignore_errors=True)
    env = dict(os.environ, TYLMP_LIBRARY=library,
               PYTHONPATH=os.path.join(REPO, "python") + os.pathsep
               + os.environ.get("PYTHONPATH", ""))
    cmd = [sys.executable, "-m", "tylmp.analysis", "reproduce", "--scale", scale, "--jobs",
           str(jobs), "--dir", rundir, "--inputs", decks] + (["--only"] + only if only else [])
    print(f"programme_speed: {variant}: {' '.join(cmd)} (TYLMP_LIBRARY={library})", flush=True)
    with open(rundir + ".out", "w") as out:
        return subprocess.Popen(cmd, env=env, stdout=out, stderr=subprocess.STDOUT)


def run_call(variant, library, decks, scale, jobs, rundir):
    """One whole reproduce call with `library`: (its row, the rows of its jobs)."""
    started = utc(time.time())
    start = time.monotonic()
    rc = start_call(variant, library, decks, scale, jobs, rundir).wait()
    wall = time.monotonic() - start
    if rc != 0:
        sys.exit(f"programme_speed: the {variant} call failed (exit {rc}); see {rundir}.out")
    jobs = job_rows(variant, rundir, started)
    row = call_row(variant, rundir, wall, started, jobs)
    print(f"programme_speed: {variant}: {wall / 60:.2f} min wall, loop time {row['loop_s']:.1f} s, "
          f"{row['steps']} steps, {row['records']} records", flush=True)
    return row, jobs


def side_by_side(libraries, decks, scale, work, only, kept, save_jobs, poll=30.0):
    """The two builds' reproduce calls at the same time, one core each (`--jobs 1`, the same
    runs in the same order); every `poll` seconds the jobs finished since are read and the rows
    saved (after `kept`). Both calls' rows carry the same start: the mark of a pair."""
    started = utc(time.time())
    calls = {v: (start_call(v, lib, decks, scale, 1, os.path.join(work, f"{v}_side"), only),
                 os.path.join(work, f"{v}_side")) for v, lib in libraries.items()}
    rows = []
    save_jobs(kept)
    while True:
        running = [p for p, _ in calls.values() if p.poll() is None]
        new = [r for v, (_, d) in calls.items()
               for r in job_rows(v, d, started, {r["job"] for r in rows if r["variant"] == v})]
        if new:    # each finished job read once, saved when it has finished
            rows += new
            save_jobs(kept + rows)
        if not running:
            break
        time.sleep(poll)
    failed = [f"{v} (exit {p.returncode}; see {d}.out)" for v, (p, d) in calls.items()
              if p.returncode != 0]
    if failed:
        sys.exit(f"programme_speed: calls failed: {', '.join(failed)}")
    return kept + rows


FIELDS = ["variant", "started_utc", "machine", "wall_s", "loop_s", "steps", "records", "records_sha256"]


def read_rows(path, fields, floats, ints):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    missing = [k for k in fields if rows and k not in rows[0]]
    if missing:
        sys.exit(f"programme_speed: {path} lacks the columns {missing} (written by an older "
                 "version of this script: measure anew into another --out)")
    for r in rows:
        for k in floats:
            r[k] = float(r[k])
        for k in ints:
            r[k] = int(r[k])
    return rows


def pairs(jrows):
    """job -> [(before row, after row)] of the jobs that ran side by side (same call start, same
    machine)."""
    by = {(r["job"], r["started_utc"], r["variant"]): r for r in jrows}
    out = {}
    for (job, started, variant), row in sorted(by.items()):
        twin = by.get((job, started, "after"))
        if variant == "before" and twin is not None and twin["machine"] == row["machine"]:
            out.setdefault(job, []).append((row, twin))
    return out


def job_figure(ps):
    """One job's figure from its pairs on one machine: medians of each build's loop and job
    wall time, and the median over the pairs of before/after."""
    return {"pairs": len(ps),
            "calls_started_utc": sorted({b["started_utc"] for b, _ in ps}),
            "steps": ps[0][0]["steps"],
            **{f"{v}_{k}": statistics.median(p[i][k] for p in ps)
               for i, v in enumerate(("before", "after")) for k in ("loop_s", "job_wall_s")},
            "loop_speedup": statistics.median(b["loop_s"] / a["loop_s"] for b, a in ps)}


def totals(figures):
    """Sums of steps and of each build's loop time and job wall time over some jobs' figures,
    and the ratios before/after. The sum of job wall times is the wall time of those jobs run
    one at a time (start-up, specimen reading and output included)."""
    out = {"jobs": len(figures), "steps": sum(f["steps"] for f in figures)}
    for k in ("loop", "job_wall"):
        for v in ("before", "after"):
            out[f"{v}_{k}_s"] = sum(f[f"{v}_{k}_s"] for f in figures)
        out[f"{k}_speedup"] = out[f"before_{k}_s"] / out[f"after_{k}_s"] if figures else None
    return out


def summarise_pairs(jrows):
    """The paper programme job by job. Timings of different machines are not comparable, so a
    job's figure comes from its pairs on one machine: the medians over them (loop time, job
    wall time of each build, the ratio before/after). A job paired on several machines counts
    with those of the machine that paired the most of the programme's steps (its figures on the
    others are kept beside it). Per machine, the totals over every job paired there. Whether
    every pair, on every machine, did the same steps and wrote the same record (the builds and
    the processors' instruction sets give bitwise the same trajectories). When every job of the
    programme has a pair, each build's loop time of the whole programme (the sum over its jobs)
    and their ratio, with the machines it was measured on."""
    every = programme_jobs()
    found = pairs(jrows)
    on = {}                                   # job -> machine -> its pairs there
    for job, ps in found.items():
        for b, a in ps:
            on.setdefault(job, {}).setdefault(b["machine"], []).append((b, a))
    machines = sorted({m for ms in on.values() for m in ms})
    covered = {m: sum(ms[m][0][0]["steps"] for ms in on.values() if m in ms) for m in machines}
    per = {}
    for job in every:
        if job not in on:
            continue
        home = max(on[job], key=lambda m: (covered[m], m))
        ps = found[job]
        per[job] = {**job_figure(on[job][home]), "machine": home,
                    "same_steps": all(b["steps"] == a["steps"] == ps[0][0]["steps"]
                                      for b, a in ps),
                    "same_record": all(b["record_sha256"] == a["record_sha256"]
                                       == ps[0][0]["record_sha256"] for b, a in ps),
                    "other_machines": {m: job_figure(q) for m, q in on[job].items() if m != home}}
    by_machine = {m: {**totals([job_figure(on[j][m]) for j in every if m in on.get(j, {})]),
                      "paired": [j for j in every if m in on.get(j, {})]} for m in machines}
    out = {"jobs_in_programme": len(every), "jobs_paired": len(per),
           "missing": [j for j in every if j not in per],
           "machines": sorted({r["machine"] for r in jrows}),
           "same_steps_every_pair": all(p["same_steps"] for p in per.values()),
           "same_record_every_pair": all(p["same_record"] for p in per.values()),
           "per_job": per, "by_machine": by_machine}
    if per:
        out["median_job_loop_speedup"] = statistics.median(p["loop_speedup"]
                                                           for p in per.values())
    if len(per) == len(every):
        whole = totals(list(per.values()))
        out.update({k: x for k, x in whole.items() if k != "jobs"})   # jobs_paired says it
        out["programme_machines"] = sorted({p["machine"] for p in per.values()})
    return out


def summarise(rows, jrows, args, before, after):
    summary = {"scale": args.scale, "before_commit": args.before, "decks_commit": args.decks,
               "before_library": before, "after_library": after,
               "machines": sorted({r["machine"] for r in rows} | {r["machine"] for r in jrows})}
    if args.scale == "paper":
        summary["design"] = "side by side, one core each, job by job in pairs"
        summary["jobs"] = summarise_pairs(jrows)
        summary["records_identical"] = summary["jobs"]["same_record_every_pair"]
        return summary
    variants = [v for v in ("before", "after") if any(r["variant"] == v for r in rows)]
    median = {v: {k: statistics.median(r[k] for r in rows if r["variant"] == v)
                  for k in ("wall_s", "loop_s", "steps")} for v in variants}
    digests = {r["records_sha256"] for r in rows}
    summary.update({
        "jobs_at_once": args.jobs,
        "calls": {v: sum(r["variant"] == v for r in rows) for v in variants},
        "sessions_utc": sorted({r["started_utc"][:10] for r in rows}),
        "median": median,
        "records_identical": len(digests) <= 1,
        "records_note": ("no whole call yet" if not rows else
                         f"all {len(rows)} calls wrote the same {rows[0]['records']} records, "
                         "byte for byte" if len(digests) == 1 else
                         f"the calls' records differ: {len(digests)} different digests")})
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
    written whole and atomically, so that an interrupted measurement keeps what it finished."""
    write_text(out + ".csv", csv_text(rows, FIELDS))
    write_text(out + "_jobs.csv", csv_text(jrows, JOB_FIELDS))
    write_result(out + ".json", summary, indent=1)


def print_summary(summary, out):
    if summary["scale"] == "paper":
        j = summary["jobs"]
        label = {m: f"M{i + 1}" for i, m in enumerate(sorted(j["by_machine"]))}
        print("\n| job | machine | pairs | steps | loop time before | after | before/after | "
              "job wall before | after | same record |\n|---|---|---|---|---|---|---|---|---|---|")
        def line(name, machine, f, same):
            print(f"| {name} | {label[machine]} | {f['pairs']} | {f['steps']} | "
                  f"{f['before_loop_s']:.0f} s | {f['after_loop_s']:.0f} s | "
                  f"{f['loop_speedup']:.2f} | {f['before_job_wall_s'] / 60:.1f} min | "
                  f"{f['after_job_wall_s'] / 60:.1f} min | {same} |")
        for name, p in j["per_job"].items():
            line(name, p["machine"], p, p["same_record"])
            for m, q in p["other_machines"].items():    # counted with p's machine, shown beside
                line(f"({name})", m, q, "")
        print("\n| machine | jobs paired | steps | loop time before | after | before/after | "
              "job wall before | after | before/after |\n|---|---|---|---|---|---|---|---|---|")
        for m, t in sorted(j["by_machine"].items()):
            print(f"| {label[m]}: {m} | {t['jobs']} | {t['steps']} | {t['before_loop_s']:.0f} s "
                  f"| {t['after_loop_s']:.0f} s | {t['loop_speedup']:.3f} | "
                  f"{t['before_job_wall_s'] / 60:.1f} min | {t['after_job_wall_s'] / 60:.1f} min "
                  f"| {t['job_wall_speedup']:.3f} |")
        print(f"\n{j['jobs_paired']} of {j['jobs_in_programme']} jobs paired"
              + (f"; missing: {', '.join(j['missing'])}" if j["missing"] else ""))
        if "loop_speedup" in j:
            print(f"programme's loop time ({j['steps']} steps; "
                  f"{', '.join(label[m] for m in j['programme_machines'])}): before "
                  f"{j['before_loop_s']:.0f} s, after {j['after_loop_s']:.0f} s: "
                  f"{j['loop_speedup']:.3f}x; its jobs' wall time one at a time: before "
                  f"{j['before_job_wall_s'] / 60:.1f} min, after "
                  f"{j['after_job_wall_s'] / 60:.1f} min: {j['job_wall_speedup']:.3f}x")
    else:
        print("\n| | calls | wall time | loop time of all LAMMPS runs | steps |\n|---|---|---|---|---|")
        for v, m in summary["median"].items():
            print(f"| {v} | {summary['calls'][v]} | {m['wall_s'] / 60:.1f} min | "
                  f"{m['loop_s']:.1f} s | {m['steps']:.0f} |")
        if "wall_speedup" in summary:
            print(f"\nspeed-up: {summary['wall_speedup']:.2f}x wall, "
                  f"{summary['loop_speedup']:.2f}x loop; {summary['records_note']}")
    print(f"records identical: {summary['records_identical']}; wrote {out}.csv, {out}_jobs.csv, "
          f"{out}.json")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scale", choices=("quick", "paper"), default="quick")
    ap.add_argument("--repeats", type=int, default=1,
                    help="quick scale: calls of each build (alternated)")
    ap.add_argument("--missing", action="store_true",
                    help="paper scale: call only the runs that lack a pair in PREFIX_jobs.csv "
                    "(and keep its rows)")
    ap.add_argument("--runs", nargs="+", metavar="NAME", default=None,
                    help="paper scale: call only these runs")
    ap.add_argument("--report", action="store_true",
                    help="paper scale: run nothing; summarise PREFIX_jobs.csv again into "
                    "PREFIX.json and print the tables")
    ap.add_argument("--before", default="3585d58", help="commit of the 'before' library")
    ap.add_argument("--decks", default="1c07cef", help="commit of the decks both builds run")
    ap.add_argument("--after", default=None, help="the 'after' library (default: this tree's "
                    "build of the running lmp's version, build/python/tylmp/tylmp-*.so)")
    ap.add_argument("--jobs", type=int, default=2, help="quick scale: jobs at once per call")
    ap.add_argument("--dir", default=None, help="work directory (default: a new one in /tmp)")
    ap.add_argument("--out", default=None,
                    help="output prefix (default: results/programme_speed_SCALE beside this script)")
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error("--repeats must be at least 1")
    if args.scale != "paper" and (args.missing or args.runs):
        ap.error("--missing and --runs are for the paper programme (--scale paper)")
    if args.report and (args.scale != "paper" or args.missing or args.runs):
        ap.error("--report is for the paper programme (--scale paper) and runs nothing "
                 "(no --missing, --runs)")
    if args.scale == "paper" and args.repeats != 1:
        ap.error("--repeats is for quick scale; at paper scale a job's pairs gather over calls "
                 "(--missing, --runs)")
    every = programme_jobs()
    unknown = [r for r in args.runs or [] if r not in every or r.startswith("prepare_")]
    if unknown:
        ap.error(f"--runs: {', '.join(unknown)} not a run of the programme; the runs are: "
                 + ", ".join(j for j in every if not j.startswith("prepare_")))
    out = args.out or os.path.join(REPO, "bench", "results", f"programme_speed_{args.scale}")
    if args.report:
        jrows = read_rows(out + "_jobs.csv", JOB_FIELDS, ("job_wall_s", "loop_s"), ("steps",))
        libraries = {}
        if os.path.isfile(out + ".json"):
            with open(out + ".json") as f:
                libraries = json.load(f)
        summary = summarise([], jrows, args, libraries.get("before_library"),
                            libraries.get("after_library"))
        save(out, [], jrows, summary)
        print_summary(summary, out)
        return 0 if summary["records_identical"] else 1
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
    work = args.dir or os.path.join("/tmp", f"programme_speed_{args.scale}")
    os.makedirs(work, exist_ok=True)
    decks = os.path.join(work, "decks")
    archive(args.decks, ["inputs"], decks)
    decks = os.path.join(decks, "inputs")
    libraries = {"before": before, "after": after}
    rows, jrows = [], []
    if args.scale == "paper":
        jrows = read_rows(out + "_jobs.csv", JOB_FIELDS, ("job_wall_s", "loop_s"), ("steps",)) \
            if args.missing else []
        paired = set(pairs(jrows))
        only = [j for j in every if not j.startswith("prepare_")
                and (args.runs is None or j in args.runs)
                and not (args.missing and j in paired)]
        if not only:
            sys.exit("programme_speed: every run asked for has a pair already")
        whole = len(only) == len(every) - len([j for j in every if j.startswith("prepare_")])
        jrows = side_by_side(libraries, decks, args.scale, work, None if whole else only, jrows,
                             lambda js: save(out, [], js, summarise([], js, args, before, after)))
    else:
        for _ in range(args.repeats):
            for variant, library in libraries.items():
                row, jobs = run_call(variant, library, decks, args.scale, args.jobs,
                                     os.path.join(work, f"{variant}_{len(rows) // 2}"))
                rows.append(row)
                jrows += jobs
                save(out, rows, jrows, summarise(rows, jrows, args, before, after))
    summary = summarise(rows, jrows, args, before, after)
    print_summary(summary, out)
    return 0 if summary["records_identical"] else 1


if __name__ == "__main__":
    sys.exit(main())
