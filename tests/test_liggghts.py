"""The Thornton-Yin model in Debian's LIGGGHTS 3.8 (plugin/liggghts/, launcher build/bin/tyliggghts)
against pair thornton/yin in LAMMPS (same steps, same integrator settings) and the closed-form
JKR values of tests/jkr_reference.py; history through neighbour rebuilds, 1 vs 2 ranks and a
restart; bad input named; the model's own pair loop against LIGGGHTS's loop (which runs the
model where a feature needs it). Skipped when the launcher was not built (no LIGGGHTS found by
CMake).
"""
import math
import os

import numpy as np
import pytest

import jkr_reference as ref
from conftest import BUILD, REPO
from lmprun import run_deck, run_ok

LAUNCHER = os.path.join(BUILD, "bin", "tyliggghts")
DECKS = os.path.join(REPO, "inputs", "liggghts")
# skipped only where the system has no LIGGGHTS (a release without the package): where it has
# one, the set-up must have built the launcher, and its absence fails the tests
LIGGGHTS_INSTALLED = os.path.exists("/usr/include/liggghts/pair_gran_base.h")
pytestmark = pytest.mark.skipif(not LIGGGHTS_INSTALLED and not os.access(LAUNCHER, os.X_OK),
                                reason="no LIGGGHTS on this system (apt-get install liggghts "
                                       "libliggghts-dev, then rebuild)")


@pytest.mark.no_lammps          # LIGGGHTS only
def test_the_launcher_was_built():
    assert os.access(LAUNCHER, os.X_OK), (
        f"LIGGGHTS is installed but {LAUNCHER} was not built: reconfigure (cmake -S . -B build)")


def run_liggghts(deck, workdir, np_ranks=1, variables=None, text=None):
    """Run a LIGGGHTS deck (the file `deck`, or `text`) with the launcher in workdir;
    returns (returncode, output)."""
    if text is None:
        with open(deck) as fh:
            text = fh.read()
    return run_deck(text, workdir, name="in.liggghts", np_ranks=np_ranks, variables=variables,
                    program=(LAUNCHER,))


def liggghts_ok(deck, workdir, **kw):
    rc, out = run_liggghts(deck, workdir, **kw)
    assert rc == 0 and "ERROR" not in out, out[-3000:]
    return out


def csv(path):
    return np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def run_both(tmp_path, lammps_text, csv_name, deck=None, text=None, variables=None):
    """The same case in LIGGGHTS (a deck file or text) and LAMMPS (text); both write csv_name
    with time first. Returns the two tables, row for row the same times (LAMMPS's fix print
    also writes step 0, which is dropped)."""
    lg, lm = tmp_path / "liggghts", tmp_path / "lammps"
    lg.mkdir(), lm.mkdir()
    liggghts_ok(deck, lg, variables=variables, text=text)
    run_ok(lammps_text, lm, variables=variables)
    a, b = csv(lg / csv_name), csv(lm / csv_name)[1:]
    assert len(a) == len(b) and np.array_equal(a[:, 0], b[:, 0])
    return a, b


def assert_same_columns(a, b, columns, rel=1e-10):
    """Columns of a equal those of b to rel of each column's largest magnitude in b."""
    for col in columns:
        scale = np.abs(b[:, col]).max()
        assert scale > 0 and np.abs(a[:, col] - b[:, col]).max() <= rel * scale, col


# ---- two spheres under displacement control: the normal cycle ----

