"""compute thornton/yin/contacts: the pair's own contacts as of
its last force evaluation, checked against independent sums (LAMMPS's virial, fix cell/servo's
contact tallies, compute pair/local within a run) and against closed forms on lattices."""
import numpy as np
import pytest

from cellspec import DT, E, LATTICE_SPECIMEN, NU, read_csv, restart_deck
from lmprun import LOAD_TYLMP, run_ok

# columns of compute thornton/yin/contacts (docs/compute_thornton_yin_contacts.md)
COLUMNS = ["id1", "id2", "fnx", "fny", "fnz", "ftx", "fty", "ftz", "lx", "ly", "lz", "P",
           "overlap", "a", "sliding", "peeling"]
VIRIAL = ["xx", "yy", "zz", "xy", "xz", "yz"]
A_OF, B_OF = [0, 1, 2, 0, 0, 1], [0, 1, 2, 1, 2, 2]    # LAMMPS's virial: xy = sum l_x f_y


@pytest.fixture(scope="module")
def specimen(tmp_path_factory):
    """216 spheres compressed isotropically to 100 kPa without friction (dense enough)."""
    work = tmp_path_factory.mktemp("contacts_specimen")
    run_ok(LATTICE_SPECIMEN + f"""pair_style thornton/yin
pair_coeff * * {E} {NU} 0.0 0.0
neighbor 2e-5 bin
timestep {DT}
fix nve all nve/sphere
fix prep all cell/servo iso 1e5 max_rate 4e-3
fix damp all damping/cundall 0.2 0.2
run 30000
write_restart spec.restart
""", work)
    return work / "spec.restart"


def read_dump_local(path):
    """the last snapshot of a dump local file -> dict of columns"""
    with open(path) as fh:
        lines = fh.read().splitlines()
    start = max(k for k, l in enumerate(lines) if l.startswith("ITEM: ENTRIES"))
    rows = np.array([[float(v) for v in l.split()] for l in lines[start + 1:]], ndmin=2)
    return {name: rows[:, k] for k, name in enumerate(lines[start].split()[2:])}


def thermo_rows(out, first):
    """thermo lines whose header starts with `first` -> list of dicts, per run"""
    lines, runs = out.splitlines(), []
    for k, line in enumerate(lines):
        if line.split()[:1] == [first]:
            names, rows = line.split(), []
            for row in lines[k + 1:]:
                try:
                    rows.append(dict(zip(names, map(float, row.split()), strict=True)))
                except ValueError:
                    break
            runs.append(rows)
    return runs


@pytest.fixture(scope="module")
def sheared(specimen, tmp_path_factory):
    """axisymmetric compression at constant p with friction and adhesion, 3000 steps, then
    `run 0`; the contacts dumped at the end of the run and after run 0"""
    work = tmp_path_factory.mktemp("contacts_shear")
    deck = restart_deck(specimen, mu=0.3, gamma=0.6) + """fix cell all cell/servo axisym z 2e-3 1e5 csv cell.csv 3000
compute c all thornton/yin/contacts
compute pl all pair/local p1 p3
compute pv all pressure NULL virial
thermo_style custom step c_pv[*] vol
thermo_modify format float %.16g
thermo 3000
dump dc all local 3000 contacts_run.txt c_c[*]
dump dp all local 3000 pair_local_run.txt c_pl[*]
dump_modify dc format float %.17g
dump_modify dp format float %.17g
run 3000
undump dc
undump dp
dump dc all local 3000 contacts_run0.txt c_c[*]
dump dp all local 3000 pair_local_run0.txt c_pl[*]
dump_modify dc format float %.17g
dump_modify dp format float %.17g
run 0
"""
    out = run_ok(deck, work)
    runs = thermo_rows(out, "Step")
    return work, runs[0][-1], runs[1][-1]


def stress_of(rec, force, volume):
    """(1/V) sum l_a f_b of the dumped contacts, LAMMPS's components"""
    l = np.stack([rec["lx"], rec["ly"], rec["lz"]])
    f = np.stack([rec[force[0]], rec[force[1]], rec[force[2]]])
    return np.array([np.sum(l[a] * f[b]) for a, b in zip(A_OF, B_OF)]) / volume


