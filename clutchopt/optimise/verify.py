"""Float64 re-evaluation of a design, outside the solver: every constraint's value, limit, margin, activity."""

from __future__ import annotations

from dataclasses import dataclass, fields
from operator import attrgetter
from types import SimpleNamespace

import numpy as np

from clutchopt.model import Constraint, Formulation, Objective, Output, namespace
from clutchopt.units import si_unit

FEASIBILITY_TOL = 1e-8  # largest relative violation accepted as feasible
ACTIVE_TOL = 1e-6  # relative margin below which a constraint is reported active


@dataclass(slots=True)  # (no attribute beyond its fields: a record's keys, and a stored window's, are these)
class ConstraintCheck:
    name: str
    equation: str
    sense: str
    value: float  # SI
    limit: float  # SI
    margin: float  # relative: (limit - value)/scale for "<=", (value - limit)/scale for ">="
    active: bool
    feasible: bool
    unit: str  # display unit (values in the JSON are SI)
    description: str
    scale: float  # the normaliser of the margin (SI)
    multiplier: float | None = None  # of the normalised constraint, objective normalised
    elasticity: float | None = None  # d ln(objective) / d ln(limit)
    tolerance: float = FEASIBILITY_TOL  # largest relative violation that is feasible (a start-up's: its case's)

    def as_dict(self) -> dict:
        """SI values; ``unit`` is their SI unit, ``display_unit`` the one the tables show them in."""
        record = dict(zip(CHECK_FIELDS, _check_fields(self)))  # fields are plain values
        record["unit"], record["display_unit"] = si_unit(self.unit), self.unit
        return record


CHECK_FIELDS = tuple(field.name for field in fields(ConstraintCheck))
_check_fields = attrgetter(*CHECK_FIELDS)


def check_design(formulation: Formulation, design: dict[str, float], params: SimpleNamespace) -> list[ConstraintCheck]:
    """Evaluate every constraint of ``formulation`` at ``design`` in float64 (the same equations, no CasADi)."""
    x = namespace({k: float(v) for k, v in design.items()})
    return check_constraints(formulation.constraints(x, params))


def check_constraints(constraints: list[Constraint], tolerance: float = FEASIBILITY_TOL) -> list[ConstraintCheck]:
    """Float64 constraints as checks; one evaluated at several points (arrays: a start-up's path, the corners of a
    scatter) reports its worst point."""
    checks = []
    for c in constraints:
        raw_scale = c.limit if c.scale is None else c.scale
        if all(isinstance(v, (int, float)) for v in (c.value, c.limit, raw_scale)):  # one point (most constraints):
            value, limit, scale = float(c.value), float(c.limit), float(raw_scale)  # no array work, same arithmetic
            margin = relative_margin(c.sense == "<=", value, limit, scale)
        else:
            values, limits, scales = np.broadcast_arrays(*(np.atleast_1d(np.asarray(v, dtype=float))
                                                           for v in (c.value, c.limit, raw_scale)))
            margins = relative_margin(c.sense == "<=", values, limits, scales)
            worst = int(np.nanargmin(margins)) if not np.isnan(margins).all() else 0
            value, limit, scale, margin = (float(a[worst]) for a in (values, limits, scales, margins))
        checks.append(constraint_check(c, value, limit, scale, margin, tolerance))
    return checks


def constraint_check(c: Constraint, value: float, limit: float, scale: float, margin: float,
                     tolerance: float = FEASIBILITY_TOL, multiplier: float | None = None,
                     flags: tuple[bool, bool] | None = None) -> ConstraintCheck:
    """A constraint's float64 figures as a check: active within ACTIVE_TOL (or violated), feasible within
    ``tolerance`` (``flags``: those two, where :func:`margin_flags` took them already)."""
    active, feasible = margin_flags(margin, tolerance) if flags is None else flags
    return ConstraintCheck(
        name=c.name, equation=c.equation, sense=c.sense, value=value, limit=limit,
        margin=margin, active=active, feasible=feasible,
        unit=c.unit, description=c.description, scale=scale, multiplier=multiplier, tolerance=tolerance)


