"""Records of the laboratory tests along an axis of fix cell/servo (inputs/k0.in,
inputs/cyclic_triaxial.in; docs/theory.md §13): oedometric (K0) loading and unloading, and the
undrained cyclic triaxial test.

Both records have eps_a (the axial natural strain), sig_a, sig_r (the mean of the two lateral
stresses) and q_a = sig_a - sig_r (signed, > 0 in compression). A k0 record adds K0 =
sig_r/sig_a, K0_inc (the ratio of the changes of sig_r and sig_a since the test began) and ocr
= (largest sig_a)/sig_a; a cyclic triaxial record r_u = 1 - p/p0, cycles (N = (half cycles
completed)/2, the first half cycle compressing the axis), N_L_ru and N_L_eps (the count of the
half cycle in which r_u >= 0.95 and the double-amplitude eps_a >= 5 % first held; 0 before).
"""
import numpy as np

from . import shear

K0_COLUMNS = ("eps_a", "sig_a", "sig_r", "K0", "K0_inc", "ocr")
CYCLIC_COLUMNS = ("eps_a", "q_a", "p", "r_u", "cycles", "N_L_ru", "N_L_eps")
RU_LIMIT = 0.95
DA_LIMIT = 0.05


def jaky(sinphi):
    """Jaky's K0 of a normally consolidated soil, 1 - sin(phi') (an empirical rule)."""
    return 1.0 - sinphi


def mayne_kulhawy(k0_nc, ocr, sinphi):
    """K0 of an unloaded soil, K0_nc OCR^sin(phi') (Mayne & Kulhawy 1982, empirical)."""
    return k0_nc * np.asarray(ocr, float) ** sinphi


def peak_row(table):
    """The row of the largest axial stress: the end of loading."""
    table.require(K0_COLUMNS)
    return int(np.argmax(table["sig_a"]))


def k0_at_ocr(table, ocr):
    """K0 at the first row of the unloading with OCR >= ocr (nan if never)."""
    k = peak_row(table)
    later = np.flatnonzero(np.asarray(table["ocr"][k:], float) >= ocr)
    return float(table["K0"][k + later[0]]) if later.size else float("nan")


def k0_summary(table):
    """K0, K0_inc, sig_a and eps_a at the end of loading; K0 and OCR at the record's end."""
    k = peak_row(table)
    return {"sig_a_peak": float(table["sig_a"][k]), "eps_a_peak": float(table["eps_a"][k]),
            "K0_loading": float(table["K0"][k]), "K0_inc_loading": float(table["K0_inc"][k]),
            "void_ratio_peak": float(table["void_ratio"][k]),
            "ocr_end": float(table["ocr"][-1]), "K0_end": float(table["K0"][-1])}


def amplitude_ratio(table):
    """CSR = q_cyc/(2 p0) as the record shows it: the median q_a at the last row of the half
    cycles that ended at the upper bound, over 2 p at the first row (nan without one)."""
    table.require(CYCLIC_COLUMNS)
    ends = shear.half_cycle_starts(table) - 1
    q = np.asarray(table["q_a"], float)[ends]
    q = q[q > 0]
    return float(np.median(q) / (2.0 * table["p"][0])) if q.size else float("nan")


def liquefaction_from_record(table, ru_limit=RU_LIMIT, da_limit=DA_LIMIT):
    """N_L by r_u and by the double-amplitude axial strain recomputed from the record's rows
    (shear.liquefaction_from_record on eps_a)."""
    return shear.liquefaction_from_record(table, ru_limit, da_limit, strain="eps_a")


def liquefaction_reported(table):
    """(N_L by r_u, N_L by double amplitude eps_a) as the fix reports them at the end."""
    return float(table["N_L_ru"][-1]), float(table["N_L_eps"][-1])


def axial_rate(table):
    """|eps_a dot| [1/s]: the median of |delta eps_a/delta t| over the rows that strain."""
    dt = np.diff(np.asarray(table["time"], float))
    de = np.abs(np.diff(np.asarray(table["eps_a"], float)))
    ok = (dt > 0) & (de > 0)
    return float(np.median(de[ok] / dt[ok])) if np.any(ok) else float("nan")
