"""The benchmarks' instruments. The one reader of LAMMPS's timing output (bench/lammps_log.py),
checked against what the running `lmp` prints for a deck whose runs are known: two runs of 20
and 30 steps of a 4x4x4 fcc lattice (256 atoms) on one process, whose timing breakdown (Pair,
Neigh, Comm, Output, Modify, Other) accounts for the whole loop time (its %total column sums
to 100). The record digest by which bench/programme_speed.py says two calls of the programme
did the same work: equal for byte-equal records, different when one byte or one name differs.
Its job accounting: the rows read from reproduce's own log, and the pairs (a job of the two
builds run side by side) by which it compares the paper programme job by job."""
import subprocess

import pytest

DECK = """units lj
lattice fcc 0.8442
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
mass 1 1.0
velocity all create 1.0 4928459
pair_style lj/cut 2.5
pair_coeff 1 1 1.0 1.0
fix 1 all nve
run 20
run 30
"""


@pytest.fixture
def log(bench):
    return bench("lammps_log")


@pytest.fixture(scope="module")
def output(tmp_path_factory):
    work = tmp_path_factory.mktemp("lammps_log")
    (work / "in.lj").write_text(DECK)
    proc = subprocess.run(["lmp", "-in", "in.lj", "-log", "none", "-nocite"], cwd=str(work),
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-2000:]
    return proc.stdout


def test_every_run_is_read_with_its_steps_atoms_and_procs(output, log):
    runs = log.loops(output)
    assert [(r["steps"], r["atoms"], r["procs"]) for r in runs] == [(20, 256, 1), (30, 256, 1)]
    assert all(r["seconds"] > 0 for r in runs)
    assert log.first_loop(output) == runs[0]


def test_breakdown_accounts_for_the_loop_time(output, log):
    sections = ("Pair", "Neigh", "Comm", "Output", "Modify", "Other")
    for run in range(2):
        pct = sum(log.section(output, s)[run]["pct"] for s in sections)
        assert pct == pytest.approx(100.0, abs=0.1)
        # the Pair row's avg column is seconds of that run's loop time
        pair = log.section(output, "Pair")[run]
        assert pair["avg"] == pytest.approx(pair["pct"] / 100 * log.loops(output)[run]["seconds"],
                                            rel=0.05, abs=2e-4)


def test_output_without_a_run_is_an_error_that_says_so(log):
    with pytest.raises(RuntimeError, match="no 'Loop time of ...' line"):
        log.first_loop("LAMMPS (29 Sep 2021)\n", "empty output")


def test_record_digest_tells_the_same_records_from_different_ones(tmp_path, bench):
    speed = bench("programme_speed")
    calls = []
    for call in ("a", "b"):
        d = tmp_path / call
        (d / "tylmp_specimens").mkdir(parents=True)
        (d / "axisym_loose_paper.csv").write_text("step,p\n0,1e5\n100,1.00001e5\n")
        (d / "tylmp_specimens" / "loose_paper.csv").write_text("phi\n0.5962\n")
        (d / "axisym_loose.log").write_text("not a record\n")
        calls.append(d)
    a, b = (speed.records_digest(str(d)) for d in calls)
    assert a == b and a[0] == 2                  # the two CSV records, not the log
    (calls[1] / "axisym_loose_paper.csv").write_text("step,p\n0,1e5\n100,1.00002e5\n")
    assert speed.records_digest(str(calls[1]))[1] != a[1]
    (calls[1] / "axisym_loose_paper.csv").write_text("step,p\n0,1e5\n100,1.00001e5\n")
    assert speed.records_digest(str(calls[1])) == a
    (calls[1] / "axisym_loose_paper.csv").rename(calls[1] / "axisym_dense_paper.csv")
    assert speed.records_digest(str(calls[1]))[1] != a[1]


