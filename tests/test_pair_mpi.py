"""Parallel bookkeeping of pair thornton/yin: 1 and 2 MPI ranks give the same trajectory.

Requirement: a ~500-sphere shaken assembly run 2000 steps on 2 ranks matches 1 rank within
1e-9 relative, with adhesion and friction active, contacts forming, breaking and migrating
between ranks. What can and cannot be asserted (measured on this plugin, 2000 steps):

* Bookkeeping is exact. With a smooth contact law (mu = 0; Gamma = 0 or 0.6) a 512-sphere 3D
  assembly drifting through the rank boundaries (~190 atoms change owner, ~500 neighbor
  rebuilds, ~1200 contacts formed and broken, adhesive contacts snap on, go tensile and
  break) matches 1 rank to 3e-14 (Gamma = 0) and 2e-13 (Gamma = 0.6) at every dump, newton
  on and off: only the summation order of forces differs.
  -> test_smooth_law_bookkeeping_is_exact (1e-12)

* 3D friction is round-off chaotic, on ONE rank already. The Mindlin-Deresiewicz law is
  history dependent: its loading/unloading/reloading branch and the turning-point memory
  (T*, T**) are chosen from the sign of the current increment, so a one-ulp change of an
  increment can select another branch; the force is continuous across the switch, but the
  memory it leaves differs by O(mu dP) and the difference then grows. Measured with the
  earlier law (2000 steps, dense 3D assembly, mu = 0.3, Gamma = 0.6): worst relative
  difference (positions / diameter, v, omega, f) 2e-16 at step 0, 2.5e-9 at step 200, 5e-5
  at 400, 3e-2 at 2000 between 1 and 2 ranks -- the same between 1 rank and 1 rank with
  re-sorted atoms, or newton on vs off on 1 rank. No jump at reneighboring or migration
  steps. 1e-9 over 2000 steps is not attainable for a 3D frictional assembly under any change
  of summation order; it holds for the first ~100 steps.
  -> test_3d_friction_is_roundoff_chaotic asserts this quantitatively.

* Full physics in a planar assembly (500 spheres in one layer, motion in the plane: friction
  sliding and dissipating, adhesive tensile contacts, contacts forming and
  breaking, ~100 atoms changing owner, many crossing the periodic boundary): 2 ranks match
  1 rank to 5e-14 over 2000 steps (worst of x, v, omega, f over all dumps, newton on and
  off, measured 2026-11-25). The first design shook twice as fast and reached overlaps of the
  order of the sphere radius, which pair thornton/yin now stops as an invalid state; there,
  1 vs 2 ranks ranged from 6e-13 to 2e-8 depending on the version of the law, because deep,
  violent contacts hit many branch switches. -> test_full_physics_matches_one_rank (1e-9)

Atom IDs (hence diameters) must not depend on the rank count: create_atoms numbers atoms
rank by rank, so the domain is split along the slowest lattice loop index (processors).
"""
import glob
import re

import numpy as np
import pytest

from lmprun import LOAD_TYLMP, run_ok

STEPS = 2000
DUMP_EVERY = 100

COMMON_RUN = f"""
{LOAD_TYLMP}
pair_style thornton/yin
pair_coeff * * 70e9 0.3 ${{mu}} ${{gamma}}
neighbor 5e-6 bin
neigh_modify every 1 delay 0 check yes
timestep 2e-7
fix nve all nve/sphere
compute diss all pair thornton/yin
compute pl all pair/local p1 p5
compute pid all property/local patom1 patom2
thermo_style custom step pe ke c_diss[1] c_diss[2]
thermo {STEPS}
dump d all custom {DUMP_EVERY} atoms.* id x y z vx vy vz omegax omegay omegaz fx fy fz proc ix iy iz
dump_modify d sort id format float %.17g
dump c all local {DUMP_EVERY} contacts.* c_pid[1] c_pid[2] c_pl[1] c_pl[2]
run ${{steps}}
"""