@pytest.mark.parametrize("Gamma", [0.3, 0.0])
def test_two_sphere_cycle_equals_lammps_pair_and_jkr_closed_form(tmp_path, Gamma):
    with open(os.path.join(REPO, "inputs", "two_spheres.in")) as fh:
        a, b = run_both(tmp_path, fh.read(), "two_spheres.csv", variables={"Gamma": Gamma},
                        deck=os.path.join(DECKS, "two_spheres.in"))
    assert_same_columns(a, b, (1, 2))    # overlap, force
    force_scale = np.abs(b[:, 2]).max()
    if Gamma == 0.0:    # Hertz: F = 4/3 E* sqrt(R*) delta^1.5 (force on sphere 2 along +x)
        E_star, R_star = ref.effective_modulus(70e9, 0.3), 0.5e-4
        delta = np.maximum(a[:, 1], 0.0)
        np.testing.assert_allclose(a[:, 2], 4 / 3 * E_star * math.sqrt(R_star) * delta ** 1.5,
                                   rtol=0, atol=1e-9 * force_scale)
        return
    R_star, E_star = 0.5e-4, ref.effective_modulus(70e9, 0.3)
    Pc = ref.pull_off_force(Gamma, R_star)
    delta_f = ref.break_overlap(R_star, E_star, Gamma)
    # fx[2]: the force on sphere 2 along +x, negative when the spheres attract
    attached = np.nonzero(a[:, 2])[0]
    # snap-in at delta = 0 with -8/9 Pc
    assert a[attached[0], 1] == pytest.approx(0.0, abs=1e-15)
    assert a[attached[0], 2] / Pc == pytest.approx(-8 / 9, rel=1e-9)
    # the minimum force under displacement control is -Pc (rows 10 steps = 1e-10 m apart)
    assert a[:, 2].min() / Pc == pytest.approx(-1.0, abs=1e-6)
    # break at delta_f: the last attached row lies within one row (1e-10 m) above delta_f, with
    # the JKR force there close to -5/9 Pc; afterwards no force
    last = attached[-1]
    assert delta_f < a[last, 1] <= delta_f + 1.0001e-10
    assert a[last + 1, 1] <= delta_f + 1e-15
    assert a[last, 2] / Pc == pytest.approx(ref.normal_force(a[last, 1], R_star, E_star, Gamma) / Pc,
                                            abs=1e-6)
    assert a[last, 2] / Pc == pytest.approx(-5 / 9, abs=0.02)
    assert np.all(a[last + 1:, 2] == 0.0)


# ---- oblique impact of unlike spheres: tangential force history ----

LAMMPS_OBLIQUE = """
units si
atom_style sphere
atom_modify map array
boundary f f f
comm_modify vel yes
region box block -1e-3 1e-3 -1e-3 1e-3 -1e-3 1e-3
create_box 2 box
create_atoms 1 single 0 0 0
create_atoms 2 single 1.8005e-4 0 0
set atom 1 diameter 2.0e-4 density 2650
set atom 2 diameter 1.6e-4 density 7800
group one id 1
group two id 2
velocity two set -0.5 0.3 0.1
python tylmp_load input 1 SELF format p here "from tylmp import load as tylmp_load"
python tylmp_load invoke
pair_style thornton/yin
pair_coeff 1 1 70e9 0.3 0.3 {G11!r}
pair_coeff 2 2 200e9 0.29 0.4 {G22!r}
neighbor 2e-6 bin
neigh_modify delay 0
timestep 1e-9
fix integrate all nve/sphere
variable t equal time
variable fx equal fx[2]
variable fy equal fy[2]
variable fz equal fz[2]
fix csv all print 1 "${{t}},${{fx}},${{fy}},${{fz}}" file oblique_impact.csv screen no title "time,fx,fy,fz"
run 1000
"""


@pytest.mark.parametrize("Gamma", [0.3, 0.0])
def test_oblique_impact_of_unlike_spheres_equals_lammps_pair(tmp_path, Gamma):
    # LAMMPS mixes the 1-2 pair from the like pairs: E*, G* from both materials, mu and Gamma
    # as geometric means, which the LIGGGHTS deck gives explicitly
    a, b = run_both(tmp_path, LAMMPS_OBLIQUE.format(G11=Gamma, G22=0.5 * Gamma),
                    "oblique_impact.csv", deck=os.path.join(DECKS, "oblique_impact.in"),
                    variables={"Gamma": Gamma})
    attached = np.nonzero(b[:, 2])[0]
    assert len(attached) > 100                        # a contact of hundreds of steps
    tangential = np.hypot(b[:, 2], b[:, 3])
    assert tangential.max() > 0.05 * np.abs(b[:, 1]).max()    # the tangential law acted
    assert_same_columns(a, b, (1, 2, 3))              # the force on sphere 2