def test_job_rows_read_what_reproduce_logs(tmp_path, bench):
    """bench/programme_speed.py's job accounting reads reproduce's own "done" lines: jobs run by
    tylmp.analysis.reproduce.run_jobs (two at once) whose logs carry known loop lines come back with
    those loop times and steps; a job that failed has no row."""
    from tylmp.analysis import reproduce
    speed = bench("programme_speed")
    rundir = tmp_path / "call"
    rundir.mkdir()
    loop = "Loop time of {t} on 1 procs for {n} steps with 3620 atoms\n"
    jobs = []
    for name, runs in (("prepare_loose", [(1.5, 10), (2.25, 30)]), ("axisym_loose", [(4.0, 7)])):
        text = "".join(loop.format(t=t, n=n) for t, n in runs)
        jobs.append(reproduce.Job(name, ["sh", "-c", f"printf '{text}' > {name}.log"], None, 1))
    jobs.append(reproduce.Job("cdst", ["sh", "-c", "exit 3"], None, 1))
    lines = []
    reproduce.run_jobs(jobs, str(rundir), 2, 60, lines.append)
    (tmp_path / "call.out").write_text("".join(f"[{0.1 * i:6.1f} min] {x}\n"
                                               for i, x in enumerate(lines)))
    rows = {r["job"]: r for r in speed.job_rows("before", str(rundir), "2026-12-02T00:00:00Z")}
    assert set(rows) == {"prepare_loose", "axisym_loose"}
    assert (rows["prepare_loose"]["loop_s"], rows["prepare_loose"]["steps"]) == (3.75, 40)
    assert (rows["axisym_loose"]["loop_s"], rows["axisym_loose"]["steps"]) == (4.0, 7)


def test_pairs_compare_each_job_with_the_same_job_beside_it(bench):
    """bench/programme_speed.py's paper-scale accounting: a job's rows of the two builds form a
    pair only when they ran side by side (the same call start); per job the medians over its
    pairs; the programme's loop time only when every job has a pair, as the sum over jobs."""
    speed = bench("programme_speed")
    every = speed.programme_jobs()

    def row(variant, job, started, loop, steps=100, sha="r"):
        return {"variant": variant, "job": job, "started_utc": started, "machine": "m",
                "job_wall_s": loop + 1.0, "loop_s": loop, "steps": steps, "record_sha256": sha}
    a, b = "2026-12-02T10:00:00Z", "2026-12-03T10:00:00Z"
    rows = [row("before", "cdst", a, 30.0), row("after", "cdst", a, 20.0),
            row("before", "cdst", b, 60.0), row("after", "cdst", b, 30.0),
            row("before", "prepare_dense", a, 10.0),          # no after beside it: no pair
            row("after", "prepare_dense", b, 8.0)]
    got = speed.summarise_pairs(rows)
    assert got["jobs_paired"] == 1 and len(got["missing"]) == len(every) - 1
    cdst = got["per_job"]["cdst"]
    assert cdst["pairs"] == 2 and cdst["loop_speedup"] == pytest.approx((1.5 + 2.0) / 2)
    assert (cdst["before_loop_s"], cdst["after_loop_s"]) == (45.0, 25.0)
    assert "loop_speedup" not in got                      # the programme is not complete
    assert got["same_steps_every_pair"] and got["same_record_every_pair"]
    # every job paired once: before 2 s a job, after 1 s, except one job 3 s against 1 s
    rows = [row(v, j, a, (2.0 if v == "before" else 1.0) + (j == "cdst" and v == "before"))
            for j in every for v in ("before", "after")]
    got = speed.summarise_pairs(rows)
    assert got["before_loop_s"] == 2.0 * len(every) + 1 and got["after_loop_s"] == len(every)
    assert got["loop_speedup"] == pytest.approx((2.0 * len(every) + 1) / len(every))
    assert got["median_job_loop_speedup"] == 2.0 and got["steps"] == 100 * len(every)
    # job wall time (loop + 1 s here) summed the same way: the jobs run one at a time
    assert got["before_job_wall_s"] == 3.0 * len(every) + 1
    assert got["after_job_wall_s"] == 2.0 * len(every)
    assert got["job_wall_speedup"] == pytest.approx((3.0 * len(every) + 1) / (2.0 * len(every)))
    # a pair that wrote different records or did different steps says so
    rows[-1] = dict(rows[-1], record_sha256="other", steps=99)
    got = speed.summarise_pairs(rows)
    assert not got["same_record_every_pair"] and not got["same_steps_every_pair"]


