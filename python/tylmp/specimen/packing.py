"""Positions of the specimen's spheres: random sequential addition (largest first, cell
list) in a box enlarged to a solid fraction where it cannot jam, then overlap-free isotropic
compression to the target (affine shrink steps, each followed by iterative removal of
overlaps); and the periodic neighbour search that both and `find_overlaps` use."""

import time

import numpy as np

from . import sizes
from .paper import N_PAPER, PHI_PAPER


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
                f"{sizes.solid_fraction(diam[:k], L):.3f}); lower rsa_solid_fraction")
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
    parsed = sizes.parse_distribution(distribution)
    if isinstance(parsed, sizes.SizeDistribution):
        diam = parsed.diameters(n)
        d_sizes, counts = np.unique(diam, return_counts=True)
    else:
        d_sizes, counts = sizes.size_counts(n, match_cell=match_cell, distribution=parsed)
        diam = np.repeat(d_sizes, counts)[::-1].copy()      # largest first
    L = sizes.box_side(diam, solid_fraction)
    rng = np.random.default_rng(seed)
    phi0 = min(float(solid_fraction), float(rsa_solid_fraction))
    L0 = sizes.box_side(diam, phi0)
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
                "solid_fraction": sizes.solid_fraction(diam, L)}
        return L, diam, pos, info
    return L, diam, pos
