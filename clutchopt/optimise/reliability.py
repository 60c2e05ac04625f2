"""Small failure probabilities in the standard normal space of the scattered quantities: the design point (FORM),
its curvatures (SORM, Breitung), importance sampling centred at it, the system of all constraints, and the inverse
problem of a chance design, the performance point on the beta-sphere (PMA); docs/robust.md, "Small probabilities".

A limit state is ``g(u)``: u the independent standard normal variables (n rows, one column per point) the
scattered quantities are mapped from exactly (:func:`clutchopt.scatter.values_from_standard`), g one row per
constraint, in the difference form capacity - demand over a constant scale, failing where g < -``tolerance``.
Nothing here knows a clutch: :func:`clutchopt.optimise.robust_models.limit_states` builds g from a formulation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

LimitStates = Callable[[np.ndarray], np.ndarray]  # u (n, m) -> g (k, m)

STEP = 1e-5  # of the central differences of g in u (u is O(1); g is O(1) near the limit)
CURVATURE_STEP = 1e-3  # of the second differences (round-off eps / h^2 ~ 1e-10)
FORM_STEPS = 200  # HL-RF iterations
FORM_TOL = 1e-10  # of the design point's move, relative
NEGLIGIBLE = 1e-9  # |grad g| below this is round-off of the differences (eps / STEP ~ 1e-11): g does not depend on u
REACH = 9.0  # ||u|| beyond which no design point is sought: Phi(-9) = 1.1e-19
IS_SAMPLES = 50_000  # importance samples: about 0.7 % relative standard error at P = 1e-3 for a near-linear limit state
NO_FAILURE = "IS: no failure"  # the estimator of an importance sampling that saw none: 0, and no upper bound
Z_CONFIDENCE = 1.959963984540054  # 95 %: the normal quantile of the intervals of importance sampling


@dataclass(frozen=True)
class Estimate:
    """A failure probability, its interval (95 %; equal to it where the estimator gives none) and the estimator
    that gave it."""

    probability: float
    low: float
    high: float
    estimator: str

    def as_dict(self) -> dict:
        """JSON: an estimate that is not defined (SORM where 1 + beta kappa <= 0) as None."""
        return {"probability": _defined(self.probability), "low": _defined(self.low), "high": _defined(self.high),
                "estimator": self.estimator}


def ndtr(x):
    """Phi(x), scipy.special's, imported on first use (0.2 s: every solve imports this module, few use it)."""
    from scipy.special import ndtr as phi

    return phi(x)


def ndtri(p):
    """Phi^-1(p), imported on first use (see :func:`ndtr`)."""
    from scipy.special import ndtri as inverse

    return inverse(p)


def _defined(value: float) -> float | None:
    return value if math.isfinite(value) else None


@dataclass(frozen=True)
class DesignPoint:
    """The most probable failure point of one limit state: u* on g(u*) = 0 closest to the origin, beta = ||u*||,
    negative where the origin (the means) fails; ``found`` False where g does not depend on u (``beta`` +-inf) or
    the failure region lies beyond ``REACH``."""

    u: np.ndarray
    beta: float
    found: bool


def _at(g: LimitStates, row: int, points: np.ndarray) -> np.ndarray:
    return np.asarray(g(points), dtype=float)[row]


def value_gradient(g: LimitStates, row: int, u: np.ndarray) -> tuple[float, np.ndarray]:
    """g_row(u) and its gradient by central differences (one vectorised call of 2n + 1 points)."""
    n = len(u)
    points = np.column_stack([u, u[:, None] + STEP * np.eye(n), u[:, None] - STEP * np.eye(n)])
    values = _at(g, row, points)
    return float(values[0]), (values[1:n + 1] - values[n + 1:]) / (2 * STEP)


def hessian(g: LimitStates, row: int, u: np.ndarray) -> np.ndarray:
    """The second derivatives of g_row at u by central differences (one vectorised call of 4 n^2 points)."""
    n, h = len(u), CURVATURE_STEP
    eye = np.eye(n)
    shifts = [(i, j, si, sj) for i in range(n) for j in range(n) for si in (1, -1) for sj in (1, -1)]
    points = np.column_stack([u + h * (si * eye[i] + sj * eye[j]) for i, j, si, sj in shifts])
    values = _at(g, row, points)
    out = np.zeros((n, n))
    for (i, j, si, sj), value in zip(shifts, values):
        out[i, j] += si * sj * value / (4 * h * h)
    return (out + out.T) / 2


def design_point(g: LimitStates, row: int, n: int, tolerance: float = 0.0) -> DesignPoint:
    """FORM's design point of g_row by the Hasofer-Lind-Rackwitz-Fiessler iteration u <- (grad.u - g) grad /
    |grad|^2 (Rackwitz & Fiessler 1978), polished by SLSQP (min |u|^2 / 2 subject to g = 0) where it does not
    settle. Where g does not depend on u (|grad| < NEGLIGIBLE at the origin) it always holds (g >= -``tolerance``)
    or always fails: beta +-inf."""
    u = np.zeros(n)
    value, grad = value_gradient(g, row, u)
    if not np.linalg.norm(grad) >= NEGLIGIBLE:
        return DesignPoint(u, math.inf if value >= -tolerance else -math.inf, False)
    origin_fails = value < 0
    for _ in range(FORM_STEPS):
        norm2 = float(grad @ grad)
        if not norm2 >= NEGLIGIBLE ** 2:
            break
        new = (grad @ u - value) / norm2 * grad
        moved = float(np.linalg.norm(new - u))
        u = new
        if np.linalg.norm(u) > REACH:
            return DesignPoint(u, -math.inf if origin_fails else math.inf, False)
        value, grad = value_gradient(g, row, u)
        if moved <= FORM_TOL * (1.0 + np.linalg.norm(u)) and abs(value) < 1e-9:
            break
    else:
        u = _polished(g, row, u)
    beta = float(np.linalg.norm(u))
    return DesignPoint(u, -beta if origin_fails else beta, beta <= REACH)


