"""Quantities derived from a `fix cell/servo` record and the key numbers of a test.

Everything is recomputed from the raw principal columns (sig1..3, eps1..3) with the
invariants module, so the derived columns the fix writes can be checked against an
independent implementation (see `consistency`).
"""
import math

import numpy as np

from . import invariants as inv

TAIL_FRACTION = 0.10       # critical-state proxy: mean over the last 10 % of the rows


def derived(table):
    """Recomputed histories (SI units, compression positive) keyed like the CSV columns."""
    sig = inv.stack(table["sig1"], table["sig2"], table["sig3"])
    eps = inv.stack(table["eps1"], table["eps2"], table["eps3"])
    px, py = inv.pi_coordinates(sig)
    ex, ey = inv.pi_coordinates(eps)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = {
            "sigma": sig, "eps": eps,
            "p": inv.mean_stress(sig), "q": inv.deviatoric_stress(sig), "b": inv.b_value(sig),
            "sinphi": inv.sinphi(sig), "eta_LD": inv.lade_duncan_eta(sig),
            "mn_ratio": inv.matsuoka_nakai_ratio(sig),
            "lode_deg": inv.lode_angle_deg(px, py), "pi_x": px, "pi_y": py,
            "pi_ex": ex, "pi_ey": ey, "lode_strain_deg": inv.lode_angle_deg(ex, ey),
            "eps_v": inv.volumetric_strain(eps), "eps_q": inv.deviatoric_strain(eps),
            "eps_d13": eps[:, 0] - eps[:, 2], "dev_stress": sig[:, 0] - sig[:, 2],
        }
    return out


def consistency(table):
    """Largest disagreement between the fix's derived columns and the recomputation:
    stresses relative to max p, strains absolute, angles in degrees (wrapped)."""
    d = derived(table)
    scale = float(np.nanmax(np.abs(d["p"]))) or 1.0
    checks = {"p": scale, "q": scale, "pi_x": scale, "pi_y": scale,
              "sinphi": 1.0, "b": 1.0, "eta_LD": 1.0,
              "eps_v": 1.0, "eps_q": 1.0, "eps_d13": 1.0, "pi_ex": 1.0, "pi_ey": 1.0}
    out = {}
    for name, s in checks.items():
        if name in table:
            diff = np.abs(table[name] - d[name]) / s
            out[name] = _nanmax(diff)
    if "lode_deg" in table:
        diff = np.abs((table["lode_deg"] - d["lode_deg"] + 180.0) % 360.0 - 180.0)
        out["lode_deg"] = _nanmax(diff)
    return out


def _nanmax(x):
    x = np.asarray(x, float)
    return float(np.nanmax(x)) if np.any(np.isfinite(x)) else 0.0


def tail_slice(n, fraction=TAIL_FRACTION):
    return slice(n - max(1, int(math.ceil(fraction * n))), n)


def tail_mean(x, fraction=TAIL_FRACTION):
    x = np.asarray(x, float)
    return float(np.nanmean(x[tail_slice(len(x), fraction)]))


def value_at(xs, ys, x0):
    """y at x = x0 by linear interpolation along the record (first crossing); None if x0 is
    never reached."""
    xs, ys = np.asarray(xs, float), np.asarray(ys, float)
    for i in range(1, len(xs)):
        a, b = xs[i - 1], xs[i]
        if (a - x0) * (b - x0) <= 0.0 and a != b:
            return float(ys[i - 1] + (ys[i] - ys[i - 1]) * (x0 - a) / (b - a))
        if a == x0:
            return float(ys[i - 1])
    if len(xs) and xs[-1] == x0:
        return float(ys[-1])
    return None


def dilation_rate(eps_d, eps_v, npoints=60):
    """-d eps_v / d eps_d (paper Fig. 6) on a uniform grid of the (running maximum of the)
    deviatoric strain, by finite differences of the interpolated record."""
    eps_d, eps_v = np.asarray(eps_d, float), np.asarray(eps_v, float)
    mono = np.maximum.accumulate(eps_d)
    keep = np.concatenate([[True], np.diff(mono) > 0])
    x, y = mono[keep], eps_v[keep]
    if len(x) < 3:
        return np.array([]), np.array([])
    grid = np.linspace(x[0], x[-1], npoints + 1)
    yv = np.interp(grid, x, y)
    mid = 0.5 * (grid[1:] + grid[:-1])
    return mid, -np.diff(yv) / np.diff(grid)


