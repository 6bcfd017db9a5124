"""LAMMPS versions (issue 12): both ways of loading the styles, the loader's refusal of a build
for another LAMMPS, and the same numbers from 29 Sep 2021 and 4 Feb 2025.

The suite runs once per LAMMPS (scripts/test.sh): `lmp` on PATH is the one under test. The
cross-version tests need both LAMMPS on this machine, each with a build of tylmp for it:
Debian's /usr/bin/lmp (29 Sep 2021) and the wrapper of scripts/lammps2025.sh (4 Feb 2025,
$TYLMP_LAMMPS2025_WRAPPER or found in its cache). They run once, in the 4 Feb 2025 half of
scripts/test.sh (marked both_lammps: tests/lammps_halves.py), and skip with the reason where
either LAMMPS is missing.
"""
import glob
import os
import re
import subprocess
import time

import numpy as np
import pytest

import jkr_reference as ref
from cellspec import DT, E, LATTICE_SPECIMEN, NU, read_csv
from conftest import BUILD, REPO
from lmprun import LOAD_TYLMP, read_table, run_deck, two_spheres_box

V2021, V2025 = 20210929, 20250204


def version_number(text):
    """'4 Feb 2025' -> 20250204 (LAMMPS's num_ver)."""
    t = time.strptime(text, "%d %b %Y")
    return t.tm_year * 10000 + t.tm_mon * 100 + t.tm_mday


def lmp_info(cmd="lmp", env=None):
    """(version YYYYMMDD, installed packages) of an lmp, from its -h text."""
    out = subprocess.run([cmd, "-h"], capture_output=True, text=True, env=env, timeout=60).stdout
    found = re.search(r"Simulator - (\d{1,2} \w{3} \d{4})", out)
    assert found, out[:500]
    packages = out.split("Installed packages:")[1].split("List of")[0].split()
    return version_number(found.group(1)), set(packages)


LMP_VERSION, LMP_PACKAGES = lmp_info()


def library_for(version, build=BUILD):
    """The tylmp build for LAMMPS `version` in a build tree (or None)."""
    path = os.path.join(build, "python", "tylmp", f"tylmp-{version}.so")
    return path if os.path.exists(path) else None


# ---- the styles load both ways: two spheres at rest in a JKR contact ------------------------

R, GAMMA, RHO = 1.0e-4, 0.6, 2650.0
R_STAR, E_STAR = R / 2, ref.effective_modulus(E, NU)


def two_spheres(load_lines, x2):
    """Two spheres of radius R, one at the origin, one at (x2, 0, 0), under thornton/yin."""
    return load_lines + two_spheres_box(x2, 2 * R, RHO) + f"""pair_style thornton/yin
pair_coeff * * {E} {NU} 0.3 {GAMMA}
neighbor 2e-6 bin
"""


def static_contact_deck(load_lines, overlap):
    return two_spheres(load_lines, 2 * R - overlap) + """run 0
print "FX2 $(fx[2]:%.17g)"
"""


def jkr_force(overlap):
    """Independent JKR load at an overlap (tests/jkr_reference.py: bisection on delta(a))."""
    a = ref.contact_radius(overlap, R_STAR, E_STAR, GAMMA)
    return ref.force_of_radius(a, R_STAR, E_STAR, GAMMA)


def loader_lines(way):
    if way == "python":
        return LOAD_TYLMP
    if "PLUGIN" not in LMP_PACKAGES:
        pytest.skip(f"this lmp (LAMMPS {LMP_VERSION}) has no PLUGIN package: 'plugin load' "
                    "needs a LAMMPS built with it (scripts/lammps2025.sh builds one)")
    import tylmp
    path = library_for(LMP_VERSION) or tylmp.library_path(LMP_VERSION)
    return f"plugin load {path}\n"


