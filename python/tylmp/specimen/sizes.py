"""Size distributions of the specimen (docs/specimen.md): the paper's candidates (the
maximum-entropy number distribution on five sizes under the facts the paper states, and three
other readings of them) and a user's distribution (uniform, lognormal, or a table by number or
mass); diameters of n spheres, their means, and the cube that holds them at a solid fraction."""

import math

import numpy as np

from .paper import D_MAX, D_MEAN, D_MIN, L_PAPER, N_PAPER, N_SIZES, PHI_PAPER

_TWO_PI_OVER_6 = math.pi / 6.0


def _dot(a, b):
    """Σ a_i b_i, correctly rounded (math.fsum of the exact-rounded products): the same bits on
    every machine. NumPy's `@` calls the BLAS, whose kernels (chosen at run time by the
    processor) sum in different orders, and a last-bit change of a diameter makes another
    specimen (docs/specimen.md "Reproducibility")."""
    return math.fsum(float(x) * float(y) for x, y in zip(a, b))


def _solve(A, b):
    """x with A x = b for a small dense system (Gaussian elimination, partial pivoting), in
    plain floating point for the same reason as _dot."""
    k = len(b)
    M = [[float(A[r][c]) for c in range(k)] + [float(b[r])] for r in range(k)]
    for c in range(k):
        piv = max(range(c, k), key=lambda r: abs(M[r][c]))
        M[c], M[piv] = M[piv], M[c]
        for r in range(c + 1, k):
            f = M[r][c] / M[c][c]
            M[r] = [M[r][q] - f * M[c][q] for q in range(k + 1)]
    x = [0.0] * k
    for r in reversed(range(k)):
        x[r] = (M[r][k] - math.fsum(M[r][q] * x[q] for q in range(r + 1, k))) / M[r][r]
    return x


def _maxent(d, constraints, targets, iters=200):
    """Maximum-entropy weights p_i ∝ exp(-Σ_k λ_k f_k(d_i)) with Σ p_i f_k(d_i) = t_k.

    Newton's method on the (convex) dual; features are scaled to O(1) for conditioning. Plain
    floating point with correctly rounded sums (_dot, _solve): the weights, and so the
    specimen, are the same bits on every machine.
    """
    F = [[float(v) for v in f(d)] for f in constraints]            # k rows of n
    scale = [max(abs(v) for v in row) for row in F]
    F = [[v / s for v in row] for row, s in zip(F, scale)]
    t = [float(v) / s for v, s in zip(targets, scale)]
    n, k = len(F[0]), len(t)
    cols = [[F[r][i] for r in range(k)] for i in range(n)]        # the features of each d_i
    lam = [0.0] * k
    for _ in range(iters):
        a = [-_dot(lam, col) for col in cols]
        top = max(a)
        w = [math.exp(v - top) for v in a]
        total = math.fsum(w)
        p = [v / total for v in w]
        m = [_dot(row, p) for row in F]
        g = [mr - tr for mr, tr in zip(m, t)]       # gradient of the dual (up to sign)
        if max(abs(v) for v in g) < 1e-15:
            break
        # covariance = Hessian
        C = [[_dot([x * y for x, y in zip(F[r], F[c])], p) - m[r] * m[c] for c in range(k)]
             for r in range(k)]
        step = _solve(C, g)
        # Newton: the dual log Σ exp(-λ·F) + λ·t has gradient t - m and Hessian C
        lam = [v + s for v, s in zip(lam, step)]
    else:
        raise RuntimeError("maximum-entropy size distribution did not converge")
    return np.array(p)


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
    return _dot(w, d) / math.fsum(w)


def volume_mean(diameters, weights=None):
    """Σ w d⁴ / Σ w d³: the volume- (and, at one density, mass-) weighted mean diameter D[4,3]."""
    d = np.asarray(diameters, float)
    w = np.ones_like(d) if weights is None else np.asarray(weights, float)
    return _dot(w, d ** 4) / _dot(w, d ** 3)


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
        resid = D_MEAN - _dot(p, d)
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
        delta = (n * D_MEAN - _dot(counts, d)) / float(counts[interior].sum())
        d[interior] += delta
        # second pass against round-off in the sum
        delta2 = (n * D_MEAN - _dot(counts, d)) / float(counts[interior].sum())
        d[interior] += delta2
    else:
        # Newton on g(delta) = Σ c d^4 - D Σ c d^3 with the interior diameters shifted
        c = counts[interior].astype(float)
        for _ in range(50):
            g = _dot(counts, d ** 4) - D_MEAN * _dot(counts, d ** 3)
            dg = _dot(c, 4.0 * d[interior] ** 3 - 3.0 * D_MEAN * d[interior] ** 2)
            step = g / dg
            d[interior] -= step
            if abs(step) < 1e-17:
                break
    return d, counts


def box_side(diameters, solid_fraction):
    """Side [m] of the cube in which spheres of these diameters fill ``solid_fraction``."""
    vs = math.fsum(_TWO_PI_OVER_6 * np.asarray(diameters, dtype=float) ** 3)
    return (vs / float(solid_fraction)) ** (1.0 / 3.0)


def solid_fraction(diameters, box):
    """Σ π d³/6 / V; ``box`` is the cube side or (Lx, Ly, Lz)."""
    vs = math.fsum(_TWO_PI_OVER_6 * np.asarray(diameters, dtype=float) ** 3)
    box = np.broadcast_to(np.asarray(box, dtype=float), (3,))
    return vs / float(np.prod(box))


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
