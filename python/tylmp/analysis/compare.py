"""The markdown comparison table (quantity | paper | ours | difference | band | inside) of our
records against the paper's numbers and bands (tylmp/analysis/paper.py)."""
import json
import math

import numpy as np

from . import invariants as inv
from . import metrics, paper
from .metrics import prestrain_end

PAPER = paper.VALUES          # the paper's numbers: one table, tylmp/analysis/paper.py
BANDS = paper.BANDS


def _num(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def _fmt(x):
    if x is None:
        return "—"
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        return str(x)
    if not math.isfinite(x):
        return "nan"
    if float(x).is_integer() and abs(x) < 1e6:
        return f"{int(x)}"
    return f"{x:.4g}"


def _band(key, mine, bands):
    """(band text, 'yes'/'no'/'—') of one quantity."""
    if key not in bands:
        return "—", "—"
    lo, hi = bands[key]
    text = f"> {_fmt(lo)}" if math.isinf(hi) else f"{_fmt(lo)}–{_fmt(hi)}"
    if not _num(mine):
        return text, "—"
    return text, "yes" if lo <= mine <= hi else "no"


def rows(ours, paper=PAPER, bands=BANDS):
    """(quantity, paper, ours, difference, band, inside, source) for every paper entry and any
    extra key of `ours`; difference = ours − paper (and relative, %); band and inside from
    paper.BANDS."""
    out = []
    for key, (value, unit, source, note) in paper.items():
        mine = ours.get(key)
        if _num(mine) and _num(value):
            diff = mine - value
            rel = f" ({100 * diff / value:+.1f} %)" if value else ""
            d = f"{diff:+.4g}{rel}"
        else:
            d = "—"
        label = f"{key} [{unit}]" if unit else key
        out.append((label, _fmt(value), _fmt(mine), d, *_band(key, mine, bands),
                    f"{source}: {note}"))
    for key, mine in ours.items():
        if key not in paper:
            out.append((key, "—", _fmt(mine), "—", "—", "—", "not reported in the paper"))
    return out


def markdown_table(ours, paper=PAPER, bands=BANDS):
    lines = ["| quantity | paper | ours | difference | band | inside | source |",
             "|---|---|---|---|---|---|---|"]
    for r in rows(ours, paper, bands):
        lines.append("| " + " | ".join(r) + " |")
    return "\n".join(lines)


def load_results(path):
    with open(path, encoding="utf-8") as fh:
        data = json.load(fh)
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a JSON object {{quantity: value}}")
    return data


# ---- our values from records --------------------------------------------------------------------

def from_axisym(table, role):
    """Values of a dense or loose axisymmetric compression record (role = 'dense'/'loose')."""
    s = metrics.summarize(table)
    out = {f"solid_fraction_{role}": s.get("solid_fraction_start"),
           f"void_ratio_start_{role}": s.get("void_ratio_start"),
           f"coordination_{role}": s.get("Zm_start"),
           f"Z_all_spheres_{role}": s.get("Z_start"),
           f"void_ratio_30pct_{role}": s.get("void_ratio_at_30pct"),
           f"sinphi_max_{role}": s["sinphi_max"], f"sinphi_end_{role}": s["sinphi_end"],
           f"q_peak_{role}_kPa": s["q_peak_kPa"]}
    # the dense peak: the midpoint of the range where q is within 1 % of its maximum; the loose
    # "constant deviator stress from about 15 %": where q first reaches that range
    # (metrics.peak_plateau; docs/fidelity.md, responses R2 and R3)
    if role == "dense":
        out["eps_d13_at_peak_dense_pct"] = s["eps_d13_q_plateau_mid_pct"]
    else:
        out["eps_d13_steady_loose_pct"] = s["eps_d13_q_plateau_lo_pct"]
    return {k: v for k, v in out.items() if v is not None}


def from_radial(tables, role="dense", compression=None):
    """b of the record with the largest sinphi_max among the radial records `tables` (with the
    axisymmetric compression record `compression`, b = 0, if given), and sinphi_max(b = 1)
    minus sinphi_max(b = 0) when both are there. Keys of the dense set carry no suffix for b."""
    radial = [metrics.summarize(t) for t in tables]
    comp = ([metrics.summarize(compression)] if compression is not None
            else [s for s in radial if abs(s["b_median"]) < 0.05])
    best = max(radial + comp, key=lambda s: s["sinphi_max"])
    suffix = "" if role == "dense" else f"_{role}"
    out = {f"b_at_max_sinphi{suffix}": best["b_median"],
           f"sinphi_max_radial{suffix}": best["sinphi_max"]}
    ext = [s for s in radial if abs(s["b_median"] - 1.0) < 0.05]
    if ext and comp:
        out[f"extension_minus_compression_{role}"] = ext[0]["sinphi_max"] - comp[0]["sinphi_max"]
    return out


def stress_rotation(table, strain_rotation_deg=paper.PS_STRAIN_ROTATION_DEG):
    """(stress rotation, strain rotation) in degrees from the end of the prestrain to the first
    row where the strain Lode angle has turned by strain_rotation_deg; None if never reached.
    Both are magnitudes; turn_direction tells which way the strain turned."""
    i0 = prestrain_end(table)
    if i0 is None:
        return None
    d = metrics.derived(table)
    te = np.degrees(np.unwrap(np.radians(d["lode_strain_deg"][i0:])))
    ts = np.degrees(np.unwrap(np.radians(d["lode_deg"][i0:])))
    turned = np.abs(te - te[0])
    hit = np.flatnonzero(turned >= strain_rotation_deg - 1e-9)
    if hit.size == 0:
        return None
    k = int(hit[0])
    return float(abs(ts[k] - ts[0])), float(turned[k])


def turn_direction(table):
    """+1 if the strain Lode angle increases after the prestrain (the decks' cw), -1 if it
    decreases (ccw), 0 without a prestrain."""
    i0 = prestrain_end(table)
    if i0 is None:
        return 0
    te = np.unwrap(np.radians(metrics.derived(table)["lode_strain_deg"][i0:]))
    return 1 if te[-1] >= te[0] else -1


def path_kind(table, tol=0.1):
    """What the strain path did after the prestrain: ('circle', radius) when, once the strain
    Lode angle has turned by 10 deg, the Pi radius stays within tol of its median (paper
    Fig. 7); else ('triangle', r0) when it reaches 1.5 r0 (r0: the radius at the end of the
    prestrain) and stays near the plane-strain triangle through that state (Fig. 8; within
    2 tol r0 on average: dilatancy moves a true plane-strain path off the nominal triangle);
    (None, None) otherwise, or without a prestrain."""
    i0 = prestrain_end(table)
    if i0 is None:
        return None, None
    d = metrics.derived(table)
    ex, ey = d["pi_ex"][i0:], d["pi_ey"][i0:]
    r = np.hypot(ex, ey)
    r0 = float(r[0])
    te = np.degrees(np.unwrap(np.radians(d["lode_strain_deg"][i0:])))
    turned = np.abs(te - te[0])
    on = turned >= 10.0
    if r0 <= 0 or on.sum() < 3:
        return None, None
    rm = float(np.median(r[on]))
    if float(np.max(np.abs(r[on] - rm))) < tol * rm:
        return "circle", rm
    if float(np.max(r)) > 1.5 * r0:
        tx, ty = inv.plane_strain_triangle_pi(r0)
        dist = np.min([_segment_distance(ex, ey, tx[k], ty[k], tx[k + 1], ty[k + 1])
                       for k in range(len(tx) - 1)], axis=0)
        if float(np.mean(dist)) < 2 * tol * r0:
            return "triangle", r0
    return None, None


def _segment_distance(x, y, x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    u = np.clip(((x - x0) * dx + (y - y0) * dy) / (dx * dx + dy * dy), 0.0, 1.0)
    return np.hypot(x - (x0 + u * dx), y - (y0 + u * dy))


def from_nonradial(table, kind, p_target_kPa=100.0):
    """kind = 'cdst' (constant deviatoric strain) or 'ps' (multi-axial plane strain)."""
    d = metrics.derived(table)
    i0 = prestrain_end(table)
    out = {}
    if i0 is not None:
        out["prestrain_eps_d_pct"] = float(d["eps_q"][i0]) * 100
        out["prestrain_eps_d13_pct"] = float(d["eps_d13"][i0]) * 100
        out["prestrain_q_kPa"] = float(d["q"][i0]) * 1e-3
        if kind == "cdst":
            out["cdst_p_deviation_kPa"] = float(np.max(np.abs(d["p"][i0:] * 1e-3 - p_target_kPa)))
    if kind == "ps":
        rot = stress_rotation(table)
        if rot is not None:
            out["ps_stress_rotation_deg"] = rot[0]
    return out
