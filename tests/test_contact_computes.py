"""compute thornton/yin/contacts and thornton/yin/micromechanics: the pair's own contacts as of
its last force evaluation, checked against independent sums (LAMMPS's virial, fix cell/servo's
contact tallies, compute pair/local within a run) and against closed forms on lattices."""
import numpy as np
import pytest

from cellspec import DT, E, LATTICE_SPECIMEN, NU, read_csv, restart_deck
from lmprun import LOAD_TYLMP, reduce_local, run_ok

# columns of compute thornton/yin/contacts (docs/compute_thornton_yin_contacts.md)
COLUMNS = ["id1", "id2", "fnx", "fny", "fnz", "ftx", "fty", "ftz", "lx", "ly", "lz", "P",
           "overlap", "a", "sliding", "peeling"]
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
compute m all thornton/yin/micromechanics
compute pl all pair/local p1 p3
compute pv all pressure NULL virial
thermo_style custom step c_pv[*] c_m[*] vol
thermo_modify format float %.16g
thermo 3000
dump dc all local 3000 contacts_run.txt c_c[*]
dump dp all local 3000 pair_local_run.txt c_pl[*]
dump_modify dc format float %.17g
dump_modify dp format float %.17g
""" + MICRO_PRINT + """
run 3000
unfix print
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


# the compute's 41 values and the strain, every 300 steps, as a fix print table
MICRO_PRINT = ('fix print all print 300 "$(step) $(f_cell[6]:%.16g)'
               + "".join(f" $(c_m[{k}]:%.16g)" for k in range(1, 42))
               + '" file micro.txt screen no title "# step eps_d13'
               + "".join(f" c_m[{k}]" for k in range(1, 42)) + '"')


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
    assert end["c_m[1]"] == len(rec["P"])
    assert end["c_m[2]"] == pytest.approx(np.mean(rec["sliding"]), abs=1e-12)


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
        assert after[f"c_m[{11 + k}]"] == pytest.approx(after[f"c_pv[{k}]"], rel=1e-9, abs=1e-6)


def test_micromechanics_splits_add_up_to_the_virial(sheared):
    work, end, _ = sheared
    m = [None] + [end[f"c_m[{k}]"] for k in range(1, 42)]     # 1-based as in LAMMPS
    virial = [end[f"c_pv[{k}]"] for k in range(1, 7)]
    scale = max(abs(v) for v in virial)
    for k in range(6):
        total, normal, tangential = m[12 + k], m[18 + k], m[24 + k]
        strong, weak = m[30 + k], m[36 + k]
        assert total == pytest.approx(virial[k], abs=1e-9 * scale)
        assert normal + tangential == pytest.approx(virial[k], abs=1e-9 * scale)
        assert strong + weak == pytest.approx(virial[k], abs=1e-9 * scale)
    # fabric: trace 1; the strong network carries most of the deviator (Thornton 2000)
    assert m[5] + m[6] + m[7] == pytest.approx(1.0, abs=1e-12)
    assert m[32] - m[30] > m[38] - m[36]
    # from the dumped contacts, independently: mean force, strong fraction, tangential stress
    rec = contacts_of(work / "contacts_run.txt")
    assert m[3] == pytest.approx(np.mean(rec["P"]), rel=1e-12)
    assert m[4] == pytest.approx(np.mean(rec["P"] > np.mean(rec["P"])), abs=1e-12)
    tangential = stress_of(rec, ("ftx", "fty", "ftz"), end["Volume"])
    np.testing.assert_allclose(m[24:30], tangential, rtol=1e-9, atol=1e-9 * scale)
    # fabric from the branch vectors
    l = np.stack([rec["lx"], rec["ly"], rec["lz"]])
    n = l / np.linalg.norm(l, axis=0)
    phi = np.array([np.mean(n[a] * n[b]) for a, b in zip(A_OF, B_OF)])
    np.testing.assert_allclose(m[5:11], phi, rtol=1e-12, atol=1e-14)


# ---- closed forms on simple orthorhombic lattices of equal spheres (Hertz, Gamma = 0) --------
D = 2e-4                                            # diameter
R_STAR = D / 4.0
E_STAR = E / (2.0 * (1.0 - NU ** 2))


