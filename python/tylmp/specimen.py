"""Specimen generator for Thornton's periodic-cell tests (random, contact-free sphere packs).

The paper's assembly: 3620 elastic spheres of five sizes, smallest diameter 0.135 mm,
largest 0.4 mm, number-mean diameter 0.26 mm, randomly generated in a cubic periodic
cell of side 4.3 mm with a solid fraction of ca. 0.5 and no interparticle contacts
(notional density 2650 kg/m^3 scaled by 1e12).  The paper gives no counts per size;
the choice made here (see docs/specimen.md) is the *maximum-entropy* number
distribution on five evenly spaced diameters subject to every number the paper states:
the number mean 0.26 mm and the mean cube of the diameter implied by 3620 spheres at
solid fraction 0.5 in a 4.3 mm cube.

Positions: random sequential addition (RSA, largest spheres first, cell list) in a
box enlarged to a low solid fraction where RSA cannot jam, then an overlap-free
isotropic compression to the target solid fraction (affine shrink steps, each followed
by iterative removal of overlaps).  The result has the exact target solid fraction,
no overlaps (also across the periodic faces) and is deterministic for a given seed.

All lengths are SI (metres); the data file is for ``units si`` / ``atom_style sphere``.

Python use::

    from tylmp import specimen
    d, frac = specimen.paper_size_distribution()
    L, diam, pos = specimen.generate(3620, 0.5, seed=1)
    specimen.write_data("specimen.data", L, diam, pos)

Command line::

    python3 -m tylmp.specimen --n 3620 --out specimen.data [--seed 1]
        [--solid-fraction 0.5] [--scale quick|paper] [--density 2650e12]
        [--distribution maxent|uniform:D_MIN:D_MAX|lognormal:D50:SIGMA|number:FILE|mass:FILE]
"""

import argparse
import math
import os
import sys
import tempfile
import time

import numpy as np

__all__ = [
    "D_MIN", "D_MAX", "D_MEAN", "N_PAPER", "L_PAPER", "PHI_PAPER", "DENSITY",
    "SCALES", "DISTRIBUTIONS", "paper_size_distribution", "size_counts", "box_side",
    "solid_fraction", "number_mean", "volume_mean", "describe_distributions",
    "generate", "find_overlaps", "write_data", "read_data", "main",
    "NAMED", "TABLES", "SizeDistribution", "parse_distribution", "user_distribution",
    "read_size_table", "diameters",
]

# ---- the paper's numbers (SI) ----
D_MIN = 0.135e-3          # smallest diameter [m]
D_MAX = 0.4e-3            # largest diameter [m]
D_MEAN = 0.26e-3          # number-mean diameter [m]
N_SIZES = 5
N_PAPER = 3620            # number of spheres
L_PAPER = 4.3e-3          # side of the periodic cube [m]
PHI_PAPER = 0.5           # "solid fraction ca. 0.5"
DENSITY = 2650e12         # 2650 kg/m^3 scaled by 1e12 (paper)

SCALES = {"paper": N_PAPER, "quick": 500}

_TWO_PI_OVER_6 = math.pi / 6.0


# ---------------------------------------------------------------------------
# size distribution
# ---------------------------------------------------------------------------

def _maxent(d, constraints, targets, iters=200):
    """Maximum-entropy weights p_i ∝ exp(-Σ_k λ_k f_k(d_i)) with Σ p_i f_k(d_i) = t_k.

    Newton's method on the (convex) dual; features are scaled to O(1) for conditioning.
    """
    F = np.array([f(d) for f in constraints], dtype=float)        # (k, n)
    t = np.asarray(targets, dtype=float)
    scale = np.abs(F).max(axis=1)
    F = F / scale[:, None]
    t = t / scale
    lam = np.zeros(len(t))
    for _ in range(iters):
        a = -lam @ F
        w = np.exp(a - a.max())
        p = w / w.sum()
        m = F @ p
        g = m - t                                   # gradient of the dual (up to sign)
        if np.max(np.abs(g)) < 1e-15:
            break
        C = (F * p) @ F.T - np.outer(m, m)          # covariance = Hessian
        step = np.linalg.solve(C, g)
        # Newton: the dual log Σ exp(-λ·F) + λ·t has gradient t - m and Hessian C
        lam = lam + step
    else:
        raise RuntimeError("maximum-entropy size distribution did not converge")
    return p