def curve_spread(curves, levels):
    """Spread of several monotone-rising curves y(x) across records (paper Fig. 5: eta against
    eps_d for eta < 7): for each level y0, the x at which each curve first reaches y0; returns
    the largest (max - min)/mean over the levels reached by every curve (None if none is)."""
    worst = None
    for y0 in levels:
        xs = [value_at(y, x, y0) for x, y in curves]
        if any(v is None for v in xs) or np.mean(xs) <= 0:
            continue
        spread = (max(xs) - min(xs)) / float(np.mean(xs))
        worst = spread if worst is None else max(worst, spread)
    return worst


PLATEAU_TOL = 0.01      # the peak plateau: q within 1 % of its largest value


def peak_plateau(xs, ys, tol=PLATEAU_TOL):
    """The strain range of a broad peak: (lo, hi, mid), lo and hi the first and the last x at
    which y reaches (1 - tol) max y (crossings interpolated linearly between rows), mid their
    midpoint. On a broad, noisy peak the position of the largest row wanders over the whole
    plateau, while mid moves only as the plateau's edges do (docs/fidelity.md, response R2)."""
    xs, ys = np.asarray(xs, float), np.asarray(ys, float)
    ok = np.isfinite(xs) & np.isfinite(ys)
    xs, ys = xs[ok], ys[ok]
    if len(ys) == 0:
        return None, None, None
    level = (1.0 - tol) * float(np.max(ys))
    above = np.flatnonzero(ys >= level)
    i, j = int(above[0]), int(above[-1])

    def crossing(a, b):         # rows a (below the level) and b (at or above it)
        return float(xs[a] + (xs[b] - xs[a]) * (level - ys[a]) / (ys[b] - ys[a]))

    lo = crossing(i - 1, i) if i > 0 else float(xs[i])
    hi = crossing(j + 1, j) if j + 1 < len(ys) else float(xs[j])
    return lo, hi, 0.5 * (lo + hi)


def _f(x, scale=1.0):
    return None if x is None or not np.isfinite(x) else float(x) * scale


def summarize(table):
    """Key numbers of one test (stresses in kPa, strains in %)."""
    d = derived(table)
    n = len(table)
    tail = tail_slice(n)
    q, s = d["q"], d["sinphi"]
    iq = int(np.nanargmax(q))
    i_s = int(np.nanargmax(s))
    loaded = q > 0.1 * q[iq]
    out = {
        "file": table.path, "rows": n, "dropped_partial_row": bool(table.dropped_partial),
        "step_end": _f(table["step"][-1]), "time_end": _f(table["time"][-1]),
        "eps_d13_end_pct": _f(d["eps_d13"][-1], 100), "eps_q_end_pct": _f(d["eps_q"][-1], 100),
        "eps_v_end_pct": _f(d["eps_v"][-1], 100),
        "q_peak_kPa": _f(q[iq], 1e-3), "eps_d13_at_q_peak_pct": _f(d["eps_d13"][iq], 100),
        "eps_q_at_q_peak_pct": _f(d["eps_q"][iq], 100),
        **dict(zip(("eps_d13_q_plateau_lo_pct", "eps_d13_q_plateau_hi_pct",
                    "eps_d13_q_plateau_mid_pct"),
                   (_f(v, 100) for v in peak_plateau(d["eps_d13"], q)))),
        "dev_stress_peak_kPa": _f(np.nanmax(d["dev_stress"]), 1e-3),
        "sinphi_max": _f(s[i_s]), "eps_d13_at_sinphi_max_pct": _f(d["eps_d13"][i_s], 100),
        "b_at_sinphi_max": _f(d["b"][i_s]), "lode_at_sinphi_max_deg": _f(d["lode_deg"][i_s]),
        "eta_at_sinphi_max": _f(d["eta_LD"][i_s]), "eta_max": _f(np.nanmax(d["eta_LD"])),
        "sinphi_end": tail_mean(s), "q_end_kPa": tail_mean(q) * 1e-3,
        "b_median": _f(np.nanmedian(d["b"][loaded])) if loaded.any() else None,
        "p_mean_kPa": float(np.mean(d["p"])) * 1e-3,
        "p_min_kPa": float(np.min(d["p"])) * 1e-3, "p_max_kPa": float(np.max(d["p"])) * 1e-3,
    }
    if "void_ratio" in table:
        e = table["void_ratio"]
        out.update({"void_ratio_start": _f(e[0]), "void_ratio_end": _f(e[-1]),
                    "void_ratio_tail": float(np.nanmean(e[tail])),
                    "void_ratio_at_30pct": _f(value_at(d["eps_d13"], e, 0.30))})
    for col in ("solid_fraction", "Z", "Zm"):
        if col in table:
            out[f"{col}_start"] = _f(table[col][0])
            out[f"{col}_end"] = _f(table[col][-1])
    if "inertial_number" in table:
        out["inertial_number_median"] = _f(np.nanmedian(table["inertial_number"]))
    out["consistency_max"] = consistency(table)
    return out


