"""SciPy SLSQP on the same scaled NLP IPOPT solves (``Posed.nlp``), for comparison.

f, g and their derivatives are CasADi functions of the scaled variables, so SLSQP sees exactly the numbers
IPOPT sees: the same scaling, bounds and start (``Posed.scaled_data``). SLSQP has no integers: integer
variables are fixed at given values (e.g. IPOPT's integer optimum). Its answer is re-checked in float64 like
every other (SLSQP's own success flag is not trusted).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import casadi as ca
import numpy as np
from scipy.optimize import minimize

from clutchopt.cases import Case
from clutchopt.optimise.problem import Problem
from clutchopt.optimise.verify import ConstraintCheck, check_design, evaluate_objective


@dataclass
class SlsqpResult:
    status: str  # optimal | unverified (SLSQP stopped, float64 check fails) | solver_failed
    objective: float
    design: dict[str, float]
    constraints: list[ConstraintCheck]
    iterations: int
    solve_s: float
    message: str

    @property
    def worst_violation(self) -> float:
        return max([0.0] + [-c.margin for c in self.constraints])


class SlsqpProblem:
    """A built IPOPT :class:`Problem`'s NLP as SciPy callables, built once, solved many times."""

    def __init__(self, problem: Problem):
        self.problem = problem
        nlp = problem.posed.nlp
        x, p = nlp["x"], nlp["p"]
        self._f = ca.Function("f", [x, p], [nlp["f"]])
        self._grad = ca.Function("grad_f", [x, p], [ca.gradient(nlp["f"], x)])
        self._g = ca.Function("g", [x, p], [nlp["g"]])
        self._jac = ca.Function("jac_g", [x, p], [ca.jacobian(nlp["g"], x)])

    def solve(self, case: Case, fixed: dict[str, float] | None = None, ftol: float = 1e-10,
              max_iter: int = 500) -> SlsqpResult:
        """Minimise from the problem's start; ``fixed`` pins variables (integers) at values through their bounds."""
        data = self.problem.posed.scaled_data(case)
        variables = self.problem.formulation.variables
        lbx, ubx, x0 = data.lbx.copy(), data.ubx.copy(), data.x0.copy()
        for i, v in enumerate(variables):
            if fixed and v.name in fixed:
                lbx[i] = ubx[i] = x0[i] = fixed[v.name] / data.scale[i]
        p = data.p
        constraints = {"type": "ineq", "fun": lambda x: -np.array(self._g(x, p), dtype=float).ravel(),
                       "jac": lambda x: -np.array(self._jac(x, p), dtype=float)}
        started = time.perf_counter()
        result = minimize(lambda x: float(self._f(x, p)), x0,
                          jac=lambda x: np.array(self._grad(x, p), dtype=float).ravel(), bounds=list(zip(lbx, ubx)),
                          constraints=[constraints], method="SLSQP", options={"ftol": ftol, "maxiter": max_iter})
        elapsed = time.perf_counter() - started
        design = {v.name: float(value) for v, value in zip(variables, np.clip(result.x, lbx, ubx) * data.scale)}
        checks = check_design(self.problem.formulation, design, data.params)
        objective = evaluate_objective(self.problem.formulation, self.problem.objective.name, design, data.params)
        status = ("optimal" if all(c.feasible for c in checks) else "unverified") if result.success else "solver_failed"
        return SlsqpResult(status, objective, design, checks, int(result.nit), elapsed, str(result.message))
