"""Warm re-solves, before and after: the same warm sweep solved by warm IPOPT alone (as before) and by SQP first
(CasADi's ``sqpmethod`` with the dense active-set QP ``qrqp``, its KKT point checked apart from the solver, warm
IPOPT if that check or the float64 check fails). Both in one run, point by point; every optimum verified."""

from __future__ import annotations

import time

import numpy as np

from clutchopt.bench.reference import bench_cases, reference_mode
from clutchopt.bench.throughput import sweep_quantity
from clutchopt.formulations import get_coupling
from clutchopt.optimise.problem import Problem
from clutchopt.optimise.solution import SolverOptions

METHODS = (("warm IPOPT (before)", SolverOptions(warm_sqp=False)), ("SQP, then warm IPOPT", SolverOptions()))


def resolve_rows(config) -> list[dict]:
    rows = []
    for case in bench_cases():
        name = sweep_quantity(case)
        values = case.values[name] * np.geomspace(0.5, 2.0, config.sweep_points)
        cases = [case.with_values(**{name: float(v)}) for v in values]
        formulation = get_coupling(case.coupling).formulation(reference_mode(case.coupling))
        results = {}
        for label, options in METHODS:
            problem = Problem(formulation, "mass", options)
            problem.solve(case)  # warm-up
            previous, solver_s, wall_s, objectives, optimal = problem.solve(cases[0]), 0.0, 0.0, [], 0
            for point in cases[1:]:
                started = time.perf_counter()
                solution = problem.solve(point, warm=previous)
                wall_s += time.perf_counter() - started
                solver_s += solution.solver.time_s
                objectives.append(solution.objective if solution.status == "optimal" else np.nan)
                optimal += solution.status == "optimal"
                previous = solution if solution.status == "optimal" else None
            results[label] = (solver_s, wall_s, np.array(objectives), optimal)
        before = results[METHODS[0][0]]
        for label, (solver_s, wall_s, objectives, optimal) in results.items():
            count = len(cases) - 1
            with np.errstate(invalid="ignore"):
                difference = np.nanmax(np.abs(objectives / before[2] - 1)) if np.isfinite(objectives).any() else None
            rows.append({"coupling": case.coupling, "mode": formulation.mode, "method": label, "resolves": count,
                         "optimal": optimal, "solver_per_resolve_s": solver_s / count, "per_resolve_s": wall_s / count,
                         "speedup": before[1] / wall_s, "max_rel_diff_objective": difference})
    return rows