# ---- deviatoric strain measures and the pre-strain amplitude (docs/fidelity.md "Definitions") ----

# Each measure of the deviatoric strain as a function of the principal natural strains (n, 3),
# with its value in axisymmetric compression as a multiple of eps1 - eps3: there
# e = (d/3)(2, -1, -1), e:e = 2 d^2/3, |e| = sqrt(2/3) d (docs/theory.md §7.1, §7.4).
STRAIN_MEASURES = {
    "eps_d13": ("ε1 − ε3", lambda e: e[:, 0] - e[:, 2], 1.0),
    "eps_q": ("ε_q = √(2/3 e:e)", inv.deviatoric_strain, 2.0 / 3.0),
    "gamma_oct": ("γ_oct = (2/√3)√(e:e)", lambda e: 2.0 / math.sqrt(3.0) * inv.pi_radius(e),
                  2.0 * math.sqrt(2.0) / 3.0),
    "pi_radius": ("|e| = √(e:e)", inv.pi_radius, math.sqrt(2.0 / 3.0)),
}

# Measures of the deviatoric stress, as multiples of q = sqrt(3 J2) (= sig1 - sig3 in
# axisymmetric compression): |s| = sqrt(2/3) q, sqrt(J2) = q/sqrt(3), tau_oct = (sqrt(2)/3) q.
STRESS_MEASURES = {
    "q": ("q = √(3J2) = σ1 − σ3", 1.0),
    "pi_radius": ("|s| = √(s:s)", math.sqrt(2.0 / 3.0)),
    "sqrt_J2": ("√J2", 1.0 / math.sqrt(3.0)),
    "tau_oct": ("τ_oct", math.sqrt(2.0) / 3.0),
}


def prestrain_end(table, tol_deg=1e-6):
    """Index of the last row of the axisymmetric-compression prestrain: the row before the
    strain Lode angle first leaves 0 deg by more than tol_deg (None if it never does).
    On the prestrain leg the fix keeps eps2 = eps3 to round-off (Lode angle < 2e-10 deg in the
    paper-scale records), while the first row on a circle or triangle has turned by the
    path speed x CSV interval (0.8 deg at paper scale), so the tolerance is tiny: a tolerance
    of 1 deg took that first, already unloading row (q 5 kPa below the prestrain's) as the end
    of the prestrain (docs/fidelity.md "Definitions")."""
    d = derived(table)
    r = np.hypot(d["pi_ex"], d["pi_ey"])
    dev = np.abs((d["lode_strain_deg"] + 180.0) % 360.0 - 180.0)
    active = (r > 1e-3 * np.nanmax(r)) & (dev > tol_deg)
    idx = np.flatnonzero(active)
    if idx.size == 0 or idx[0] == 0 or not r[idx[0] - 1] > 1e-3 * np.nanmax(r):
        return None                  # never leaves compression, or no compression prestrain
    return int(idx[0]) - 1


