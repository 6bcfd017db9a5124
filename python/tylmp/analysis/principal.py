"""Six-component records of `fix cell/servo` (triclinic cell): the stress and strain-rate
tensors rebuilt from the CSV columns, their principal values and in-plane directions, the
non-coaxiality angle (docs/theory.md §10.5), and the key numbers of the undrained triaxial test
and of principal stress rotation (§13).

Everything is recomputed from the raw columns (sig1..3, sig_xy..sig_yz; rate1..3,
rate_xy..rate_yz), independently of the fix's own derived columns (sig_major ..,
stress_angle, rate_angle, noncoaxiality), so that those can be checked against it.
Conventions (docs/fix_cell_servo.md): compression positive; sig1..3 are the stresses along x,
y, z; sig_ij the shear stresses (compression-positive tensor entries); rate1..3 the
compression-positive axial strain rates; rate_ij = L_ij the tilt rate, so that the
compression-positive strain-rate tensor has the off-diagonal entry -rate_ij/2.
"""
import numpy as np

from . import metrics

AXES = "xyz"


def plane_indices(plane):
    """(i, j) of a plane 'xy', 'xz' or 'yz'."""
    if plane not in ("xy", "xz", "yz"):
        raise ValueError(f"plane {plane!r} is not xy, xz or yz")
    return AXES.index(plane[0]), AXES.index(plane[1])


def _tensors(diag, shears):
    n = len(diag[0])
    t = np.zeros((n, 3, 3))
    for k in range(3):
        t[:, k, k] = diag[k]
    for (i, j), s in zip(((0, 1), (0, 2), (1, 2)), shears):
        t[:, i, j] = t[:, j, i] = s
    return t


def stress_tensor(table):
    """(n, 3, 3) compression-positive stress tensors of the record's rows."""
    return _tensors([np.asarray(table[f"sig{k}"], float) for k in (1, 2, 3)],
                    [np.asarray(table[f"sig_{c}"], float) for c in ("xy", "xz", "yz")])


def strain_rate_tensor(table):
    """(n, 3, 3) compression-positive strain-rate tensors: diagonal rate1..3, off-diagonal
    -rate_ij/2 (rate_ij = L_ij is the engineering shear rate in the tilt sense)."""
    return _tensors([np.asarray(table[f"rate{k}"], float) for k in (1, 2, 3)],
                    [-0.5 * np.asarray(table[f"rate_{c}"], float) for c in ("xy", "xz", "yz")])


def principal_values(tensors):
    """(n, 3) eigenvalues, major (most compressive) first."""
    return np.linalg.eigvalsh(tensors)[:, ::-1]


def major_angle_deg(tensors, i, j):
    """Angle in degrees, in (-90, 90], from axis i towards axis j of the major principal
    direction of the in-plane part: tan 2θ = 2 s_ij/(s_ii - s_jj)."""
    s_ii, s_jj, s_ij = tensors[:, i, i], tensors[:, j, j], tensors[:, i, j]
    theta = 0.5 * np.degrees(np.arctan2(2.0 * s_ij, s_ii - s_jj))
    return wrap_axis(theta)


def wrap_axis(angle_deg):
    """An axis angle wrapped to (-90, 90] (a direction and its opposite are one axis)."""
    a = np.asarray(angle_deg, float)
    w = a - 180.0 * np.ceil((a - 90.0) / 180.0)
    return w


def noncoaxiality_deg(table, plane):
    """θ_σ - θ_ε̇ in the plane, wrapped to (-90, 90] (§10.5), from the raw columns."""
    i, j = plane_indices(plane)
    return wrap_axis(major_angle_deg(stress_tensor(table), i, j)
                     - major_angle_deg(strain_rate_tensor(table), i, j))


def unwrapped_angle_deg(angle_deg):
    """A record of axis angles in (-90, 90] made continuous (rotation past ±90°)."""
    a = np.asarray(angle_deg, float)
    return np.degrees(np.unwrap(np.radians(2.0 * a)) / 2.0)


def invariants_of_principal(values):
    """p, q = √(3J2) and b = (σ2 - σ3)/(σ1 - σ3) of (n, 3) principal values (major first)."""
    s1, s2, s3 = values[:, 0], values[:, 1], values[:, 2]
    p = (s1 + s2 + s3) / 3.0
    q = np.sqrt(0.5 * ((s1 - s2) ** 2 + (s2 - s3) ** 2 + (s3 - s1) ** 2))
    with np.errstate(invalid="ignore", divide="ignore"):
        b = (s2 - s3) / (s1 - s3)
    return p, q, b


