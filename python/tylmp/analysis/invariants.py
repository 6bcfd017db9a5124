"""Principal-space invariants, Pi-plane coordinates and failure surfaces (docs/theory.md §7).

Mirrors plugin/core/pi_plane.hpp so that Python and the C++ fix agree:

* principal triples v = (v1, v2, v3) hold values along the box axes x, y, z (NOT sorted),
  compression positive, for stresses and natural strains alike;
* Pi plane: x = (v2 - v3)/sqrt 2, y = (2 v1 - v2 - v3)/sqrt 6, i.e. the deviator is
  s = x e_x + y e_y with e_x = (0, 1, -1)/sqrt 2 and e_y = (2, -1, -1)/sqrt 6; the radius
  sqrt(x^2 + y^2) equals the Frobenius norm |s|;
* Lode angle theta = atan2(x, y) in [0, 360) degrees, measured from the axis-1 direction:
  0 = axisymmetric compression along 1 (b = 0), 60 = extension along 3 (v1 = v2, b = 1),
  30 = b = 0.5, 120 = compression along 2, 180 = extension along 1, ...

All functions accept a single triple (shape (3,)) or a history (shape (n, 3)).
"""
import math

import numpy as np

SQRT2 = math.sqrt(2.0)
SQRT6 = math.sqrt(6.0)
PI_UNIT_X = np.array([0.0, 1.0, -1.0]) / SQRT2
PI_UNIT_Y = np.array([2.0, -1.0, -1.0]) / SQRT6

LADE_DUNCAN = "lade-duncan"
MATSUOKA_NAKAI = "matsuoka-nakai"
CRITERIA = (LADE_DUNCAN, MATSUOKA_NAKAI)


def _triples(v):
    a = np.asarray(v, dtype=float)
    if a.shape[-1] != 3:
        raise ValueError(f"expected principal triples (last axis of length 3), got shape {a.shape}")
    return a


def stack(v1, v2, v3):
    """(n,) columns -> (n, 3) triples."""
    return np.stack([np.asarray(v1, float), np.asarray(v2, float), np.asarray(v3, float)], axis=-1)


# ---- stress invariants -------------------------------------------------------------------

def invariants(sigma):
    """I1, I2, I3 of principal triples."""
    s = _triples(sigma)
    s1, s2, s3 = s[..., 0], s[..., 1], s[..., 2]
    return s1 + s2 + s3, s1 * s2 + s2 * s3 + s3 * s1, s1 * s2 * s3


def mean_stress(sigma):
    """p = I1/3."""
    return _triples(sigma).mean(axis=-1)


def deviator(v):
    a = _triples(v)
    return a - a.mean(axis=-1, keepdims=True)


def deviatoric_stress(sigma):
    """q = sqrt(3 J2) = sqrt(3/2) |s|."""
    return math.sqrt(1.5) * np.linalg.norm(deviator(sigma), axis=-1)


def sorted_descending(v):
    return -np.sort(-_triples(v), axis=-1)


def b_value(sigma):
    """b = (s2 - s3)/(s1 - s3) of the sorted values (paper eq. 1); NaN when isotropic."""
    s = sorted_descending(sigma)
    span = s[..., 0] - s[..., 2]
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(span == 0.0, np.nan, (s[..., 1] - s[..., 2]) / np.where(span == 0, 1, span))


def sinphi(sigma):
    """Mobilised friction sin(phi) = (s_max - s_min)/(s_max + s_min) (paper section 3)."""
    s = _triples(sigma)
    hi, lo = s.max(axis=-1), s.min(axis=-1)
    return (hi - lo) / (hi + lo)


def lade_duncan_eta(sigma):
    """eta = I1^3/I3 - 27 (paper eq. 2); 0 for an isotropic state."""
    i1, _, i3 = invariants(sigma)
    return i1 ** 3 / i3 - 27.0