# Candidate size distributions (docs/specimen.md, "Candidate distributions"): each honours the
# paper's five sizes from 0.135 to 0.4 mm and reads its other facts in one way.
#   name: (spacing of the five diameters, which mean is 0.26 mm, whether the mean d^3 of the
#          paper's cell -- 3620 spheres at solid fraction 0.5 in a 4.3 mm cube -- is imposed)
DISTRIBUTIONS = {
    "maxent": ("even", "number", True),        # default: every stated fact, even spacing
    "geometric": ("geometric", "number", True),  # every stated fact, sieve-like spacing
    "mean-only": ("even", "number", False),    # relaxes the cell: phi0 0.584 in 4.3 mm
    "volume-mean": ("even", "volume", False),  # "average" = D[4,3]; relaxes the cell
}
DEFAULT_DISTRIBUTION = "maxent"


def _distribution_name(distribution, match_cell):
    name = distribution or (DEFAULT_DISTRIBUTION if match_cell else "mean-only")
    if name not in DISTRIBUTIONS:
        raise ValueError(f"unknown size distribution {name!r}; use one of {sorted(DISTRIBUTIONS)}")
    return name


# ---- a user's size distribution (docs/specimen.md, "Your own size distribution") ----
# a distribution is named by a string: a candidate above (maxent, ...), or
#   uniform:D_MIN:D_MAX      diameters uniform by number between D_MIN and D_MAX [m]
#   lognormal:D50:SIGMA      ln d normal by number: median D50 [m], standard deviation SIGMA
#   number:FILE, mass:FILE   a table of "diameter fraction" lines (# comments), fractions by
#                            number or by mass (one density: mass fraction ∝ count × d³)
NAMED = {"uniform": ("D_MIN", "D_MAX"), "lognormal": ("D50", "SIGMA")}
TABLES = ("number", "mass")


class SizeDistribution:
    """A user's size distribution: either discrete (diameters and number fractions) or one of
    NAMED with its parameters.  ``diameters(n)`` gives n diameters, largest first:
    largest-remainder counts of n × fractions for a discrete one, the midpoint quantiles
    F⁻¹((k + ½)/n), k = 0..n−1, of the cumulative number distribution F for a named one
    (deterministic; every n-th of the population represented once)."""

    def __init__(self, spec, sizes=None, fractions=None, kind=None, params=None):
        self.spec, self.sizes, self.fractions = spec, sizes, fractions
        self.kind, self.params = kind, params

    def diameters(self, n):
        n = int(n)
        if n < 1:
            raise ValueError(f"need at least one sphere, got {n}")
        if self.sizes is not None:
            raw = n * self.fractions
            counts = np.floor(raw).astype(np.int64)
            order = np.argsort(-(raw - counts), kind="stable")
            counts[order[:n - int(counts.sum())]] += 1
            d = np.repeat(self.sizes, counts)
        else:
            u = (np.arange(n) + 0.5) / n
            if self.kind == "uniform":
                lo, hi = self.params
                d = lo + (hi - lo) * u
            else:
                from statistics import NormalDist
                d50, sigma = self.params
                z = np.array([NormalDist().inv_cdf(float(x)) for x in u])
                d = d50 * np.exp(sigma * z)
        return np.sort(d)[::-1].copy()


def _positive(spec, what, text):
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"size distribution {spec!r}: {what} {text!r} is not a number") from None
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"size distribution {spec!r}: {what} must be a finite number > 0, "
                         f"got {text}")
    return value


def read_size_table(path, basis="number", spec=None):
    """(diameters [m], number fractions) of a table file: lines "diameter fraction" (# starts
    a comment), fractions by ``basis`` "number" or "mass", normalised here."""
    spec = spec or f"{basis}:{path}"
    rows = []
    try:
        with open(path, encoding="utf-8") as fh:
            for k, line in enumerate(fh, 1):
                fields = line.split("#", 1)[0].replace(",", " ").split()
                if not fields:
                    continue
                if len(fields) != 2:
                    raise ValueError(f"size distribution {spec!r}: line {k} of {path} has "
                                     f"{len(fields)} fields; each line is 'diameter fraction'")
                rows.append(fields)
    except OSError as err:
        raise ValueError(f"size distribution {spec!r}: cannot read {path} ({err.strerror})") \
            from None
    return user_distribution([r[0] for r in rows], [r[1] for r in rows], basis, spec)


