"""An oracle for the tangential force of a Hertzian contact under any history of the overlap
delta(t) and the tangential displacement s(t): the method of dimensionality reduction
(Popov & Hess, "Method of Dimensionality Reduction in Contact Mechanics and Friction",
Springer 2015, ch. 2 and 5; Hess 2011), which reproduces the Cattaneo-Mindlin-Deresiewicz
solution of the contact of elastic spheres exactly, without branch rules or reversal memories
(docs/theory.md §2.5).

Written from that method, not from plugin/core: a row of independent springs on
x in [0, x_max] (the contact is symmetric, so the half-row counts twice) under the rigid 1-D
profile g(x) = x^2/R*, normal stiffness E* and tangential stiffness 4 G* per unit length,
E* and G* as in docs/theory.md §0 (so that 2a E* = dP/d(delta) and 2a 4G* = 8 G* a):
  * a spring is in contact while w = delta - g(x) > 0; it enters with no tangential
    displacement and leaves with none;
  * in contact its tangential displacement u follows the rigid increment of s, then is held to
    the local Coulomb limit |4 G* u| <= mu E* w (slip of that spring);
  * P = 2 int E* w dx, T = 2 int 4 G* u dx.
A spring that enters during a step (delta rising linearly across its g(x)) takes only the part
of the step's ds after it entered. With a tangential displacement that turns in the plane, u
is a vector per spring held to the Coulomb disc: the exactness of the method is established
for collinear histories; for turning ones it is the Mindlin-Deresiewicz answer only as far as
the tractions of neighbouring annuli do not couple across directions, which is the reading of
the method used by Thornton's law too (docs/theory.md §2.5 says what this decides).
The number of springs sets the quadrature error: about 1e-4 of the force with 20 000.
"""
import numpy as np


class HertzMDR:
    """One Hertzian contact of effective radius R, contact moduli E* and G*, friction mu,
    stepped through a history of overlap and tangential displacement (dims = 1: collinear,
    2: a displacement in the tangent plane)."""

    def __init__(self, R, E_star, G_star, mu, delta_max, springs=20000, dims=1):
        self.R, self.E, self.G, self.mu, self.dims = R, E_star, G_star, mu, dims
        x_max = np.sqrt(R * delta_max) * 1.0005
        self.dx = x_max / springs
        self.x = (np.arange(springs) + 0.5) * self.dx
        self.g = self.x**2 / R
        self.u = np.zeros((springs, dims))
        self.delta = 0.0
        self.s = np.zeros(dims)
        self.dissipation = 0.0
        # Coulomb limit of u per unit of w: |4 G* u| <= mu E* w
        self.slope = mu * E_star / (4.0 * G_star)

    def copy(self):
        c = HertzMDR.__new__(HertzMDR)
        c.__dict__.update(self.__dict__)
        c.u = self.u.copy()
        c.s = self.s.copy()
        return c

    def step(self, delta, s):
        """Move to overlap delta and tangential displacement s (absolute); returns (P, T) with
        T a float (dims 1) or a vector (dims 2)."""
        s = np.atleast_1d(np.asarray(s, dtype=float))
        ds = s - self.s
        w_old, w = self.delta - self.g, delta - self.g
        inside_before, inside = w_old > 0.0, w > 0.0
        # springs in contact all step take all of ds; springs that enter take the part after
        # they entered (delta rises linearly across g(x) during the step)
        part = np.where(inside_before, 1.0, 0.0)
        entering = inside & ~inside_before
        if np.any(entering):
            part[entering] = w[entering] / (delta - self.delta)
        trial = np.where(inside[:, None], self.u + part[:, None] * ds[None, :], 0.0)
        limit = self.slope * np.maximum(w, 0.0)
        size = np.sqrt(np.sum(trial * trial, axis=1))
        over = size > limit
        scale = np.ones_like(size)
        scale[over] = limit[over] / size[over]
        new_u = trial * scale[:, None]
        # frictional work: local friction force mu E* w dx times the slip |trial - new|
        slip = size - np.minimum(size, limit)
        self.dissipation += 2.0 * np.sum(self.mu * self.E * np.maximum(w, 0.0) * slip) * self.dx
        self.u, self.delta, self.s = new_u, delta, s
        P = 2.0 * self.E * np.sum(np.maximum(w, 0.0)) * self.dx
        T = 2.0 * 4.0 * self.G * np.sum(self.u, axis=0) * self.dx
        return P, (T[0] if self.dims == 1 else T)

    def stored_energy(self):
        """Elastic energy of the tangential springs: 2 int 4 G* u^2 / 2 dx."""
        return 4.0 * self.G * np.sum(self.u * self.u) * self.dx

    def force(self):
        T = 2.0 * 4.0 * self.G * np.sum(self.u, axis=0) * self.dx
        return T[0] if self.dims == 1 else T

    def displacement_for_force(self, delta, T_target, guess=0.0):
        """The displacement s (dims 1) at which the contact moved to `delta` carries T_target,
        found on a copy (the state is unchanged): T is continuous and non-decreasing in s."""
        s0 = float(self.s[0])
        scale = max(abs(T_target), 1e-30) / (8.0 * self.G * np.sqrt(self.R * max(delta, 1e-300)))

        def force_at(s):
            return self.copy().step(delta, s)[1]

        lo, hi = s0 + guess - scale, s0 + guess + scale
        while force_at(lo) > T_target:
            lo -= 2.0 * (hi - lo)
        while force_at(hi) < T_target:
            hi += 2.0 * (hi - lo)
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if force_at(mid) < T_target:
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)


def hertz_overlap(P, R, E_star):
    """delta of the Hertz load P: P = (4/3) E* sqrt(R) delta^(3/2) (docs/theory.md §1.6)."""
    return (3.0 * np.maximum(P, 0.0) / (4.0 * E_star * np.sqrt(R))) ** (2.0 / 3.0)
