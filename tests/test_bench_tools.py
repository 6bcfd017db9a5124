"""The benchmarks' instruments. The one reader of LAMMPS's timing output (bench/lammps_log.py),
checked against what the running `lmp` prints for a deck whose runs are known: two runs of 20
and 30 steps of a 4x4x4 fcc lattice (256 atoms) on one process, whose timing breakdown (Pair,
Neigh, Comm, Output, Modify, Other) accounts for the whole loop time (its %total column sums
to 100). The record digest by which bench/programme_speed.py says two calls of the programme
did the same work: equal for byte-equal records, different when one byte or one name differs."""
import importlib.util
import os
import subprocess

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

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


def _bench(name):
    path = os.path.join(REPO, "bench", f"{name}.py")
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _lammps_log():
    return _bench("lammps_log")


@pytest.fixture(scope="module")
def output(tmp_path_factory):
    work = tmp_path_factory.mktemp("lammps_log")
    (work / "in.lj").write_text(DECK)
    proc = subprocess.run(["lmp", "-in", "in.lj", "-log", "none", "-nocite"], cwd=str(work),
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-2000:]
    return proc.stdout


def test_every_run_is_read_with_its_steps_atoms_and_procs(output):
    log = _lammps_log()
    runs = log.loops(output)
    assert [(r["steps"], r["atoms"], r["procs"]) for r in runs] == [(20, 256, 1), (30, 256, 1)]
    assert all(r["seconds"] > 0 for r in runs)
    assert log.first_loop(output) == runs[0]


def test_breakdown_accounts_for_the_loop_time(output):
    log = _lammps_log()
    sections = ("Pair", "Neigh", "Comm", "Output", "Modify", "Other")
    for run in range(2):
        pct = sum(log.section(output, s)[run]["pct"] for s in sections)
        assert pct == pytest.approx(100.0, abs=0.1)
        # the Pair row's avg column is seconds of that run's loop time
        pair = log.section(output, "Pair")[run]
        assert pair["avg"] == pytest.approx(pair["pct"] / 100 * log.loops(output)[run]["seconds"],
                                            rel=0.05, abs=2e-4)


def test_output_without_a_run_is_an_error_that_says_so():
    with pytest.raises(RuntimeError, match="no 'Loop time of ...' line"):
        _lammps_log().first_loop("LAMMPS (29 Sep 2021)\n", "empty output")


def test_record_digest_tells_the_same_records_from_different_ones(tmp_path):
    speed = _bench("programme_speed")
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


def test_job_rows_read_what_reproduce_logs(tmp_path):
    """bench/programme_speed.py's job accounting reads reproduce's own "done" lines: jobs run by
    tyanalysis.reproduce.run_jobs (two at once) whose logs carry known loop lines come back with
    those loop times and steps; a job that failed has no row."""
    from tyanalysis import reproduce
    speed = _bench("programme_speed")
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