def test_a_job_counts_with_its_pairs_on_one_machine(bench):
    """Sessions land on different machines, whose timings are not comparable: a job's figure
    comes from its pairs on one machine (for a job paired on two, the machine that paired more
    of the programme's steps), each machine has its own totals, and the programme's sum takes
    every job once, naming the machines; rows of different machines never form a pair."""
    speed = bench("programme_speed")
    every = speed.programme_jobs()

    def row(variant, job, started, machine, loop, steps=100, sha="r"):
        return {"variant": variant, "job": job, "started_utc": started, "machine": machine,
                "job_wall_s": loop + 1.0, "loop_s": loop, "steps": steps, "record_sha256": sha}
    a, b = "2026-12-02T10:00:00Z", "2026-12-03T10:00:00Z"
    rows = [row("before", "prepare_dense", a, "A", 9.0), row("after", "prepare_dense", a, "A", 10.0),
            row("before", "cdst", a, "A", 12.0), row("after", "cdst", a, "A", 10.0),
            row("before", "prepare_dense", b, "B", 3.0), row("after", "prepare_dense", b, "B", 2.0),
            row("before", "axisym_dense", b, "B", 40.0, steps=1000),
            row("after", "axisym_dense", b, "B", 20.0, steps=1000),
            row("before", "friction_mu0", b, "B", 5.0), row("after", "friction_mu0", b, "A", 1.0)]
    got = speed.summarise_pairs(rows)
    assert set(got["per_job"]) == {"prepare_dense", "cdst", "axisym_dense"}   # no A-B pair
    dense = got["per_job"]["prepare_dense"]
    assert dense["machine"] == "B" and dense["pairs"] == 1                   # B: 1100 steps
    assert (dense["before_loop_s"], dense["after_loop_s"]) == (3.0, 2.0)
    assert dense["other_machines"]["A"]["loop_speedup"] == pytest.approx(0.9)
    assert got["per_job"]["cdst"]["machine"] == "A"
    on_a, on_b = got["by_machine"]["A"], got["by_machine"]["B"]
    assert (on_a["jobs"], on_a["steps"], on_a["before_loop_s"], on_a["after_loop_s"]) \
        == (2, 200, 21.0, 20.0)
    assert (on_b["jobs"], on_b["steps"]) == (2, 1100)
    assert on_b["loop_speedup"] == pytest.approx(43.0 / 22.0)
    assert (on_b["before_job_wall_s"], on_b["after_job_wall_s"]) == (45.0, 24.0)
    assert "loop_speedup" not in got
    # the same job on another machine must still write the same record
    rows[4] = dict(rows[4], record_sha256="other")
    rows[5] = dict(rows[5], record_sha256="other")
    assert not speed.summarise_pairs(rows)["same_record_every_pair"]
    # every job paired, some on A, the rest on B: the programme is their sum, both named
    rows = [row(v, j, a if i % 2 else b, "A" if i % 2 else "B", 2.0 if v == "before" else 1.0)
            for i, j in enumerate(every) for v in ("before", "after")]
    got = speed.summarise_pairs(rows)
    assert got["programme_machines"] == ["A", "B"]
    assert (got["before_loop_s"], got["after_loop_s"]) == (2.0 * len(every), 1.0 * len(every))
    assert got["by_machine"]["A"]["jobs"] + got["by_machine"]["B"]["jobs"] == len(every)


def test_report_summarises_the_saved_rows_without_running(tmp_path, bench, capsys):
    """`--report` reads PREFIX_jobs.csv, rewrites PREFIX.json from it and prints the tables:
    the figures of a later session's rules from rows measured earlier, nothing run."""
    import json
    speed = bench("programme_speed")
    out = str(tmp_path / "p")
    rows = [{"variant": v, "job": "cdst", "started_utc": "2026-12-02T10:00:00Z",
             "machine": "A", "job_wall_s": 61.0, "loop_s": loop, "steps": 100,
             "record_sha256": "r"} for v, loop in (("before", 30.0), ("after", 20.0))]
    (tmp_path / "p_jobs.csv").write_text(speed.csv_text(rows, speed.JOB_FIELDS))
    assert speed.main(["--scale", "paper", "--report", "--out", out]) == 0
    with open(out + ".json") as f:
        jobs = json.load(f)["jobs"]
    assert jobs["per_job"]["cdst"]["loop_speedup"] == pytest.approx(1.5)
    assert jobs["by_machine"]["A"]["before_loop_s"] == 30.0
    assert "| cdst | M1 | 1 | 100 | 30 s | 20 s | 1.50 |" in capsys.readouterr().out
