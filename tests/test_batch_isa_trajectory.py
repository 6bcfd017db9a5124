"""The builds of the batch contact law give the same trajectory (issues 13 and 29).

The pair runs tycore::advance_batch in the widest build this processor runs; the environment
variable TYLMP_LAW_ISA=B (a setting for tests and benchmarks, not a keyword of the pair style)
makes it run build B (plugin/core/contact_batch.hpp). Every build is an instantiation of the
law's one text (plugin/core/contact_law.hpp) doing the same arithmetic operation for operation
(no fused multiply-add, the same cube root bit for bit), so a whole NVE trajectory of the
3620-sphere dense specimen (bench/data/dense_paper_100kPa.data, mu = 0.3 with Gamma = 0.6 and
0, and mu = 0 with Gamma = 0 as in the dense specimen's preparation, whose vector batches skip
the tangential law; 1000 steps of fix nve/sphere, no servo) must agree with the scalar build's: the issue asks for
1e-12 relative, and by that construction they are equal to the last bit, which is what is
asserted (a dense packing is chaotic: a round-off difference would grow over 1000 steps and
show). Each supported build is compared, bad values of the variable are refused, and the
former keyword `isa` is refused as an argument of the style.
"""
import os

import numpy as np
import pytest

from conftest import REPO, cpu_flags
from lmprun import LOAD_TYLMP, run_deck, run_ok

DATA = os.path.join(REPO, "bench", "data", "dense_paper_100kPa.data")
# E, nu and the time step of bench/pair_speed.py (0.2 Rayleigh times of the smallest sphere)
E, NU = 70e9, 0.3
DT = 0.2 * np.pi * 0.0675e-3 * np.sqrt(2650e12 / (E / 2.6)) / (0.1631 * NU + 0.8766)
STEPS = 1000
COLUMNS = "x y z vx vy vz omegax omegay omegaz"


FLAGS = cpu_flags()
SUPPORTED = {"scalar": True, "sse2": True, "avx2": "avx2" in FLAGS,
             "avx512": {"avx512f", "avx512dq", "avx512vl"} <= FLAGS}


def deck(Gamma, mu, dump):
    return f"""{LOAD_TYLMP}atom_style sphere
units si
boundary p p p
read_data {DATA}
comm_modify vel yes
pair_style thornton/yin
pair_coeff * * {E!r} {NU} {mu} {Gamma}
neighbor 1.35e-5 bin
neigh_modify every 1 delay 0 check yes
timestep {DT!r}
fix integrate all nve/sphere
thermo {STEPS}
write_dump all custom start_{dump} id {COLUMNS} modify sort id format float %.17g
run {STEPS}
write_dump all custom {dump} id {COLUMNS} modify sort id format float %.17g
"""


def trajectory(tmp_path, isa, Gamma, mu):
    """(start, end) of the run: id and COLUMNS per atom, sorted by id"""
    dump = f"end_{isa}_{Gamma}_{mu}.dump"
    run_ok(deck(Gamma, mu, dump), tmp_path, name=f"in.{isa}_{Gamma}_{mu}",
           environment={"TYLMP_LAW_ISA": isa})
    return tuple(np.loadtxt(tmp_path / name, skiprows=9) for name in (f"start_{dump}", dump))


# Gamma = 0 and mu = 0 are branches inside the law's builds, the same object code under either
# LAMMPS; what LAMMPS does here (the pair's neighbour loop and history feeding the batches) the
# (0.6, 0.3) run takes under both. So those two run in the 29 Sep 2021 half only
# (tests/lammps_halves.py).
LAW_BRANCH_ONCE = pytest.mark.lammps_once(
    reason="a branch inside the law's builds; the LAMMPS side runs in the (0.6, 0.3) case")


@pytest.mark.parametrize("Gamma, mu", [(0.6, 0.3), pytest.param(0.0, 0.3, marks=LAW_BRANCH_ONCE),
                                       pytest.param(0.0, 0.0, marks=LAW_BRANCH_ONCE)])
def test_vector_builds_follow_the_scalar_trajectory(tmp_path, Gamma, mu):
    start, reference = trajectory(tmp_path, "scalar", Gamma, mu)
    assert reference.shape == (3620, 10)
    # the packing moves: every sphere's position changed over the run, and the velocity of
    # most (the rest are rattlers without a contact, in free flight)
    assert np.all(reference[:, 1:4] != start[:, 1:4])
    assert np.mean(np.any(reference[:, 4:7] != start[:, 4:7], axis=1)) > 0.8
    builds = [b for b in ("sse2", "avx2", "avx512") if SUPPORTED[b]]
    for isa in builds:
        end = trajectory(tmp_path, isa, Gamma, mu)[1]
        scale = np.maximum(np.abs(reference[:, 1:]), 1e-300)
        relative = np.max(np.abs(end[:, 1:] - reference[:, 1:]) / scale)
        assert relative <= 1e-12, f"isa {isa}, Gamma {Gamma}, mu {mu}: max relative difference {relative:.3g}"
        assert np.array_equal(end, reference), \
            f"isa {isa}, Gamma {Gamma}, mu {mu}: not bitwise (max relative difference {relative:.3g})"


@pytest.mark.parametrize("value, message", [
    ("avx1024", "TYLMP_LAW_ISA (a setting for tests and benchmarks) must be scalar, sse2, avx2 "
                "or avx512, got 'avx1024'"),
    ("auto", "must be scalar, sse2, avx2 or avx512, got 'auto'"),
])
def test_bad_law_isa_is_refused(tmp_path, value, message):
    rc, out = run_deck(deck(0.6, 0.3, "unused.dump"), tmp_path, environment={"TYLMP_LAW_ISA": value})
    assert rc != 0 and message in out, out[-2000:]


def test_isa_is_no_keyword(tmp_path):
    text = deck(0.6, 0.3, "unused.dump").replace("pair_style thornton/yin", "pair_style thornton/yin isa avx2")
    rc, out = run_deck(text, tmp_path)
    assert rc != 0 and "pair_style thornton/yin takes no arguments, got 'isa'" in out, out[-2000:]


@pytest.mark.skipif(SUPPORTED["avx512"] and SUPPORTED["avx2"],
                    reason="this processor runs every build")
def test_missing_isa_is_named(tmp_path):
    missing = "avx512" if not SUPPORTED["avx512"] else "avx2"
    rc, out = run_deck(deck(0.6, 0.3, "unused.dump"), tmp_path, environment={"TYLMP_LAW_ISA": missing})
    assert rc != 0 and f"does not run {missing} instructions" in out, out[-2000:]
