"""Drained simple shear at constant normal stress in YADE's periodic cell, started from the same
LAMMPS data file as the LAMMPS side (bench/yade_simple_shear.in, fix cell/servo shear xz): the
independent-engine cross-check of docs/validation.md ("Simple shear against YADE").

    nice yade -n -x bench/yade_simple_shear.py [--data bench/data/dense_paper_100kPa.data]
        [--rate 1e-4] [--sigma-n 1e5] [--gamma 0.10] [--csv OUT.csv] [--every 200]
        [--max-steps N] [--check OUT.json]

(Debian 12: `apt-get install yade`, YADE 2023.02a; -n: no GUI, -x: exit when the script ends.)

The scene is that of bench/yade_axisym.py (its docstring; built by the same function): one
sphere per atom of the data file, velocities and spins zero, periodic cell = the box,
Hertz-Mindlin (Ip2_FrictMat_FrictMat_MindlinPhys without viscous damping,
Law2_ScGeom_MindlinPhys_Mindlin), mu = 0.3, NewtonIntegrator(damping = 0), dt = 0.2 Rayleigh
times of the smallest sphere (inputs/common/numerics.in).

The test: YADE's O.cell.velGrad is the velocity gradient L (v_i = L_ij x_j; every step
hSize <- (1 + L dt) hSize), so L_xz = --rate tilts the cell's third edge (the one along z)
towards +x, as LAMMPS's tilt xz grows under fix cell/servo shear xz. L_xx = L_yy = 0 (rigid
lateral boundaries), the other shears zero, and L_zz is set every step by a proportional +
integral servo in a PyRunner holding sigma_zz = --sigma-n, fix cell/servo's control law
(docs/theory.md §6.2) with the one row sigma_zz and the one actuator L_zz:

    C_zzzz u = g (sigma_n - sigma_zz) + g_I S - dsigma_zz/dgamma * gamma_dot dt,

u the compressive strain increment along z, g = 0.25, g_I = 0.005, the servo rate capped at
four times the shear rate, the affine stiffnesses C_zzzz and dsigma_zz/dgamma recomputed every
1000 steps from the interactions (tangent Hertz normal stiffness, Mindlin tangential
stiffness, branch vectors; the affine_stiffness of bench/yade_axisym.py and its shear
column). The stress is YADE's Love-Weber contact stress utils.getStress() (tension positive),
sign flipped to compression positive as fix cell/servo reports it and symmetrised; tau =
-sigma_xz in that sign (= YADE's sigma_xz), positive while gamma grows; gamma = the sum of L_xz dt over the steps
(as the fix's gamma column); eps_v = -ln(V/V0), compression positive. The run ends when gamma
reaches --gamma, or after --max-steps steps.

Output: --csv, a record with the columns of fix cell/servo's shear mode that the comparison
reads (COLUMNS below), every 10 steps up to step 2000, then every --every steps, and at the
last step; --check, a JSON file with the step-0 state, and at the last step the stress
tensor of utils.getStress() (compression positive, not symmetrised) beside the Love-Weber sum
(1/V) sum_c f_c (x) l_c computed here from the interactions' forces and branch vectors, the
cell (hSize), the positions and the contact forces, and YADE's steps per second of the run.
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
BENCH = os.path.dirname(os.path.abspath(sys.argv[0]))
REPO = os.path.dirname(BENCH)
sys.path.insert(0, os.path.join(REPO, "python"))
from tylmp.analysis.io import write_json  # noqa: E402

# the axisymmetric scene's definitions (material, timestep, scene, contact rows, affine
# stiffness): one scene for both YADE tests; its main() runs only when it is the script
_axisym = {"__name__": "yade_axisym", "O": O}
_axisym.update({k: v for k, v in globals().items() if not k.startswith("_")})
with open(os.path.join(BENCH, "yade_axisym.py"), encoding="utf-8") as _fh:
    exec(compile(_fh.read(), os.path.join(BENCH, "yade_axisym.py"), "exec"), _axisym)
DT, DENSITY = _axisym["DT"], _axisym["DENSITY"]
build_scene, real_contacts = _axisym["build_scene"], _axisym["real_contacts"]
axisym_stiffness = _axisym["affine_stiffness"]
step0_state = _axisym["step0_state"]

GAIN, INTEGRAL_GAIN, INTEGRAL_BAND = 0.25, 0.005, 0.05
STIFFNESS_EVERY = 1000
DENSE_EVERY, DENSE_UNTIL = 10, 2000
COLUMNS = ("step", "time", "gamma", "tau", "sig_n", "tau_ratio", "eps_v", "eps_zz", "p",
           "sig_xx", "sig_yy", "sig_zz", "sig_xy", "sig_xz", "sig_yz", "void_ratio",
           "solid_fraction", "Z", "Zm", "unbalanced", "inertial_number", "rate_zz", "volume")


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(REPO, "bench", "data", "dense_paper_100kPa.data"))
    ap.add_argument("--rate", type=float, default=1e-4, help="shear rate L_xz = gamma_dot [1/s]")
    ap.add_argument("--sigma-n", type=float, default=1e5, help="normal stress sigma_zz held [Pa]")
    ap.add_argument("--gamma", type=float, default=0.10, help="end at gamma = GAMMA")
    ap.add_argument("--csv", default=None)
    ap.add_argument("--every", type=int, default=200)
    ap.add_argument("--max-steps", type=int, default=None)
    ap.add_argument("--check", default=None, help="JSON file of the step-0 state, stress check, speed")
    a = ap.parse_args(argv)
    for name in ("rate", "sigma_n", "gamma"):
        v = getattr(a, name)
        if not (math.isfinite(v) and v > 0):
            ap.error(f"--{name.replace('_', '-')} must be a finite positive number, got {v!r}")
    if a.every < 1:
        ap.error(f"--every must be >= 1, got {a.every}")
    a.law = "mindlin"
    return a


def shear_coupling(volume):
    """d sigma_zz / d gamma of the affine shear L_xz, compression positive:
    -(1/V) sum_c l^2 (k_N - k_T) n_x n_z^3 (a contact's approach l n.L.n = l gamma n_x n_z moves
    its normal force by k_N, its tangential displacement by k_T)."""
    s = 0.0
    for _, _, _, _, delta, kno, ks, n, length in real_contacts():
        kn = 1.5 * kno * math.sqrt(max(delta, 0.0))
        s += length ** 2 * (kn - ks) * n[0] * n[2] ** 3
    return -s / volume


def love_weber():
    """(1/V) sum_c F_c (x) l_c, compression positive: F_c the force on id2 (YADE's Law2 adds
    normalForce + shearForce to id2 and its negative to id1), l_c = x2 - x1 + hSize cellDist."""
    h = np.array([[O.cell.hSize[i, j] for j in range(3)] for i in range(3)])
    s = np.zeros((3, 3))
    for i in O.interactions:
        if not i.isReal:
            continue
        f = np.array(i.phys.normalForce) + np.array(i.phys.shearForce)
        shift = h @ np.array([i.cellDist[k] for k in range(3)], dtype=float)
        branch = np.array(O.bodies[i.id2].state.pos) - np.array(O.bodies[i.id1].state.pos) + shift
        s += np.outer(f, branch)
    return s / O.cell.volume


class Test:
    def __init__(self, args, diameters):
        self.args = args
        self.n = len(diameters)
        self.solid_volume = float(np.sum(math.pi / 6 * diameters ** 3))
        self.mean_diameter = float(np.mean(diameters))
        self.V0 = O.cell.volume
        self.Lz0 = O.cell.hSize[2, 2]
        self.gamma = 0.0
        self.rate_zz = 0.0                         # compression positive
        self.integral = 0.0
        self.czz = self.coupling = None
        i_rate = 1e-3 * math.sqrt(args.sigma_n / DENSITY) / self.mean_diameter
        self.max_rate = max(i_rate, 4 * args.rate)
        self.fh = None
        if args.csv:
            self.fh = open(args.csv, "w", encoding="utf-8")
            self.fh.write(",".join(COLUMNS) + "\n")
            self.fh.flush()
        self.apply()

    def apply(self):
        O.cell.velGrad = Matrix3(0, 0, self.args.rate, 0, 0, 0, 0, 0, -self.rate_zz)

    def stress(self):
        """utils.getStress(), compression positive, symmetrised: YADE's sum_c f_i l_j is not
        symmetric while the spheres' spins accelerate (0.4 % in sigma_xz at gamma = 10 %, the
        quick specimen); LAMMPS's virial is, as the continuum stress."""
        s = utils.getStress()
        s = -np.array([[s[i, j] for j in range(3)] for i in range(3)])
        return 0.5 * (s + s.T)

    def due(self, it):
        return it % (DENSE_EVERY if it <= DENSE_UNTIL else self.args.every) == 0

    def step(self):
        """Called every step before the cell moves: the strain the cell has reached (gamma is
        counted from the velGrad of the steps done), the stress of the last force evaluation."""
        it = O.iter
        if it > 0:
            self.gamma += self.args.rate * O.dt
        sigma = self.stress()
        if self.czz is None or it % STIFFNESS_EVERY == 0:
            volume = O.cell.volume
            self.czz = axisym_stiffness(real_contacts(), volume)[2, 2]
            self.coupling = shear_coupling(volume)
        if self.fh and self.due(it):
            self.record(it, sigma)
        if self.gamma >= self.args.gamma * (1 - 1e-12) or (self.args.max_steps and it >= self.args.max_steps):
            if self.fh and not self.due(it):
                self.record(it, sigma)
            O.pause()
            return
        error = self.args.sigma_n - sigma[2, 2]
        level = max(self.args.sigma_n, abs(sigma[2, 2]))
        integral = self.integral + (error if abs(error) <= INTEGRAL_BAND * level else 0.0)
        u = (GAIN * error - self.coupling * self.args.rate * O.dt + INTEGRAL_GAIN * integral) / self.czz
        rate = u / O.dt
        if abs(rate) > self.max_rate:
            rate = math.copysign(self.max_rate, rate)
        else:
            self.integral = integral
        self.rate_zz = rate
        self.apply()

    def record(self, it, sigma):
        volume = O.cell.volume
        phi = self.solid_volume / volume
        p = float(np.trace(sigma) / 3)
        tau = -float(sigma[0, 2])
        inertial = self.args.rate * self.mean_diameter * math.sqrt(DENSITY / p) if p > 0 else float("nan")
        values = {
            "step": it, "time": it * O.dt, "gamma": self.gamma, "tau": tau, "sig_n": sigma[2, 2],
            "tau_ratio": tau / sigma[2, 2], "eps_v": -math.log(volume / self.V0),
            "eps_zz": -math.log(O.cell.hSize[2, 2] / self.Lz0), "p": p,
            "sig_xx": sigma[0, 0], "sig_yy": sigma[1, 1], "sig_zz": sigma[2, 2],
            "sig_xy": sigma[0, 1], "sig_xz": sigma[0, 2], "sig_yz": sigma[1, 2],
            "void_ratio": 1 / phi - 1, "solid_fraction": phi,
            "Z": 2 * O.interactions.countReal() / self.n,
            "Zm": utils.avgNumInteractions(skipFree=True),
            "unbalanced": utils.unbalancedForce(), "inertial_number": inertial,
            "rate_zz": self.rate_zz, "volume": volume}
        self.fh.write(",".join(repr(float(values[c])) for c in COLUMNS) + "\n")
        self.fh.flush()