def user_distribution(diameters, fractions, basis="number", spec=None):
    """A discrete SizeDistribution from diameters [m] and their fractions by ``basis``
    ("number" or "mass"; any positive scale, normalised here)."""
    spec = spec or f"{basis} fractions"
    if basis not in TABLES:
        raise ValueError(f"size distribution {spec!r}: fractions are by 'number' or 'mass', "
                         f"not {basis!r}")
    if len(diameters) == 0 or len(diameters) != len(fractions):
        raise ValueError(f"size distribution {spec!r}: give one fraction per diameter "
                         f"({len(diameters)} diameters, {len(fractions)} fractions)")
    d = np.array([_positive(spec, "diameter", str(x)) for x in diameters])
    w = []
    for x in fractions:
        try:
            value = float(x)
        except ValueError:
            raise ValueError(f"size distribution {spec!r}: fraction {x!r} is not a number") \
                from None
        if not (math.isfinite(value) and value >= 0.0):
            raise ValueError(f"size distribution {spec!r}: a fraction must be finite and "
                             f">= 0, got {x}")
        w.append(value)
    w = np.array(w)
    if basis == "mass":
        w = w / d ** 3
    if not w.sum() > 0.0:
        raise ValueError(f"size distribution {spec!r}: the fractions sum to zero")
    order = np.argsort(d)
    return SizeDistribution(spec, sizes=d[order], fractions=w[order] / w.sum())


def parse_distribution(spec):
    """The candidate name (a string) or a SizeDistribution for a distribution string (see
    NAMED and TABLES above); an error names what is wrong."""
    if isinstance(spec, SizeDistribution):
        return spec
    if spec is None or spec in DISTRIBUTIONS:
        return spec
    kind, _, rest = str(spec).partition(":")
    if kind in TABLES and rest:
        return read_size_table(rest, kind, spec)
    if kind in NAMED:
        names = NAMED[kind]
        args = rest.split(":") if rest else []
        if len(args) != len(names):
            raise ValueError(f"size distribution {spec!r}: {kind} takes "
                             f"{kind}:{':'.join(names)}")
        params = [_positive(spec, name, text) for name, text in zip(names, args)]
        if kind == "uniform" and not params[0] < params[1]:
            raise ValueError(f"size distribution {spec!r}: D_MIN must be below D_MAX")
        return SizeDistribution(spec, kind=kind, params=tuple(params))
    raise ValueError(f"unknown size distribution {spec!r}; use one of {sorted(DISTRIBUTIONS)}, "
                     "uniform:D_MIN:D_MAX, lognormal:D50:SIGMA, number:FILE or mass:FILE")


def diameters(n, distribution=None, match_cell=True):
    """n diameters [m] of the distribution (a candidate's name, a distribution string or a
    SizeDistribution), largest first."""
    parsed = parse_distribution(distribution)
    if isinstance(parsed, SizeDistribution):
        return parsed.diameters(n)
    d_sizes, counts = size_counts(n, match_cell=match_cell, distribution=parsed)
    return np.repeat(d_sizes, counts)[::-1].copy()


def number_mean(diameters, weights=None):
    """Σ w d / Σ w: the number-mean diameter (weights = counts or number fractions)."""
    d = np.asarray(diameters, float)
    w = np.ones_like(d) if weights is None else np.asarray(weights, float)
    return float(w @ d / w.sum())


def volume_mean(diameters, weights=None):
    """Σ w d⁴ / Σ w d³: the volume- (and, at one density, mass-) weighted mean diameter D[4,3]."""
    d = np.asarray(diameters, float)
    w = np.ones_like(d) if weights is None else np.asarray(weights, float)
    return float(w @ d ** 4 / (w @ d ** 3))