def contacts_of(path):
    rec = read_dump_local(path)
    return {name: rec[f"c_c[{k + 1}]"] for k, name in enumerate(COLUMNS)}


def test_contacts_stress_is_the_virial_lammps_reports(sheared):
    work, end, _ = sheared
    rec = contacts_of(work / "contacts_run.txt")
    fx, fy, fz = (rec["fnx"] + rec["ftx"], rec["fny"] + rec["fty"], rec["fnz"] + rec["ftz"])
    rec.update(fx=fx, fy=fy, fz=fz)
    sigma = stress_of(rec, ("fx", "fy", "fz"), end["Volume"])
    virial = np.array([end[f"c_pv[{k}]"] for k in range(1, 7)])
    np.testing.assert_allclose(sigma, virial, rtol=1e-9, atol=1e-9 * abs(virial[:3]).max())
    # the deviator is real: axial stress well above the lateral ones
    assert virial[2] > 1.2 * virial[0]
    # every row is a contact: both IDs, overlap no deeper than the break overlap, a > 0
    assert np.all(rec["a"] > 0) and np.all(rec["id1"] != rec["id2"])
    assert np.any(rec["P"] < 0)    # adhesive contacts in tension are included
    # n . f_n = P and t . n = 0 (force split into normal and tangential parts)
    l = np.stack([rec["lx"], rec["ly"], rec["lz"]])
    n = l / np.linalg.norm(l, axis=0)
    fn = np.stack([rec["fnx"], rec["fny"], rec["fnz"]])
    ft = np.stack([rec["ftx"], rec["fty"], rec["ftz"]])
    np.testing.assert_allclose(np.sum(n * fn, axis=0), rec["P"], rtol=1e-12, atol=1e-15)
    assert np.max(np.abs(np.sum(n * ft, axis=0))) <= 1e-12 * np.max(np.abs(rec["P"]))
    assert np.max(np.linalg.norm(ft, axis=0)) > 0.01 * np.max(np.abs(rec["P"]))


def test_contact_count_and_sliding_agree_with_the_cell_fix_tallies(sheared, specimen):
    work, end, _ = sheared
    rec = contacts_of(work / "contacts_run.txt")
    row = read_csv(work / "cell.csv")
    last = int(np.argmax(row["step"]))
    # the fix counts contacts from the pair's tallies: Z = 2C/N, N = 216
    assert len(rec["P"]) == pytest.approx(row["Z"][last] * 216 / 2, abs=1e-9)
    assert np.mean(rec["sliding"]) == pytest.approx(row["sliding_fraction"][last], abs=1e-12)


def test_contacts_agree_with_pair_local_within_the_run(sheared):
    # inside the run compute pair/local (single() on its own list) sees the same contacts
    work, _, _ = sheared
    rec = contacts_of(work / "contacts_run.txt")
    pl = read_dump_local(work / "pair_local_run.txt")
    touching = pl["c_pl[2]"] > 0    # contact radius > 0
    assert np.sum(touching) == len(rec["P"])
    assert np.sum(pl["c_pl[1]"]) == pytest.approx(np.sum(rec["P"]), rel=1e-12)


def test_contacts_stay_current_after_run_0(sheared):
    # same positions, forces recomputed in setup: the contacts and the stress must not change
    # (compute pair/local does, docs/compute_thornton_yin_contacts.md)
    work, end, after = sheared
    before = contacts_of(work / "contacts_run.txt")
    now = contacts_of(work / "contacts_run0.txt")
    assert len(now["P"]) == len(before["P"])
    assert np.sum(now["P"]) == pytest.approx(np.sum(before["P"]), rel=1e-12)
    for k in range(1, 7):
        assert after[f"c_pv[{k}]"] == pytest.approx(end[f"c_pv[{k}]"], rel=1e-9, abs=1e-6)
