"""The preparation's progress and, when it stops short, its diagnosis (inputs/common/
prepare*.in): the criteria of quasi-equilibrium of fix cell/servo, each one's value against its
limit, and what to change."""

import math

from .session import lammps_at, say, variable_values

# fix cell/servo (ID iso) outputs 37-40: whether each criterion held at its last check (1 met,
# 0 failed, NaN before the first check; docs/fix_cell_servo.md)
_CRITERIA = (("stress", 36), ("unbalanced", 37), ("kinetic", 38), ("coordination", 39))
_z_history = []          # (step, Z) at each equilibrium check (prep_track), for the drift of Z


def _criteria_ok(L):
    from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR
    return {name: L.extract_fix("iso", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, k)
            for name, k in _CRITERIA}


def _prep_state(L, span):
    """The preparation's state: the fix's outputs and, for each criterion, its measured value
    (the stress: the largest principal stress off its 1e5 Pa target, relative; Z: its drift
    over the last `span` steps)."""
    out = {n: L.extract_variable(f"iso_{n}") for n in
           ("p", "sig1", "sig2", "sig3", "solid_fraction", "Z", "Zm", "unbalanced",
            "kinetic_ratio")}
    step = L.extract_global("ntimestep")
    window = [z for s, z in _z_history if s >= step - span]
    measured = {
        "stress": max(abs(out[s] - 1e5) for s in ("sig1", "sig2", "sig3")) / 1e5,
        "unbalanced": out["unbalanced"], "kinetic": out["kinetic_ratio"],
        "coordination": (max(window) - min(window)) if len(window) > 1 else float("nan")}
    return step, out, measured


def prep_track(ptr):
    """fix python/invoke of the preparation, at each equilibrium check: records Z (no LAMMPS
    command may run during a run)."""
    L = lammps_at(ptr)
    step = L.extract_global("ntimestep")
    if _z_history and step < _z_history[-1][0]:            # a new preparation
        _z_history.clear()
    _z_history.append((step, L.extract_variable("iso_Z")))
    del _z_history[:-1000]


def prep_status(ptr, stress, unbalanced, kinetic, coordination, span):
    """The progress line (a python-style variable that fix print shows every prep_progress
    steps): p, solid fraction, Z, Zm, each criterion's value against its limit, and which
    criteria still fail."""
    L = lammps_at(ptr)
    span = int(span)
    limits = dict(zip(("stress", "unbalanced", "kinetic", "coordination"),
                      (stress, unbalanced, kinetic, coordination)))
    step, out, measured = _prep_state(L, span)
    ok = _criteria_ok(L)
    if all(math.isnan(v) for v in ok.values()):
        verdict = "no equilibrium check yet (compressing towards p = 1e5 Pa)"
    else:
        failing = [n for n in ok if ok[n] == 0]
        verdict = ("failing at the last check: " + ", ".join(failing) if failing
                   else "every criterion met at the last check")
    return (f"preparation step {step}: p = {out['p']:.5g} Pa, solid fraction "
            f"{out['solid_fraction']:.4f}, Z = {out['Z']:.3f}, Zm = {out['Zm']:.3f}; "
            + "; ".join(f"{n} {measured[n]:.3g} (limit {limits[n]:g})" for n in ok
                        if n != "coordination")
            + f"; Z moved by {measured['coordination']:.3g} over the last {span} steps (limit "
              f"{coordination:g} from the first of the passing checks)"
            + f"; {verdict}")


def prep_report(ptr):
    """The preparation stopped without quasi-equilibrium: which criterion failed at the last
    check, by how much, and what to change."""
    L = lammps_at(ptr)
    v = variable_values(L, ["prep_max_steps", "prep_protocol", "prep_check_every", "prep_eq_window",
                            "prep_stress", "prep_unbalanced", "prep_kinetic", "prep_coordination"])
    limits = {n: float(v["prep_" + n]) for n in ("stress", "unbalanced", "kinetic",
                                                 "coordination")}
    step, out, measured = _prep_state(
        L, int(v["prep_check_every"]) * int(v["prep_eq_window"]))
    ok = _criteria_ok(L)
    damping = "prep_hold_damping" if v["prep_protocol"] == "two_stage" else "prep_damping"
    lines = [f"WARNING: preparation did not reach quasi-equilibrium within {v['prep_max_steps']} "
             f"steps (solid fraction {out['solid_fraction']:.4f}, Z = {out['Z']:.3f}; the "
             "specimen is written as it is). At the last check:"]
    if all(math.isnan(x) for x in ok.values()):
        lines.append(f"  no equilibrium check yet: the compression had not reached p = 1e5 Pa "
                     f"(p = {out['p']:.6g} Pa). Change: more steps (-var prep_max_steps N) or "
                     "a faster compression (-var prep_max_rate R)")
    labels = {
        "stress": f"stress: sigma = {out['sig1']:.6g} {out['sig2']:.6g} {out['sig3']:.6g} Pa, "
                  f"each must lie within {v['prep_stress']} p of 1e5 Pa",
        "unbalanced": f"unbalanced force ratio {out['unbalanced']:.3g} (criterion eq_unbalanced "
                      f"{v['prep_unbalanced']})",
        "kinetic": "kinetic energy of the load-bearing particles E_k/(pV) = "
                   f"{out['kinetic_ratio']:.3g} (criterion eq_kinetic {v['prep_kinetic']})",
        "coordination": f"coordination: Z = {out['Z']:.3f} moved by "
                        f"{measured['coordination']:.3g} over the last "
                        f"{int(v['prep_check_every']) * int(v['prep_eq_window'])} steps "
                        f"(criterion eq_coordination {v['prep_coordination']} from the first "
                        "of the passing checks)"}
    change = {
        "stress": "more steps for the servo (-var prep_max_steps N)",
        "unbalanced": f"more steps (-var prep_max_steps N), more damping (-var {damping} D) "
                      "or a looser -var prep_unbalanced",
        "kinetic": f"more damping (-var {damping} D: a frictional packing keeps rattlers and "
                   "slow rearrangements alive without it), more steps (-var prep_max_steps N) "
                   "or a looser -var prep_kinetic",
        "coordination": "more steps (-var prep_max_steps N): the packing still creeps"}
    for name in ok:
        if ok[name] == 0:
            lines.append(f"  FAILED {labels[name]}: {measured[name] / limits[name]:.3g} times "
                         f"its limit. Change: {change[name]}")
    for line in lines:
        say(L, line)
