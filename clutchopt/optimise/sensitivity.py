"""Sensitivities at an optimum of a posed problem: the elasticity of the objective to every case quantity, every
fixed design variable and every constraint's limit, d ln f* / d ln p, from the gradient of the Lagrangian in the
parameters (envelope theorem), with the multipliers the solver returns."""

from __future__ import annotations

import math
from typing import Callable

import casadi as ca
import numpy as np

from clutchopt.optimise.compiled import compiled_function, is_compiled
from clutchopt.optimise.posed import Posed
from clutchopt.optimise.sx_columns import SXColumns, replayable
from clutchopt.optimise.verify import ConstraintCheck
from clutchopt.window_records import values_by_name


def _case_gradient(posed: Posed, batched: bool) -> ca.Function:
    """dL/dp_case of the scaled Lagrangian as a function of (x, p, lam_g); ``batched`` (for a window of points),
    compiled where the batched sweep's NLP functions are (``clutchopt.optimise.compiled``: the ball's; 1.6 ms a
    1000 points on CasADi's virtual machine, 0.2 compiled)."""
    def build(_):
        function = ca.Function("dL_dcase", [posed.nlp["x"], posed.nlp["p"], posed.lam_g],
                               [ca.gradient(posed.lagrangian, posed.p_case)])
        return compiled_function(function) if batched and is_compiled(posed.solver("sqp_chain")) else function

    return posed.built("case_gradient", batched, build)


def _window_gradient(posed: Posed) -> Callable:
    """The case gradient of a window's points, columns in and out: compiled (:func:`_case_gradient`), else replayed
    by NumPy over all the columns at once (``clutchopt.optimise.sx_columns``: the wedge's 1000 points in 0.2 ms
    against 0.65-1.0 on CasADi's virtual machine, the run store's largest cost in a stored sweep), else mapped on the
    virtual machine (columns padded to a power of two)."""
    def build(_):
        function = _case_gradient(posed, True)
        if replayable(function):
            return SXColumns(function)

        def mapped(x, p, lam_g):
            count = x.shape[1]
            width = 1 << (count - 1).bit_length()
            return tuple(out[:, :count] for out in posed.mapped(function, width)(*(_padded(a, width)
                                                                                  for a in (x, p, lam_g))))
        return mapped

    return posed.built("window_gradient", None, build)


def sensitivities(posed: Posed, run: dict, objective: float) -> dict[str, float]:
    """d ln f* / d ln p for every case quantity with a finite non-zero value and every fixed variable, at a
    run's primal-dual point (``x``, ``p``, ``lam_x``, ``lam_g``, ``lbx``, ``ubx``); see :func:`sensitivity_table`."""
    column = (np.reshape(run[key], (-1, 1)) for key in ("x", "p", "lam_x", "lam_g", "lbx", "ubx"))
    names, values, applies = sensitivity_table(posed, *column, np.array([objective]))
    return values_by_name(names, values.T.tolist(), applies.T.tolist())[0]


def with_followers(elasticities: dict[str, float], follows: dict[str, tuple[str, float]]) -> dict[str, float]:
    """Each source quantity's elasticity with those of the defaults that follow it added (``Case.follows``: a start-up's
    driven inertia and load follow the duty's, its start time limit t_p): editing the source moves them with it,
    d ln follower / d ln source = 1, so the optimum moves by the sum (the NLP holds them as parameters of their own,
    and its gradient in the source alone misses them: lever_motor_start's d ln m / d ln I read 0, re-solves +0.263)."""
    total = dict(elasticities)
    for name, (source, _factor) in follows.items():
        if name in elasticities and source in total:
            total[source] += elasticities[name]
    return total


def sensitivity_table(posed: Posed, x, p, lam_x, lam_g, lbx, ubx, objective: np.ndarray,
                      window: bool = False) -> tuple[list[str], np.ndarray, np.ndarray]:
    """:func:`sensitivities` of primal-dual points given as columns (their objectives in ``objective``) as a table,
    one column per point: the name of each row, its values and where it applies (``values_by_name`` makes each
    point's dict). The case gradients of a ``window``'s points (every point of it, one or more, so that a point read
    alone has the numbers of its window's records) by :func:`_window_gradient`, else on CasADi's virtual machine.

    Case quantities: f_scale * dL/dp (L the scaled Lagrangian), where the quantity's value is finite and non-zero.
    A continuous variable fixed through its bounds at b (a row after the quantities', added to a quantity of its
    name): its bound multiplier gives d f_hat / d(b / scale) = -lam_x. None apply where the objective is 0 or not
    finite.
    """
    f = posed.formulation
    m, n = len(f.quantities), len(f.variables)
    if window:
        gradient = _window_gradient(posed)(x, p, lam_g)[0]
    else:
        gradient = posed.mapped(_case_gradient(posed, False), len(objective))(x, p, lam_g)[0]
    values, scale, f_scale = p[:m], p[m:m + n], p[m + n]
    valid = (objective != 0) & np.isfinite(objective)
    continuous = [i for i, v in enumerate(f.variables) if not v.integer]  # fixed through their bounds: bound = value
    table = np.empty((m + len(continuous), len(objective)))  # the quantities' rows, then the fixed variables'
    applies = np.empty(table.shape, dtype=bool)  # (filled in place: no temporaries to concatenate, 20 % faster)
    elasticity = table[:m]
    with np.errstate(invalid="ignore", divide="ignore"):
        np.multiply(values, f_scale, out=elasticity)  # values * f_scale * gradient / objective in place: 5x faster
        elasticity *= gradient  # (the gradient is column-major; a row broadcast over it is slow)
        elasticity /= objective
        bound = lbx[continuous] * scale[continuous]
        np.negative(bound * f_scale * lam_x[continuous] / (scale[continuous] * objective), out=table[m:])
    np.isfinite(elasticity, out=applies[:m])
    applies[:m] &= values != 0
    np.equal(lbx[continuous], ubx[continuous], out=applies[m:])
    applies[m:] &= bound != 0
    applies &= valid
    return [q.name for q in f.quantities] + [f.variables[i].name for i in continuous], table, applies


def _padded(columns: np.ndarray, width: int) -> np.ndarray:
    """``columns`` padded to ``width`` by their last, in CasADi's column-major memory (which ``InPlace`` reads without
    a copy)."""
    padded = np.empty((width, columns.shape[0]))
    padded[:columns.shape[1]] = columns.T
    padded[columns.shape[1]:] = columns[:, -1]
    return padded.T


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
