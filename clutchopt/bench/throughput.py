"""Throughput: one built CasADi problem re-solved, warm-started, over a sweep of one case quantity.

The sweep runs the first non-integer quantity of the case's first section (the duty: inertia, torque or power)
from 0.5x to 2x its value. Serial: one process, each point warm-started from the previous optimum (and, for
comparison, each from the case's own start: "cold starts"). Pool: warm, the sweep cut into contiguous chunks,
one per worker process, each worker building its own problem (counted).
"""

from __future__ import annotations

import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from clutchopt.bench.reference import bench_cases, reference_mode
from clutchopt.cases import Case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.problem import Problem


def sweep_quantity(case: Case) -> str:
    quantities = [q for q in get_coupling(case.coupling).quantities if not q.integer and q.name in case.values]
    return next(q.name for q in quantities if q.section == quantities[0].section)


def warm_sweep(case: Case, name: str, values, warm: bool = True) -> tuple[int, int]:
    """Solve the case at each value of ``name`` in turn, warm-started from the previous optimum unless ``warm`` is
    false (each point from the case's own start); (points optimal, points)."""
    problem = Problem(get_coupling(case.coupling).formulation(reference_mode(case.coupling)))
    previous, optimal = None, 0
    for value in values:
        solution = problem.solve(case.with_values(**{name: float(value)}), warm=previous if warm else None)
        optimal += solution.status == "optimal"
        previous = solution if solution.status == "optimal" else previous
    return optimal, len(values)


def throughput_rows(config) -> list[dict]:
    rows = []
    for case in bench_cases():
        name = sweep_quantity(case)
        values = case.values[name] * np.geomspace(0.5, 2.0, config.sweep_points)
        problem = Problem(get_coupling(case.coupling).formulation(reference_mode(case.coupling)))
        problem.solve(case)  # warm-up: first solve of this process
        started = time.perf_counter()
        optimal, points = warm_sweep(case, name, values)
        serial = time.perf_counter() - started
        rows.append(_row(case, name, "serial", 1, points, optimal, serial))
        started = time.perf_counter()
        optimal, points = warm_sweep(case, name, values, warm=False)
        rows.append(_row(case, name, "serial, cold starts", 1, points, optimal, time.perf_counter() - started))
        chunks = np.array_split(values, config.processes)
        started = time.perf_counter()
        with ProcessPoolExecutor(config.processes) as pool:
            results = list(pool.map(warm_sweep, [case] * len(chunks), [name] * len(chunks), chunks))
        pooled = time.perf_counter() - started
        rows.append(_row(case, name, "process pool", config.processes, points, sum(r[0] for r in results), pooled))
    return rows


def _row(case, name, how, processes, points, optimal, seconds):
    return {"coupling": case.coupling, "mode": reference_mode(case.coupling), "swept": f"{name} x0.5..2",
            "how": how, "processes": processes, "points": points, "optimal": optimal, "wall_s": seconds,
            "points_per_s": points / seconds}
