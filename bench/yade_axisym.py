"""Axisymmetric compression at constant mean stress in YADE's periodic cell, started from the
same LAMMPS data file as the LAMMPS side (bench/yade_axisym.in): the independent-engine
cross-check of docs/validation.md ("Axisymmetric compression against YADE").

    nice yade -n -x bench/yade_axisym.py [--data bench/data/dense_paper_100kPa.data]
        [--law mindlin|deresiewitz] [--rate 5e-5] [--p 1e5] [--strain 0.10]
        [--csv OUT.csv] [--every 200] [--max-steps N] [--check OUT.json]

(Debian 12: `apt-get install yade`, YADE 2023.02a; -n: no GUI, -x: exit when the script ends.)

The scene: one sphere per atom of the data file (positions relative to the box's low corner,
diameters from the file), velocities and spins zero, periodic cell = the box; material
FrictMat(young = 70 GPa, poisson = 0.3, friction angle atan 0.3, density 2650e12 kg/m^3, the
density scaling of the decks); Ig2_Sphere_Sphere_ScGeom, Ip2_FrictMat_FrictMat_MindlinPhys
(no viscous damping: betan = betas = 0) and Law2_ScGeom_MindlinPhys_Mindlin (Hertz normal
force, incremental Mindlin tangential stiffness 8 G* a, Coulomb limit) or, with
--law deresiewitz, Law2_ScGeom_MindlinPhys_MindlinDeresiewitz (Mindlin-Deresiewicz partial
slip after Thornton 1991); NewtonIntegrator(damping = 0). Time step: 0.2 Rayleigh times of
the smallest sphere (d = 0.135 mm), the formula of inputs/common/numerics.in.

The test: the cell's axis x is compressed at the prescribed natural strain rate --rate
(O.cell.velGrad), the axes y and z are free and a proportional + integral servo in a PyRunner
(every step) holds sigma_y = sigma_z and p = --p, the control law of fix cell/servo written
here anew (docs/theory.md §6.2): with the affine stiffness C (recomputed every 1000 steps from
the interactions' normal and tangential stiffnesses and branch vectors), rows
A = [(0, 1, -1), (1, 1, 1)/3], targets t = (0, p), actuators W = [e_y, e_z],

    (A C W) u = g (t - A sigma) + g_I S - A C r_p dt,   S <- S + (t - A sigma) near target,

g = 0.25, g_I = 0.005 (fix cell/servo's defaults), the servo part capped at four times the
prescribed rate. The stress is YADE's Love-Weber contact stress utils.getStress() (contact
part only, as fix cell/servo), sign flipped to compression positive. The run ends when
eps1 - eps3 reaches --strain, or after --max-steps steps.

Output: --csv, a record in the column layout of fix cell/servo (docs/fix_cell_servo.md; the
columns it does not compute, e.g. sliding_fraction and the equilibrium flags, are left out;
Z = 2C/N from the real interactions, Zm from YADE's utils.avgNumInteractions(skipFree=True)),
written append-only and flushed row by row, every 10 steps up to step 2000 (to resolve the
first 0.01 % of strain), then every --every steps, and at the last step; --check, a JSON file with the scene's
solid fraction, contact counts and mean stress at step 0 (the interactions of the first step
are those of the step-0 positions), the largest tangential force and the mean ratio
|F_s|/|F_n| of the last step, and YADE's steps per second of the run (wall clock of O.run).
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np
from yade import utils

# yade -x runs the script with execfile: __file__ is yade's own, sys.argv[0] the script
REPO = os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[0])))
sys.path.insert(0, os.path.join(REPO, "python"))
from tylmp.analysis import invariants as inv  # noqa: E402
from tylmp.analysis.io import read_sphere_data, write_json  # noqa: E402
from tylmp.analysis.metrics import coordination  # noqa: E402

E, NU, MU, DENSITY = 70e9, 0.3, 0.3, 2650e12
# inputs/common/numerics.in: dt_fraction x Rayleigh time of the smallest sphere (R = 0.0675 mm)
DT_FRACTION = 0.2
DT = DT_FRACTION * math.pi * 0.0675e-3 * math.sqrt(DENSITY / (E / 2.6)) / (0.1631 * NU + 0.8766)
GAIN, INTEGRAL_GAIN, INTEGRAL_BAND = 0.25, 0.005, 0.05
STIFFNESS_EVERY = 1000
# record rows: every DENSE_EVERY steps up to step DENSE_UNTIL (to resolve the first 0.01 %), then --every
DENSE_EVERY, DENSE_UNTIL = 10, 2000
COLUMNS = ("step", "time", "eps1", "eps2", "eps3", "eps_v", "eps_q", "eps_d13", "sig1", "sig2",
           "sig3", "p", "q", "b", "lode_deg", "eta_LD", "sinphi", "void_ratio",
           "solid_fraction", "Z", "Zm", "unbalanced", "inertial_number",
           "pi_x", "pi_y", "pi_ex", "pi_ey", "rate1", "rate2", "rate3", "volume")


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(REPO, "bench", "data", "dense_paper_100kPa.data"))
    ap.add_argument("--law", choices=("mindlin", "deresiewitz"), default="mindlin")
    ap.add_argument("--rate", type=float, default=5e-5, help="axial strain rate, compression > 0")
    ap.add_argument("--p", type=float, default=1e5, help="mean stress held [Pa]")
    ap.add_argument("--strain", type=float, default=0.10, help="end at eps1 - eps3 = STRAIN")
    ap.add_argument("--csv", default=None)
    ap.add_argument("--every", type=int, default=200)
    ap.add_argument("--max-steps", type=int, default=None)
    ap.add_argument("--check", default=None, help="JSON file of the step-0 state and speed")
    a = ap.parse_args(argv)
    for name in ("rate", "p", "strain"):
        v = getattr(a, name)
        if not (math.isfinite(v) and v > 0):
            ap.error(f"--{name} must be a finite positive number, got {v!r}")
    if a.every < 1:
        ap.error(f"--every must be >= 1, got {a.every}")
    return a


def build_scene(args):
    lo, hi, ids, diameters, positions = read_sphere_data(args.data)
    O.reset()
    O.periodic = True
    O.cell.setBox(*(hi - lo))
    mat = O.materials.append(FrictMat(young=E, poisson=NU, frictionAngle=math.atan(MU),
                                      density=DENSITY))
    for d, x in zip(diameters, positions):
        O.bodies.append(utils.sphere(tuple(x - lo), 0.5 * d, material=mat))
    law = (Law2_ScGeom_MindlinPhys_Mindlin() if args.law == "mindlin"
           else Law2_ScGeom_MindlinPhys_MindlinDeresiewitz())
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                        [Ip2_FrictMat_FrictMat_MindlinPhys(betan=0.0, betas=0.0)], [law]),
        NewtonIntegrator(damping=0.0),
        PyRunner(command="servo_step()", iterPeriod=1, initRun=True, label="servo_runner"),
    ]
    O.dt = DT
    for b in O.bodies:
        b.state.vel = Vector3(0, 0, 0)
        b.state.angVel = Vector3(0, 0, 0)
    return diameters


def real_contacts():
    """(ids1, ids2, normal forces, shear-force norms, overlaps, kno, ks, normals, branch
    lengths) of the interactions carrying force."""
    rows = []
    for i in O.interactions:
        if not i.isReal:
            continue
        g, ph = i.geom, i.phys
        rows.append((i.id1, i.id2, ph.normalForce.norm(), ph.shearForce.norm(),
                     g.penetrationDepth, ph.kno, ph.ks, tuple(g.normal),
                     g.refR1 + g.refR2 - g.penetrationDepth))
    return rows


def affine_stiffness(rows, volume):
    """C_ij = (1/V) sum_c l^2 [k_N n_i^2 n_j^2 + k_T (delta_ij n_i^2 - n_i^2 n_j^2)], k_N the
    tangent Hertz stiffness 3/2 kno sqrt(delta) (docs/theory.md §6.1)."""
    c = np.zeros((3, 3))
    for _, _, _, _, delta, kno, ks, n, length in rows:
        n2 = np.array(n) ** 2
        kn = 1.5 * kno * math.sqrt(max(delta, 0.0))
        c += length ** 2 * ((kn - ks) * np.outer(n2, n2) + ks * np.diag(n2))
    return c / volume


class Test:
    def __init__(self, args, diameters):
        self.args = args
        self.n = len(diameters)
        self.solid_volume = float(np.sum(math.pi / 6 * diameters ** 3))
        self.mean_diameter = float(np.mean(diameters))
        self.L0 = np.array([O.cell.hSize[k, k] for k in range(3)])
        self.rate = np.array([args.rate, 0.0, 0.0])     # compression positive
        self.integral = np.zeros(2)
        self.C = None
        i_rate = 1e-3 * math.sqrt(args.p / DENSITY) / self.mean_diameter
        self.max_rate = max(i_rate, 4 * args.rate)
        self.A = np.array([[0.0, 1.0, -1.0], [1 / 3, 1 / 3, 1 / 3]])
        self.W = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
        self.targets = np.array([0.0, args.p])
        self.fh = None
        self.done = False
        if args.csv:
            self.fh = open(args.csv, "w", encoding="utf-8")
            self.fh.write(",".join(COLUMNS) + "\n")
            self.fh.flush()
        self.apply(self.rate)

    def apply(self, rate):
        O.cell.velGrad = Matrix3(-rate[0], 0, 0, 0, -rate[1], 0, 0, 0, -rate[2])

    def strains(self):
        L = np.array([O.cell.hSize[k, k] for k in range(3)])
        return -np.log(L / self.L0)

    def stress(self):
        s = utils.getStress()
        return np.array([-s[0, 0], -s[1, 1], -s[2, 2]])

    def due(self, it):
        every = DENSE_EVERY if it <= DENSE_UNTIL else self.args.every
        return it % every == 0

    def step(self):
        sigma = self.stress()
        it = O.iter
        if self.C is None or it % STIFFNESS_EVERY == 0:
            self.C = affine_stiffness(real_contacts(), O.cell.volume)
        eps = self.strains()
        if self.fh and self.due(it):
            self.record(it, eps, sigma)
        if eps[0] - eps[2] >= self.args.strain or (self.args.max_steps and it >= self.args.max_steps):
            if self.fh and not self.due(it):
                self.record(it, eps, sigma)
            self.done = True
            O.pause()
            return
        # fix cell/servo's control law (docs/theory.md §6.2), written anew
        r_p = np.array([self.args.rate, 0.0, 0.0])
        response = self.A @ self.C @ self.W
        error = self.targets - self.A @ sigma
        level = max(np.max(np.abs(self.targets)), abs(np.mean(sigma)))
        near = np.max(np.abs(error)) <= INTEGRAL_BAND * level
        integral = self.integral + (error if near else 0.0)
        feed = self.A @ self.C @ (r_p * O.dt)
        u = np.linalg.solve(response, GAIN * error - feed + INTEGRAL_GAIN * integral)
        servo = self.W @ u / O.dt
        largest = np.max(np.abs(servo))
        if largest > self.max_rate:
            servo *= self.max_rate / largest
        else:
            self.integral = integral
        self.rate = r_p + servo
        self.apply(self.rate)

    def record(self, it, eps, sigma):
        """One row in the fix cell/servo layout; it = O.iter counts the steps done before this
        one, whose forces (and interactions) were evaluated on the positions after them."""
        two_c = 2 * O.interactions.countReal()
        # YADE's own mechanical coordination number (2C - N1)/(N - N0 - N1) (Thornton 2000)
        zm = utils.avgNumInteractions(skipFree=True)
        volume = O.cell.volume
        phi = self.solid_volume / volume
        p = float(np.mean(sigma))
        q = float(np.sqrt(1.5 * np.sum(inv.deviator(sigma) ** 2)))
        srt = np.sort(sigma)[::-1]
        b = (srt[1] - srt[2]) / (srt[0] - srt[2]) if srt[0] > srt[2] else float("nan")
        px, py = inv.pi_coordinates(sigma)
        ex, ey = inv.pi_coordinates(eps)
        dev_e = inv.deviator(eps)
        eps_q = math.sqrt(2 / 3 * float(np.sum(dev_e ** 2)))
        i1, _, i3 = inv.invariants(sigma)
        rate_q = math.sqrt(2 / 3 * float(np.sum(inv.deviator(self.rate) ** 2)))
        inertial = rate_q * self.mean_diameter * math.sqrt(DENSITY / p) if p > 0 else float("nan")
        values = {
            "step": it, "time": it * O.dt, "eps1": eps[0], "eps2": eps[1], "eps3": eps[2],
            "eps_v": float(np.sum(eps)), "eps_q": eps_q, "eps_d13": eps[0] - eps[2],
            "sig1": sigma[0], "sig2": sigma[1], "sig3": sigma[2], "p": p, "q": q, "b": b,
            "lode_deg": float(inv.lode_angle_deg(px, py)), "eta_LD": i1 ** 3 / i3 - 27,
            "sinphi": (srt[0] - srt[2]) / (srt[0] + srt[2]), "void_ratio": 1 / phi - 1,
            "solid_fraction": phi, "Z": two_c / self.n, "Zm": zm,
            "unbalanced": utils.unbalancedForce(),
            "inertial_number": inertial, "pi_x": px, "pi_y": py, "pi_ex": ex, "pi_ey": ey,
            "rate1": self.rate[0], "rate2": self.rate[1], "rate3": self.rate[2],
            "volume": volume}
        line = ",".join(repr(float(values[c])) for c in COLUMNS) + "\n"
        self.fh.write(line)
        self.fh.flush()


def step0_state(diameters, volume0):
    """Solid fraction, contacts and mean contact stress of the step-0 positions: the
    interactions after the first step were detected and evaluated on them (the integrator
    moves the spheres afterwards; the cell has moved by one step's strain, 7e-7)."""
    rows = real_contacts()
    counts = np.zeros(len(diameters), dtype=np.int64)
    for id1, id2, *_ in rows:
        counts[id1] += 1
        counts[id2] += 1
    co = coordination(counts)
    phi = float(np.sum(math.pi / 6 * diameters ** 3)) / volume0
    stress = utils.getStress()
    p = -float(stress[0, 0] + stress[1, 1] + stress[2, 2]) / 3
    return {"solid_fraction": phi, "p": p, "two_C": int(counts.sum()), "N0": co["N0"], "N1": co["N1"],
            "Z": co["Z"], "Zm": co["Zm"], "N": len(diameters)}


def main():
    args = parse(sys.argv[1:])
    diameters = build_scene(args)
    test = Test(args, diameters)
    global servo_step
    servo_step = test.step
    volume0 = O.cell.volume
    O.step()
    state0 = step0_state(diameters, volume0)
    print("yade_axisym step 0:", json.dumps(state0), flush=True)
    t0 = time.time()
    steps0 = O.iter
    O.run()
    O.wait()
    wall = time.time() - t0
    steps = O.iter - steps0
    if test.fh:
        test.fh.close()
    shear = [(i.phys.shearForce.norm(), i.phys.normalForce.norm()) for i in O.interactions
             if i.isReal]
    result = {"step0": state0, "law": args.law, "dt": O.dt, "steps": O.iter,
              # tangential forces of the last step: Law2_ScGeom_MindlinPhys_MindlinDeresiewitz
              # of YADE 2023.02a applies none (docs/validation.md, "Axisymmetric compression against YADE")
              "end_max_shear_force_N": max((fs for fs, _ in shear), default=0.0),
              "end_mean_shear_to_normal": (sum(fs / fn for fs, fn in shear if fn > 0)
                                           / max(1, sum(1 for _, fn in shear if fn > 0))),
              "wall_s": wall, "steps_per_s": steps / wall if wall > 0 else None,
              "eps_d13_end": float(test.strains()[0] - test.strains()[2])}
    print("yade_axisym:", json.dumps(result), flush=True)
    if args.check:
        write_json(args.check, result)


# bench/yade_simple_shear.py executes this file for its scene under another __name__
if __name__ == "__main__":
    main()