@pytest.mark.parametrize("way", ["python", "plugin"])
def test_styles_load_and_give_the_jkr_force(tmp_path, way):
    overlap = 0.02 * (9 * np.pi * GAMMA * R_STAR**2 / E_STAR) ** (2 / 3) / R_STAR
    rc, out = run_deck(static_contact_deck(loader_lines(way), overlap), tmp_path)
    assert rc == 0 and "ERROR" not in out, out[-3000:]
    if way == "plugin":
        assert "Loading plugin: tylmp pair thornton/yin" in out
        assert "compiled for LAMMPS version" not in out       # built for this very version
    force = float(re.search(r"^FX2 (\S+)$", out, re.M).group(1))
    expected = jkr_force(overlap)
    assert expected < 0                                      # tensile: adhesion at this overlap
    assert force == pytest.approx(expected, rel=1e-9)


def with_version_tag(src, dst, version):
    """A copy of a tylmp library whose version tag names another LAMMPS."""
    data = open(src, "rb").read()
    tag = re.search(rb"tylmp-lammps-version=\d{8}", data)
    assert tag, "no version tag in " + src
    new = b"tylmp-lammps-version=%08d" % version
    with open(dst, "wb") as fh:
        fh.write(data[:tag.start()] + new + data[tag.end():])


def test_loader_refuses_a_build_for_another_lammps(tmp_path):
    import tylmp
    src = library_for(LMP_VERSION) or tylmp.library_path(LMP_VERSION)
    other = V2025 if LMP_VERSION != V2025 else V2021
    fake = tmp_path / f"tylmp-{other}.so"
    with_version_tag(src, fake, other)
    deck = static_contact_deck(LOAD_TYLMP, 1e-9)
    env_before = os.environ.get("TYLMP_LIBRARY")
    os.environ["TYLMP_LIBRARY"] = str(fake)
    try:
        rc, out = run_deck(deck, tmp_path)
    finally:
        if env_before is None:
            del os.environ["TYLMP_LIBRARY"]
        else:
            os.environ["TYLMP_LIBRARY"] = env_before
    assert rc != 0
    names = {V2021: "29 Sep 2021", V2025: "4 Feb 2025"}
    assert f"was built for LAMMPS {names[other]} ({other})" in out, out[-2000:]
    assert "the running LAMMPS is" in out and f"({LMP_VERSION})" in out


def test_loader_takes_the_build_for_the_version_from_any_tylmp_directory(tmp_path, monkeypatch):
    """Builds for two LAMMPS versions in two tylmp package directories on one sys.path: each
    version gets its own; the version tag is read from the file, not from its name."""
    import sys

    import tylmp
    versions = (20990101, 20990202)                   # versions no real build has
    for v in versions:
        d = tmp_path / str(v) / "tylmp"
        d.mkdir(parents=True)
        (d / f"tylmp-{v}.so").write_bytes(b"\0ELF...tylmp-lammps-version=%d\0" % v)
    monkeypatch.delenv("TYLMP_LIBRARY", raising=False)
    monkeypatch.setattr(sys, "path", [str(tmp_path / str(v)) for v in versions] + sys.path)
    for v in versions:
        path = tylmp.library_path(v)
        assert path == str(tmp_path / str(v) / "tylmp" / f"tylmp-{v}.so")
        assert tylmp.built_for(path) == v


# ---- the same numbers from both versions -------------------------------------------------------

def lammps2025_wrapper():
    path = os.environ.get("TYLMP_LAMMPS2025_WRAPPER")
    if path:
        return path if os.path.exists(path) else None
    cache = os.environ.get("TYLMP_CACHE") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "tylmp")
    found = sorted(glob.glob(os.path.join(cache, f"lammps-{V2025}-*/tylmp/bin/lmp")),
                   key=os.path.getmtime)
    return found[-1] if found else None


def both_lammps():
    """{version: (lmp command, PYTHONPATH)} for 29 Sep 2021 and 4 Feb 2025, or skip. Each side's
    PYTHONPATH has its own build of tylmp when the repository has one (else the installed one)."""
    if os.environ.get("TYLMP_TEST_HALF") == "2021":
        pytest.fail("a test that runs both LAMMPS versions must be marked both_lammps, so that it "
                    "runs once, in the 4 Feb 2025 half (tests/lammps_halves.py)")
    sides = {}
    build21 = BUILD if library_for(V2021) else os.path.join(REPO, "build")
    build25 = BUILD if library_for(V2025) else os.environ.get(
        "TYLMP_LAMMPS2025_BUILD_DIR", os.path.join(REPO, "build-lammps2025"))
    for version, cmd, build in ((V2021, "/usr/bin/lmp", build21),
                                (V2025, lammps2025_wrapper(), build25)):
        if not cmd or not os.path.exists(cmd):
            pytest.skip(f"no LAMMPS {version} on this machine (scripts/lammps2025.sh builds 4 Feb 2025)")
        path = [os.path.join(build, "python")] if library_for(version, build) else []
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(path))
        if lmp_info(cmd, env)[0] != version:
            pytest.skip(f"{cmd} is not LAMMPS {version}")
        sides[version] = (cmd, env["PYTHONPATH"])
    return sides