def matsuoka_nakai_ratio(sigma):
    """I1 I2 / I3 (= 9 for an isotropic state)."""
    i1, i2, i3 = invariants(sigma)
    return i1 * i2 / i3


def criterion_value(criterion, sigma):
    if criterion == LADE_DUNCAN:
        return lade_duncan_eta(sigma)
    if criterion == MATSUOKA_NAKAI:
        return matsuoka_nakai_ratio(sigma)
    raise ValueError(f"unknown failure criterion {criterion!r}; use one of {CRITERIA}")


# ---- strain measures (docs/theory.md §7.1) --------------------------------------------------

def volumetric_strain(eps):
    return _triples(eps).sum(axis=-1)


def deviatoric_strain(eps):
    """eps_q = sqrt(2/3 e:e); equals 2/3 (eps1 - eps3) in axisymmetric compression."""
    return math.sqrt(2.0 / 3.0) * np.linalg.norm(deviator(eps), axis=-1)


# ---- Pi plane (docs/theory.md §7.2, plugin/core/pi_plane.hpp) ----------------------------------

def pi_coordinates(v):
    """(x, y) = ((v2 - v3)/sqrt 2, (2 v1 - v2 - v3)/sqrt 6), keeping the axis labels."""
    a = _triples(v)
    return (a[..., 1] - a[..., 2]) / SQRT2, (2.0 * a[..., 0] - a[..., 1] - a[..., 2]) / SQRT6


def pi_radius(v):
    x, y = pi_coordinates(v)
    return np.hypot(x, y)


def deviator_from_pi(x, y):
    """Traceless triple with Pi coordinates (x, y)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    return x[..., None] * PI_UNIT_X + y[..., None] * PI_UNIT_Y


def principal_from_pi(x, y, mean):
    return deviator_from_pi(x, y) + np.asarray(mean, float)[..., None]


def lode_angle_deg(x, y):
    """Lode angle from the axis-1 direction, tan(theta) = x/y, in [0, 360); NaN at the origin."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    theta = np.degrees(np.arctan2(x, y))
    theta = np.where(theta < 0.0, theta + 360.0, theta)
    return np.where((x == 0.0) & (y == 0.0), np.nan, theta)


def lode_angle_of(v):
    return lode_angle_deg(*pi_coordinates(v))


def pi_point(radius, lode_deg):
    t = np.radians(np.asarray(lode_deg, float))
    r = np.asarray(radius, float)
    return r * np.sin(t), r * np.cos(t)


def lode_from_b(b):
    """Lode angle (deg, in [0, 60]) of a sorted state sigma1 >= sigma2 >= sigma3 with ratio b:
    tan(theta) = sqrt(3) b/(2 - b)."""
    b = np.asarray(b, float)
    return np.degrees(np.arctan2(math.sqrt(3.0) * b, 2.0 - b))


def b_from_lode(theta_deg):
    """Inverse of lode_from_b on [0, 60] degrees: b = 2 t/(sqrt 3 + t), t = tan(theta)."""
    t = np.tan(np.radians(np.asarray(theta_deg, float)))
    return 2.0 * t / (math.sqrt(3.0) + t)


def fold_lode(theta_deg):
    """Map any Lode angle onto the sector [0, 60] by the symmetries of isotropic criteria
    (reflection about 0 deg and 60 deg, period 120 deg)."""
    t = np.mod(np.asarray(theta_deg, float), 120.0)
    return np.where(t > 60.0, 120.0 - t, t)


# ---- failure surfaces through a compression (b = 0) strength (docs/theory.md §7.3) --------------

def stress_ratio_from_sinphi(s):
    """K = sigma1/sigma3 = (1 + sin phi)/(1 - sin phi)."""
    s = np.asarray(s, float)
    return (1.0 + s) / (1.0 - s)


def sinphi_from_stress_ratio(K):
    K = np.asarray(K, float)
    return (K - 1.0) / (K + 1.0)