# ---- touch, slide, separate, touch again: a separated contact is forgotten ----

def retouch_deck(liggghts, Gamma):
    """Sphere 2 driven along x by a cosine (overlap 20 nm, then 40 nm apart, twice) while
    sliding along y: the second contact must start without the first one's history."""
    if liggghts:
        head = "newton off\ncommunicate single vel yes\n"
        pair = ("fix m1 all property/global youngsModulus peratomtype 70e9\n"
                "fix m2 all property/global poissonsRatio peratomtype 0.3\n"
                "fix m3 all property/global coefficientFriction peratomtypepair 1 0.3\n"
                f"fix m4 all property/global interfaceEnergy peratomtypepair 1 {Gamma!r}\n"
                "pair_style gran model thornton_yin tangential thornton_yin\npair_coeff * *\n")
    else:
        head = "comm_modify vel yes\n"
        pair = ('python tylmp_load input 1 SELF format p here "from tylmp import load as '
                'tylmp_load"\npython tylmp_load invoke\n'
                f"pair_style thornton/yin\npair_coeff * * 70e9 0.3 0.3 {Gamma!r}\n")
    return f"""units si
atom_style sphere
atom_modify map array
boundary f f f
{head}region box block -1e-3 1e-3 -1e-3 1e-3 -1e-3 1e-3
create_box 1 box
create_atoms 1 single 0 0 0
create_atoms 1 single 2.0001e-4 0 0
set atom * diameter 2.0e-4 density 2650
group one id 1
group two id 2
{pair}neighbor 2e-7 bin
neigh_modify delay 0
timestep 1e-9
variable w equal 2*PI/20e-6
variable px equal "-3e-8*(1-cos(v_w*time))"
variable vx equal "-3e-8*v_w*sin(v_w*time)"
variable py equal "2e-3*time"
variable vy equal "2e-3"
fix hold one move linear 0 0 0
fix drive two move variable v_px v_py NULL v_vx v_vy NULL
variable t equal time
variable fx equal fx[2]
variable fy equal fy[2]
fix csv all print 20 "${{t}},${{fx}},${{fy}}" file retouch.csv screen no title "time,fx,fy"
run 40000
"""


@pytest.mark.parametrize("Gamma", [0.0, 0.3])
def test_second_touch_starts_afresh_as_in_lammps(tmp_path, Gamma):
    a, b = run_both(tmp_path, retouch_deck(False, Gamma), "retouch.csv",
                    text=retouch_deck(True, Gamma))
    touching = b[:, 1] != 0.0
    assert 2 <= np.count_nonzero(np.diff(touching.astype(int)) == 1)    # two separate contacts
    assert np.abs(b[:, 2]).max() > 0                                   # with friction
    assert_same_columns(a, b, (1, 2))


# ---- 512 spheres: neighbour rebuilds, 1 vs 2 ranks, restart ----