def paper_size_distribution(match_cell=True, n_sizes=N_SIZES, distribution=None):
    """Five diameters [m] and their number fractions (sum 1) of a candidate distribution.

    ``distribution`` names a key of DISTRIBUTIONS (default "maxent"; ``match_cell=False``
    without a name selects "mean-only", as before).  The fractions are the maximum-entropy
    distribution on the five diameters (evenly or geometrically spaced from 0.135 to 0.4 mm)
    subject to the candidate's constraints: the number mean 0.26 mm (or, for "volume-mean",
    the volume-weighted mean Σ p d⁴ / Σ p d³ = 0.26 mm) and, where imposed, the mean d^3
    implied by the paper's cell (3620 spheres, solid fraction 0.5, cube side 4.3 mm).
    "mean-only" would need a 4.53 mm cube at solid fraction 0.5.
    """
    spacing, mean_kind, cell = DISTRIBUTIONS[_distribution_name(distribution, match_cell)]
    d = (np.linspace if spacing == "even" else np.geomspace)(D_MIN, D_MAX, n_sizes)
    if mean_kind == "number":
        features, targets = [lambda x: x], [D_MEAN]
    else:                        # Σ p (d^4 - D d^3) = 0 is linear in p
        features, targets = [lambda x: x ** 4 - D_MEAN * x ** 3], [0.0]
    if cell:
        features.append(lambda x: x ** 3)
        targets.append(PHI_PAPER * L_PAPER ** 3 / (N_PAPER * _TWO_PI_OVER_6))
    p = _maxent(d, features, targets)
    if mean_kind == "number":
        # polish the mean to round-off: move the tiny residual into the end fractions
        # (keeps Σp = 1; the correction is at the 1e-16 level)
        resid = D_MEAN - float(p @ d)
        dp = resid / (d[-1] - d[0])
        p[-1] += dp
        p[0] -= dp
    return d, p


def size_counts(n, match_cell=True, distribution=None):
    """Integer counts per size for ``n`` spheres and the diameters [m] actually used.

    Counts: largest-remainder rounding of n × fractions (sum exactly n).  Because
    integer counts cannot reproduce a mean of exactly 0.26 mm with fixed diameters,
    the three interior diameters are shifted by one common, tiny amount (≈1e-5 mm for
    n = 3620) so that the candidate's mean (number mean, or D[4,3] for "volume-mean") is
    0.26 mm to round-off; the end diameters stay exactly 0.135 and 0.4 mm.
    """
    n = int(n)
    if n < N_SIZES:
        raise ValueError(f"need at least {N_SIZES} spheres, got {n}")
    name = _distribution_name(distribution, match_cell)
    d, p = paper_size_distribution(distribution=name)
    raw = n * p
    counts = np.floor(raw).astype(np.int64)
    short = n - int(counts.sum())
    order = np.argsort(-(raw - counts), kind="stable")
    counts[order[:short]] += 1
    if np.any(counts[1:-1] == 0):
        raise ValueError(f"n = {n} too small for the size distribution")
    d = d.copy()
    interior = slice(1, -1)
    if DISTRIBUTIONS[name][1] == "number":
        delta = (n * D_MEAN - float(counts @ d)) / float(counts[interior].sum())
        d[interior] += delta
        # second pass against round-off in the sum
        delta2 = (n * D_MEAN - float(counts @ d)) / float(counts[interior].sum())
        d[interior] += delta2
    else:
        # Newton on g(delta) = Σ c d^4 - D Σ c d^3 with the interior diameters shifted
        c = counts[interior].astype(float)
        for _ in range(50):
            g = float(counts @ d ** 4 - D_MEAN * (counts @ d ** 3))
            dg = float(c @ (4.0 * d[interior] ** 3 - 3.0 * D_MEAN * d[interior] ** 2))
            step = g / dg
            d[interior] -= step
            if abs(step) < 1e-17:
                break
    return d, counts


def box_side(diameters, solid_fraction):
    """Side [m] of the cube in which spheres of these diameters fill ``solid_fraction``."""
    vs = float(np.sum(_TWO_PI_OVER_6 * np.asarray(diameters, dtype=float) ** 3))
    return (vs / float(solid_fraction)) ** (1.0 / 3.0)


