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