def lattice_deck(steps, restart_in=None, restart_out=None):
    """A periodic simple-cubic lattice of touching adhesive spheres (8^3, 0.1 % overlap) sheared
    in three directions at once (velocity ramps; LIGGGHTS's velocity has no `create`): contacts
    slide, peel, break and form; the small skin rebuilds the neighbour lists every few steps."""
    head = f"read_restart {restart_in}\nnewton off\n" if restart_in else """
units si
atom_style sphere
atom_modify map array
boundary p p p
newton off
lattice sc 1.998e-4
region box block 0 8 0 8 0 8 units lattice
create_box 1 box
create_atoms 1 box
set atom * diameter 2.0e-4 density 2650
velocity all ramp vx -0.5 0.5 y 0 0.0015984 units box
velocity all ramp vy -0.4 0.4 z 0 0.0015984 sum yes units box
velocity all ramp vz -0.3 0.3 x 0 0.0015984 sum yes units box
"""
    tail = f"write_restart {restart_out}\n" if restart_out else ""
    return head + f"""communicate single vel yes
fix m1 all property/global youngsModulus peratomtype 70e9
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientFriction peratomtypepair 1 0.3
fix m4 all property/global interfaceEnergy peratomtypepair 1 0.3
pair_style gran model thornton_yin tangential thornton_yin
pair_coeff * *
neighbor 5e-8 bin
neigh_modify delay 0
timestep 1e-9
fix integrate all nve/sphere
thermo 100
run {steps}
dump forces all custom 1 forces.txt id x y z fx fy fz omegax omegay omegaz
dump_modify forces sort id
run 0
{tail}"""


def final_state(workdir):
    with open(workdir / "forces.txt") as fh:
        lines = fh.read().splitlines()
    start = lines.index(next(l for l in lines if l.startswith("ITEM: ATOMS"))) + 1
    return np.array([[float(v) for v in l.split()] for l in lines[start:]])


@pytest.mark.no_lammps          # LIGGGHTS only
def test_lattice_one_and_two_ranks_and_restart_agree(tmp_path):
    runs = {}
    for name, ranks in [("serial", 1), ("mpi", 2)]:
        d = tmp_path / name
        d.mkdir()
        out = liggghts_ok(None, d, np_ranks=ranks, text=lattice_deck(600))
        builds = [l for l in out.splitlines() if l.startswith("Neighbor list builds")]
        assert builds and int(builds[0].split("=")[1]) >= 10, out[-2000:]
        runs[name] = final_state(d)
    d = tmp_path / "restart"
    d.mkdir()
    liggghts_ok(None, d, text=lattice_deck(300, restart_out="half.restart"))
    liggghts_ok(None, d, text=lattice_deck(300, restart_in="half.restart"))
    runs["restart"] = final_state(d)
    ref_state = runs["serial"]
    assert ref_state.shape == (512, 10)
    force_scale = np.abs(ref_state[:, 4:7]).max()
    assert force_scale > 0
    for name in ("mpi", "restart"):
        s = runs[name]
        assert np.array_equal(s[:, 0], ref_state[:, 0])
        assert np.abs(s[:, 4:7] - ref_state[:, 4:7]).max() <= 1e-9 * force_scale, name
        assert np.abs(s[:, 1:4] - ref_state[:, 1:4]).max() <= 1e-9 * 2e-4, name
        spin_scale = np.abs(ref_state[:, 7:10]).max()
        assert np.abs(s[:, 7:10] - ref_state[:, 7:10]).max() <= 1e-9 * spin_scale, name


# ---- bad input: named errors ----

TWO_SPHERES_HEAD = """units si
atom_style sphere
boundary f f f
newton off
communicate single vel yes
region box block -1e-3 1e-3 -1e-3 1e-3 -1e-3 1e-3
create_box 1 box
create_atoms 1 single 0 0 0
create_atoms 1 single 1.999e-4 0 0
set atom * diameter 2.0e-4 density 2650
timestep 1e-9
fix integrate all nve/sphere
"""
GOOD = {"youngsModulus": "peratomtype 70e9", "poissonsRatio": "peratomtype 0.3",
        "coefficientFriction": "peratomtypepair 1 0.3", "interfaceEnergy": "peratomtypepair 1 0.3"}