def lattice_deck(spacing):
    """4x4x4 spheres of diameter D on an orthorhombic lattice of the given spacings (m):
    each sphere touches its neighbours along the axes where spacing < D; forces at run 0"""
    sx, sy, sz = spacing
    return f"""units si
atom_style sphere
atom_modify map array
boundary p p p
comm_modify vel yes
lattice custom 1.0 a1 {sx} 0 0 a2 0 {sy} 0 a3 0 0 {sz} basis 0 0 0
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
set atom * diameter {D} density 2650
{LOAD_TYLMP}pair_style thornton/yin
pair_coeff * * {E} {NU} 0.3 0.0
neighbor 1e-5 bin
fix nve all nve/sphere
compute m all thornton/yin/micromechanics
compute pv all pressure NULL virial
thermo_style custom step c_m[*] c_pv[*]
thermo_modify format float %.16g
run 0
"""


def hertz(delta):
    return 4.0 / 3.0 * E_STAR * np.sqrt(R_STAR) * delta ** 1.5


def micromechanics_of(out):
    row = thermo_rows(out, "Step")[0][0]
    return [None] + [row[f"c_m[{k}]"] for k in range(1, 42)]


@pytest.mark.parametrize("spacing, fabric, deviator", [
    ((1.99e-4, 1.995e-4, 1.998e-4), (1 / 3, 1 / 3, 1 / 3), 0.0),   # isotropic fabric
    ((1.99e-4, 1.99e-4, 2.1e-4), (1 / 2, 1 / 2, 0.0), 0.5),         # x, y chains: phi1 - phi3
    ((1.99e-4, 2.1e-4, 2.1e-4), (1.0, 0.0, 0.0), 1.0),              # x chains only
])
def test_lattice_fabric_and_stress_are_the_closed_forms(spacing, fabric, deviator, tmp_path):
    m = micromechanics_of(run_ok(lattice_deck(spacing), tmp_path))
    touching = [s < D for s in spacing]
    forces = [hertz(D - s) if t else 0.0 for s, t in zip(spacing, touching)]
    n_atoms = 64
    assert m[1] == n_atoms * sum(touching)                 # one contact per atom and axis
    np.testing.assert_allclose(m[5:8], fabric, atol=1e-15)
    np.testing.assert_allclose(m[8:11], 0.0, atol=1e-15)
    assert m[11] == pytest.approx(deviator, abs=1e-14)
    # sigma_aa = P_a l_a / (l_x l_y l_z) per atom: P_a/(area normal to a)
    sx, sy, sz = spacing
    areas = (sy * sz, sx * sz, sx * sy)
    expected = [f / area for f, area in zip(forces, areas)]
    np.testing.assert_allclose(m[12:15], expected, rtol=1e-9)
    np.testing.assert_allclose(m[15:18], 0.0, atol=1e-9 * max(expected))
    np.testing.assert_allclose(m[18:24], m[12:18], rtol=1e-14)         # no tangential forces
    np.testing.assert_allclose(m[24:30], 0.0, atol=1e-9 * max(expected))
    assert m[2] == 0.0                                                  # nothing slides
    mean = sum(f for f, t in zip(forces, touching) if t) / sum(touching)
    assert m[3] == pytest.approx(mean, rel=1e-9)


def test_lattice_strong_and_weak_networks(tmp_path):
    # overlaps 1, 0.5, 0.2 um: P_x > <P> > P_y > P_z, so the strong network is the x chains
    spacing = (1.99e-4, 1.995e-4, 1.998e-4)
    m = micromechanics_of(run_ok(lattice_deck(spacing), tmp_path))
    p_x, p_y, p_z = (hertz(D - s) for s in spacing)
    assert p_x > (p_x + p_y + p_z) / 3 > p_y
    assert m[4] == pytest.approx(1 / 3, abs=1e-15)
    sx, sy, sz = spacing
    np.testing.assert_allclose(m[30:33], [p_x / (sy * sz), 0.0, 0.0], rtol=1e-9, atol=1e-6)
    np.testing.assert_allclose(m[36:39], [0.0, p_y / (sx * sz), p_z / (sx * sy)], rtol=1e-9,
                               atol=1e-6)
    # LAMMPS's virial is the same stress
    row = thermo_rows(run_ok(lattice_deck(spacing), tmp_path), "Step")[0][0]
    np.testing.assert_allclose(m[12:18], [row[f"c_pv[{k}]"] for k in range(1, 7)], rtol=1e-12,
                               atol=1e-6)