def margin_flags(margin, tolerance: float = FEASIBILITY_TOL):
    """Whether a constraint with this relative margin is active (within ACTIVE_TOL, or violated) and feasible
    (within ``tolerance``): booleans for a float, arrays for an array (a NaN margin is neither)."""
    return (abs(margin) <= ACTIVE_TOL) | (margin < 0), margin >= -tolerance


def column_checks(constraints: list[Constraint], table: tuple[np.ndarray, ...]) -> list[list[ConstraintCheck]]:
    """Each point's checks (a list per column of :func:`constraint_table`'s ``table``), the flags taken over the
    whole table at once: :func:`constraint_check`'s figures and flags, the same bits (one design at a run of a
    sweep's points, ``verdict.figures_at``: a check's flags had cost as much as its object)."""
    value, limit, scale, margin = (column.tolist() for column in table)
    active, feasible = (flags.tolist() for flags in margin_flags(table[3]))
    return [[constraint_check(c, value[i][j], limit[i][j], scale[i][j], margin[i][j],
                              flags=(active[i][j], feasible[i][j])) for i, c in enumerate(constraints)]
            for j in range(table[0].shape[1])]


def constraint_table(constraints: list[Constraint], count: int) -> tuple[np.ndarray, ...]:
    """Value, limit, scale and relative margin of each float64 constraint (rows) at ``count`` points (columns; a
    constraint that does not vary is broadcast)."""
    table = np.empty((3, len(constraints), count))
    for i, c in enumerate(constraints):
        table[0, i], table[1, i] = c.value, c.limit
        table[2, i] = c.limit if c.scale is None else c.scale
    value, limit, scale = table
    at_most = np.array([c.sense == "<=" for c in constraints], dtype=bool)[:, None]
    with np.errstate(invalid="ignore", divide="ignore"):
        margin = relative_margin(at_most, value, limit, scale)
    return value, limit, scale, margin


def column_figures(formulation: Formulation, objective: Objective, x: SimpleNamespace, params: SimpleNamespace,
                   count: int) -> tuple[list[Constraint], tuple[np.ndarray, ...], np.ndarray]:
    """The float64 constraints of ``formulation`` at ``x`` and ``params`` whose values are arrays of ``count``
    columns (a point each) or floats (the same at every point), their table (:func:`constraint_table`: value, limit,
    scale, margin) and ``objective``'s value at each point, shape (count,). Batched points
    (``batch_window.Checked``) and one design at several cases (``verdict.figures_at``) are checked by it."""
    with np.errstate(all="ignore"):
        constraints = formulation.constraints(x, params)
        values = np.broadcast_to(np.asarray(objective.function(x, params), dtype=float), (count,))
    return constraints, constraint_table(constraints, count), values


def column_outputs(formulation: Formulation, x: SimpleNamespace, params: SimpleNamespace,
                   count: int) -> dict[str, tuple[np.ndarray, Output]]:
    """The derived quantities of ``formulation`` at the same columns as :func:`column_figures`: each one's values,
    shape (count,), and its declaration."""
    with np.errstate(all="ignore"):
        return {name: (np.broadcast_to(np.asarray(out.value, dtype=float), (count,)), out)
                for name, out in formulation.outputs(x, params).items()}


def relative_margin(at_most, value, limit, scale):
    """(limit - value) / scale where the constraint is "<=" (``at_most``), (value - limit) / scale where ">=": on
    floats, or on arrays with ``at_most`` a boolean array (one per row). The same bits either way: a - b is
    exactly -(b - a)."""
    sign = np.where(at_most, 1.0, -1.0) if isinstance(at_most, np.ndarray) else (1.0 if at_most else -1.0)
    return sign * (limit - value) / scale


def evaluate_outputs(formulation: Formulation, design: dict[str, float], params: SimpleNamespace) -> dict[str, Output]:
    """Derived quantities at ``design``, values as floats."""
    x = namespace({k: float(v) for k, v in design.items()})
    return {name: Output(float(out.value), out.unit, out.description)
            for name, out in formulation.outputs(x, params).items()}


def evaluate_objective(formulation: Formulation, objective: str, design: dict[str, float], params: SimpleNamespace) -> float:
    x = namespace({k: float(v) for k, v in design.items()})
    return float(formulation.objective(objective).function(x, params))