@pytest.mark.no_lammps          # LIGGGHTS only
@pytest.mark.parametrize("change, pair, message", [
    ({"interfaceEnergy": None}, "thornton_yin tangential thornton_yin",
     "needs 'fix ID all property/global interfaceEnergy peratomtypepair"),
    ({"youngsModulus": None}, "thornton_yin tangential thornton_yin",
     "needs 'fix ID all property/global youngsModulus peratomtype"),
    ({"youngsModulus": "peratomtype 1e400"}, "thornton_yin tangential thornton_yin",
     "youngsModulus of type 1 must be finite and > 0"),
    ({"youngsModulus": "peratomtype -1e9"}, "thornton_yin tangential thornton_yin",
     "youngsModulus of type 1 must be finite and > 0"),
    ({"poissonsRatio": "peratomtype 0.5"}, "thornton_yin tangential thornton_yin",
     "poissonsRatio of type 1 must be finite and in (-1, 0.5)"),
    ({"coefficientFriction": "peratomtypepair 1 -0.1"}, "thornton_yin tangential thornton_yin",
     "coefficientFriction of type 1 1 must be finite and >= 0"),
    ({"interfaceEnergy": "peratomtypepair 1 -1e400"}, "thornton_yin tangential thornton_yin",
     "interfaceEnergy of type 1 1 must be finite and >= 0"),
    ({"interfaceEnergy": "peratomtypepair 1 1e9"}, "thornton_yin tangential thornton_yin",
     "interfaceEnergy must be below E* R*/(9 pi)"),
    ({}, "thornton_yin tangential history", "thornton_yin is one law"),
    ({}, "hertz tangential thornton_yin", "thornton_yin is one law"),
    ({}, "thornton_yin tangential thornton_yin cohesion sjkr", "thornton_yin is one law"),
])
def test_bad_input_stops_with_a_named_error(tmp_path, change, pair, message):
    props = dict(GOOD, **change)
    fixes = "".join(f"fix p{k} all property/global {name} {value}\n"
                    for k, (name, value) in enumerate(props.items()) if value is not None)
    text = TWO_SPHERES_HEAD + fixes + f"pair_style gran model {pair}\npair_coeff * *\nrun 10\n"
    rc, out = run_liggghts(None, tmp_path, text=text)
    assert "ERROR" in out and message in out, out[-2000:]


@pytest.mark.no_lammps          # LIGGGHTS only
def test_multicontact_radii_stop_with_liggghts_error(tmp_path):
    # the one feature of LIGGGHTS's loop with no test of its own below: fix multicontact/halfspace
    # needs the multicontact surface model, which thornton_yin does not pair with
    text = (TWO_SPHERES_HEAD + "".join(f"fix p{k} all property/global {name} {value}\n"
                                       for k, (name, value) in enumerate(GOOD.items()))
            + "pair_style gran model thornton_yin tangential thornton_yin\npair_coeff * *\n"
            "fix mc all multicontact/halfspace\nrun 10\n")
    rc, out = run_liggghts(None, tmp_path, text=text)
    assert "ERROR" in out and "Surface model is not multicontact" in out, out[-2000:]