def test_micromechanics_group_keeps_contacts_with_both_atoms_in_it(tmp_path):
    # group of the spheres with x < 2 lattice spacings: y and z contacts of those 32 spheres,
    # x contacts only between the two layers inside (16), none across the group's edge
    deck = lattice_deck((1.99e-4, 1.995e-4, 1.998e-4)).replace(
        "compute m all", "region half block 0 1.5 0 4 0 4 units lattice\n"
        "group half region half\ncompute m half")
    m = micromechanics_of(run_ok(deck, tmp_path))
    assert m[1] == 32 * 2 + 16


def test_tyanalysis_draws_the_recorded_micromechanics(sheared):
    # the figure of the record, and the shares it reports add up (normal + tangential, strong +
    # weak = total), with the compute's last values
    import subprocess
    import sys
    work, end, _ = sheared
    out = subprocess.run([sys.executable, "-m", "tylmp.analysis", "micromechanics",
                          str(work / "micro.txt"), "--out", str(work / "micro.png")],
                         capture_output=True, text=True, check=True).stdout
    values = dict(kv.split("=") for kv in out.splitlines()[0].split(": ", 1)[1].split())
    # the shares are printed to 6 significant digits: two of them add up to 1 within 1e-6
    # (0.9999997 on one specimen, 1.000000 on another)
    assert float(values["q_normal_share"]) + float(values["q_tangential_share"]) == \
        pytest.approx(1.0, abs=1e-6)
    assert float(values["q_strong_share"]) + float(values["q_weak_share"]) == \
        pytest.approx(1.0, abs=1e-6)
    assert float(values["p_strong_share"]) + float(values["p_weak_share"]) == \
        pytest.approx(1.0, abs=1e-6)
    # normal forces carry most of the deviator, tangential ones a positive part (Thornton 2000)
    assert 0.5 < float(values["q_normal_share"]) < 1.0
    assert float(values["phi_d"]) == pytest.approx(end["c_m[11]"], rel=1e-5)    # printed to 6 digits
    assert float(values["contacts"]) == end["c_m[1]"]
    assert (work / "micro.png").stat().st_size > 10000


@pytest.mark.parametrize("newton", ["on", "off"])
def test_two_ranks_count_each_contact_once(newton, tmp_path):
    # with newton off a contact across the rank boundary is computed on both ranks; the
    # computes must still count it once, and the lattice's closed forms must hold
    spacing = (1.99e-4, 1.995e-4, 1.998e-4)
    deck = lattice_deck(spacing).replace("comm_modify vel yes", f"comm_modify vel yes\nnewton {newton}")
    deck = deck.replace("thermo_style custom step c_m[*] c_pv[*]",
                        "compute c all thornton/yin/contacts\n" + reduce_local("sP", "c_c[12]") +
                        "thermo_style custom step c_m[*] c_pv[*] c_sP")
    out = run_ok(deck, tmp_path, np_ranks=2)
    assert "2 by 1 by 1" in out or "1 by 2 by 1" in out or "1 by 1 by 2" in out
    m = micromechanics_of(out)
    forces = [hertz(D - s) for s in spacing]
    assert m[1] == 64 * 3
    sum_P = thermo_rows(out, "Step")[0][0]["c_sP"]
    assert sum_P == pytest.approx(64 * sum(forces), rel=1e-9)
    sx, sy, sz = spacing
    np.testing.assert_allclose(m[12:15], [forces[0] / (sy * sz), forces[1] / (sx * sz),
                                          forces[2] / (sx * sy)], rtol=1e-9)


def test_sliding_fraction_after_a_change_of_mu(specimen, tmp_path):
    """The setup pass of a run evaluates forces without a step of the history: the sliding
    state it reports must be that of the mu now in force. The specimen was compressed with
    mu = 0, where every contact is at its (zero) sliding limit; with mu = 0.3 the kept T = 0
    is far from mu (P + 2Pc) > 0, so no contact slides (the record's first row showed 1)."""
    runs = {}
    for mu in (0.0, 0.3):
        out = run_ok(restart_deck(specimen, mu=mu, gamma=0.6) + """
compute m all thornton/yin/micromechanics
fix cell all cell/servo iso 1e5
thermo_style custom step c_m[1] c_m[2] f_cell[20]
thermo_modify format float %.16g
run 0
""", tmp_path)
        (row,) = thermo_rows(out, "Step")[0]
        runs[mu] = row
    for mu, expected in ((0.0, 1.0), (0.3, 0.0)):
        row = runs[mu]
        assert row["c_m[1]"] > 100, row                 # contacts of the packing
        assert row["c_m[2]"] == expected, (mu, row)     # compute's sliding fraction
        assert row["f_cell[20]"] == expected, (mu, row)  # the cell fix's record column
