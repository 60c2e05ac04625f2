"""The Hertz contact of an outer ball on the grooved drum: eq. (9) made consistent (errata B5), with n_a, n_b of
the contact ellipse from the elliptic integrals, differentiable for the NLP and exact for reference."""

from __future__ import annotations

import math

from clutchopt.backend import cbrt, ellipke, exp, fmax, fmin, log, sqrt
from clutchopt.formulations.ball.equations import ball_load
from clutchopt.monotone import MonotoneFunction


def contact_modulus(p):
    """E* = 1 / ((1 - nu_1^2) / E_1 + (1 - nu_2^2) / E_2), the Hertz contact modulus (our reading of E' in (9))."""
    return 1.0 / ((1.0 - p.ball_poisson**2) / p.ball_modulus + (1.0 - p.drum_poisson**2) / p.drum_modulus)


def curvatures(radius, ball_radius, conformity):
    """Relative principal curvatures of ball on grooved drum: around the drum 1/r_c - 1/R_a, across the groove
    1/r_c - 1/(beta r_c). Returns (sum rho, B/A >= 1) with B/A the larger over the smaller (beta r_c < R_a):
    sum rho = (2 - 1/beta) / r_c - 1/R_a and B/A = (1 - r_c/R_a) / (1 - 1/beta), the same values written with each
    variable once in a factor, so that interval bounds over a box are tight (the sum and the quotient of the two
    curvatures had r_c in both terms: on a box 14 % wide in r_c near beta = 1.01, the bounds of the contact stress's
    slope in r_c were [-266, 233], now [-71, 57], against its values' [-2.5, -2.3]; docs/tradeoffs.md)."""
    across = 1.0 - 1.0 / conformity  # times 1/r_c
    return (2.0 - 1.0 / conformity) / ball_radius - 1.0 / radius, (1.0 - ball_radius / radius) / across


KAPPA_RANGE = (math.log(1.01), math.log(1e5))  # ln(B/A) over which the Newton start is fitted
KAPPA_START = (0.6195049581568469, -0.04819203413574859, 0.017114963528664155, -0.0010213762429290012,
               -0.005777536213994348, 0.0075816120696768595, -0.0072777845352428585, 0.003622163387927758,
               0.0015625642464741274, -0.002686491922902393, 0.0008446148249083446)
# ln(a/b) / ln(B/A) as a polynomial in t = (2 ln(B/A) - lo - hi) / (hi - lo): the degree-10 Chebyshev fit to the
# exact solution at 400 Chebyshev points of KAPPA_RANGE (scipy ellipk/ellipe and brentq); within 4e-6 of ln(a/b)
# there (tests/test_ball_closed_forms.py refits it)
NEWTON_STEPS = 1  # from the fitted start (4e-6): float64 accuracy, value and derivatives alike


def kappa_start(ratio):
    """ln(a/b) of the contact ellipse to 4e-6 for 1.01 <= B/A <= 1e5 (KAPPA_START); beyond, the fit at its ends."""
    lo, hi = KAPPA_RANGE
    log_ratio = log(ratio)
    t = fmin(fmax((2.0 * log_ratio - lo - hi) / (hi - lo), -1.0), 1.0)
    value = 0.0
    for coefficient in reversed(KAPPA_START):  # Horner
        value = value * t + coefficient
    return log_ratio * value


def _curvature_ratio(m):
    """B/A = ((1/(1 - m)) E - K) / (K - E) of the contact ellipse, e^2 = m = 1 - (b/a)^2, and d(B/A)/dm; K, E."""
    k, e = ellipke(m)
    num, den = e / (1.0 - m) - k, k - e
    de, dk = (e - k) / (2.0 * m), (e - (1.0 - m) * k) / (2.0 * m * (1.0 - m))
    dnum, dden = e / (1.0 - m) ** 2 + de / (1.0 - m) - dk, dk - de
    return num / den, (dnum * den - num * dden) / den**2, k, e


def _hertz_coefficients(ratio):
    """Hertz's n_a, n_b (Timoshenko's m, n) of an elliptic contact with curvature ratio B/A = ``ratio`` >= 1.01:
    a = n_a (3F / (2 E* sum rho))^(1/3), b = n_b (...)^(1/3).

    Solves B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e)) for kappa = ln(a/b) by Newton (NEWTON_STEPS) from a
    fitted start (:func:`kappa_start`) with K, E by the AGM (:func:`clutchopt.backend.ellipke`); then
    n_a^3 = 2 (K - E) (1 + B/A) / (pi e^2), n_b = n_a b/a. Differentiable in CasADi; agrees with the exact
    solution (:func:`hertz_coefficients_exact`) to 1e-10 for 1.01 <= B/A <= 1e5 (tested).
    """
    kappa = kappa_start(ratio)
    for _ in range(NEWTON_STEPS):
        m = 1.0 - exp(-2.0 * kappa)
        r, dr, _, _ = _curvature_ratio(m)
        kappa = kappa - (log(r) - log(ratio)) * r / (dr * 2.0 * (1.0 - m))
    m = 1.0 - exp(-2.0 * kappa)
    k, e = ellipke(m)
    n_a = cbrt(2.0 * (k - e) * (1.0 + ratio) / (math.pi * m))
    return n_a, n_a * sqrt(1.0 - m)


