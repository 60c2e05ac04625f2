"""Geometric programming with cvxpy (``solve(gp=True)``) for the formulations that are posynomial.

Nothing is rewritten by hand: the formulation's own constraint and objective functions are called with cvxpy
positive variables for the free design variables and floats for everything else (case values, fixed variables,
integers fixed at a given value). A "<=" constraint becomes ``value / limit <= 1``, a ">=" one
``limit / value <= 1``; cvxpy's DGP analysis then decides whether the posed problem is a geometric programme.

Which models are posynomial (decided by cvxpy's DGP analysis in :func:`gp_problem`; the bench table shows it):
- wedge ``paper`` mode: with the geometry given, the friction torque is a monomial in m_r, the flank pressure a
  monomial in m_r, the finger stress a monomial in m_r and d_n, the mass a posynomial: a GP as posed.
- ball ``paper`` mode is not, since it poses the case's allowable Hertz stress (9): p_0 of R_a goes through the
  contact ellipse's elliptic integrals (the leading-order torque (4), K5 = l / R_a, the outer diameter and the mass
  alone are monomials and posynomials: without that row it was a GP).
- lever ``paper`` mode is not: the worn-state radial force is the centrifugal force *minus* the return-spring
  force (a difference of monomials: signomial) in the lining-pressure and link constraints.
- cable ``paper`` mode is not, even with the integer cable count fixed: the weight-thread and hub-thread
  constraints subtract the cable's pull and the spring force from inertia forces (signomial).
- the geometry/design/threads modes are not: sin, tan of free angles, differences of radii.
The float64 verification of :mod:`clutchopt.optimise.verify` checks the GP optimum like any other.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import cvxpy as cp

from clutchopt.model import Formulation, namespace
from clutchopt.optimise.verify import ConstraintCheck, check_design, evaluate_objective


@dataclass
class GPResult:
    status: str  # optimal | not_posynomial | infeasible | solver_failed
    objective: float
    design: dict[str, float]
    constraints: list[ConstraintCheck]
    iterations: int
    build_s: float  # building the cvxpy problem and its DGP check
    solve_s: float  # cvxpy solve (canonicalisation and the conic solver)
    detail: str = ""  # not_posynomial: the constraints (or objective) that are not

    @property
    def worst_violation(self) -> float:
        return max([0.0] + [-c.margin for c in self.constraints])


def gp_problem(formulation: Formulation, objective: str, params, fixed: dict[str, float],
               bounds: dict[str, tuple[float, float]]):
    """(cvxpy Problem, {name: Variable}, names of non-posynomial parts) for the free variables not in ``fixed``."""
    variables = {v.name: cp.Variable(pos=True, name=v.name) for v in formulation.variables if v.name not in fixed}
    x = namespace({**fixed, **variables})
    constraints, not_gp = [], []
    for c in formulation.constraints(x, params):
        if not isinstance(c.value, cp.Expression) and not isinstance(c.limit, cp.Expression):
            continue  # no free variable in it: a fixed fact of the case, checked in float64 afterwards
        ratio = c.value / c.limit if c.sense == "<=" else c.limit / c.value
        constraint = ratio <= 1
        if constraint.is_dgp():
            constraints.append(constraint)
        else:
            not_gp.append(c.name)
    for name, var in variables.items():
        lower, upper = bounds[name]
        constraints += [var >= lower] if lower > 0 else []
        constraints += [var <= upper] if upper < float("inf") else []
    problem = cp.Problem(cp.Minimize(formulation.objective(objective).function(x, params)), constraints)
    if not problem.objective.is_dgp():
        not_gp.append(f"objective {objective}")
    return problem, variables, not_gp


class GPModel:
    """One posed problem as a cvxpy GP, built once (the case's numbers are constants of it)."""

    def __init__(self, formulation: Formulation, objective: str, params, fixed: dict[str, float],
                 bounds: dict[str, tuple[float, float]]):
        self.formulation, self.objective, self.params, self.fixed = formulation, objective, params, fixed
        started = time.perf_counter()
        try:
            self.problem, self.variables, self.not_posynomial = gp_problem(formulation, objective, params, fixed,
                                                                           bounds)
        except (RuntimeError, TypeError, ValueError):  # a NumPy function (sin, sqrt, ...) of a free variable
            self.problem, self.variables = None, {}
            self.not_posynomial = ["a NumPy function (sin, sqrt, ...) applied to a free variable"]
        self.build_s = time.perf_counter() - started

    def solve(self) -> GPResult:
        if self.not_posynomial:
            return GPResult("not_posynomial", float("nan"), {}, [], 0, self.build_s, 0.0,
                            "not posynomial: " + ", ".join(self.not_posynomial))
        started = time.perf_counter()
        try:
            self.problem.solve(gp=True)
        except cp.error.SolverError as exc:
            return GPResult("solver_failed", float("nan"), {}, [], 0, self.build_s, time.perf_counter() - started,
                            str(exc))
        elapsed = time.perf_counter() - started
        if self.problem.status not in ("optimal", "optimal_inaccurate"):
            status = "infeasible" if "infeasible" in self.problem.status else "solver_failed"
            return GPResult(status, float("nan"), {}, [], 0, self.build_s, elapsed, self.problem.status)
        design = {**self.fixed, **{name: float(var.value) for name, var in self.variables.items()}}
        checks = check_design(self.formulation, design, self.params)
        status = "optimal" if all(c.feasible for c in checks) else "unverified"
        return GPResult(status, evaluate_objective(self.formulation, self.objective, design, self.params), design,
                        checks, int(self.problem.solver_stats.num_iters or 0), self.build_s, elapsed)

