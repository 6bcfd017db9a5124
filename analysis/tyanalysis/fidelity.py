"""The trace study of docs/fidelity.md: one factor at a time against a base set of runs.

Each factor changes the preparation, the shear, or both, of the base set: the dense and loose
axisymmetric tests (5e-5 1/s), the loose radial test at b = 1 (5e-5 1/s) and the clockwise
multi-axial plane-strain test (the deck's 1e-5 1/s). `tyanalysis reproduce --programme
fidelity` runs them (reproduce.PROGRAMMES["fidelity"], built from FACTORS below); `tyanalysis fidelity DIR`
tabulates every response of every factor with its shift from the base, and the shift of the
second seed, the run-to-run scatter against which a shift is judged.
"""
import math
import os

import numpy as np

from . import compare, io, metrics

# The base set's shear runs: name -> (deck, shear variables; `specimen` names the specimen)
BASE_RUNS = {
    "axisym_dense": ("axisym.in", {"specimen": "dense", "rate": "5e-5"}),
    "axisym_loose": ("axisym.in", {"specimen": "loose", "rate": "5e-5"}),
    "radial_loose": ("radial.in", {"specimen": "loose", "b": "1", "strain": "0.30",
                                   "rate": "5e-5"}),
    "plane_strain_cw": ("plane_strain.in", {"rotation": "cw"}),
}
# expected core-minutes of each base run at paper scale (docs/fidelity.md)
BASE_WEIGHT = {"axisym_dense": 4, "axisym_loose": 5, "radial_loose": 5, "plane_strain_cw": 2}

# factor -> (preparation variables, shear variables, runs (None: all of BASE_RUNS), weight
# factor, what it changes), in the order `reproduce` starts them: the base set and its
# scatter, then the factors likeliest to move the residuals of validation.md, the protocol
# whose shift the damped and two-stage paper programmes already give (docs/validation/damped/
# against docs/validation/) last. Preparation variables go to the preparation and to each of its
# runs (the specimen cache is keyed by them); shear variables to the runs only.
FACTORS = {
    "base": ({}, {}, None, 1.0, "the chosen protocol: two-stage preparation, seed 1, maxent"),
    "seed2": ({"seed": "2"}, {}, None, 1.0, "run-to-run scatter: generator seed 2"),
    "gamma0_shear": ({}, {"gamma": "0"}, None, 1.0, "Γ = 0 during shear (paper: 0.6)"),
    "gamma06_prep": ({"prep_gamma": "0.6"}, {}, None, 1.0, "Γ = 0.6 during the preparation (base: 0)"),
    "geometric": ({"distribution": "geometric"}, {}, None, 1.0, "size distribution geometric"),
    "mean_only": ({"distribution": "mean-only"}, {}, None, 1.0, "size distribution mean-only"),
    "volume_mean": ({"distribution": "volume-mean"}, {}, None, 1.0,
                    "size distribution volume-mean"),
    "hold_undamped": ({"prep_hold_damping": "0"}, {}, ("axisym_loose", "radial_loose"), 1.0,
                      "two-stage without damping in the hold (loose only: a frictionless "
                      "packing never settles without dissipation)"),
    # to eps1 - eps3 = 80 %: eps1 = 50 % at constant volume is 75 %, and dilation by 7 % adds 3.5 %
    "n8000": ({"nspheres": "8000"}, {"strain": "0.80"}, ("axisym_dense", "axisym_loose"), 2.5,
              "8000 spheres, sheared to ε1 − ε3 = 80 % (past ε1 = 50 %)"),
    "settle": ({}, {"settle": "50000"}, None, 1.0,
               "50 000 steps of isotropic settling at the shearing μ and Γ before the shear"),
    "dt01": ({"dt_fraction": "0.1"}, {}, None, 2.0, "timestep 0.1 of the Rayleigh time (base 0.2)"),
    "damped": ({"prep_protocol": "damped"}, {}, None, 1.0,
               "the earlier protocol: compression and hold under damping 0.7"),
}


# the strain-rate factor: the paper programme's runs at 1e-5 1/s (reproduce.PROGRAMME names) in
# place of the base set's at 5e-5, when both programmes ran in one directory (the plane-strain
# test runs at 1e-5 in both)
RATE_FACTOR = "rate_1e-5"
RATE_RUNS = {"axisym_dense": "axisym_dense", "axisym_loose": "axisym_loose",
             "radial_loose": "radial_loose_b1"}
RATE_TEXT = "strain rate 1e-5 1/s, the paper's (base 5e-5): the paper programme's records"


def run_name(factor, run):
    return f"{factor}_{run}"


def factor_rank(name):
    """Place in FACTORS of the factor of a run named by run_name."""
    for i, factor in enumerate(FACTORS):
        if name.startswith(factor + "_") and name[len(factor) + 1:] in BASE_RUNS:
            return i
    raise KeyError(f"{name}: not a run of the trace study")


def out_prefix(factor, run):
    return f"fid_{factor}_{run}"