# 512 spheres, simple cubic 8^3, diameters 0.18-0.22 mm at spacing 0.19 mm: strongly
# overlapping, the assembly explodes into a dense shaken packing; a drift along z carries
# atoms through both rank boundaries (the domain is split along z).
ASSEMBLY_3D = """
units si
atom_style sphere
atom_modify map array sort ${sortfreq} ${sortbin}
boundary p p p
processors 1 1 *
comm_modify vel yes
newton ${newton}
lattice sc 1.9e-4
region box block 0 8 0 8 0 8
create_box 1 box
create_atoms 1 box
# polydisperse diameters 0.18-0.22 mm, deterministic and independent of the rank count
variable d atom 1.8e-4+4e-5*(0.6180339887*id-floor(0.6180339887*id))
set atom * diameter v_d density 2650e6
displace_atoms all random 2e-5 2e-5 2e-5 4711 units box
velocity all set 0.3 0.5 ${drift} units box
""" + COMMON_RUN

# 500 spheres in one layer (20 x 25, spacing 0.24 mm, diameters 0.18-0.22 mm), shaken with
# random in-plane velocities ~0.25 m/s plus a drift along y (the split direction): a dense
# granular gas whose collisions last ~1000 steps, so contacts form, stick, slide, go tensile
# and break; z stays exactly 0, so every contact's tangential motion lies in the plane.
ASSEMBLY_PLANAR = """
units si
atom_style sphere
atom_modify map array sort ${sortfreq} ${sortbin}
boundary p p f
processors 1 * 1
comm_modify vel yes
newton ${newton}
lattice sc 2.4e-4
region box block 0 20 0 25 -4 4
create_box 1 box
region layer block INF INF INF INF -0.1 0.1
create_atoms 1 region layer
variable d atom 1.8e-4+4e-5*(0.6180339887*id-floor(0.6180339887*id))
set atom * diameter v_d density 2650e6
displace_atoms all random 2e-5 2e-5 0 4711 units box
velocity all create 1e20 8123 loop geom
velocity all set NULL NULL 0.0
velocity all set 0.5 $(v_drift/2) 0.0 sum yes units box
""" + COMMON_RUN

BOX = {"3d": np.array([8, 8, 8]) * 1.9e-4, "planar": np.array([20, 25, 8]) * 2.4e-4}
DIAMETER = 2e-4


class Run:
    """One LAMMPS run: per-atom dumps and per-contact dumps every DUMP_EVERY steps."""

    def __init__(self, tmp_path, geometry, ranks, **variables):
        deck = ASSEMBLY_3D if geometry == "3d" else ASSEMBLY_PLANAR
        values = dict(newton="on", mu=0.3, gamma=0.6, drift=3.0, sortfreq=1000, sortbin=0.0,
                      steps=STEPS)
        values.update(variables)
        tag = "_".join(f"{k}{v}" for k, v in sorted(variables.items()))
        self.work = tmp_path / f"{geometry}_np{ranks}_{tag}"
        self.work.mkdir()
        self.geometry = geometry
        self.out = run_ok(deck, self.work, np_ranks=ranks, variables=values)
        assert "Dangerous builds = 0" in self.out

    def atoms(self, step):
        return np.loadtxt(self.work / f"atoms.{step}", skiprows=9)

    def contacts(self, step):
        """touching pairs at `step`: (id1, id2, normal force, sliding); P = 0 means not touching"""
        c = np.loadtxt(self.work / f"contacts.{step}", skiprows=9, ndmin=2)
        return c[c[:, 2] != 0.0] if c.size else np.zeros((0, 4))

    def steps(self):
        return sorted(int(p.rsplit(".", 1)[1]) for p in glob.glob(str(self.work / "atoms.*")))

    def thermo_last(self):
        lines = self.out.splitlines()
        k = max(i for i, l in enumerate(lines) if l.split()[:1] == ["Step"])
        return dict(zip(lines[k].split(), map(float, lines[k + 1 + 1].split())))

    def neighbor_builds(self):
        return int(re.search(r"Neighbor list builds = (\d+)", self.out).group(1))


def deviation(a, b, box):
    """largest difference of two dumps: positions / sphere diameter (minimum image),
    velocities, angular velocities and forces each relative to their largest magnitude"""
    assert np.array_equal(a[:, 0], b[:, 0])
    dx = a[:, 1:4] - b[:, 1:4]
    dx -= box * np.round(dx / box)
    worst = np.max(np.abs(dx)) / DIAMETER
    for cols in (slice(4, 7), slice(7, 10), slice(10, 13)):
        scale = np.max(np.abs(a[:, cols]))
        if scale > 0.0:
            worst = max(worst, np.max(np.abs(a[:, cols] - b[:, cols])) / scale)
    return worst


