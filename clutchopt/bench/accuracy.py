"""Accuracy against time: one case per coupling, in each of its modes, solved by every method, each answer
re-checked in float64.

Methods: the paper's closed form (the comparison's ``closed_form`` column); cvxpy GP where the posed problem is
posynomial; CasADi/IPOPT at several tolerances; SciPy SLSQP on the same scaled NLP. The relative error is
taken against the tightest IPOPT solve. "first" times building the problem and solving it once; "re-solve"
solves the already-built problem again for the same case (median and interquartile range after a warm-up).
"""

from __future__ import annotations

import math

import numpy as np

from clutchopt.bench.reference import bench_cases, closed_form, reference_mode
from clutchopt.bench.timing import repeated, time_once
from clutchopt.cases import Case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.gp import GPModel
from clutchopt.optimise.problem import Problem
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.optimise.scipy_slsqp import SlsqpProblem

IPOPT_TOLERANCES = (1e-4, 1e-6, 1e-8, 1e-10)
SLSQP_FTOL = (1e-6, 1e-10)
OBJECTIVE = "mass"


def _row(case: Case, mode: str, method: str, status: str, objective: float, reference: float, violation: float,
         iterations, first_s: float, resolve: dict, note: str = "") -> dict:
    error = abs(objective - reference) / abs(reference) if math.isfinite(objective) else None
    return {"coupling": case.coupling, "case": case.path.rsplit("/", 1)[-1], "mode": mode, "method": method,
            "status": status, "objective": objective, "rel_error": error, "worst_violation": violation,
            "iterations": iterations, "first_s": first_s, "resolve_median_s": resolve.get("median_s"),
            "resolve_iqr_s": resolve.get("iqr_s"), "note": note}


def _ipopt_runs(case, formulation, repeats):
    """(tol, built problem, solution, first_s, re-solve timing) from the loosest tolerance to the tightest."""
    runs = []
    for tol in sorted(IPOPT_TOLERANCES, reverse=True):
        first_s, (problem, solution) = time_once(lambda: _build_and_solve(formulation, SolverOptions(tol=tol), case))
        runs.append((tol, problem, solution, first_s, repeated(lambda: problem.solve(case), repeats)))
    return runs


def _build_and_solve(formulation, options, case) -> tuple[Problem, Solution]:
    problem = Problem(formulation, OBJECTIVE, options)
    return problem, problem.solve(case)


def mode_rows(case: Case, mode: str, repeats: int) -> list[dict]:
    """Every method on one case in one mode; the closed form in the mode it belongs to."""
    formulation = get_coupling(case.coupling).formulation(mode)
    runs = _ipopt_runs(case, formulation, repeats)
    _, problem, best, _, _ = runs[-1]
    reference = best.objective
    pinned = {n: best.design[n] for n, (lo, hi) in best.bounds.items()
              if lo == hi or formulation.variable(n).integer}
    rows = []

    form = closed_form(case, OBJECTIVE) if mode == reference_mode(case.coupling) else None
    if form is not None:
        first_s, _ = time_once(lambda: closed_form(case, OBJECTIVE))
        rows.append(_row(case, mode, "closed form", "feasible" if form.feasible else "infeasible", form.objective,
                         reference, form.worst_violation, None, first_s,
                         repeated(lambda: closed_form(case, OBJECTIVE), repeats), "closed_form column, float64"))

    params = problem.posed.params(case)
    first_s, gp = time_once(lambda: GPModel(formulation, OBJECTIVE, params, pinned, best.bounds))
    result = gp.solve()
    if result.status == "not_posynomial":
        rows.append(_row(case, mode, "cvxpy gp", result.status, math.nan, reference, math.nan, None, math.nan, {},
                         result.detail))
    else:
        rows.append(_row(case, mode, "cvxpy gp", result.status, result.objective, reference, result.worst_violation,
                         result.iterations, first_s + result.solve_s, repeated(gp.solve, repeats),
                         "integers fixed at the IPOPT optimum" if any(formulation.variable(n).integer for n in pinned)
                         else ""))
    rows += [_row(case, mode, f"ipopt tol {tol:.0e}", s.status, s.objective, reference, s.worst_violation,
                  s.solver.iterations, first_s, resolve, f"{s.solver.solves} solves" if s.solver.solves > 1 else "")
             for tol, _, s, first_s, resolve in runs]

    integers = {n: v for n, v in pinned.items() if formulation.variable(n).integer}
    for ftol in SLSQP_FTOL:
        first_s, (slsqp, result) = time_once(lambda: _slsqp_first(formulation, case, integers, ftol))
        rows.append(_row(case, mode, f"slsqp ftol {ftol:.0e}", result.status, result.objective, reference,
                         result.worst_violation, result.iterations, first_s,
                         repeated(lambda: slsqp.solve(case, integers, ftol), repeats),
                         "integers fixed at the IPOPT optimum" if integers else ""))
    return rows


def _slsqp_first(formulation, case, integers, ftol):
    slsqp = SlsqpProblem(Problem(formulation, OBJECTIVE))
    return slsqp, slsqp.solve(case, integers, ftol)


def accuracy_rows(config) -> list[dict]:
    """The accuracy-vs-time table: every mode of every coupling with a case file, the closed form's mode first."""
    rows = []
    with np.errstate(invalid="ignore", divide="ignore"):
        for case in bench_cases():
            first = reference_mode(case.coupling)
            for mode in [first] + [m for m in get_coupling(case.coupling).formulations if m != first]:
                rows += mode_rows(case, mode, config.repeats)
    return rows