def run_with(cmd, pythonpath, deck, work):
    work.mkdir(exist_ok=True)
    (work / "in.deck").write_text(deck)
    # a clean environment: no PYTHONPATH entries of the LAMMPS under test (its lammps module)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "TYLMP_LIBRARY")}
    env["PYTHONPATH"] = pythonpath
    proc = subprocess.run([cmd, "-in", "in.deck", "-log", "none", "-nocite"], cwd=work, env=env,
                          capture_output=True, text=True, timeout=600)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0 and "ERROR" not in out, out[-3000:]
    return out


def cycle_deck():
    """Atom 2 approaches atom 1, is sheared sideways back and forth (peeling, Mindlin, sliding),
    and pulled off past the JKR break: every branch of the contact law."""
    speed, dt = 0.05, 2e-9
    return two_spheres(LOAD_TYLMP, 2 * R + 1e-8) + f"""group one id 1
group two id 2
neigh_modify every 1 delay 0 check yes
timestep {dt}
variable t equal step*dt
variable vx equal -{speed}*(v_t<2e-6)+{speed}*(v_t>=6e-6)
variable vy equal {speed}*(v_t>=2e-6)*(v_t<3e-6)-{speed}*(v_t>=3e-6)*(v_t<5e-6)+{speed}*(v_t>=5e-6)*(v_t<6e-6)
variable zero equal 0
fix hold one move linear 0 0 0
fix drive two move variable NULL NULL v_zero v_vx v_vy v_zero
compute diss all pair thornton/yin
fix out all print 25 "$(step) $(x[2]:%.17g) $(fx[2]:%.17g) $(fy[2]:%.17g) $(fz[2]:%.17g) $(c_diss[1]:%.17g) $(c_diss[2]:%.17g)" file out.txt screen no title "# step x fx fy fz friction break"
run 5000
"""


@pytest.mark.both_lammps
def test_two_spheres_agree_across_versions(tmp_path):
    sides = both_lammps()
    records = {}
    for version, (cmd, pythonpath) in sides.items():
        run_with(cmd, pythonpath, cycle_deck(), tmp_path / str(version))
        records[version] = read_table(tmp_path / str(version) / "out.txt")
    a, b = records[V2021], records[V2025]
    assert np.array_equal(a["step"], b["step"])
    assert np.max(a["break"]) > 0 and np.max(a["friction"]) > 0    # broke, and slid
    for name in ("x", "fx", "fy", "fz", "friction", "break"):
        scale = max(np.max(np.abs(a[name])), 1e-300)
        assert np.max(np.abs(a[name] - b[name])) <= 1e-12 * scale, name


def assembly_deck(steps):
    """The 216-sphere lattice of tests/cellspec.py compressed by fix cell/servo with friction
    and adhesion, Cundall damping on: contacts form, slide, peel and break in 3D."""
    return LATTICE_SPECIMEN + f"""pair_style thornton/yin
pair_coeff * * {E} {NU} 0.3 {GAMMA}
neighbor 2e-5 bin
timestep {DT}
fix nve all nve/sphere
fix cell all cell/servo iso 1e5 max_rate 2e-3 csv cell.csv 50
fix damp all damping/cundall 0.2 0.2
compute diss all pair thornton/yin
thermo_style custom step ke pe c_diss[1] c_diss[2]
thermo_modify format float %.17g
thermo 500
run {steps}
"""


ASSEMBLY_COMPARED = ["eps1", "eps2", "eps3", "sig1", "sig2", "sig3", "p", "volume", "Z"]