HERTZ_ERROR = 1e-9  # relative: 10 times the agreement with the exact solution tested (tests/test_ball_closed_forms.py)
hertz_coefficients = MonotoneFunction(
    _hertz_coefficients, increasing=(True, False), slope_increasing=(False, True), domain=(1.01, 1e5),
    error=HERTZ_ERROR, source="n_a rises and n_b falls with B/A (the classical table of m, n: Timoshenko & Goodier, "
    "Theory of Elasticity, Hertz contact of two bodies); n_a concave and n_b convex in B/A: our check at 200,001 "
    "points of the domain, tests/test_interval_nodes.py")
hertz_coefficients.__doc__ = _hertz_coefficients.__doc__


def _hertz_area_coefficient(ratio):
    """n_a n_b: the contact area pi a b in units of pi (3F / (2 E* sum rho))^(2/3), what the peak pressure takes."""
    n_a, n_b = _hertz_coefficients(ratio)
    return (n_a * n_b,)


hertz_area_coefficient = MonotoneFunction(
    _hertz_area_coefficient, increasing=(True,), slope_increasing=(False,), domain=(2.6, 1e5), error=3 * HERTZ_ERROR,
    source="n_a n_b rises with B/A, concave above B/A = 2.55 (its inflection): our check at 200,001 points of the "
    "domain, tests/test_interval_nodes.py; its error: the product of two values within HERTZ_ERROR each")
hertz_area_coefficient.__doc__ = _hertz_area_coefficient.__doc__


def hertz_coefficients_exact(ratio):
    """n_a, n_b by bracketing the exact elliptic-integral equation (scipy ellipk/ellipe); floats only, reference."""
    from scipy.optimize import brentq  # (imported where this reference is used, the paper procedure's: 0.3-0.4 s a
    from scipy.special import ellipe, ellipk  # process, which the ball's design-mode solve no longer pays)

    m = brentq(lambda m: (ellipe(m) / (1 - m) - ellipk(m)) / (ellipk(m) - ellipe(m)) - ratio, 1e-9, 1 - 1e-15,
               xtol=1e-300, rtol=1e-15)
    n_a = (2 * (ellipk(m) - ellipe(m)) * (1 + ratio) / (math.pi * m)) ** (1 / 3)
    return n_a, n_a * math.sqrt(1 - m)


def hertz_peak_pressure(load, curvature_sum, modulus, n_a, n_b):
    """p_0 = 3F / (2 pi a b) = 1.5 / (pi n_a n_b) (F (2 E* sum rho / 3)^2)^(1/3): the Hertz form behind (9)."""
    return 1.5 / (math.pi * n_a * n_b) * cbrt(load * (2.0 * modulus * curvature_sum / 3.0) ** 2)


def contact_stress(p, radius, filling, ball_radius, conformity):
    """p_0 of the outer balls on the drum, eq. (9) made consistent (errata B5): Hertz with the ball load and the
    contact's own curvatures, n_a, n_b from the elliptic integrals. p_0 takes F and sum rho as F sum rho^2 only, so
    they are passed as F / r_c^2 (the ball load of a unit ball radius, F being proportional to r_c^2) and
    r_c sum rho = 2 - 1/beta - r_c/R_a: the same value with r_c once, whose interval bounds are tight (F rises and
    sum rho^2 falls with r_c nearly in proportion: replayed apart, the bounds of the slope in r_c were 30x its
    values' span; docs/tradeoffs.md); and n_a n_b as one declared value (:data:`hertz_area_coefficient`, passed
    as n_a with n_b = 1), whose bounds are its values at the ends of B/A (n_a rises and n_b falls: bounded apart,
    their product's slope in beta was 15x too wide)."""
    _, ratio = curvatures(radius, ball_radius, conformity)
    area, = hertz_area_coefficient(ratio)
    relative_sum = 2.0 - 1.0 / conformity - ball_radius / radius  # r_c sum rho (curvatures)
    return hertz_peak_pressure(ball_load(p, radius, filling, 1.0), relative_sum, contact_modulus(p), area, 1.0)