def compression_leg(table):
    """Slice of the rows of the first axisymmetric-compression leg: up to the end of a
    pre-strain (prestrain_end), or the whole record if the strain never leaves
    compression (an axisymmetric test)."""
    i0 = prestrain_end(table)
    return slice(0, len(table) if i0 is None else i0 + 1)


def q_at_amplitude(table, amplitude, measure):
    """Deviatoric stress q [Pa] and eps1 - eps3 where the deviatoric strain measure `measure`
    (a key of STRAIN_MEASURES) first reaches `amplitude` on the compression leg, by linear
    interpolation between rows; (None, None) if the leg ends before."""
    d = derived(table)
    leg = compression_leg(table)
    m = STRAIN_MEASURES[measure][1](d["eps"][leg])
    return value_at(m, d["q"][leg], amplitude), value_at(m, d["eps_d13"][leg], amplitude)


def prestrain_readings(table, amplitude):
    """q at the pre-strain amplitude read as each strain measure: rows of
    (measure, label, eps1 - eps3 needed in axisymmetric compression, q [Pa] or None)."""
    out = []
    for key, (label, _, factor) in STRAIN_MEASURES.items():
        q, _ = q_at_amplitude(table, amplitude, key)
        out.append((key, label, amplitude / factor, q))
    return out


def strain_at_q(table, q_target):
    """eps1 - eps3 where q first reaches q_target on the compression leg (None if never)."""
    d = derived(table)
    leg = compression_leg(table)
    return value_at(d["q"][leg], d["eps_d13"][leg], q_target)


# ---- coordination numbers (docs/theory.md §7.1; docs/fidelity.md "Coordination") --------------

def contacts(box, diameters, positions):
    """Contacts in an orthogonal periodic box of side lengths `box` (3,): the pairs (i, j)
    closer than r_i + r_j by minimum image (a geometric overlap, which is a contact of the law
    at Γ = 0), with their overlap relative to r_i + r_j."""
    from scipy.spatial import cKDTree
    box = np.asarray(box, float)
    d = np.asarray(diameters, float)
    x = np.mod(np.asarray(positions, float), box)
    x = np.where(x >= box, x - box, x)                   # np.mod may return box itself
    pairs = cKDTree(x, boxsize=box).query_pairs(float(d.max()), output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    dv = x[j] - x[i]
    dv -= box * np.round(dv / box)
    dist = np.sqrt(np.einsum("ij,ij->i", dv, dv))
    sumr = 0.5 * (d[i] + d[j])
    touching = dist < sumr
    return i[touching], j[touching], 1.0 - dist[touching] / sumr[touching]


def counts_per_sphere(i, j, n):
    """Contacts of each of n spheres from the contact list (i, j)."""
    return np.bincount(i, minlength=n) + np.bincount(j, minlength=n)


def coordination(counts):
    """Z = 2C/N and the mechanical (rattler-free) coordination number of Thornton (2000,
    Géotechnique 50(1), eq. 8) Z_m = (2C - N1)/(N - N0 - N1), N0 and N1 the numbers of spheres
    with no and with one contact, from the contacts per sphere."""
    c = np.asarray(counts, dtype=np.int64)
    n, two_c = len(c), int(c.sum())
    n0, n1 = int(np.sum(c == 0)), int(np.sum(c == 1))
    return {"N": n, "C": two_c // 2, "N0": n0, "N1": n1, "Z": two_c / n,
            "Zm": (two_c - n1) / (n - n0 - n1) if n > n0 + n1 else float("nan")}


def rattlers_from_z(n, z, zm, tol=1e-6):
    """(N0, N1) from a record's Z and Z_m of n spheres: 2C = Z n is an integer, and
    Z_m (N - N0 - N1) = 2C - N1 holds for integer N0, N1 >= 0; every solution within `tol`
    of an integer (the CSV keeps 12 digits) is returned, ideally exactly one."""
    two_c = int(round(z * n))
    out = []
    for n1 in range(0, n + 1):
        active = (two_c - n1) / zm
        k = round(active)
        if abs(active - k) < tol and 0 <= n - k - n1 <= n:
            out.append((int(n - k - n1), n1))
    return out