@pytest.mark.no_lammps          # LIGGGHTS only
def test_axisymmetric_deck_holds_the_lateral_stress_and_reads_as_a_cell_record(tmp_path):
    # inputs/liggghts/axisym.in on the committed 3620-sphere dense specimen to 0.2 % axial
    # strain: LIGGGHTS's fix deform shortens x at the true rate 5e-5 1/s while its lateral edges
    # follow the deck's stress servo; tyanalysis reads the record as a fix cell/servo one
    from tylmp.analysis import liggghts
    from tylmp.analysis.io import read_sphere_data
    specimen = os.path.join(REPO, "bench", "data", "dense_paper_100kPa.data")
    liggghts_ok(os.path.join(DECKS, "axisym.in"), tmp_path,
                variables={"strain": 0.002, "data": specimen})
    rec = liggghts.servo_record(str(tmp_path / "axisym_liggghts_raw.csv"))
    # the axial natural strain grows at the prescribed rate
    assert rec["eps1"] == pytest.approx(5e-5 * rec["time"], rel=1e-9)
    assert rec["eps1"][-1] >= 0.002 - 5e-5 * 100 * 0.0144
    # the lateral stresses are held at 100 kPa (within 2 % once the servo has caught up) and
    # equal to each other, while the axial stress rises
    late = slice(len(rec) // 2, None)
    for k in ("sig2", "sig3"):
        assert np.all(np.abs(rec[k][late] / 1e5 - 1.0) < 0.02), k
    assert np.all(np.abs(rec["sig2"] - rec["sig3"]) < 2e3)
    assert rec["sig1"][-1] - rec["sig3"][-1] > 5e4
    # the record's state against the data file: the deck's solid volume is the sum of the
    # sphere volumes, so the void ratio is the cell's volume over it
    lo, hi, _, diameters, _ = read_sphere_data(specimen)
    solid = float(np.sum(np.pi / 6.0 * diameters ** 3))
    strain = np.exp(-(rec["eps1"] + rec["eps2"] + rec["eps3"]))
    assert rec["void_ratio"] == pytest.approx(float(np.prod(hi - lo)) * strain / solid - 1.0,
                                              rel=1e-9)
    # the same packing as LAMMPS reads it (Z = 5.336 at step 0, tests/test_cell_servo_any_pair.py)
    assert rec["Z"][0] == pytest.approx(5.336, rel=0.01)
    assert np.all(np.isnan(rec["sliding_fraction"]))
    # the command line writes the same record, which reads as a fix cell/servo one
    from tylmp.analysis import cli
    from tylmp.analysis.io import read_servo_csv
    out = str(tmp_path / "axisym_liggghts.csv")
    assert cli.main(["liggghts-record", str(tmp_path / "axisym_liggghts_raw.csv"),
                     "--out", out]) in (0, None)
    written = read_servo_csv(out)
    for name in ("eps1", "sig2", "void_ratio", "Z"):
        assert np.array_equal(written[name], rec[name]), name


# ---- the model's own pair loop: the same bits as LIGGGHTS's loop, one contact at a time ----

# what makes LIGGGHTS's own pair loop run the model (liggghts_loop_feature in
# plugin/liggghts/normal_model_thornton_yin.h), and the words of the log line that names it
LIGGGHTS_LOOP_FEATURES = {
    # its pair/gran/local output reads each contact's force inside LIGGGHTS's loop
    "compute pair/gran/local": "compute local all pair/gran/local id force\n",
    # LIGGGHTS's loop adds each contact's normal force to this per-atom property
    "the sum of normal forces (fix property/atom sum_normal_force_)":
        "fix snf all property/atom sum_normal_force_ scalar no no no 0.\n",
    # LIGGGHTS's loop stores each contact's force for this fix's coarse-grained stress
    "contact forces stored for a stress (fix continuum/weighted)":
        "fix cw all continuum/weighted kernel_radius 1e-4 compute stress\n",
}
OWN_LOOP_NOTE = "pair gran model thornton_yin: LIGGGHTS's pair loop evaluates the contacts, for "


def specimen_deck(damping, extra="", steps=300):
    """The committed dense specimen (3620 spheres at 100 kPa), Gamma = 0.6 J/m^2, plain NVE for
    `steps` steps with positions, velocities, forces, torques and spins dumped to 17 digits every
    100 steps, and every 50 steps to 17 digits the kinetic and rotational energies, the virial
    stress tensor (from the pair's global virial), the number of contacts and the sum of the
    per-atom virials (compute stress/atom: the pair's per-atom tallies). extra: lines before the run (a feature that makes
    LIGGGHTS's loop run the model, LIGGGHTS_LOOP_FEATURES)."""
    data = os.path.join(REPO, "bench", "data", "dense_paper_100kPa.data")
    damped = ("fix m6 all property/global dampingRatioNormal peratomtypepair 1 0.2\n"
              "fix m7 all property/global dampingRatioTangential peratomtypepair 1 0.1\n"
              if damping else "")
    fmt = " ".join(["%d"] + ["%.17g"] * 15)
    return f"""atom_style granular
hard_particles yes
units si
boundary p p p
newton off
communicate single vel yes
read_data {data}
fix m1 all property/global youngsModulus peratomtype 70e9
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 1.0
fix m4 all property/global coefficientFriction peratomtypepair 1 0.3
fix m5 all property/global interfaceEnergy peratomtypepair 1 0.6
{damped}pair_style gran model thornton_yin tangential thornton_yin
pair_coeff * *
neighbor 1.35e-5 bin
neigh_modify every 1 delay 0 check yes
timestep 1.4e-8
fix integrate all nve/sphere
{extra}compute rke all erotate/sphere
compute cn all contact/atom
compute contacts all reduce sum c_cn
compute p all pressure thermo_temp virial
compute s all stress/atom
compute stress_sum all reduce sum c_s[1] c_s[2] c_s[3] c_s[4] c_s[5] c_s[6]
dump d all custom 100 state.dump id x y z vx vy vz fx fy fz tqx tqy tqz omegax omegay omegaz
dump_modify d format "{fmt}" sort id
thermo_style custom step ke c_rke c_p[1] c_p[2] c_p[3] c_p[4] c_p[5] c_p[6] c_contacts &
    c_stress_sum[1] c_stress_sum[2] c_stress_sum[3] c_stress_sum[4] c_stress_sum[5] &
    c_stress_sum[6]
thermo_modify norm no format float %.17g
thermo 50
run {steps}
"""


def thermo_rows(out):
    """The thermo rows of a LIGGGHTS run's output (step first)."""
    lines = out.splitlines()
    start = next(k for k, l in enumerate(lines) if l.split()[:2] == ["Step", "KinEng"]) + 1
    rows = []
    for line in lines[start:]:
        if not line.split() or not line.split()[0].isdigit():
            break
        rows.append([float(v) for v in line.split()])
    return np.array(rows)


@pytest.mark.no_lammps          # LIGGGHTS only
@pytest.mark.parametrize("feature", sorted(LIGGGHTS_LOOP_FEATURES))
@pytest.mark.parametrize("damping", [False, True])
def test_own_pair_loop_gives_the_bits_of_liggghts_loop(tmp_path, damping, feature):
    # the model's own pair loop gathers the contacts into batches and runs the law in SIMD lanes;
    # where the run needs LIGGGHTS's loop (here: `feature`), that loop hands the model one
    # contact at a time and the law runs in the scalar build. Both must give the same trajectory,
    # energies, virial stress and contacts to the bit (one atom type: one batch, the forces
    # summed in the loop's order), and the log says which loop ran
    dumps, thermo = {}, {}
    for liggghts_loop in (False, True):
        d = tmp_path / ("liggghts_loop" if liggghts_loop else "own_loop")
        d.mkdir()
        extra = LIGGGHTS_LOOP_FEATURES[feature] if liggghts_loop else ""
        out = liggghts_ok(None, d, text=specimen_deck(damping, extra))
        notes = [l for l in out.splitlines() if l.startswith(OWN_LOOP_NOTE)]
        assert notes == ([OWN_LOOP_NOTE + feature + " (the model's own loop is faster)"]
                         if liggghts_loop else []), out[-2000:]
        with open(d / "state.dump") as fh:
            dumps[liggghts_loop] = fh.read()
        thermo[liggghts_loop] = thermo_rows(out)
    assert dumps[False] == dumps[True]
    assert np.array_equal(thermo[False], thermo[True])
    rows = [l.split() for l in dumps[False].splitlines()
            if l[:1].isdigit() and len(l.split()) == 16]
    assert len(rows) == 4 * 3620
    torques = np.array([[float(v) for v in r[10:13]] for r in rows[-3620:]])
    assert np.count_nonzero(np.abs(torques).sum(axis=1)) > 1000    # tangential forces act
    # the tallies are there: 7 rows; a compressive stress near the specimen's 100 kPa; about 5.3
    # contacts per sphere (its coordination number, as LAMMPS reads it:
    # test_axisymmetric_deck_...); the per-atom virials sum to -V times the global virial stress
    # (LIGGGHTS's stress/atom is stress times volume, with the kinetic part, here 2e-6 of it)
    t = thermo[False]
    assert len(t) == 7
    assert np.all(np.abs(t[:, 3:6] / 1e5 - 1.0) < 0.1)
    assert np.all(np.abs(t[:, 9] / 3620 - 5.336) < 0.05 * 5.336)
    with open(os.path.join(REPO, "bench", "data", "dense_paper_100kPa.data")) as fh:
        box = [[float(v) for v in l.split()[:2]] for l in fh.read(4096).splitlines()
               if l.endswith(("xlo xhi", "ylo yhi", "zlo zhi"))]
    volume = np.prod([hi - lo for lo, hi in box])
    np.testing.assert_allclose(-t[:, 10:16] / volume, t[:, 3:9], rtol=0, atol=1e-4 * 1e5)


def two_type_lattice_deck(extra):
    """lattice_deck with two materials (half the spheres, at random, of type 2: stiffer, more
    friction, less adhesion; the unlike pairs in between) for 300 steps, the final state dumped
    to 17 digits; extra: lines before the runs."""
    deck = lattice_deck(300).replace("create_box 1 box", "create_box 2 box").replace(
        "set atom * diameter 2.0e-4 density 2650\n",
        "set atom * diameter 2.0e-4 density 2650\nset group all type/fraction 2 0.5 4321\n")
    materials = """fix m1 all property/global youngsModulus peratomtype 70e9
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientFriction peratomtypepair 1 0.3
fix m4 all property/global interfaceEnergy peratomtypepair 1 0.3
"""
    assert materials in deck
    deck = deck.replace(materials, """fix m1 all property/global youngsModulus peratomtype 70e9 200e9
fix m2 all property/global poissonsRatio peratomtype 0.3 0.29
fix m3 all property/global coefficientFriction peratomtypepair 2 0.3 0.346 0.346 0.4
fix m4 all property/global interfaceEnergy peratomtypepair 2 0.3 0.212 0.212 0.15
""")
    fmt = " ".join(["%d"] + ["%.17g"] * 9)
    deck = deck.replace("fix integrate all nve/sphere\n", "fix integrate all nve/sphere\n" + extra)
    return deck.replace("dump_modify forces sort id\n",
                        f'dump_modify forces sort id format "{fmt}"\n')


@pytest.mark.no_lammps          # LIGGGHTS only
def test_own_pair_loop_with_two_types_agrees_with_liggghts_loop_to_round_off(tmp_path):
    # with several atom types the model's loop sums each sphere's contact forces in another order
    # than LIGGGHTS's loop (its batches of the type pairs interleave): the same trajectory to
    # round-off. Bound: 1e-12 of each quantity's scale over 300 steps of this sheared lattice, a
    # thousand times the 1e-15 of one reordered sum (observed: 6e-15 for forces and spins), as
    # the two engines' virial stresses on the dense specimen, summed in different orders, agree
    # to 2e-12 of |p| over 2000 steps (bench/results/liggghts_loop_assembly.json)
    states = {}
    for liggghts_loop in (False, True):
        d = tmp_path / ("liggghts_loop" if liggghts_loop else "own_loop")
        d.mkdir()
        extra = LIGGGHTS_LOOP_FEATURES["compute pair/gran/local"] if liggghts_loop else ""
        out = liggghts_ok(None, d, text=two_type_lattice_deck(extra))
        assert any(l.startswith(OWN_LOOP_NOTE) for l in out.splitlines()) == liggghts_loop
        states[liggghts_loop] = final_state(d)
    a, b = states[False], states[True]
    assert a.shape == (512, 10) and np.array_equal(a[:, 0], b[:, 0])
    for cols in (slice(1, 4), slice(4, 7), slice(7, 10)):    # positions, forces, spins
        scale = np.abs(b[:, cols]).max() if cols.start > 1 else 2e-4
        assert scale > 0
        assert np.abs(a[:, cols] - b[:, cols]).max() <= 1e-12 * scale, cols
