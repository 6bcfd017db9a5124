"""The contacts' viscous damping ratio and the coefficient of restitution of a head-on Hertz
impact, each from the other (docs/theory.md §3.5): the decks' -var restitution."""

import math


def restitution_of_damping_ratio(beta):
    """Coefficient of restitution of a head-on Hertz impact under the viscous damping of pair
    thornton/yin with ratio beta (docs/theory.md §3.5): the dimensionless equation of motion
    x'' = -x^(3/2) - 2 beta sqrt(3/2) x^(1/4) x' from x = 0, x' = 1 until x returns to 0;
    e = -x' there, the same at every speed, mass and stiffness."""
    from scipy.integrate import solve_ivp
    if beta == 0.0:
        return 1.0

    def motion(_, y):
        x = max(y[0], 0.0)
        return [y[1], -x ** 1.5 - 2.0 * beta * math.sqrt(1.5) * x ** 0.25 * y[1]]

    def separated(_, y):
        return y[0]
    separated.terminal, separated.direction = True, -1
    sol = solve_ivp(motion, (0.0, 100.0), [0.0, 1.0], events=separated, rtol=1e-11,
                    atol=1e-14, first_step=1e-6)
    if not sol.t_events[0].size:         # overdamped: the spheres do not separate
        return 0.0
    return -float(sol.y_events[0][0][1])


def damping_ratio_for_restitution(e):
    """The damping ratio beta of pair thornton/yin whose head-on Hertz impact rebounds with
    restitution e, 0 < e <= 1 (restitution_of_damping_ratio inverted; docs/theory.md §3.5)."""
    from scipy.optimize import brentq
    if not 0.0 < e <= 1.0:
        raise ValueError(f"restitution {e} must lie in (0, 1]")
    if e == 1.0:
        return 0.0
    high = 0.1
    while restitution_of_damping_ratio(high) > e:
        high *= 2.0
    return brentq(lambda b: restitution_of_damping_ratio(b) - e, 0.0, high, xtol=1e-12)
