"""Simple-shear records of fix cell/servo (inputs/simple_shear.in, inputs/cyclic_simple_shear.in;
docs/theory.md §13): the kind of test, the shear rate, the cycle count and liquefaction.

A record of a test in a plane has the columns gamma, tau (= -sigma_ij, positive while gamma
grows), sig_n and tau_ratio; a constant-volume test adds r_u = 1 - sig_n/sig_n0, a cyclic one
also cycles (N = (half cycles completed)/2: 0 during the first half cycle, N once 2N are over),
N_L_ru and N_L_gamma (the count of the half cycle in which r_u >= 0.95 and the double-amplitude
gamma >= 3.75 % first held, (half cycles completed + 1)/2; 0 before).
"""
import numpy as np

SHEAR_COLUMNS = ("gamma", "tau", "sig_n", "tau_ratio")
RU_LIMIT = 0.95
DA_LIMIT = 0.0375


def kind(table):
    """'drained', 'constant_volume' or 'cyclic', from the record's columns."""
    table.require(SHEAR_COLUMNS)
    if "cycles" in table:
        return "cyclic"
    return "constant_volume" if "r_u" in table else "drained"


def shear_rate(table):
    """|gamma_dot| [1/s]: the median of |delta gamma/delta t| over the record's rows."""
    dt = np.diff(np.asarray(table["time"], float))
    dg = np.abs(np.diff(np.asarray(table["gamma"], float)))
    ok = dt > 0
    return float(np.median(dg[ok] / dt[ok])) if np.any(ok) else float("nan")


def peak(table):
    """(tau/sigma_n at its maximum, gamma there)."""
    k = int(np.argmax(table["tau_ratio"]))
    return float(table["tau_ratio"][k]), float(table["gamma"][k])


def half_cycle_starts(table):
    """Row indices where the record's cycle count grows: the first row of each half cycle after
    the first (the reversal happened between that row and the one before)."""
    return np.flatnonzero(np.diff(table["cycles"]) > 0) + 1


def continuous_cycles(table):
    """The cycle count as a continuous measure: within the half cycle whose rows show N (rows
    of equal `cycles`, N the cycles completed before it), from N at its first row to N + 0.5
    at the first row of the next, linear in time; the running half cycle at the record's end
    reaches N + 0.5 at the record's last row."""
    c = np.asarray(table["cycles"], float)
    t = np.asarray(table["time"], float)
    starts = [0] + [int(k) for k in half_cycle_starts(table)]
    ends = starts[1:] + [len(c)]
    out = c.copy()
    for a, b in zip(starts, ends):
        t_end = t[b] if b < len(c) else t[b - 1]
        span = t_end - t[a]
        if span > 0:
            out[a:b] = c[a] + 0.5 * (t[a:b] - t[a]) / span
    return out


def liquefaction_rows(table, ru_limit=RU_LIMIT, da_limit=DA_LIMIT, strain="gamma"):
    """The first rows at which r_u >= ru_limit and |gamma - gamma at the last reversal| >=
    da_limit hold (None where never), gamma at a reversal being the record's gamma at the last
    row of the half cycle before (exact when the record has a row every step); `strain` names
    the cycled strain's column (eps_a of a cyclic triaxial record)."""
    gamma = np.asarray(table[strain], float)
    hit_ru = np.flatnonzero(np.asarray(table["r_u"], float) >= ru_limit)
    at_reversal = np.zeros_like(gamma)
    for k in half_cycle_starts(table):
        at_reversal[k:] = gamma[k - 1]
    hit_da = np.flatnonzero(np.abs(gamma - at_reversal) >= da_limit)
    return (int(hit_ru[0]) if hit_ru.size else None, int(hit_da[0]) if hit_da.size else None)


def liquefaction_from_record(table, ru_limit=RU_LIMIT, da_limit=DA_LIMIT, strain="gamma"):
    """N_L by both criteria recomputed from the record's rows: the count of the half cycle of
    the first row at which each criterion holds (liquefaction_rows), its cycles + 0.5; 0 where
    it never holds, as the fix reports it."""
    c = np.asarray(table["cycles"], float)
    return tuple(float(c[r]) + 0.5 if r is not None else 0.0
                 for r in liquefaction_rows(table, ru_limit, da_limit, strain))


def liquefaction_reported(table):
    """(N_L by r_u, N_L by double amplitude) as the fix reports them at the record's end."""
    return float(table["N_L_ru"][-1]), float(table["N_L_gamma"][-1])


def cyclic_stress_ratio(table):
    """CSR = tau_cyc/sigma_n0 as the record shows it: the median |tau| at the last row of each
    complete half cycle over sigma_n at the first row (nan without a reversal)."""
    ends = half_cycle_starts(table) - 1
    if not ends.size:
        return float("nan")
    return float(np.median(np.abs(table["tau"][ends])) / table["sig_n"][0])
