"""A design's constraints as limit states in the standard normal space of its scatter, and what the reliability
methods (``clutchopt.optimise.reliability``) make of them: each constraint's design point, FORM, SORM and
importance sampling, the system's failure probability, and a chance design's performance points
(``clutchopt.optimise.robust``; docs/robust.md).

The form of every limit state: the difference g = (capacity - demand) / s, capacity - demand = limit - value for a
``<=`` constraint (value - limit for ``>=``), s the constraint's scale at the means of the scatter, a constant: so
g is linear in u wherever value and limit are (the torque T - T_max is linear in a normal inertia), which the ratio
1 - T / T_max is not.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from clutchopt.model import Formulation
from clutchopt.optimise.reliability import (
    NO_FAILURE,
    DesignPoint,
    Estimate,
    design_point,
    form,
    importance_sampling,
    performance_point,
    sorm,
)
from clutchopt.optimise.robust_models import SEED, constraints_at
from clutchopt.optimise.verify import FEASIBILITY_TOL, constraint_table
from clutchopt.scatter import values_from_standard


def limit_states(formulation: Formulation, design: dict, params: SimpleNamespace, scatter, correlation=None,
                 names: tuple[str, ...] | None = None):
    """(the constraints' names, g): g(u) one row per constraint (those in ``names``, or all) in the difference
    form over its scale at the means (module docstring), u independent standard normals (n rows)."""
    n = len(scatter)
    at_means = constraints_at(formulation, design, params, values_from_standard(scatter, np.zeros((n, 1)), correlation))
    rows = [i for i, c in enumerate(at_means) if names is None or c.name in names]
    scale = constraint_table(at_means, 1)[2][rows, 0]
    sign = np.array([1.0 if at_means[i].sense == "<=" else -1.0 for i in rows])[:, None]

    def g(u: np.ndarray) -> np.ndarray:
        u = np.atleast_2d(u)
        constraints = constraints_at(formulation, design, params, values_from_standard(scatter, u, correlation))
        value, limit = constraint_table(constraints, u.shape[1])[:2]
        with np.errstate(invalid="ignore", divide="ignore"):
            return sign * (limit[rows] - value[rows]) / scale[:, None]

    return tuple(at_means[i].name for i in rows), g


@dataclass
class ConstraintReliability:
    """One constraint at a design: its design point (in u, and as the quantities' values) and the estimates."""

    point: DesignPoint
    values: dict[str, float]  # quantity -> its value at the design point (SI)
    estimates: list[Estimate]  # FORM, SORM, importance sampling (where there is a design point), or one exact

    @property
    def best(self) -> Estimate:
        """The estimate to go by: importance sampling where there is one and it saw a failure, else SORM where it is
        defined, else FORM (an importance sampling that saw none shows no upper bound: its "0 to 0" is no
        interval), else the only one."""
        shown = [e for e in self.estimates if not e.estimator.startswith(NO_FAILURE) and not math.isnan(e.probability)]
        return (shown or self.estimates)[-1]

    def as_dict(self) -> dict:
        return {"beta": _finite(self.point.beta), "design_point": self.values if self.point.found else None,
                "estimates": [e.as_dict() for e in self.estimates], "failure_probability": self.best.as_dict()}


@dataclass
class Reliability:
    """Every constraint of a design under scatter, and the system: P(any constraint fails)."""

    constraints: dict[str, ConstraintReliability]
    system: Estimate

    def as_dict(self) -> dict:
        return {"constraints": {name: c.as_dict() for name, c in self.constraints.items()},
                "system": self.system.as_dict()}


def _finite(value: float) -> float | str:
    return value if math.isfinite(value) else ("inf" if value > 0 else "-inf")


def reliability_at(formulation: Formulation, design: dict, params: SimpleNamespace, scatter, correlation=None,
                   names: tuple[str, ...] | None = None, samples: int | None = None) -> Reliability:
    """Each constraint's design point and its FORM, SORM (Breitung) and importance-sampling estimates (centred at
    the design point, seeded), and the system's by importance sampling from the mixture of the origin and every
    design point. A constraint that does not depend on the scatter holds or fails with certainty ("exact"); one
    whose failure region lies beyond ||u|| = REACH gets FORM's bound Phi(-REACH)."""
    from clutchopt.optimise.reliability import IS_SAMPLES, REACH

    samples = samples or IS_SAMPLES
    n = len(scatter)
    shown, g = limit_states(formulation, design, params, scatter, correlation, names)
    out, centres = {}, []
    for row, name in enumerate(shown):
        point = design_point(g, row, n, FEASIBILITY_TOL)
        values = {q: float(v[0]) for q, v in values_from_standard(scatter, point.u[:, None], correlation).items()}
        if point.found:
            centres.append(point.u)
            estimates = [form(point), sorm(g, row, point),
                         importance_sampling(g, [row], [point.u], n, samples, SEED, FEASIBILITY_TOL, defensive=False)]
        elif math.isinf(point.beta) and not np.linalg.norm(point.u):
            certain = 0.0 if point.beta > 0 else 1.0
            estimates = [Estimate(certain, certain, certain, "exact: independent of the scatter")]
        else:
            bound = float(form(DesignPoint(point.u, REACH, False)).probability)
            estimates = [Estimate(0.0, 0.0, bound, f"FORM (no design point within beta {REACH:g})")
                         if point.beta > 0 else Estimate(1.0, 1.0 - bound, 1.0, f"FORM (fails within beta {REACH:g})")]
        out[name] = ConstraintReliability(point, values, estimates)
    system = importance_sampling(g, list(range(len(shown))), centres, n, samples, SEED + 1, FEASIBILITY_TOL)
    if system.estimator.startswith(NO_FAILURE):  # no upper bound of its own: the constraints' (a union bound)
        system = union_bound([c.best for c in out.values()], f"estimates summed (union bound; {system.estimator})")
    return Reliability(out, system)


def union_bound(estimates: list[Estimate], estimator: str) -> Estimate:
    """P(any of the events whose ``estimates`` these are) at most the sum of each one's: the sums of the estimates
    and of the upper ends, the largest lower end (Boole's inequality)."""
    return Estimate(sum(e.probability for e in estimates), max((e.low for e in estimates), default=0.0),
                    sum(e.high for e in estimates), estimator)


def performance_points(formulation: Formulation, design: dict, params: SimpleNamespace, scatter,
                       betas: dict[str, float], correlation=None) -> dict[str, np.ndarray]:
    """Each constraint's performance point at ``design`` in the independent standard normal space u (PMA: where its
    limit state is smallest on the sphere ||u|| = betas[name]); the origin for one the formulation replaces (a
    start-up's torque)."""
    n = len(scatter)
    shown, g = limit_states(formulation, design, params, scatter, correlation, tuple(betas))
    rows = {name: row for row, name in enumerate(shown)}
    return {name: performance_point(g, rows[name], n, betas[name]) if name in rows else np.zeros(n)
            for name in betas}


def performance_corners(formulation: Formulation, design: dict, params: SimpleNamespace, scatter,
                        betas: dict[str, float], correlation=None,
                        points: dict[str, np.ndarray] | None = None) -> dict[str, dict[str, float]]:
    """Each constraint's performance point at ``design`` (:func:`performance_points`, unless given as ``points``)
    as the quantities' values: the corner a chance design evaluates it at (SORA, Du & Chen 2004: the
    deterministic problem with each constraint at its shifted values, re-solved until the points settle)."""
    points = points or performance_points(formulation, design, params, scatter, betas, correlation)
    return {name: {q: float(v[0]) for q, v in values_from_standard(scatter, u[:, None], correlation).items()}
            for name, u in points.items()}
