"""Sensitivities at an optimum of a posed problem: the elasticity of the objective to every case quantity, every
fixed design variable and every constraint's limit, d ln f* / d ln p, from the gradient of the Lagrangian in the
parameters (envelope theorem), with the multipliers the solver returns."""

from __future__ import annotations

import itertools
import math

import casadi as ca
import numpy as np

from clutchopt.optimise.posed import Posed
from clutchopt.optimise.verify import ConstraintCheck


def _case_gradient(posed: Posed) -> ca.Function:
    """dL/dp_case of the scaled Lagrangian as a function of (x, p, lam_g)."""
    return posed.built("case_gradient", None, lambda _: ca.Function(
        "dL_dcase", [posed.nlp["x"], posed.nlp["p"], posed.lam_g], [ca.gradient(posed.lagrangian, posed.p_case)]))


def sensitivities(posed: Posed, run: dict, objective: float) -> dict[str, float]:
    """d ln f* / d ln p for every case quantity with a finite non-zero value and every fixed variable, at a
    run's primal-dual point (``x``, ``p``, ``lam_x``, ``lam_g``, ``lbx``, ``ubx``); see :func:`sensitivity_columns`."""
    column = (np.reshape(run[key], (-1, 1)) for key in ("x", "p", "lam_x", "lam_g", "lbx", "ubx"))
    return sensitivity_columns(posed, *column, np.array([objective]))[0]


def sensitivity_columns(posed: Posed, x, p, lam_x, lam_g, lbx, ubx, objective: np.ndarray) -> list[dict[str, float]]:
    """:func:`sensitivities` of primal-dual points given as columns (their objectives in ``objective``), the case
    gradients by one mapped CasADi evaluation (columns padded to a power of two).

    Case quantities: f_scale * dL/dp (L the scaled Lagrangian). A variable fixed through its bounds at b:
    its bound multiplier gives d f_hat / d(b / scale) = -lam_x. None (an empty dict) where the objective is 0 or
    not finite.
    """
    f = posed.formulation
    count = len(objective)
    width = 1 << (count - 1).bit_length()
    padded = [np.pad(a, ((0, 0), (0, width - count)), mode="edge") if width > count else a for a in (x, p, lam_g)]
    m, n = len(f.quantities), len(f.variables)
    gradient = posed.mapped(_case_gradient(posed), width)(*padded)[0][:, :count]
    values, scale, f_scale = p[:m], p[m:m + n], p[m + n]
    with np.errstate(invalid="ignore", divide="ignore"):
        elasticity = values * f_scale * gradient / objective
        fixed = []  # (name, where it applies, its term) of each continuous variable fixed through its bounds
        for i, v in enumerate(f.variables):
            if not v.integer:
                value = lbx[i] * scale[i]
                fixed.append((v.name, ((lbx[i] == ubx[i]) & (value != 0)).tolist(),
                              (value * f_scale * lam_x[i] / (scale[i] * objective)).tolist()))
    names = [q.name for q in f.quantities]
    kept = (np.isfinite(elasticity) & (values != 0)).T.tolist()
    valid = ((objective != 0) & np.isfinite(objective)).tolist()
    result = []
    for j, (row, keep) in enumerate(zip(elasticity.T.tolist(), kept)):
        point = dict(itertools.compress(zip(names, row), keep)) if valid[j] else {}
        for name, applies, term in fixed if valid[j] else ():
            if applies[j]:
                point[name] = point.get(name, 0.0) - term[j]
        result.append(point)
    return result


def limit_elasticity(check: ConstraintCheck, lam: float, f_scale: float, objective: float) -> float | None:
    """d ln f* / d ln(limit) from the multiplier of the normalised constraint (envelope theorem).

    For "<=": g = (v - l)/s, so df*/d ln l = -lam f_s l/s; for ">=" the sign flips.
    """
    if objective == 0 or not math.isfinite(objective):
        return None
    return limit_elasticities(sense_sign(check.sense), lam, f_scale, check.limit, check.scale, objective)


def sense_sign(sense: str) -> float:
    """-1 for a "<=" constraint, 1 for ">=": the sign of d f* / d ln(limit) per unit multiplier."""
    return -1.0 if sense == "<=" else 1.0


def limit_elasticities(sign, lam, f_scale, limit, scale, objective):
    """:func:`limit_elasticity`'s formula, sign * lam f_s l / (s f*), on floats or arrays alike."""
    return sign * lam * f_scale * limit / (scale * objective)
