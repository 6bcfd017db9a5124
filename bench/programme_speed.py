#!/usr/bin/env python3
"""Wall time of the paper's whole programme (`tyanalysis reproduce`: every preparation and run
behind docs/validation.md, two at a time, then the figures) with two builds of the library on
the same decks: a commit's build ("before", by default 3585d58, the last commit whose pair
evaluated the law in its own loop with the staged scalar kernel, before the batch entry
tycore::advance_batch and its SIMD builds) and this tree's ("after").

    /usr/bin/python3 bench/programme_speed.py [--scale quick|paper] [--repeats 1]
        [--before 3585d58] [--decks 1c07cef] [--after build/python/tylmp/tylmp-20210929.so]
        [--jobs 2] [--dir DIR] [--out PREFIX]

Both builds run the decks of one commit (--decks, by default 1c07cef: the newest decks that
the "before" library understands; later decks use fix cell/servo's `variables yes`), checked
out by `git archive` into DIR/decks, so that the library is the only difference; TYLMP_LIBRARY
picks the build for each call (python/tylmp/__init__.py). The "before" build is configured
and built once from `git archive BEFORE` into $TYLMP_CACHE/bench/BEFORE (default
~/.cache/tylmp) and reused.

The two builds' trajectories are bitwise the same (tests/test_batch_isa_trajectory.py and the
batch entry's differential tests), so both calls do the same work, step for step: the
benchmark checks it by comparing every CSV record of the two calls byte for byte (the
preparations' records, the runs' records), and says so when they differ. Calls alternate
(before, after, before, ...), `repeats` of each; the figure is the median wall time of the
whole call, with the sum of the LAMMPS loop times and steps over all its logs beside it.

Run it on an otherwise idle machine: a paper-scale call takes about an hour (docs/performance.md).
Writes PREFIX.csv (one row per call) and PREFIX.json (medians, the ratio, whether the records
agree; default PREFIX: programme_speed_SCALE in the results folder beside this script) and
prints a table.
"""
import argparse
import csv
import filecmp
import glob
import io
import os
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


def loop_totals(rundir):
    """Sum of LAMMPS's loop times (s) and steps over every log of a reproduce call."""
    seconds, steps = 0.0, 0
    for log in glob.glob(os.path.join(rundir, "*.log")):
        with open(log, errors="replace") as f:
            for run in loops(f.read()):
                seconds += run["seconds"]
                steps += run["steps"]
    return seconds, steps


def records(rundir):
    """The CSV records of a reproduce call, relative paths: runs and preparations."""
    found = glob.glob(os.path.join(rundir, "*.csv"))
    found += glob.glob(os.path.join(rundir, "tylmp_specimens", "*.csv"))
    return sorted(os.path.relpath(p, rundir) for p in found)


def same_records(a, b):
    """(agree, note): whether every CSV record of the two calls is byte-identical."""
    ra, rb = records(a), records(b)
    if ra != rb:
        return False, f"different sets of records: {sorted(set(ra) ^ set(rb))}"
    differ = [r for r in ra if not filecmp.cmp(os.path.join(a, r), os.path.join(b, r),
                                               shallow=False)]
    if differ:
        return False, f"{len(differ)} of {len(ra)} records differ: {differ[:5]}"
    return True, f"all {len(ra)} records byte-identical"


def run_call(variant, library, decks, scale, jobs, rundir):
    shutil.rmtree(rundir, ignore_errors=True)
    env = dict(os.environ, TYLMP_LIBRARY=library,
               PYTHONPATH=os.path.join(REPO, "analysis") + os.pathsep
               + os.environ.get("PYTHONPATH", ""))
    cmd = [sys.executable, "-m", "tyanalysis", "reproduce", "--scale", scale, "--jobs",
           str(jobs), "--dir", rundir, "--inputs", decks]
    print(f"programme_speed: {variant}: {' '.join(cmd)} (TYLMP_LIBRARY={library})", flush=True)
    start = time.monotonic()
    with open(rundir + ".out", "w") as out:
        rc = subprocess.run(cmd, env=env, stdout=out, stderr=subprocess.STDOUT).returncode
    wall = time.monotonic() - start
    if rc != 0:
        sys.exit(f"programme_speed: the {variant} call failed (exit {rc}); see {rundir}.out")
    loop, steps = loop_totals(rundir)
    print(f"programme_speed: {variant}: {wall / 60:.2f} min wall, loop time {loop:.1f} s, "
          f"{steps} steps", flush=True)
    return {"variant": variant, "wall_s": wall, "loop_s": loop, "steps": steps}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scale", choices=("quick", "paper"), default="quick")
    ap.add_argument("--repeats", type=int, default=1, help="calls of each build (alternated)")
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
    work = args.dir or os.path.join("/tmp", f"programme_speed_{args.scale}")
    os.makedirs(work, exist_ok=True)
    decks = os.path.join(work, "decks")
    archive(args.decks, ["inputs"], decks)
    decks = os.path.join(decks, "inputs")

    rows = []
    for rep in range(args.repeats):
        for variant, library in (("before", before), ("after", after)):
            row = run_call(variant, library, decks, args.scale, args.jobs,
                           os.path.join(work, f"{variant}_{rep}"))
            row["repeat"] = rep
            rows.append(row)
    agree, note = same_records(os.path.join(work, "before_0"), os.path.join(work, "after_0"))
    print(f"programme_speed: records of before and after: {note}")

    table = io.StringIO()
    w = csv.DictWriter(table, fieldnames=["variant", "repeat", "wall_s", "loop_s", "steps"])
    w.writeheader()
    w.writerows(rows)
    write_text(out + ".csv", table.getvalue())
    median = {v: {k: statistics.median(r[k] for r in rows if r["variant"] == v)
                  for k in ("wall_s", "loop_s", "steps")} for v in ("before", "after")}
    summary = {
        "scale": args.scale, "jobs": args.jobs, "repeats": args.repeats,
        "before_commit": args.before, "decks_commit": args.decks,
        "before_library": before, "after_library": after,
        "median": median,
        "wall_speedup": median["before"]["wall_s"] / median["after"]["wall_s"],
        "loop_speedup": median["before"]["loop_s"] / median["after"]["loop_s"],
        "records_identical": agree, "records_note": note,
    }
    write_json(out + ".json", summary)
    print("\n| | wall time | loop time of all LAMMPS runs | steps |\n|---|---|---|---|")
    for v in ("before", "after"):
        m = median[v]
        print(f"| {v} | {m['wall_s'] / 60:.1f} min | {m['loop_s']:.1f} s | {m['steps']:.0f} |")
    print(f"\nspeed-up: {summary['wall_speedup']:.2f}x wall, {summary['loop_speedup']:.2f}x loop; "
          f"{note}; wrote {out}.csv, {out}.json")
    return 0 if agree else 1


if __name__ == "__main__":
    sys.exit(main())