def last_thermo(out, step):
    """ke pe friction break of the thermo line of `step`."""
    line = re.search(rf"^\s*{step}\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$", out, re.M)
    assert line, out[-2000:]
    return np.array([float(v) for v in line.groups()])


# The runs of both versions were bitwise identical (records and 17-digit thermo) over these
# 30000 steps: same compiler for our library, same neighbor-list order in both LAMMPS. The
# tolerance allows round-off, should a LAMMPS change its summation order.
@pytest.mark.both_lammps
def test_assembly_agrees_across_versions(tmp_path):
    sides = both_lammps()
    steps = 30000
    records, thermo = {}, {}
    for version, (cmd, pythonpath) in sides.items():
        out = run_with(cmd, pythonpath, assembly_deck(steps), tmp_path / str(version))
        records[version] = read_csv(tmp_path / str(version) / "cell.csv")
        thermo[version] = last_thermo(out, steps)
    a, b = records[V2021], records[V2025]
    assert np.array_equal(a["step"], b["step"])
    assert a["Z"][-1] > 4.0 and thermo[V2021][3] > 0        # jammed; contacts broke on the way
    for name in ASSEMBLY_COMPARED:
        scale = max(np.max(np.abs(a[name])), 1e-300)
        assert np.max(np.abs(a[name] - b[name])) <= 1e-12 * scale, name
    assert thermo[V2025] == pytest.approx(thermo[V2021], rel=1e-12)


CONTINUE = LOAD_TYLMP + """read_restart {restart}
comm_modify vel yes
neighbor 2e-5 bin
fix nve all nve/sphere
fix cell all cell/servo iso 1e5 max_rate 2e-3 csv cell.csv 50
thermo_style custom step ke pe
thermo_modify format float %.17g
thermo 1000
run 1000
"""


@pytest.mark.both_lammps
def test_restart_files_across_versions(tmp_path):
    """29 Sep 2021 -> 4 Feb 2025: continues as 29 Sep 2021 itself does (contact histories
    included, plugin/lammps/fix_neigh_history_thornton_yin.cpp); 4 Feb 2025 -> 29 Sep 2021:
    LAMMPS refuses the newer format revision."""
    sides = both_lammps()
    for version, (cmd, pythonpath) in sides.items():
        run_with(cmd, pythonpath, assembly_deck(5000) + "write_restart a.restart\n",
                 tmp_path / f"write{version}")
    old = tmp_path / f"write{V2021}" / "a.restart"
    thermo, records = {}, {}
    for version, (cmd, pythonpath) in sides.items():
        work = tmp_path / f"read{version}"
        out = run_with(cmd, pythonpath, CONTINUE.format(restart=old), work)
        thermo[version] = (last_thermo3(out, 5000), last_thermo3(out, 6000))
        records[version] = read_csv(work / "cell.csv")
    # the stored elastic energy at the first step after reading holds the tangential springs
    # and the adhesive contacts: without the histories it was 2.4 % lower
    assert thermo[V2025][0] == pytest.approx(thermo[V2021][0], rel=1e-12)
    assert thermo[V2025][1] == pytest.approx(thermo[V2021][1], rel=1e-12)
    for name in ASSEMBLY_COMPARED:
        a, b = records[V2021][name], records[V2025][name]
        assert np.max(np.abs(a - b)) <= 1e-12 * max(np.max(np.abs(a)), 1e-300), name
    cmd, pythonpath = sides[V2021]
    new = tmp_path / f"write{V2025}" / "a.restart"
    work = tmp_path / "read_new_in_old"
    work.mkdir()
    (work / "in.deck").write_text(CONTINUE.format(restart=new))
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "TYLMP_LIBRARY")}
    proc = subprocess.run([cmd, "-in", "in.deck", "-log", "none"], cwd=work, capture_output=True,
                          text=True, env=dict(env, PYTHONPATH=pythonpath), timeout=600)
    assert proc.returncode != 0
    assert "Restart file format revision incompatible" in proc.stdout + proc.stderr


def last_thermo3(out, step):
    """ke pe of the thermo line of `step`."""
    line = re.search(rf"^\s*{step}\s+(\S+)\s+(\S+)\s*$", out, re.M)
    assert line, out[-2000:]
    return np.array([float(v) for v in line.groups()])