# ---- undrained triaxial test ---------------------------------------------------------------

def critical_state(table):
    """The tail state of a drained record (the critical-state proxy of `tyanalysis pq`): the
    means over its last 10 % of rows of q/p, p and the void ratio."""
    p = np.asarray(table["p"], float)
    return {"M": float(metrics.tail_mean(np.asarray(table["q"], float) / p)),
            "p": float(metrics.tail_mean(p)),
            "e": float(metrics.tail_mean(table["void_ratio"]))}


def critical_state_line(tables):
    """The drained records' critical states and the line through them in e–ln p:
    e = e_ref - lam ln(p/p_ref), p_ref the geometric mean of their p (least squares in e).
    With one mean stress only (the decks' drained tests at their default p = 100 kPa) the
    slope is not determined by them: lam is None and the line is the level e_ref (the mean of
    their void ratios) at p_ref. scatter: the standard deviation of the points' e about the
    line (n - 2 degrees of freedom; None with fewer than three points on a line, or one p)."""
    states = [critical_state(t) for t in tables]
    p = np.array([s["p"] for s in states])
    e = np.array([s["e"] for s in states])
    M = float(np.mean([s["M"] for s in states]))
    p_ref = float(np.exp(np.mean(np.log(p))))
    scatter = None
    if np.ptp(np.log(p)) > 0.1:
        lam, e_ref = np.polyfit(-np.log(p / p_ref), e, 1)
        lam = float(lam)
        if len(e) > 2:
            residual = e - (e_ref - lam * np.log(p / p_ref))
            scatter = float(np.sqrt(np.sum(residual ** 2) / (len(e) - 2)))
    else:
        lam, e_ref = None, float(np.mean(e))
    return {"M": M, "p_ref": p_ref, "e_ref": float(e_ref), "lam": lam, "scatter": scatter,
            "states": states}


def critical_void_ratio(csl, p):
    """e on the critical-state line csl (critical_state_line) at mean stress p [Pa]."""
    if csl["lam"] is None:
        return csl["e_ref"] + 0.0 * np.asarray(p, float)
    return csl["e_ref"] - csl["lam"] * np.log(np.asarray(p, float) / csl["p_ref"])


def undrained_summary(table):
    """Key numbers of an undrained record: start and end p (last row; p_tail, the mean over the
    last 10 % of the rows, the end state's p), q, q/p, void ratio, the largest |eps_v| and the
    largest |sig2 - sig3| relative to p (the lateral stresses along y and z)."""
    p, q = np.asarray(table["p"], float), np.asarray(table["q"], float)
    e = np.asarray(table["void_ratio"], float)
    lateral = np.abs(np.asarray(table["sig2"], float) - np.asarray(table["sig3"], float))
    return {"p_start": float(p[0]), "p_end": float(p[-1]), "p_tail": metrics.tail_mean(p),
            "q_end": float(q[-1]), "q_over_p_end": float(metrics.tail_mean(q / p)),
            "p_min": float(p.min()), "p_max": float(p.max()),
            "e_start": float(e[0]), "e_end": float(e[-1]),
            "eps_v_max_abs": float(np.max(np.abs(table["eps_v"]))),
            "lateral_diff_over_p_max": float(np.max(lateral / p))}


# ---- principal stress rotation -------------------------------------------------------------

def rotation_summary(table, plane="xz"):
    """Key numbers of a rotation record: the turn of the major stress direction, p, q and b
    from the principal values (their ranges), the non-coaxiality (mean and range) and the
    largest out-of-plane shear stress relative to p."""
    i, j = plane_indices(plane)
    sigma = stress_tensor(table)
    p, q, b = invariants_of_principal(principal_values(sigma))
    alpha = unwrapped_angle_deg(major_angle_deg(sigma, i, j))
    k = 3 - i - j
    out_of_plane = np.maximum(np.abs(sigma[:, i, k]), np.abs(sigma[:, j, k]))
    psi = noncoaxiality_deg(table, plane)
    return {"turned_deg": float(alpha[-1] - alpha[0]),
            "p_min": float(p.min()), "p_max": float(p.max()),
            "q_min": float(q.min()), "q_max": float(q.max()),
            "b_min": float(np.nanmin(b)), "b_max": float(np.nanmax(b)),
            "noncoaxiality_mean_deg": float(np.nanmean(psi)),
            "noncoaxiality_min_deg": float(np.nanmin(psi)),
            "noncoaxiality_max_deg": float(np.nanmax(psi)),
            "out_of_plane_shear_over_p_max": float(np.max(out_of_plane / p))}