def state_at_ratio(K, b):
    """(K, 1 + b (K - 1), 1): sigma3 = 1, sigma1 = K, intermediate by b."""
    K, b = np.broadcast_arrays(np.asarray(K, float), np.asarray(b, float))
    return np.stack([K, 1.0 + b * (K - 1.0), np.ones_like(K)], axis=-1)


def criterion_constant(criterion, sinphi_tc):
    """Criterion value on the surface through (sinphi_tc, b = 0); e.g. LD eta = (K + 2)^3/K - 27."""
    return criterion_value(criterion, state_at_ratio(stress_ratio_from_sinphi(sinphi_tc), 0.0))


def sinphi_from_constant(criterion, constant, b):
    """sin(phi) at ratio b on the surface criterion = constant (bisection on K > 1, along which
    both criteria grow monotonically). Vectorised over b."""
    b = np.atleast_1d(np.asarray(b, float))
    if np.any((b < 0.0) | (b > 1.0)):
        raise ValueError(f"b must lie in [0, 1], got {b}")
    isotropic = criterion_value(criterion, np.ones(3))
    if not constant > isotropic:
        raise ValueError(f"{criterion} constant {constant} must exceed the isotropic value {isotropic}")
    lo = np.ones_like(b)
    hi = np.full_like(b, 2.0)
    while True:
        short = criterion_value(criterion, state_at_ratio(hi, b)) < constant
        if not short.any():
            break
        hi = np.where(short, hi * 2.0, hi)
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        below = criterion_value(criterion, state_at_ratio(mid, b)) < constant
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    return sinphi_from_stress_ratio(0.5 * (lo + hi))


def sinphi_on_surface(criterion, sinphi_tc, b):
    """sin(phi) at ratio b on the surface through the compression strength sinphi_tc."""
    if not 0.0 < sinphi_tc < 1.0:
        raise ValueError(f"sinphi_tc = {sinphi_tc} must lie in (0, 1)")
    out = sinphi_from_constant(criterion, criterion_constant(criterion, sinphi_tc), b)
    return out if np.ndim(b) else float(out[0])


def surface_radius(criterion, constant, lode_deg, p=1.0):
    """Pi-plane radius |s| of the surface criterion = constant at mean stress p and the given
    Lode angle(s)."""
    theta = fold_lode(np.atleast_1d(lode_deg))
    b = np.clip(b_from_lode(theta), 0.0, 1.0)
    K = stress_ratio_from_sinphi(sinphi_from_constant(criterion, constant, b))
    state = state_at_ratio(K, b)
    state = state * (p / state.mean(axis=-1))[..., None]
    return np.linalg.norm(deviator(state), axis=-1)


def failure_surface_pi(criterion, p=1.0, sinphi_tc=None, constant=None, n=361):
    """Closed Pi-plane curve (x, y) of a failure surface at mean stress p, either through the
    compression strength sinphi_tc or at a given criterion constant."""
    if constant is None:
        if sinphi_tc is None:
            raise ValueError("give sinphi_tc or constant")
        constant = criterion_constant(criterion, sinphi_tc)
    theta = np.linspace(0.0, 360.0, n)
    return pi_point(surface_radius(criterion, constant, theta, p), theta)


# ---- strain-path guides (paper Figs 7-9) ------------------------------------------------------

def circle_pi(radius, n=361):
    """Constant deviatoric strain path: circle of Pi radius `radius`."""
    theta = np.linspace(0.0, 360.0, n)
    return pi_point(radius, theta)


def plane_strain_triangle_pi(start_radius):
    """Triangular multi-axial plane-strain path (paper Fig. 8) starting from axisymmetric
    compression at Pi radius `start_radius`: legs of zero strain in one axis run parallel to
    that axis' zero line, so the vertices are the extension states at Lode 60, 180, 300 deg with
    radius 2 * start_radius, and the start (Lode 0) is the midpoint of the 300-60 side."""
    theta = np.array([60.0, 180.0, 300.0, 60.0])
    return pi_point(2.0 * start_radius, theta)