def solid_fraction(diameters, box):
    """Σ π d³/6 / V; ``box`` is the cube side or (Lx, Ly, Lz)."""
    vs = float(np.sum(_TWO_PI_OVER_6 * np.asarray(diameters, dtype=float) ** 3))
    box = np.broadcast_to(np.asarray(box, dtype=float), (3,))
    return vs / float(np.prod(box))


# ---------------------------------------------------------------------------
# neighbour search (cell list, minimum image)
# ---------------------------------------------------------------------------

def _pairs_within(pos, L, cutoff):
    """All pairs i<j with minimum-image distance < cutoff: (i, j, dvec, dist)."""
    n = len(pos)
    nc = int(L // cutoff)
    if nc < 3:
        i, j = np.triu_indices(n, k=1)
    else:
        cell = np.floor(pos * (nc / L)).astype(np.int64) % nc
        cid = (cell[:, 0] * nc + cell[:, 1]) * nc + cell[:, 2]
        order = np.argsort(cid, kind="stable")
        scid = cid[order]
        ncell = nc ** 3
        start = np.searchsorted(scid, np.arange(ncell), side="left")
        cnt = np.searchsorted(scid, np.arange(ncell), side="right") - start
        ii, jj = [], []
        idx = np.arange(n)
        for ox in (-1, 0, 1):
            for oy in (-1, 0, 1):
                for oz in (-1, 0, 1):
                    nb = (((cell[:, 0] + ox) % nc) * nc + (cell[:, 1] + oy) % nc) * nc \
                        + (cell[:, 2] + oz) % nc
                    c = cnt[nb]
                    tot = int(c.sum())
                    if tot == 0:
                        continue
                    rep_i = np.repeat(idx, c)
                    offs = np.arange(tot) - np.repeat(np.cumsum(c) - c, c)
                    rep_j = order[np.repeat(start[nb], c) + offs]
                    keep = rep_i < rep_j
                    ii.append(rep_i[keep])
                    jj.append(rep_j[keep])
        i = np.concatenate(ii)
        j = np.concatenate(jj)
    dv = pos[j] - pos[i]
    dv -= L * np.round(dv / L)
    dist = np.sqrt(np.einsum("ij,ij->i", dv, dv))
    m = dist < cutoff
    return i[m], j[m], dv[m], dist[m]


def find_overlaps(positions, diameters, L, gap=0.0):
    """Two index arrays (i, j), i < j, of the pairs whose minimum-image centre distance in the
    periodic cube of side L is below (r_i + r_j)(1 + gap): overlapping pairs at gap = 0 (touching
    pairs, at exactly r_i + r_j, are not listed). L is the side, or the three sides of a cube
    as read_data returns them."""
    sides = np.atleast_1d(np.asarray(L, dtype=float))
    if not np.all(sides == sides[0]):
        raise ValueError(f"find_overlaps: the cell must be a cube, got sides {sides.tolist()}")
    L = float(sides[0])
    pos = np.asarray(positions, dtype=float)
    d = np.asarray(diameters, dtype=float)
    i, j, _, dist = _pairs_within(np.mod(pos, L), L, float(d.max()) * (1.0 + gap))
    contact = 0.5 * (d[i] + d[j]) * (1.0 + gap)
    m = dist < contact
    return i[m], j[m]


# ---------------------------------------------------------------------------
# generation
# ---------------------------------------------------------------------------

def _wrap(pos, L):
    pos = np.mod(pos, L)
    pos[pos >= L] -= L          # np.mod can return L for tiny negative inputs
    pos[pos < 0.0] = 0.0
    return pos


def _rsa(diam, L, rng, gap, max_attempts):
    """Random sequential addition in order of ``diam`` (pure python + cell list)."""
    n = len(diam)
    dmax = float(diam.max())
    nc = max(1, int(L // (dmax * (1.0 + gap))))
    cw = L / nc
    cells = {}
    pos = np.empty((n, 3))
    # neighbour offsets (deduplicated when nc < 3)
    offsets = sorted({(ox % nc, oy % nc, oz % nc)
                      for ox in (-1, 0, 1) for oy in (-1, 0, 1) for oz in (-1, 0, 1)})
    for k in range(n):
        rk = 0.5 * diam[k]
        for _attempt in range(max_attempts):
            x = rng.random(3) * L
            c = (int(x[0] / cw) % nc, int(x[1] / cw) % nc, int(x[2] / cw) % nc)
            cand = []
            for o in offsets:
                lst = cells.get(((c[0] + o[0]) % nc, (c[1] + o[1]) % nc, (c[2] + o[2]) % nc))
                if lst:
                    cand.extend(lst)
            if cand:
                cand = np.asarray(cand)
                dv = pos[cand] - x
                dv -= L * np.round(dv / L)
                dist2 = np.einsum("ij,ij->i", dv, dv)
                lim = (0.5 * diam[cand] + rk) * (1.0 + gap)
                if np.any(dist2 < lim * lim):
                    continue
            pos[k] = x
            cells.setdefault(c, []).append(k)
            break
        else:
            raise RuntimeError(
                f"RSA jammed at sphere {k + 1}/{n} (solid fraction "
                f"{solid_fraction(diam[:k], L):.3f}); lower rsa_solid_fraction")
    return pos


def _relax(pos, diam, L, gap, overshoot=1e-2, damp=0.5, max_iter=20000):
    """Remove overlaps by iterative pairwise separation (Jacobi), Verlet list with skin."""
    n = len(pos)
    r = 0.5 * diam
    dmax = float(diam.max())
    skin = 0.25 * dmax
    # push overlapping pairs apart to a slightly larger distance than required
    target = 1.0 + 2.0 * gap + overshoot
    accept = 1.0 + gap
    it = 0
    while True:
        i, j, _, _ = _pairs_within(pos, L, dmax * target + skin)
        ref = pos.copy()
        sumr = r[i] + r[j]
        # weights: the smaller sphere moves more (inverse volume)
        wi = r[j] ** 3 / (r[i] ** 3 + r[j] ** 3)
        wj = 1.0 - wi
        while True:
            dv = pos[j] - pos[i]
            dv -= L * np.round(dv / L)
            dist = np.sqrt(np.einsum("ij,ij->i", dv, dv))
            bad = dist < sumr * accept
            if not np.any(bad):
                return _wrap(pos, L), it
            it += 1
            if it > max_iter:
                raise RuntimeError("overlap removal did not converge")
            b = np.nonzero(bad)[0]
            db = np.maximum(dist[b], 1e-12 * dmax)
            push = (sumr[b] * target - dist[b])[:, None] * dv[b] / db[:, None]
            disp = np.zeros((n, 3))
            for ax in range(3):
                disp[:, ax] -= np.bincount(i[b], weights=wi[b] * push[:, ax], minlength=n)
                disp[:, ax] += np.bincount(j[b], weights=wj[b] * push[:, ax], minlength=n)
            # a sphere in several overlaps receives the sum: damp to avoid overshoot
            nb = np.bincount(i[b], minlength=n) + np.bincount(j[b], minlength=n)
            disp /= np.maximum(nb, 1)[:, None] ** damp
            pos += disp
            moved = pos - ref
            moved -= L * np.round(moved / L)
            if np.max(np.einsum("ij,ij->i", moved, moved)) > (0.5 * skin) ** 2:
                pos = _wrap(pos, L)
                break                 # rebuild the neighbour list


def generate(n=N_PAPER, solid_fraction=PHI_PAPER, seed=1, match_cell=True, gap=1e-6,
             rsa_solid_fraction=0.30, compress_step=0.02, max_attempts=100000,
             return_info=False, distribution=None):
    """Random contact-free periodic assembly.

    Returns ``(box_side, diameters, positions)`` in metres, spheres ordered largest
    first; positions lie in [0, box_side)^3 and every minimum-image centre distance is
    at least (r_i + r_j)(1 + gap).  ``box_side`` is chosen so that Σ π d³/6 / L³ equals
    ``solid_fraction``.  If the target exceeds ``rsa_solid_fraction`` (RSA jams well
    below 0.5), RSA is done in a larger box and the assembly is compressed
    isotropically to the target in steps of ``compress_step`` (relative box side),
    removing overlaps after each step.  ``distribution`` names the size distribution
    (DISTRIBUTIONS; default "maxent").  ``return_info=True`` appends a dict.
    """
    t0 = time.perf_counter()
    phi_fn = globals()["solid_fraction"]
    parsed = parse_distribution(distribution)
    if isinstance(parsed, SizeDistribution):
        diam = parsed.diameters(n)
        d_sizes, counts = np.unique(diam, return_counts=True)
    else:
        d_sizes, counts = size_counts(n, match_cell=match_cell, distribution=parsed)
        diam = np.repeat(d_sizes, counts)[::-1].copy()      # largest first
    L = box_side(diam, solid_fraction)
    rng = np.random.default_rng(seed)
    phi0 = min(float(solid_fraction), float(rsa_solid_fraction))
    L0 = box_side(diam, phi0)
    pos = _rsa(diam, L0, rng, gap, max_attempts)
    t_rsa = time.perf_counter() - t0
    steps = 0
    relax_iters = 0
    Lc = L0
    while Lc > L:
        Ln = max(L, Lc * (1.0 - compress_step))
        if Ln - L < 1e-9 * L:
            Ln = L
        pos *= Ln / Lc
        Lc = Ln
        pos = _wrap(pos, Lc)
        pos, k = _relax(pos, diam, Lc, gap)
        relax_iters += k
        steps += 1
    pos = _wrap(pos, L)
    if return_info:
        info = {"counts": counts, "size_diameters": d_sizes, "rsa_box_side": L0,
                "rsa_solid_fraction": phi0, "compress_steps": steps,
                "relax_iterations": relax_iters, "time_rsa": t_rsa,
                "time": time.perf_counter() - t0,
                "solid_fraction": phi_fn(diam, L)}
        return L, diam, pos, info
    return L, diam, pos


# ---------------------------------------------------------------------------
# LAMMPS data file
# ---------------------------------------------------------------------------

def write_data(path, box, diameters, positions, density=DENSITY, comment=None):
    """Write a LAMMPS data file (``atom_style sphere``, ``units si``) atomically.

    Atoms lines: ``id type diameter density x y z``; box from 0 to L on every axis.
    """
    L = np.broadcast_to(np.asarray(box, dtype=float), (3,))
    d = np.asarray(diameters, dtype=float)
    x = np.asarray(positions, dtype=float)
    n = len(d)
    if x.shape != (n, 3):
        raise ValueError("positions must have shape (n, 3)")
    if comment is None:
        comment = (f"Thornton periodic-cell specimen: {n} spheres, solid fraction "
                   f"{solid_fraction(d, L):.6f} (tylmp.specimen)")
    lines = [f"LAMMPS data file - {comment}", "",
             f"{n} atoms", "1 atom types", "",
             f"0 {L[0]!r} xlo xhi", f"0 {L[1]!r} ylo yhi", f"0 {L[2]!r} zlo zhi", "",
             "Atoms # sphere", ""]
    rho = float(density)
    body = [f"{k + 1} 1 {d[k]!r} {rho!r} {x[k, 0]!r} {x[k, 1]!r} {x[k, 2]!r}"
            for k in range(n)]
    text = "\n".join(lines + body) + "\n"
    path = os.fspath(path)
    directory = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".specimen-", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    return path


def read_data(path):
    """Read back a file written by :func:`write_data`: (box (3,), diam, density, pos)."""
    box = np.zeros(3)
    rows = []
    in_atoms = False
    with open(path) as f:
        next(f)
        for line in f:
            s = line.split("#")[0].strip() if not line.startswith("Atoms") else line.strip()
            if not s:
                continue
            if s.startswith("Atoms"):
                in_atoms = True
                continue
            t = s.split()
            if not in_atoms:
                for a, key in enumerate(("xlo", "ylo", "zlo")):
                    if len(t) >= 3 and t[2] == key:
                        box[a] = float(t[1]) - float(t[0])
            else:
                rows.append([float(v) for v in t[:7]])
    a = np.array(rows)
    a = a[np.argsort(a[:, 0])]
    return box, a[:, 2], a[:, 3], a[:, 4:7]


def describe_distributions(n=N_PAPER):
    """Markdown table of the candidate distributions for n spheres: diameters and counts per
    size, number mean, D[4,3], standard deviation, cube side at solid fraction 0.5 and solid
    fraction in the paper's 4.3 mm cube (scaled to n spheres: side 4.3 mm × (n/3620)^(1/3))."""
    lines = ["| distribution | diameters [mm] | counts | number mean [mm] | D[4,3] [mm] | "
             "std [mm] | side at φ0 = 0.5 [mm] | φ0 in the paper's cube |",
             "|---|---|---|---|---|---|---|---|"]
    cube = L_PAPER * (n / N_PAPER) ** (1.0 / 3.0)
    for name in DISTRIBUTIONS:
        d, c = size_counts(n, distribution=name)
        diam = np.repeat(d, c)
        lines.append(
            f"| {name} | {', '.join(f'{x * 1e3:.5f}' for x in d)} | {', '.join(map(str, c))} | "
            f"{number_mean(d, c) * 1e3:.4f} | {volume_mean(d, c) * 1e3:.4f} | "
            f"{float(np.std(diam)) * 1e3:.4f} | {box_side(diam, PHI_PAPER) * 1e3:.4f} | "
            f"{solid_fraction(diam, cube):.4f} |")
    return "\n".join(lines)


# ---------------------------------------------------------------------------
# command line
# ---------------------------------------------------------------------------

def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="python3 -m tylmp.specimen",
        description="Random contact-free periodic sphere assembly (Thornton's specimen) "
                    "as a LAMMPS data file (units si, atom_style sphere).")
    ap.add_argument("--n", type=int, default=None,
                    help="number of spheres (default: from --scale; paper 3620)")
    ap.add_argument("--scale", choices=sorted(SCALES), default="paper",
                    help="paper: 3620 spheres; quick: 500 spheres, same distribution")
    ap.add_argument("--out", default="specimen.data", help="data file to write")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--solid-fraction", type=float, default=PHI_PAPER)
    ap.add_argument("--density", type=float, default=DENSITY,
                    help="particle density [kg/m^3] (default 2650e12, paper's scaling)")
    ap.add_argument("--gap", type=float, default=1e-6,
                    help="minimum relative gap between surfaces (default 1e-6)")
    ap.add_argument("--distribution", default=None,
                    help="size distribution: a candidate (" + ", ".join(sorted(DISTRIBUTIONS))
                         + "; default maxent), uniform:D_MIN:D_MAX, lognormal:D50:SIGMA, "
                         "number:FILE or mass:FILE (docs/specimen.md)")
    ap.add_argument("--mean-only", action="store_true",
                    help="max-entropy distribution constrained by the mean diameter only "
                         "(= --distribution mean-only)")
    ap.add_argument("--distributions", action="store_true",
                    help="print the candidate size distributions for n spheres (markdown table) "
                         "and exit")
    args = ap.parse_args(argv)
    n = args.n if args.n is not None else SCALES[args.scale]
    if args.distributions:
        print(describe_distributions(n))
        return 0
    if not 0.0 < args.solid_fraction < 0.6:
        ap.error("--solid-fraction must be in (0, 0.6)")
    if args.mean_only and args.distribution not in (None, "mean-only"):
        ap.error(f"--mean-only contradicts --distribution {args.distribution}")
    try:
        parse_distribution(args.distribution)
    except ValueError as err:
        ap.error(str(err))
    L, diam, pos, info = generate(n, args.solid_fraction, seed=args.seed,
                                  match_cell=not args.mean_only, gap=args.gap,
                                  return_info=True, distribution=args.distribution)
    write_data(args.out, L, diam, pos, density=args.density)
    ds = info["size_diameters"]
    print(f"wrote {args.out}: {n} spheres, cube side {L * 1e3:.6f} mm, "
          f"solid fraction {info['solid_fraction']:.12f}, "
          f"mean diameter {diam.mean() * 1e3:.12f} mm, seed {args.seed}")
    if len(ds) <= 20:
        print("sizes [mm] / counts: " + ", ".join(
            f"{d * 1e3:.6f}:{c}" for d, c in zip(ds, info["counts"])))
    else:
        print(f"{len(ds)} sizes from {diam.min() * 1e3:.6f} to {diam.max() * 1e3:.6f} mm")
    print(f"RSA at solid fraction {info['rsa_solid_fraction']:.3f} "
          f"(side {info['rsa_box_side'] * 1e3:.4f} mm), {info['compress_steps']} "
          f"compression steps, {info['relax_iterations']} relaxation sweeps, "
          f"{info['time']:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