def main():
    args = parse(sys.argv[1:])
    diameters = build_scene(args)
    test = Test(args, diameters)
    _axisym["servo_step"] = test.step          # the PyRunner of build_scene calls servo_step()
    globals()["servo_step"] = test.step
    volume0 = O.cell.volume
    O.step()
    state0 = step0_state(diameters, volume0)
    print("yade_simple_shear step 0:", json.dumps(state0), flush=True)
    t0 = time.time()
    steps0 = O.iter
    O.run()
    O.wait()
    wall = time.time() - t0
    if test.fh:
        test.fh.close()
    yade_stress = -np.array([[utils.getStress()[i, j] for j in range(3)] for i in range(3)])
    h = O.cell.hSize
    result = {"step0": state0, "dt": O.dt, "steps": O.iter, "gamma_end": test.gamma,
              "hSize_end": [[h[i, j] for j in range(3)] for i in range(3)],
              "stress_getStress_end": yade_stress.tolist(),
              "stress_love_weber_end": love_weber().tolist(),
              # for an independent Love-Weber sum (tests/test_yade_crosscheck.py): positions
              # and, per interaction carrying force, the ids and the force on id2
              "positions_end": [list(b.state.pos) for b in O.bodies],
              "contact_forces_end": [[i.id1, i.id2] + list(i.phys.normalForce + i.phys.shearForce)
                                     for i in O.interactions if i.isReal],
              "wall_s": wall, "steps_per_s": (O.iter - steps0) / wall if wall > 0 else None}
    print("yade_simple_shear:", json.dumps({k: v for k, v in result.items()
                                            if k not in ("positions_end", "contact_forces_end")}),
          flush=True)
    if args.check:
        write_json(args.check, result)


main()