def programme():
    """name -> (deck, variables, out prefix, weight, preparation variables): the runs in the
    form of reproduce.PROGRAMME."""
    out = {}
    for factor, (prep, shear, runs, scale, _) in FACTORS.items():
        for run in runs or BASE_RUNS:
            deck, base_vars = BASE_RUNS[run]
            variables = dict(base_vars, **shear)
            out[run_name(factor, run)] = (deck, variables, out_prefix(factor, run),
                                          BASE_WEIGHT[run] * scale, dict(prep))
    return out


# ---- the table ---------------------------------------------------------------------------------

# (label, response key), the responses of docs/fidelity.md
RESPONSES = [
    ("R1 dense φ", "phi_dense"), ("R1 dense Z_m", "zm_dense"),
    ("R1 loose φ", "phi_loose"), ("R1 loose Z_m", "zm_loose"),
    ("R2 dense peak ε1−ε3 [%]", "peak_dense"), ("R2 peak σ1−σ3 [kPa]", "dev_peak_dense"),
    ("R3 loose levels off [%]", "steady_loose"),
    ("R4 e at 30 %, dense", "e30_dense"), ("R4 e at 30 %, loose", "e30_loose"),
    ("R5 q after pre-strain [kPa]", "q_prestrain"), ("R6 rotation [°]", "rotation"),
    ("R7 loose sinφ_max b=0", "sinphi_loose_b0"), ("R7 loose sinφ_max b=1", "sinphi_loose_b1"),
    ("e at ε1 = 50 %, dense", "e50_dense"), ("e at ε1 = 50 %, loose", "e50_loose"),
]


def _void_ratio_at_eps1(table, eps1):
    e1, e = np.asarray(table["eps1"], float), np.asarray(table["void_ratio"], float)
    if not len(e1) or np.nanmax(e1) < eps1:
        return None
    return float(np.interp(eps1, e1, e))


def responses(directory, factor):
    """Every response of one factor that its records in `directory` give."""
    from .reproduce import PROGRAMMES, record_name      # reproduce imports this module
    out = {}

    def read(run):
        if factor == RATE_FACTOR:
            if run not in RATE_RUNS:
                return None
            path = os.path.join(directory, record_name(RATE_RUNS[run], PROGRAMMES["paper"]))
        else:
            name = run_name(factor, run)
            if name not in PROGRAMMES["fidelity"]:
                return None
            path = os.path.join(directory, record_name(name, PROGRAMMES["fidelity"]))
        path = io.find_record(path)              # NAME.csv, or compressed NAME.csv.xz
        return io.read_servo_csv(path) if path else None

    for role in ("dense", "loose"):
        t = read(f"axisym_{role}")
        if t is None:
            continue
        s = metrics.summarize(t)
        out[f"phi_{role}"] = s.get("solid_fraction_start")
        out[f"zm_{role}"] = s.get("Zm_start")
        out[f"e30_{role}"] = s.get("void_ratio_at_30pct")
        out[f"e50_{role}"] = _void_ratio_at_eps1(t, 0.50)
        if role == "dense":
            out["peak_dense"] = s.get("eps_d13_q_plateau_mid_pct")
            out["dev_peak_dense"] = s.get("dev_stress_peak_kPa")
        else:
            out["steady_loose"] = s.get("eps_d13_q_plateau_lo_pct")
            out["sinphi_loose_b0"] = s.get("sinphi_max")
    t = read("radial_loose")
    if t is not None:
        out["sinphi_loose_b1"] = metrics.summarize(t).get("sinphi_max")
    t = read("plane_strain_cw")
    if t is not None:
        ps = compare.from_nonradial(t, "ps")
        out["q_prestrain"] = ps.get("prestrain_q_kPa")
        out["rotation"] = ps.get("ps_stress_rotation_deg")
    return {k: v for k, v in out.items() if v is not None and math.isfinite(v)}


def _cell(value, base):
    if value is None:
        return "—"
    text = f"{value:.4g}"
    if base is not None:
        text += f" ({value - base:+.3g})"
    return text


def table(directory):
    """Markdown: one row per factor with its records present, a column per response that some
    factor has; each cell the value and, but for the base, its shift from the base."""
    if not os.path.isdir(directory):
        raise ValueError(f"{directory}: no such directory")
    values = {f: responses(directory, f) for f in list(FACTORS) + [RATE_FACTOR]}
    values = {f: v for f, v in values.items() if v}
    if not values:
        raise ValueError(f"{directory}: no record of tyanalysis reproduce --programme fidelity "
                         "(fid_<factor>_<run>.csv) or of the paper programme there")
    base = values.get("base", {})
    keys = [(label, k) for label, k in RESPONSES if any(k in v for v in values.values())]
    lines = ["| factor | " + " | ".join(label for label, _ in keys) + " |",
             "|---|" + "---|" * len(keys)]
    for f, v in values.items():
        cells = [_cell(v.get(k), None if f == "base" else base.get(k)) for _, k in keys]
        text = RATE_TEXT if f == RATE_FACTOR else FACTORS[f][4]
        lines.append(f"| {f}: {text} | " + " | ".join(cells) + " |")
    return "\n".join(lines)