def migrated(run):
    """atoms whose owning rank changed between the first and last dump"""
    return int(np.sum(run.atoms(0)[:, 13] != run.atoms(STEPS)[:, 13]))


def contact_census(run):
    """formed / broken contacts between consecutive dumps, tensile and sliding sightings"""
    formed = broken = tensile = sliding = 0
    previous = None
    for step in run.steps():
        c = run.contacts(step)
        pairs = {tuple(sorted(p)) for p in c[:, :2].astype(int)}
        tensile += int(np.sum(c[:, 2] < 0.0))
        sliding += int(np.sum(c[:, 3] > 0.0))
        if previous is not None:
            formed += len(pairs - previous)
            broken += len(previous - pairs)
        previous = pairs
    return dict(formed=formed, broken=broken, tensile=tensile, sliding=sliding)


@pytest.mark.parametrize("newton", ["on", "off"])
@pytest.mark.parametrize("gamma", [0.0, 0.6])
def test_smooth_law_bookkeeping_is_exact(tmp_path, newton, gamma):
    """mu = 0: 3D, 512 spheres, 2000 steps, atoms migrating; 1 and 2 ranks agree to 1e-12."""
    one = Run(tmp_path, "3d", 1, newton=newton, mu=0.0, gamma=gamma)
    two = Run(tmp_path, "3d", 2, newton=newton, mu=0.0, gamma=gamma)
    for step in one.steps():
        assert deviation(one.atoms(step), two.atoms(step), BOX["3d"]) <= 1e-12, step
    # the decomposition was really exercised
    assert migrated(two) > 100
    assert two.neighbor_builds() > 50
    census = contact_census(one)
    assert census["formed"] > 100 and census["broken"] > 100
    if gamma > 0.0:
        assert census["tensile"] > 0
        assert one.thermo_last()["c_diss[2]"] > 0.0    # adhesive contacts broke at delta_f


@pytest.mark.parametrize("newton", ["on", "off"])
def test_full_physics_matches_one_rank(tmp_path, newton):
    """mu = 0.3, Gamma = 0.6, 500 spheres, 2000 steps: 1 and 2 ranks agree to 1e-9."""
    one = Run(tmp_path, "planar", 1, newton=newton)
    two = Run(tmp_path, "planar", 2, newton=newton)
    for step in one.steps():
        worst = deviation(one.atoms(step), two.atoms(step), BOX["planar"])
        print(f"planar full physics, step {step}: 1 vs 2 ranks {worst:.3g}")
        assert worst <= 1e-9, step
    # atoms change owner and cross the periodic boundary
    assert migrated(two) >= 50
    assert np.count_nonzero(two.atoms(STEPS)[:, 14:17]) > 50
    # friction and adhesion really act: energy dissipated by micro-slip and sliding and at
    # adhesive separations, contacts seen sliding and tensile, contacts formed and broken
    last = one.thermo_last()
    assert last["c_diss[1]"] > 0.01 * last["KinEng"] and last["c_diss[2]"] > 0.0
    census = contact_census(one)
    assert census["sliding"] > 100 and census["tensile"] > 0
    assert census["formed"] > 100 and census["broken"] > 10


def test_3d_friction_is_roundoff_chaotic(tmp_path):
    """mu = 0.3, Gamma = 0.6 in 3D: round-off alone (another atom order on ONE rank) makes
    the trajectory diverge beyond 1e-9 before step 2000, and 2 ranks diverge no faster;
    1e-9 between 1 and 2 ranks holds for the first 100 steps."""
    one = Run(tmp_path, "3d", 1)
    resorted = Run(tmp_path, "3d", 1, sortfreq=1, sortbin=5e-5)    # other atom order
    two = Run(tmp_path, "3d", 2)
    box = BOX["3d"]
    early = DUMP_EVERY
    assert deviation(one.atoms(early), two.atoms(early), box) <= 1e-9
    assert deviation(one.atoms(early), resorted.atoms(early), box) <= 1e-9
    roundoff = deviation(one.atoms(STEPS), resorted.atoms(STEPS), box)
    parallel = deviation(one.atoms(STEPS), two.atoms(STEPS), box)
    assert roundoff > 1e-9            # the requirement is beyond what round-off allows in 3D
    assert parallel <= 100 * roundoff    # and the rank split adds nothing beyond round-off
    assert migrated(two) > 100
