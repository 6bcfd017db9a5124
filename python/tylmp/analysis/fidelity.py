"""The trace study of docs/fidelity.md: one factor at a time against a base set of runs.

Each factor changes the preparation, the shear, or both, of the base set: the dense and loose
axisymmetric tests (5e-5 1/s), the loose radial test at b = 1 (5e-5 1/s) and the clockwise
multi-axial plane-strain test (the deck's 1e-5 1/s), as programmes.FACTORS lists them.
`tyanalysis reproduce --programme fidelity` runs them (programmes.PROGRAMMES["fidelity"]);
`tyanalysis fidelity DIR` tabulates every response of every factor with its shift from the base, and the shift of the
second seed, the run-to-run scatter against which a shift is judged.
"""
import math
import os

import numpy as np

from . import compare, io, metrics
from .programmes import FACTORS, PROGRAMMES, record_name, run_name

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
    out = {}

    def read(run):
        name = run_name(factor, run)
        if name not in PROGRAMMES["fidelity"]:
            return None
        path = io.find_record(os.path.join(directory, record_name(name, PROGRAMMES["fidelity"])))
        return io.read_servo_csv(path) if path else None   # NAME.csv, or compressed NAME.csv.xz

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
    values = {f: responses(directory, f) for f in FACTORS}
    values = {f: v for f, v in values.items() if v}
    if not values:
        raise ValueError(f"{directory}: no record of tyanalysis reproduce --programme fidelity "
                         "(fid_<factor>_<run>.csv) there")
    base = values.get("base", {})
    keys = [(label, k) for label, k in RESPONSES if any(k in v for v in values.values())]
    lines = ["| factor | " + " | ".join(label for label, _ in keys) + " |",
             "|---|" + "---|" * len(keys)]
    for f, v in values.items():
        cells = [_cell(v.get(k), None if f == "base" else base.get(k)) for _, k in keys]
        lines.append(f"| {f}: {FACTORS[f][4]} | " + " | ".join(cells) + " |")
    return "\n".join(lines)