def _polished(g: LimitStates, row: int, u: np.ndarray) -> np.ndarray:
    from scipy.optimize import minimize

    result = minimize(lambda v: 0.5 * v @ v, u, jac=lambda v: v, method="SLSQP",
                      constraints=[{"type": "eq", "fun": lambda v: value_gradient(g, row, v)[0],
                                    "jac": lambda v: value_gradient(g, row, v)[1]}], options={"ftol": 1e-14})
    return result.x


def form(point: DesignPoint) -> Estimate:
    """P = Phi(-beta): exact where g is linear in u."""
    return Estimate(float(ndtr(-point.beta)), float(ndtr(-point.beta)), float(ndtr(-point.beta)), "FORM")


def sorm(g: LimitStates, row: int, point: DesignPoint) -> Estimate:
    """Breitung's asymptotic SORM (Breitung 1984): P = Phi(-beta) prod_i (1 + beta kappa_i)^(-1/2), kappa_i the
    principal curvatures of g = 0 at the design point (positive curving away from the origin): the eigenvalues of
    the Hessian of g projected on the tangent plane over |grad g|. NaN where some 1 + beta kappa_i <= 0."""
    _, grad = value_gradient(g, row, point.u)
    if not np.linalg.norm(grad) >= NEGLIGIBLE:
        return Estimate(math.nan, math.nan, math.nan, "SORM (Breitung)")
    normal = grad / np.linalg.norm(grad)
    tangent = np.linalg.svd(np.eye(len(grad)) - np.outer(normal, normal))[0][:, :len(grad) - 1]
    curvatures = np.linalg.eigvalsh(tangent.T @ hessian(g, row, point.u) @ tangent / np.linalg.norm(grad))
    factors = 1.0 + point.beta * curvatures
    p = float(ndtr(-point.beta) / np.sqrt(np.prod(factors))) if np.all(factors > 0) else math.nan
    return Estimate(p, p, p, "SORM (Breitung)")


def importance_sampling(g: LimitStates, rows: list[int], centres: list[np.ndarray], n: int,
                        samples: int = IS_SAMPLES, seed: int = 0, tolerance: float = 0.0,
                        defensive: bool = True) -> Estimate:
    """P(any of ``rows`` fails) by importance sampling from the mixture of standard normals centred at each of
    ``centres`` (design points) and, ``defensive``, at the origin (which keeps the weights bounded where several
    failure regions meet: Hesterberg's defensive mixture; one constraint is sampled around its design point
    alone): weight phi(u) / q(u), the estimate the mean of weight x failed, its 95 % interval from the sample
    standard deviation (central limit)."""
    rng = np.random.default_rng(seed)
    means = np.array([*([np.zeros(n)] if defensive or not centres else []), *centres])
    pick = rng.integers(len(means), size=samples)
    u = rng.standard_normal((n, samples)) + means[pick].T
    # phi(u) / q(u) = 1 / mean_c exp(u.c - |c|^2 / 2)
    exponents = means @ u - 0.5 * np.sum(means * means, axis=1)[:, None]
    top = exponents.max(axis=0)
    weight = np.exp(-top) / np.mean(np.exp(exponents - top), axis=0)
    failed = np.any(np.asarray(g(u), dtype=float)[rows] < -tolerance, axis=0)
    terms = weight * failed
    if not failed.any():
        return Estimate(0.0, 0.0, 0.0, f"{NO_FAILURE} in {samples} samples")
    p = float(terms.mean())
    half = Z_CONFIDENCE * float(terms.std(ddof=1)) / math.sqrt(samples)
    return Estimate(p, max(0.0, p - half), min(1.0, p + half), "importance sampling")


def generalised_beta(probability: float) -> float:
    """-Phi^-1(P): the reliability index a failure probability corresponds to."""
    return float(-ndtri(probability))


def performance_point(g: LimitStates, row: int, n: int, beta: float) -> np.ndarray:
    """PMA's most probable point at ``beta`` (Tu, Choi & Park 1999): argmin g_row(u) on ||u|| = beta, by the
    advanced mean value iteration u <- -beta grad g / |grad g|, polished by SLSQP where it does not settle (it
    may cycle on a concave g). g_row(u) >= 0 there is the chance constraint P(g < 0) <= Phi(-beta) to first
    order."""
    u = np.zeros(n)
    for _ in range(FORM_STEPS):
        _, grad = value_gradient(g, row, u)
        norm = float(np.linalg.norm(grad))
        if not norm >= NEGLIGIBLE:
            return u  # g does not depend on the scatter here
        new = -beta * grad / norm
        if np.linalg.norm(new - u) <= FORM_TOL * (1.0 + beta):
            return new
        u = new
    from scipy.optimize import minimize

    result = minimize(lambda v: value_gradient(g, row, v)[0], u, jac=lambda v: value_gradient(g, row, v)[1],
                      method="SLSQP", constraints=[{"type": "eq", "fun": lambda v: v @ v - beta * beta,
                                                    "jac": lambda v: 2 * v}], options={"ftol": 1e-14})
    return result.x
