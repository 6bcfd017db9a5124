"""Micromechanics of the contact network from records of `compute thornton/yin/micromechanics`
(docs/compute_thornton_yin_micromechanics.md): contact-normal fabric, the normal/tangential and
strong/weak splits of the stress (Thornton 2000, Geotechnique 50(1)), sliding fraction.

A record holds the compute's 41 values as columns, named either as NAMES below or as
`PREFIX[k]` (k = 1..41, the compute's 1-based index, e.g. `c_micro[11]` written by fix print or
by fix cell/servo's record).
"""
import re

import numpy as np

from . import io

TENSOR = ("xx", "yy", "zz", "xy", "xz", "yz")
# the compute's vector in order: one source of truth for the Python side, checked against the
# C++ enum of plugin/lammps/compute_thornton_yin_micromechanics.h by tests/test_analysis_micro.py
NAMES = (("contacts", "sliding_fraction", "mean_normal_force", "strong_fraction")
         + tuple(f"phi_{c}" for c in TENSOR) + ("phi_d",)
         + tuple(f"s_{c}" for c in TENSOR) + tuple(f"s_normal_{c}" for c in TENSOR)
         + tuple(f"s_tangential_{c}" for c in TENSOR) + tuple(f"s_strong_{c}" for c in TENSOR)
         + tuple(f"s_weak_{c}" for c in TENSOR))
STRESS_PARTS = ("s", "s_normal", "s_tangential", "s_strong", "s_weak")

_INDEXED = re.compile(r"^(.*)\[(\d+)\]$")


def read_record(path):
    """a fix cell/servo CSV (comma-separated, header repeated on restarts), or a table of fix
    print or fix ave/time: whitespace-separated, the columns named by the last '#' line before
    the data (fix ave/time writes a title line first)"""
    with open(path, encoding="utf-8", errors="replace") as fh:
        text = fh.read()
    first = text.lstrip().split("\n", 1)[0]
    if "," in first and not first.startswith("#"):
        return io.read_servo_csv(path, require=None)
    lines = text.split("\n")
    header_at = None
    for k, line in enumerate(lines):
        if line.strip().startswith("#"):
            header_at = k
        elif line.strip():
            break
    if header_at is None:
        return io.read_print_table(path)
    names = lines[header_at].lstrip().lstrip("#").replace(",", " ").split()
    data = [(k + 1, l) for k, l in enumerate(lines)
            if k > header_at and l.strip() and not l.strip().startswith("#")]
    cols, dropped = io._read_rows(path, names, data, lambda s: s.replace(",", " ").split(),
                                  text.endswith("\n"))
    table = io.Table(cols, path, dropped)
    if len(table) == 0:
        raise ValueError(f"{path}: no complete data rows")
    return table


def columns(table, prefix=None):
    """name -> array for every value of NAMES, from named or indexed (`prefix[k]`) columns."""
    keys = list(table.keys())
    if all(n in keys for n in NAMES):
        return {n: np.asarray(table[n], float) for n in NAMES}
    indexed = {}
    for key in keys:
        m = _INDEXED.match(key)
        if m and (prefix is None or m.group(1) == prefix):
            indexed.setdefault(m.group(1), {})[int(m.group(2))] = key
    full = {p: cols for p, cols in indexed.items() if all(k in cols for k in range(1, 42))}
    if len(full) != 1:
        raise ValueError(f"{table.path}: expected the 41 columns of compute thornton/yin/"
                         f"micromechanics, named {NAMES[0]}, {NAMES[1]}, ... or PREFIX[1..41]"
                         + (f" (found indexed prefixes {sorted(full)}; choose one with --prefix)"
                            if full else ""))
    (cols,) = full.values()
    return {n: np.asarray(table[cols[k + 1]], float) for k, n in enumerate(NAMES)}


def tensor(values, part):
    """(n, 3, 3) symmetric tensors of part (e.g. 's_strong'), off-diagonals as recorded"""
    n = len(values[f"{part}_xx"])
    t = np.zeros((n, 3, 3))
    for k, (a, b) in enumerate(((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))):
        t[:, a, b] = t[:, b, a] = values[f"{part}_{TENSOR[k]}"]
    return t


def mean_and_deviator(t):
    """p = tr/3 and q = sqrt(3/2 s:s) of each tensor of t (n, 3, 3)"""
    p = np.trace(t, axis1=1, axis2=2) / 3.0
    s = t - p[:, None, None] * np.eye(3)
    return p, np.sqrt(1.5 * np.einsum("nij,nij->n", s, s))


def summary(values):
    """the measures at the last row: fabric invariant, shares of p and q of each stress part"""
    out = {"contacts": values["contacts"][-1], "phi_d": values["phi_d"][-1],
           "sliding_fraction": values["sliding_fraction"][-1],
           "strong_fraction": values["strong_fraction"][-1]}
    p_total, q_total = mean_and_deviator(tensor(values, "s"))
    for part in STRESS_PARTS[1:]:
        p, q = mean_and_deviator(tensor(values, part))
        name = part[2:]
        out[f"p_{name}_share"] = p[-1] / p_total[-1] if p_total[-1] else float("nan")
        # deviator of the part measured along the total's deviatoric direction: the shares of
        # the two halves of a split add up to 1
        s_total = tensor(values, "s")[-1] - p_total[-1] * np.eye(3)
        s_part = tensor(values, part)[-1] - p[-1] * np.eye(3)
        norm2 = np.sum(s_total * s_total)
        out[f"q_{name}_share"] = np.sum(s_part * s_total) / norm2 if norm2 else float("nan")
    return out
